//! `lsys build`, `lsys render` and each rebuild of `lsys watch`: a grammar
//! -> a model file (.glb, .gltf, .obj + .mtl) or a picture (.png), written
//! atomically, with `--stats` as JSON (or, for `watch`, a one-line summary)
//! on standard output.

use std::path::{Path, PathBuf};

use super::args::{BuildArgs, ModelArgs, PailouArgs, PailouTypeArg, PictureArgs, RenderArgs};
use super::options::{grammar_options, picture};
use super::report::{failed, pailou_failed, report};
use super::{EX_DATAERR, EX_OK, EX_USAGE};
use crate::driver::{self, Check, Event, Format, Job, Output, Pailou, PailouType, TomlFile};
use crate::progress::Progress;

pub fn build_cmd(b: &BuildArgs, color: bool) -> i32 {
    match format_of(&b.output) {
        Ok(f) if is_toml(&b.model) => build_toml(&b.model, &b.output, &b.picture, f, color),
        Ok(f) => {
            build_once(
                model_job(&b.model),
                &b.output,
                &b.picture,
                f,
                color,
                Report::Stats,
                b.model.look.stats,
            )
            .code
        }
        Err(msg) => {
            eprintln!("{msg}");
            EX_USAGE
        }
    }
}

pub fn render_cmd(r: &RenderArgs, color: bool) -> i32 {
    if Format::of(&r.output) != Some(Format::Png) {
        eprintln!(
            "lsys: `render` writes PNG pictures; name the output FILE.png (for models use `lsys build -o {}`)",
            r.output.display()
        );
        return EX_USAGE;
    }
    let picture = PictureArgs {
        style: r.style,
        ..r.picture.clone()
    };
    if is_toml(&r.model) {
        return build_toml(&r.model, &r.output, &picture, Format::Png, color);
    }
    build_once(
        model_job(&r.model),
        &r.output,
        &picture,
        Format::Png,
        color,
        Report::Stats,
        r.model.look.stats,
    )
    .code
}

/// A guided scene or a Pailou graph (`FILE.toml`) rather than a grammar.
fn is_toml(m: &ModelArgs) -> bool {
    m.common.file.ends_with(".toml")
}

/// `lsys build FILE.toml`: a guided scene (docs/guided.md), or a Pailou
/// component graph built as `lsys pailou FILE.toml` builds it; told apart
/// by their keys.
fn build_toml(m: &ModelArgs, out: &Path, pic: &PictureArgs, format: Format, color: bool) -> i32 {
    let path = Path::new(&m.common.file);
    let kind = match std::fs::read_to_string(path) {
        Ok(text) => driver::toml_file(path, &text),
        // The scene's reader says why it cannot be read.
        Err(_) => Ok(TomlFile::GuidedScene),
    };
    match kind {
        Ok(TomlFile::GuidedScene) => super::guided::build_scene(m, out, pic, format, color),
        Ok(TomlFile::PailouGraph) => {
            let pailou = match Pailou::graph_file(path, None) {
                Ok(p) => p,
                Err(e) => return pailou_failed(e, color),
            };
            for u in pailou.unplaced() {
                eprintln!("lsys: warning: graph: {u}");
            }
            let c = &m.common;
            let job = pailou.job(grammar_options(&c.define, Some(&c.source), &m.run, &m.look));
            build_once(job, out, pic, format, color, Report::Stats, m.look.stats).code
        }
        Err(e) => {
            report(&e, color);
            EX_DATAERR
        }
    }
}

pub fn pailou_cmd(p: &PailouArgs, color: bool) -> i32 {
    let pailou = match &p.graph {
        Some(path) => Pailou::graph_file(path, p.relations.as_deref()),
        None => {
            let kind = match p.kind {
                PailouTypeArg::Ridge => PailouType::Ridge,
                PailouTypeArg::Pillar => PailouType::Pillar,
            };
            Pailou::style(&p.style, kind)
        }
    };
    let pailou = match pailou {
        Ok(g) => g,
        Err(e) => return pailou_failed(e, color),
    };
    for u in pailou.unplaced() {
        eprintln!("lsys: warning: graph: {u}");
    }
    if p.emit_graph {
        print!("{}", pailou.graph_toml());
    }
    if p.chart {
        print!("{}", pailou.chart());
    }
    if p.emit_lsys {
        print!("{}", pailou.grammar_text());
    }
    let Some(out) = &p.output else {
        if p.chart || p.emit_lsys || p.emit_graph {
            return EX_OK;
        }
        eprintln!(
            "lsys: say what to write: -o FILE (.glb, .gltf, .obj, .png), --chart, --emit-lsys or --emit-graph"
        );
        return EX_USAGE;
    };
    let format = match format_of(out) {
        Ok(f) => f,
        Err(msg) => {
            eprintln!("{msg}");
            return EX_USAGE;
        }
    };
    let job = pailou.job(grammar_options(&p.define, None, &p.run, &p.look));
    build_once(
        job,
        out,
        &p.picture,
        format,
        color,
        Report::Stats,
        p.look.stats,
    )
    .code
}

/// A build from `lsys build`, `render` or `watch`.
pub(super) fn model_job(m: &ModelArgs) -> Job {
    let options = grammar_options(&m.common.define, Some(&m.common.source), &m.run, &m.look);
    let check = if m.look.collisions {
        Check::Library
    } else {
        Check::None
    };
    Job::for_arg(&m.common.file, options).check(check)
}

/// The format of `lsys build`'s output, or the usage error to print.
pub(super) fn format_of(out: &Path) -> Result<Format, String> {
    driver::format_of(out).map_err(|why| format!("lsys: {why}"))
}

/// What a successful build prints on standard output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Report {
    /// The `--stats` JSON when asked for, else nothing.
    Stats,
    /// The `--stats` JSON when asked for, else one summary line (`watch`).
    Summary,
}

/// What one build did.
pub(super) struct Outcome {
    pub code: i32,
    /// Every file the model was read from (root, includes, view and
    /// function files), when it could be read.
    pub sources: Option<Vec<PathBuf>>,
}

/// Runs `job` writing `out`; prints diagnostics, warnings, the progress
/// bar and the report.
pub(super) fn build_once(
    job: Job,
    out: &Path,
    pic: &PictureArgs,
    format: Format,
    color: bool,
    report_as: Report,
    stats: bool,
) -> Outcome {
    let job = job.output(Output::File {
        path: out.to_path_buf(),
        format,
        picture: picture(pic),
    });
    let mut progress: Option<Progress> = None;
    let result = driver::run(&job, &mut |event| match event {
        Event::Warning(w) => report(w, color),
        Event::Notice(n) => eprintln!("lsys: warning: {n}"),
        Event::Stage(s) => progress.get_or_insert_with(|| Progress::new(true)).stage(s),
        Event::Writing(f) => {
            progress
                .get_or_insert_with(|| Progress::new(true))
                .message(if f == Format::Png {
                    "rendering"
                } else {
                    "writing"
                })
        }
    });
    drop(progress);
    match result {
        Ok(done) => {
            if stats {
                println!("{}", done.stats());
            } else if report_as == Report::Summary {
                println!("{}", done.summary());
            }
            let sources = Some(done.sources.clone());
            // Freeing a big model (W2: a quarter of a million tube chains,
            // each its own allocation) took milliseconds after the file
            // was complete: it is freed beside the exit (or the next build,
            // in `watch`). Should no thread start, the refused closure
            // frees it here.
            let _ = std::thread::Builder::new().spawn(move || drop(done));
            Outcome {
                code: EX_OK,
                sources,
            }
        }
        Err(f) => Outcome {
            sources: (!f.sources.is_empty()).then_some(f.sources),
            code: failed(f.reason, &job.name, color),
        },
    }
}
