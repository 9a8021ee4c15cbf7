//! `pailou._native`, the compiled half of the Python package `pailou`:
//! lsys's public API and driver as Python classes and functions. Input:
//! calls from Python; output: Python objects (strings, NumPy arrays,
//! bytes, dicts) or an `LsysError`. The Python half (`pailou/__init__.py`)
//! re-exports these and adds nothing that builds.
//!
//! * `errors.rs`: `LsysError` and its `.diagnostics`;
//! * `grammar.rs`: `Grammar` (compile, derive, steps, build, pickling);
//! * `derived.rs`: `Derived` and the `steps()` iterator;
//! * `scene.rs`: `Scene` (arrays without copying, GLB, files, stats);
//! * `viewer.rs`: a scene's interactive view in a notebook;
//! * `pailou.rs`: `pailou(style=..., graph=...)`;
//! * `batch.rs`: `generate(spec)`, one batch item.

use pyo3::prelude::*;

mod batch;
mod derived;
mod errors;
mod grammar;
mod pailou;
mod scene;
mod viewer;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LsysError", py.get_type::<errors::LsysError>())?;
    m.add_class::<grammar::Grammar>()?;
    m.add_class::<derived::Derived>()?;
    m.add_class::<derived::StepIter>()?;
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(grammar::_grammar_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(pailou::pailou, m)?)?;
    m.add_function(wrap_pyfunction!(batch::generate, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
