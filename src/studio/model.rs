//! One model for the page: a compiled grammar (with its defines) -> the
//! GLB bytes the 3D view loads, the structural check's problems with the
//! parts they name, and diagnostics as JSON (file:line:col, code, text).

use std::path::PathBuf;

use miette::Diagnostic;
use serde_json::{json, Value};

use crate::api::{Grammar, Scene};
use crate::driver::{self, Check, Job, Output, Problem};
use crate::{Diagnostics, Message};

/// A model built for the page.
pub struct Model {
    pub glb: Vec<u8>,
    pub triangles: usize,
    /// Component instances (the GLB's nodes named `<symbol>#<n>`).
    pub parts: usize,
    /// Structural problems: `{"message", "parts": [names]}`.
    pub problems: Vec<Value>,
    pub scene: Scene,
}

/// The job of building `input` (named `name`) with `defines` for the
/// page: a GLB in memory, checked against the library's relation matrix
/// when `check`.
pub fn job(
    input: driver::Input,
    name: &str,
    defines: &[(String, String)],
    steps: Option<u32>,
    check: bool,
    budget: usize,
) -> Job {
    let o = Grammar::options().steps(steps).defines_from(defines);
    let check = if check { Check::Library } else { Check::None };
    for_page(Job::new(input, name, o).check(check), budget)
}

/// Triangles a studio model may have by default (instances counted in
/// full; `lsys studio --max-triangles`): more is refused before it is
/// meshed, with the mesh stage's diagnostic. Software WebGL draws 365 k
/// triangles in about a second; a 6-5-15 Pailou has 2.1 M. An 88 M
/// triangle grammar used to be built (5.3 GB) and served as a 2 GB GLB.
pub const DEFAULT_MAX_TRIANGLES: usize = 8_000_000;

/// The GLB the page may be sent, at most: a model within the triangle
/// budget can still be larger (tubes and polygons are not instanced).
pub const MAX_GLB_BYTES: usize = 256 << 20;

/// The refusal of a model whose GLB is over [`MAX_GLB_BYTES`].
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("the model's GLB is {mib} MiB, more than the {limit} MiB the studio sends to a page")]
#[diagnostic(
    code(lsys::studio::too_large),
    help("derive fewer steps or draw less; `lsys build` writes a model of any size to a file")
)]
pub struct TooLarge {
    mib: usize,
    limit: usize,
}

/// Whether a GLB of `bytes` may be sent to a page ([`MAX_GLB_BYTES`]).
pub fn within_page_limit(bytes: usize) -> Result<(), TooLarge> {
    if bytes > MAX_GLB_BYTES {
        return Err(TooLarge {
            mib: bytes >> 20,
            limit: MAX_GLB_BYTES >> 20,
        });
    }
    Ok(())
}

/// `job` writing the GLB the page's 3D view loads, in memory, with at
/// most `budget` triangles.
pub fn for_page(mut job: Job, budget: usize) -> Job {
    let options = job.options.clone();
    let limit = options.build.mesh.max_triangles.min(budget);
    job.options = options.max_triangles(limit);
    job.output(Output::Bytes {
        format: driver::Format::Glb,
        picture: Default::default(),
    })
}

/// Runs `job` (warnings and progress are the page's to show, from the
/// result); the model and its grammar.
pub fn build(job: &Job) -> Result<(Model, Grammar), Diagnostics> {
    build_reading(job).0
}

/// [`build`], and the files the grammar was read from (root, includes,
/// view and function files; as far as it was read when it failed, none
/// when it could not be read), for the watcher.
pub fn build_reading(job: &Job) -> (Result<(Model, Grammar), Diagnostics>, Vec<PathBuf>) {
    match driver::run(job, &mut |_| {}) {
        Ok(mut done) => {
            let sources = std::mem::take(&mut done.sources);
            if let Err(e) = within_page_limit(done.bytes.as_ref().map_or(0, Vec::len)) {
                return (Err(Diagnostics::new(vec![miette::Report::new(e)])), sources);
            }
            (Ok(model_of(done)), sources)
        }
        Err(mut f) => {
            let sources = std::mem::take(&mut f.sources);
            (Err(f.diagnostics()), sources)
        }
    }
}

/// The page's model of a finished job, and its grammar.
fn model_of(done: driver::Done) -> (Model, Grammar) {
    let problems = done
        .problems
        .iter()
        .map(|p| json!({"message": p.to_string(), "parts": parts_of(p)}))
        .collect();
    let model = Model {
        glb: done.bytes.unwrap_or_default(),
        triangles: done.scene.triangle_count(),
        parts: done.scene.instance_count(),
        problems,
        scene: done.scene,
    };
    (model, done.grammar)
}

fn parts_of(p: &Problem) -> Vec<String> {
    use Problem::*;
    match p {
        Unsupported { part, .. } => vec![part.clone()],
        OneSided { part, .. } => vec![part.clone()],
        Interpenetrate { a, b, .. } | RoofsMeet { a, b, .. } => vec![a.clone(), b.clone()],
        PillarOnRoof { part, roof, .. } => vec![part.clone(), roof.clone()],
        RoofOverNothing { part, .. } => vec![part.clone()],
    }
}

/// Every diagnostic as `{"severity", "file", "line", "col", "code",
/// "message", "rendered"}` (lines and columns from 1; the rendering is
/// the CLI's, without colour).
pub fn diagnostics_json(d: &Diagnostics) -> Vec<Value> {
    d.iter().map(|d| one_json(d)).collect()
}

/// One diagnostic as [`diagnostics_json`] gives it (no place: an empty
/// file and line and column 0).
pub fn one_json(d: &dyn Diagnostic) -> Value {
    let m = Message::from_diagnostic(d);
    json!({
        "severity": m.severity.as_str(),
        "file": m.file.as_deref().unwrap_or_default(),
        "line": m.line.unwrap_or(0),
        "col": m.column.unwrap_or(0),
        "code": m.code.as_deref().unwrap_or_default(),
        "message": m.message,
        "rendered": m.rendered(),
    })
}
