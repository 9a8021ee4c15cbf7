//! `lsys build`, `lsys render` and each rebuild of `lsys watch`: a grammar
//! -> a model file (.glb, .gltf, .obj + .mtl) or a picture (.png), written
//! atomically, with `--stats` as JSON (or, for `watch`, a one-line summary)
//! on standard output.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::args::{BuildArgs, ModelArgs, PictureArgs, RenderArgs, ViewArg};
use super::commands::{compile, report};
use super::{EX_DATAERR, EX_IOERR, EX_OK, EX_USAGE};
use crate::build::{self, BuildOptions, Built};
use crate::derive::DeriveOptions;
use crate::export::output::{write_scene, Format, WriteError};
use crate::export::render;
use crate::mesh::{ComponentSearch, MeshOptions};
use crate::progress::Progress;
use crate::resolve::Input;
use crate::source::Origin;

pub fn build_cmd(b: &BuildArgs, color: bool) -> i32 {
    match format_of(&b.output) {
        Ok(f) => build_once(&b.model, &b.output, &b.picture, f, color, Report::Stats).code,
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
    build_once(
        &r.model,
        &r.output,
        &r.picture,
        Format::Png,
        color,
        Report::Stats,
    )
    .code
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

/// The options of a build from the command line.
fn options(m: &ModelArgs) -> BuildOptions {
    let grammar_dir = match Input::from_arg(&m.common.file) {
        Input::Path(p) => Some(
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf(),
        ),
        _ => None,
    };
    BuildOptions {
        steps: m.run.steps,
        derive: DeriveOptions {
            seed: m.run.seed,
            max_modules: m.run.max_modules,
            max_params: m.run.max_params,
        },
        angle: m.angle,
        step: m.step,
        width: m.width,
        components: ComponentSearch {
            grammar_dir,
            dirs: m.components.clone(),
        },
        mesh: MeshOptions {
            sides: m.facets,
            max_triangles: m.max_triangles,
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
    /// The files the grammar was read from (root and includes), when it
    /// compiled.
    pub sources: Option<Vec<PathBuf>>,
}

/// Compiles and builds `m`, writes `out`; prints diagnostics and the
/// report.
pub(super) fn build_once(
    m: &ModelArgs,
    out: &Path,
    pic: &PictureArgs,
    format: Format,
    color: bool,
    report_as: Report,
) -> Outcome {
    let t0 = Instant::now();
    let comp = match compile(&m.common, color) {
        Ok(c) => c,
        Err(code) => {
            return Outcome {
                code,
                sources: None,
            }
        }
    };
    let sources = Some(
        comp.program
            .sources
            .files()
            .iter()
            .filter_map(|f| match &f.origin {
                Origin::Disk(p) => Some(p.clone()),
                _ => None,
            })
            .collect(),
    );
    let code = build_compiled(m, &comp, (out, pic, format), color, report_as, t0);
    Outcome { code, sources }
}

/// Builds the compiled grammar and writes `out` as `format`; the exit code.
fn build_compiled(
    m: &ModelArgs,
    comp: &crate::pipeline::Compilation,
    (out, pic, format): (&Path, &PictureArgs, Format),
    color: bool,
    report_as: Report,
    t0: Instant,
) -> i32 {
    let parse = t0.elapsed();
    let progress = Progress::new(true);
    let built = match build::build_observed(comp, &options(m), &mut |s| progress.stage(s)) {
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
    if built.scene.triangle_count() == 0 {
        eprintln!(
            "lsys: warning: {} draws nothing (its string of {} modules has no drawing command with a size); the output is empty",
            m.common.file, built.modules
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
    match written {
        Ok(bytes) => {
            if m.stats {
                println!("{}", stats(&built, parse, write_time, out, bytes));
            } else if report_as == Report::Summary {
                println!("{}", summary(&built, out, bytes, t0.elapsed()));
            }
            EX_OK
        }
        Err(WriteError::Export(e)) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        Err(WriteError::Io(e)) => {
            eprintln!("lsys: cannot write {}: {e}", out.display());
            EX_IOERR
        }
    }
}

fn picture(pic: &PictureArgs) -> render::RenderOptions {
    render::RenderOptions {
        view: match pic.view {
            ViewArg::Front => render::View::Front,
            ViewArg::Side => render::View::Side,
            ViewArg::Top => render::View::Top,
            ViewArg::Iso => render::View::Iso,
        },
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

fn ms(d: Duration) -> f64 {
    (d.as_secs_f64() * 1e6).round() / 1e3
}

fn stats(built: &Built, parse: Duration, write: Duration, out: &Path, bytes: u64) -> String {
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
    serde_json::json!({
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
    })
    .to_string()
}
