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
) -> Job {
    let o = Grammar::options().steps(steps).defines_from(defines);
    for_page(Job::new(input, name, o).check(if check { Check::Library } else { Check::None }))
}

/// `job` writing the GLB the page's 3D view loads, in memory.
pub fn for_page(job: Job) -> Job {
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
        Interpenetrate { a, b, .. } => vec![a.clone(), b.clone()],
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
