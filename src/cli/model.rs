//! `lsys build` and `lsys render`: a grammar -> a model file (.glb, .gltf,
//! .obj + .mtl) or a picture (.png), written atomically, with `--stats` as
//! JSON on standard output.

use std::io;
use std::path::Path;
use std::time::{Duration, Instant};

use super::args::{
    BuildArgs, DeriveRun, LookArgs, ModelArgs, PailouArgs, PailouTypeArg, PictureArgs, RenderArgs,
    ViewArg,
};
use super::commands::{compile_input, report};
use super::{EX_DATAERR, EX_IOERR, EX_OK, EX_USAGE};
use crate::build::{self, BuildOptions, Built};
use crate::derive::DeriveOptions;
use crate::export::atomic::AtomicFiles;
use crate::export::{gltf, obj, render};
use crate::mesh::{ComponentSearch, MeshOptions};
use crate::resolve::Input;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Format {
    Glb,
    Gltf,
    Obj,
    Png,
}

impl Format {
    fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "glb" => Format::Glb,
            "gltf" => Format::Gltf,
            "obj" => Format::Obj,
            "png" => Format::Png,
            _ => return None,
        })
    }
}

pub fn build_cmd(b: &BuildArgs, color: bool) -> i32 {
    match Format::of(&b.output) {
        Some(f) => model_run(&b.model, &b.output, &b.picture, f, color),
        None => {
            eprintln!(
                "lsys: cannot tell the format of `{}` from its extension; name the output .glb, .gltf, .obj or .png",
                b.output.display()
            );
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
    model_run(&r.model, &r.output, &r.picture, Format::Png, color)
}

fn model_run(m: &ModelArgs, out: &Path, pic: &PictureArgs, format: Format, color: bool) -> i32 {
    let input = Input::from_arg(&m.common.file);
    let job = Job {
        input: &input,
        name: &m.common.file,
        defines: &m.common.define,
        run: &m.run,
        look: &m.look,
        collisions: m.look.collisions,
    };
    run(&job, out, pic, format, color)
}

pub fn pailou_cmd(p: &PailouArgs, color: bool) -> i32 {
    use crate::pailou::{self, graph, PailouType};
    let mut defines = Vec::new();
    let (layout, kind, title, name) = match &p.graph {
        Some(path) => {
            let text = match std::fs::read_to_string(path) {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("lsys: cannot read {}: {e}", path.display());
                    return super::EX_NOINPUT;
                }
            };
            let relations = match &p.relations {
                Some(r) => match std::fs::read_to_string(r) {
                    Ok(t) => t,
                    Err(e) => {
                        eprintln!("lsys: cannot read {}: {e}", r.display());
                        return super::EX_NOINPUT;
                    }
                },
                None => graph::RELATIONS.to_string(),
            };
            match graph::read(&path.display().to_string(), &text, &relations) {
                Ok(g) => {
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
    let Some(format) = Format::of(out) else {
        eprintln!(
            "lsys: cannot tell the format of `{}` from its extension; name the output .glb, .gltf, .obj or .png",
            out.display()
        );
        return EX_USAGE;
    };
    let job = Job {
        input: &input,
        name: &name,
        defines: &defines,
        run: &p.run,
        look: &p.look,
        collisions: true,
    };
    run(&job, out, &p.picture, format, color)
}

/// One build: the grammar and the options that shape it.
struct Job<'a> {
    input: &'a Input,
    /// How messages name the grammar.
    name: &'a str,
    defines: &'a [(String, String)],
    run: &'a DeriveRun,
    look: &'a LookArgs,
    /// Report interpenetrating components.
    collisions: bool,
}

/// The options of a build from the command line.
fn options(m: &Job) -> BuildOptions {
    let grammar_dir = match m.input {
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
        angle: m.look.angle,
        step: m.look.step,
        width: m.look.width,
        components: ComponentSearch {
            grammar_dir,
            dirs: m.look.components.clone(),
            within: Vec::new(),
        },
        mesh: MeshOptions {
            sides: m.look.facets,
            max_triangles: m.look.max_triangles,
        },
    }
}

fn run(m: &Job, out: &Path, pic: &PictureArgs, format: Format, color: bool) -> i32 {
    let t0 = Instant::now();
    let comp = match compile_input(m.input, m.name, m.defines, color) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let parse = t0.elapsed();
    let built = match build::build(&comp, &options(m)) {
        Ok(b) => b,
        Err(e) => {
            report(&e, color);
            return EX_DATAERR;
        }
    };
    for w in &built.warnings {
        report(w, color);
    }
    if m.collisions {
        let found = crate::mesh::collide::collisions(&built.scene);
        for c in found.iter().take(20) {
            eprintln!(
                "lsys: warning: components {} and {} collide ({:.0}% of the smaller one's box is inside the other)",
                c.a,
                c.b,
                c.shared * 100.0
            );
        }
        if found.len() > 20 {
            eprintln!(
                "lsys: warning: ... and {} more collisions",
                found.len() - 20
            );
        }
    }
    if built.scene.triangle_count() == 0 {
        eprintln!(
            "lsys: warning: {} draws nothing (its string of {} modules has no drawing command with a size); the output is empty",
            m.name, built.modules
        );
    }
    let t1 = Instant::now();
    let written = write(&built, out, pic, format);
    let write_time = t1.elapsed();
    match written {
        Ok(bytes) => {
            if m.look.stats {
                println!("{}", stats(&built, parse, write_time, out, bytes));
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

enum WriteError {
    Export(Box<dyn miette::Diagnostic + Send + Sync>),
    Io(io::Error),
}

impl From<io::Error> for WriteError {
    fn from(e: io::Error) -> Self {
        WriteError::Io(e)
    }
}

fn export_err<E: miette::Diagnostic + Send + Sync + 'static>(e: E) -> WriteError {
    WriteError::Export(Box::new(e))
}

/// Writes the output file(s); returns the bytes written.
fn write(built: &Built, out: &Path, pic: &PictureArgs, format: Format) -> Result<u64, WriteError> {
    let scene = &built.scene;
    let mut files = AtomicFiles::new();
    let bytes: u64;
    match format {
        Format::Glb | Format::Gltf => {
            let data = if format == Format::Glb {
                gltf::to_glb(scene)
            } else {
                gltf::to_gltf(scene)
            }
            .map_err(export_err)?;
            bytes = data.len() as u64;
            files.write(out, |w| w.write_all(&data))?;
        }
        Format::Obj => {
            let mtl_path = out.with_extension("mtl");
            let mtl_name = mtl_path
                .file_name()
                .map_or("model.mtl".into(), |n| n.to_string_lossy().into_owned());
            let mut mtl = Vec::new();
            let mut obj = Vec::new();
            obj::write_obj(scene, &mtl_name, &mut obj, &mut mtl)?;
            bytes = (obj.len() + mtl.len()) as u64;
            // The .mtl first: the .obj refers to it.
            files.write(&mtl_path, |w| w.write_all(&mtl))?;
            files.write(out, |w| w.write_all(&obj))?;
        }
        Format::Png => {
            let opts = render::RenderOptions {
                view: match pic.view {
                    ViewArg::Front => render::View::Front,
                    ViewArg::Side => render::View::Side,
                    ViewArg::Top => render::View::Top,
                    ViewArg::Iso => render::View::Iso,
                },
                width: pic.size.0,
                height: pic.size.1,
                ..Default::default()
            };
            let image = render::render(scene, &opts);
            let mut png = Vec::new();
            render::write_png(&image, &mut png).map_err(export_err)?;
            bytes = png.len() as u64;
            files.write(out, |w| w.write_all(&png))?;
        }
    }
    files.commit()?;
    Ok(bytes)
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
