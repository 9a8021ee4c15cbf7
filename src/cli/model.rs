//! `lsys build`, `lsys render` and each rebuild of `lsys watch`: a grammar
//! -> a model file (.glb, .gltf, .obj + .mtl) or a picture (.png), written
//! atomically, with `--stats` as JSON (or, for `watch`, a one-line summary)
//! on standard output.

use std::path::{Path, PathBuf};

use super::args::{
    BuildArgs, DeriveRun, LookArgs, ModelArgs, PailouArgs, PailouTypeArg, PictureArgs, RenderArgs,
    SourceArgs,
};
use super::commands::report;
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK, EX_USAGE};
use crate::driver::{
    self, Check, Event, Format, Job, Output, Pailou, PailouError, PailouType, Reason, TomlFile,
};
use crate::progress::Progress;
use crate::GrammarOptions;

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
    if is_toml(&r.model) {
        return build_toml(&r.model, &r.output, &r.picture, Format::Png, color);
    }
    build_once(
        model_job(&r.model),
        &r.output,
        &r.picture,
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

/// Prints why a Pailou could not be read; the exit code.
fn pailou_failed(e: PailouError, color: bool) -> i32 {
    match e {
        PailouError::Graph(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        e @ PailouError::Read { .. } => {
            eprintln!("lsys: {e}");
            EX_NOINPUT
        }
        e @ PailouError::Style { .. } => {
            eprintln!("lsys: {e}");
            EX_USAGE
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

/// The options of a build from the command line's flags.
pub(super) fn grammar_options(
    defines: &[(String, String)],
    source: Option<&SourceArgs>,
    run: &DeriveRun,
    look: &LookArgs,
) -> GrammarOptions {
    let mut o = GrammarOptions::default();
    for (name, value) in defines {
        o = o.define(name, value);
    }
    if let Some(s) = source {
        o = s.apply(o);
    }
    o = o
        .steps(run.steps)
        .max_modules(run.max_modules)
        .max_params(run.max_params);
    if let Some(seed) = run.seed {
        o = o.seed(seed);
    }
    look.apply(o)
}

/// The format of `lsys build`'s output, or the usage error to print.
pub(super) fn format_of(out: &Path) -> Result<Format, String> {
    Format::of(out).ok_or_else(|| {
        format!(
            "lsys: cannot tell the format of `{}` from its extension; name the output .glb, .gltf, .obj or .png",
            out.display()
        )
    })
}

/// Reports an output that was not written; the exit code (65 when the
/// exporter refused the model, 74 when the file could not be written).
pub(super) fn write_failed(reason: Reason, color: bool) -> i32 {
    match reason {
        Reason::Export(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        Reason::Write { path, error } => {
            eprintln!("lsys: cannot write {}: {error}", path.display());
            EX_IOERR
        }
        Reason::Scene(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        other => failed(other, "", color),
    }
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

/// Prints why a job failed; the exit code.
fn failed(reason: Reason, name: &str, color: bool) -> i32 {
    match reason {
        Reason::Input(d) => {
            eprint!("{}", d.render(color));
            EX_NOINPUT
        }
        Reason::Grammar(d) => {
            let errors = d.error_count();
            eprint!("{}", d.render(color));
            eprintln!(
                "{}: {errors} error{}",
                name,
                if errors == 1 { "" } else { "s" }
            );
            EX_DATAERR
        }
        Reason::Build(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        other => write_failed(other, color),
    }
}

pub(super) fn picture(pic: &PictureArgs) -> driver::Picture {
    driver::Picture {
        view: pic.view,
        width: pic.size.0,
        height: pic.size.1,
        ..Default::default()
    }
}
