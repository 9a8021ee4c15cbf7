//! `lsys build`, `lsys render` and each rebuild of `lsys watch`: a grammar
//! -> a model file (.glb, .gltf, .obj + .mtl) or a picture (.png), written
//! atomically, with `--stats` as JSON (or, for `watch`, a one-line summary)
//! on standard output.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::args::{
    BuildArgs, DeriveRun, LookArgs, ModelArgs, PailouArgs, PailouTypeArg, PictureArgs, RenderArgs,
    SourceArgs,
};
use super::commands::{compile_reporting, report};
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK, EX_USAGE};
use crate::build::{self, BuildOptions, Built};
use crate::derive::DeriveOptions;
use crate::export::output::{write_scene, Format, WriteError};
use crate::export::render;
use crate::load::Input;
use crate::mesh::{ComponentSearch, MeshOptions};
use crate::progress::Progress;

pub fn build_cmd(b: &BuildArgs, color: bool) -> i32 {
    match format_of(&b.output) {
        Ok(f) if is_scene(&b.model) => {
            super::guided::build_scene(&b.model, &b.output, &b.picture, f, color)
        }
        Ok(f) => {
            build_once(
                &model_job(&b.model),
                &b.output,
                &b.picture,
                f,
                color,
                Report::Stats,
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
    if is_scene(&r.model) {
        return super::guided::build_scene(&r.model, &r.output, &r.picture, Format::Png, color);
    }
    build_once(
        &model_job(&r.model),
        &r.output,
        &r.picture,
        Format::Png,
        color,
        Report::Stats,
    )
    .code
}

/// A guided scene (`FILE.toml`, docs/guided.md) rather than a grammar.
fn is_scene(m: &ModelArgs) -> bool {
    m.common.file.ends_with(".toml")
}

pub fn pailou_cmd(p: &PailouArgs, color: bool) -> i32 {
    use crate::pailou::{self, graph, PailouType};
    let mut defines = Vec::new();
    let mut relations_text: Option<String> = None;
    let (layout, kind, title, name) = match &p.graph {
        Some(path) => {
            let text = match std::fs::read_to_string(path) {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("lsys: cannot read {}: {e}", path.display());
                    return EX_NOINPUT;
                }
            };
            let relations = match &p.relations {
                Some(r) => match std::fs::read_to_string(r) {
                    Ok(t) => t,
                    Err(e) => {
                        eprintln!("lsys: cannot read {}: {e}", r.display());
                        return EX_NOINPUT;
                    }
                },
                None => graph::RELATIONS.to_string(),
            };
            let found = graph::read(&path.display().to_string(), &text, &relations);
            if p.relations.is_some() {
                relations_text = Some(relations);
            }
            match found {
                Ok(g) => {
                    for u in &g.unplaced {
                        eprintln!("lsys: warning: graph: {u}");
                    }
                    defines = g.defines;
                    let stem = path
                        .file_stem()
                        .map_or("graph".into(), |s| s.to_string_lossy().into_owned());
                    (
                        g.layout,
                        g.kind,
                        format!("graph {}", path.display()),
                        format!("{stem}.lsys"),
                    )
                }
                Err(e) => {
                    report(e.as_ref(), color);
                    return EX_DATAERR;
                }
            }
        }
        None => {
            let kind = match p.kind {
                PailouTypeArg::Ridge => PailouType::Ridge,
                PailouTypeArg::Pillar => PailouType::Pillar,
            };
            match pailou::style_layout(&p.style, kind) {
                Ok(l) => {
                    let k = if kind == PailouType::Ridge {
                        "ridge"
                    } else {
                        "pillar"
                    };
                    (
                        l,
                        kind,
                        format!("style {}, {k} type", p.style),
                        format!("pailou-{}-{k}.lsys", p.style),
                    )
                }
                Err(e) => {
                    eprintln!("lsys: cannot build the style {}: {e}", p.style);
                    return EX_USAGE;
                }
            }
        }
    };
    let input = pailou::input(&layout, kind, &title, &name);
    // The command line's -D win over the graph's [defines].
    defines.extend(p.define.iter().cloned());
    pailou::toukung_levels(&mut defines);
    if p.emit_graph {
        print!("{}", graph::emit(&layout, kind, &title));
    }
    if p.chart {
        print!("{}", layout.chart());
    }
    if p.emit_lsys {
        if let Input::Text { text, .. } = &input {
            print!("{text}");
        }
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
    let job = Job {
        input,
        name: &name,
        defines: &defines,
        source: None,
        run: &p.run,
        look: &p.look,
        collisions: true,
        relations: relations_text.as_deref(),
    };
    build_once(&job, out, &p.picture, format, color, Report::Stats).code
}

/// One build: the grammar and the options that shape it.
pub(super) struct Job<'a> {
    input: Input,
    /// How messages name the grammar.
    name: &'a str,
    defines: &'a [(String, String)],
    /// `--include-dir`, `--max-include-depth`, ...; `None` takes the defaults.
    source: Option<&'a SourceArgs>,
    run: &'a DeriveRun,
    look: &'a LookArgs,
    /// Run the structural check (supports and interpenetration).
    collisions: bool,
    /// The relation matrix for it (`None`: the library's).
    relations: Option<&'a str>,
}

/// A build from `lsys build`, `render` or `watch`.
pub(super) fn model_job(m: &ModelArgs) -> Job<'_> {
    Job {
        input: Input::from_arg(&m.common.file),
        name: &m.common.file,
        defines: &m.common.define,
        source: Some(&m.common.source),
        run: &m.run,
        look: &m.look,
        collisions: m.look.collisions,
        relations: None,
    }
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

/// The folder whose `components/` is searched first: the grammar file's.
pub(super) fn grammar_dir(input: &Input) -> Option<std::path::PathBuf> {
    match input {
        Input::Path(p) => Some(
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf(),
        ),
        _ => None,
    }
}

/// Reports an output that was not written; the exit code (65 when the
/// exporter refused the model, 74 when the file could not be written).
pub(super) fn write_failed(e: WriteError, out: &Path, color: bool) -> i32 {
    match e {
        WriteError::Export(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        WriteError::Io(e) => {
            eprintln!("lsys: cannot write {}: {e}", out.display());
            EX_IOERR
        }
    }
}

/// The options of a build from the command line.
fn options(m: &Job, source: crate::load::Options) -> BuildOptions {
    let grammar_dir = grammar_dir(&m.input);
    BuildOptions {
        source,
        steps: m.run.steps,
        derive: DeriveOptions {
            seed: m.run.seed,
            max_modules: m.run.max_modules,
            max_params: m.run.max_params,
        },
        angle: m.look.angle,
        step: m.look.step,
        width: m.look.width,
        components: component_search(m.look, grammar_dir),
        mesh: mesh_options(m.look),
        early: Default::default(),
    }
}

/// Where components are searched: `grammar_dir`'s `components/`, then the
/// `--components` folders.
pub(super) fn component_search(
    look: &LookArgs,
    grammar_dir: Option<std::path::PathBuf>,
) -> ComponentSearch {
    ComponentSearch {
        grammar_dir,
        dirs: look.components.clone(),
        within: Vec::new(),
        detail: look.detail,
    }
}

/// The mesher's options from the command line's look flags.
pub(super) fn mesh_options(look: &LookArgs) -> MeshOptions {
    MeshOptions {
        sides: look.facets.unwrap_or(MeshOptions::default().sides),
        adaptive: look.facets.is_none(),
        detail: look.detail,
        instanced: look.instanced,
        max_triangles: look.max_triangles,
    }
}

/// The compilation options of a job from the command line.
fn source_options(m: &Job) -> crate::load::Options {
    match m.source {
        Some(s) => s.options(m.defines),
        None => crate::load::Options {
            defines: m.defines.to_vec(),
            ..Default::default()
        },
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
    /// function files), when it compiled.
    pub sources: Option<Vec<PathBuf>>,
}

/// Compiles and builds `m`, writes `out`; prints diagnostics and the
/// report.
pub(super) fn build_once(
    m: &Job,
    out: &Path,
    pic: &PictureArgs,
    format: Format,
    color: bool,
    report_as: Report,
) -> Outcome {
    let t0 = Instant::now();
    let opts = source_options(m);
    let mut build_opts = options(m, opts.clone());
    // The grammar components its text places are built on the other core
    // while it compiles (a Pailou's Toukungs; see `build::Early`).
    if let Some(text) = root_text(&m.input) {
        build_opts.early = build::Early::start(&text, &build_opts);
    }
    let comp = match compile_reporting(&m.input, m.name, &opts, color) {
        Ok(c) => c,
        Err((code, files)) => {
            // A grammar that failed still names what it read: watch waits
            // for a fix in an include or a function file too.
            return Outcome {
                code,
                sources: (!files.is_empty()).then_some(files),
            };
        }
    };
    let sources = Some(comp.program.sources.disk_paths());
    let code = build_compiled(
        m,
        &comp,
        &build_opts,
        (out, pic, format),
        color,
        report_as,
        t0,
    );
    Outcome { code, sources }
}

/// The text of the grammar's own file, if it can be had without a
/// diagnostic (compiling reads it again, and reports what is wrong).
fn root_text(input: &crate::load::Input) -> Option<std::borrow::Cow<'static, str>> {
    use crate::load::Input;
    match input {
        Input::Std(name) => crate::stdlib::get(name).map(Into::into),
        Input::Path(path) => std::fs::read_to_string(path).ok().map(Into::into),
        Input::Text { text, .. } | Input::Edited { text, .. } => Some(text.clone().into()),
    }
}

/// Builds the compiled grammar and writes `out` as `format`; the exit code.
fn build_compiled(
    m: &Job,
    comp: &crate::pipeline::Compilation,
    opts: &BuildOptions,
    (out, pic, format): (&Path, &PictureArgs, Format),
    color: bool,
    report_as: Report,
    t0: Instant,
) -> i32 {
    let parse = t0.elapsed();
    let progress = Progress::new(true);
    let built = match build::build_observed(comp, opts, &mut |s| progress.stage(s)) {
        Ok(b) => b,
        Err(e) => {
            drop(progress);
            report(&e, color);
            return EX_DATAERR;
        }
    };
    for w in &built.warnings {
        report(w, color);
    }
    if m.collisions {
        structural_warnings(
            &built.scene,
            m.relations.unwrap_or(crate::pailou::graph::RELATIONS),
        );
    }
    if built.scene.triangle_count() == 0 {
        let input_path = match &m.input {
            Input::Path(p) => Some(p.as_path()),
            _ => None,
        };
        let hint = super::guided::built_without_its_guides(&comp.program, input_path)
            .map(|h| format!("\n  help: {h}"))
            .unwrap_or_default();
        let why = match built.modules {
            0 => "its module string is empty".to_string(),
            1 => "its string of 1 module has no drawing command with a size".to_string(),
            n => format!("its string of {n} modules has no drawing command with a size"),
        };
        eprintln!(
            "lsys: warning: {} draws nothing ({why}); the output is empty{hint}",
            m.name
        );
    }
    let t1 = Instant::now();
    progress.message(if format == Format::Png {
        "rendering"
    } else {
        "writing"
    });
    let written = write_scene(&built.scene, out, format, &picture(pic));
    drop(progress);
    let write_time = t1.elapsed();
    let code = match written {
        Ok(bytes) => {
            if m.look.stats {
                println!(
                    "{}",
                    stats(&built, &comp.program, parse, write_time, out, bytes)
                );
            } else if report_as == Report::Summary {
                println!("{}", summary(&built, out, bytes, t0.elapsed()));
            }
            EX_OK
        }
        Err(e) => write_failed(e, out, color),
    };
    // Freeing a big model (W2: a quarter of a million tube chains, each
    // its own allocation) took milliseconds after the file was complete:
    // it is freed beside the exit (or the next build, in `watch`). Should
    // no thread start, the refused closure frees it here.
    let _ = std::thread::Builder::new().spawn(move || drop(built));
    code
}

/// Prints the structural check's problems as warnings (at most 40, then
/// how many more).
fn structural_warnings(scene: &crate::mesh::Scene, relations: &str) {
    use crate::mesh::structure;
    let rules = match structure::Rules::pailou(relations) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("lsys: warning: no structural check: the relation matrix does not read: {e}");
            return;
        }
    };
    let found = structure::check(scene, &rules);
    for p in found.iter().take(40) {
        eprintln!("lsys: warning: structure: {p}");
    }
    if found.len() > 40 {
        eprintln!(
            "lsys: warning: structure: ... and {} more problems",
            found.len() - 40
        );
    }
}

pub(super) fn picture(pic: &PictureArgs) -> render::RenderOptions {
    render::RenderOptions {
        view: pic.view,
        width: pic.size.0,
        height: pic.size.1,
        ..Default::default()
    }
}

/// One line for `watch`: what was written and how big the model is.
fn summary(built: &Built, out: &Path, bytes: u64, took: Duration) -> String {
    format!(
        "wrote {}: {} modules, {} triangles, {bytes} bytes in {} ms",
        out.display(),
        built.modules,
        built.scene.triangle_count(),
        took.as_millis()
    )
}

pub(super) fn ms(d: Duration) -> f64 {
    (d.as_secs_f64() * 1e6).round() / 1e3
}

fn stats(
    built: &Built,
    program: &crate::resolve::Program,
    parse: Duration,
    write: Duration,
    out: &Path,
    bytes: u64,
) -> String {
    let s = &built.scene;
    // f32 coordinates printed through f64 would show binary noise
    // (84.05000305175781); print the shortest decimal that reads back.
    let short = |v: glam::Vec3| {
        v.to_array()
            .map(|x| x.to_string().parse::<f64>().unwrap_or(f64::NAN))
    };
    let bounds = s
        .bounds()
        .map(|(lo, hi)| serde_json::json!([short(lo), short(hi)]));
    let t = &built.timings;
    let mut json = serde_json::json!({
        "modules": built.modules,
        "instances": s.instance_counts(),
        "vertices": s.vertex_count(),
        "triangles": s.triangle_count(),
        "bounds": bounds,
        "output": {"path": out.display().to_string(), "bytes": bytes},
        "timings_ms": {
            "parse": ms(parse),
            "derive": ms(t.derive),
            "interpret": ms(t.interpret),
            "mesh": ms(t.mesh),
            "write": ms(write),
        },
    });
    super::shape_stats::add(&mut json, built, program);
    json.to_string()
}
