//! `pailou.generate(spec, out_dir=".")`: one batch item, the function a
//! Ray, Dask or multiprocessing map calls. Input: a dict with the keys of
//! one `lsys batch` manifest line; output: its `index.jsonl` entry as a
//! dict, after writing `out_dir/<id>.<format>` with the same bytes `lsys
//! batch` writes for it (the same driver function does both).

use std::path::PathBuf;

use lsys::driver::batch;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::args::PathOrStr;

/// Builds the item `spec` into `out_dir` (created if missing); relative
/// grammar paths are read from `base_dir` (default: the current folder).
/// A build that fails is not raised: its entry has `status: "error"` and
/// the diagnostics, as in `lsys batch`'s index. A `spec` that is not an
/// item raises `ValueError`.
#[pyfunction]
#[pyo3(signature = (spec, out_dir=None, base_dir=None))]
pub fn generate<'py>(
    py: Python<'py>,
    spec: &Bound<'py, PyAny>,
    out_dir: Option<PathOrStr>,
    base_dir: Option<PathOrStr>,
) -> PyResult<Bound<'py, PyAny>> {
    let json = py.import("json")?;
    let text: String = json.call_method1("dumps", (spec,))?.extract()?;
    let value: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let base = base_dir.map_or_else(|| PathBuf::from("."), |p| PathBuf::from(p.0));
    let item = batch::item_from_json(&value, &base).map_err(|e| {
        let m = lsys::Message::from_diagnostic(&e);
        let help = m.help.map(|h| format!("; {h}")).unwrap_or_default();
        PyValueError::new_err(format!("not a batch item: {}{help}", m.message))
    })?;
    let out = out_dir.map_or_else(|| PathBuf::from("."), |p| PathBuf::from(p.0));
    std::fs::create_dir_all(&out).map_err(|e| {
        pyo3::exceptions::PyOSError::new_err(format!("cannot create {}: {e}", out.display()))
    })?;
    let line = py.detach(|| batch::generate(&item, &out).to_line());
    json.call_method1("loads", (line,))
}
