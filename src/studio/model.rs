//! One model for the page: a compiled grammar (with its defines) -> the
//! GLB bytes the 3D view loads, the structural check's problems with the
//! parts they name, and diagnostics as JSON (file:line:col, code, text).

use miette::Diagnostic;
use serde_json::{json, Value};

use crate::api::{Grammar, GrammarOptions, Scene};
use crate::diag::Diagnostics;
use crate::mesh::structure;

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

/// Compiles `text` (named `name`) or, with `text = None`, the file at
/// `name`, with `defines`.
pub fn compile(
    name: &str,
    text: Option<&str>,
    defines: &[(String, String)],
) -> Result<Grammar, Diagnostics> {
    let mut o: GrammarOptions = Grammar::options();
    for (k, v) in defines {
        o = o.define(k, v);
    }
    match text {
        Some(t) => o.from_str(name, t),
        None => o.from_path(name),
    }
}

/// The library's symbols and relation matrix, read once per process
/// (every Pailou build and every palette reads them).
pub fn rules() -> &'static structure::Rules {
    static RULES: std::sync::OnceLock<structure::Rules> = std::sync::OnceLock::new();
    RULES.get_or_init(|| {
        structure::Rules::pailou(crate::pailou::graph::RELATIONS)
            .expect("the library's relation matrix reads")
    })
}

/// Builds `g` at `steps` and runs the structural check when `check`.
pub fn build(g: &Grammar, steps: u32, check: bool) -> Result<Model, Diagnostics> {
    let scene = g.build(steps)?;
    let glb = crate::export::gltf::to_glb(scene.mesh()).map_err(Diagnostics::one)?;
    let problems = if check {
        structure::check(scene.mesh(), rules())
            .iter()
            .map(|p| json!({"message": p.to_string(), "parts": parts_of(p)}))
            .collect()
    } else {
        Vec::new()
    };
    Ok(Model {
        glb,
        triangles: scene.triangle_count(),
        parts: scene.instance_count(),
        problems,
        scene,
    })
}

fn parts_of(p: &structure::Problem) -> Vec<String> {
    use structure::Problem::*;
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

/// One diagnostic as [`diagnostics_json`] gives it.
pub fn one_json(d: &dyn Diagnostic) -> Value {
    let code = d.code().map(|c| c.to_string()).unwrap_or_default();
    let severity = match d.severity() {
        Some(miette::Severity::Warning) => "warning",
        Some(miette::Severity::Advice) => "advice",
        _ => "error",
    };
    let (mut file, mut line, mut col) = (String::new(), 0, 0);
    let label = d.labels().and_then(|mut l| l.next());
    if let (Some(src), Some(l)) = (d.source_code(), label) {
        if let Ok(c) = src.read_span(l.inner(), 0, 0) {
            file = c.name().unwrap_or_default().to_string();
            line = c.line() + 1;
            col = c.column() + 1;
        }
    }
    json!({
        "severity": severity,
        "file": file,
        "line": line,
        "col": col,
        "code": code,
        "message": d.to_string(),
        "rendered": crate::diag::render_plain(d),
    })
}
