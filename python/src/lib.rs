//! `pailou._native`, the compiled half of the Python package `pailou`:
//! lsys's public API and driver as Python classes and functions. Input:
//! calls from Python; output: Python objects (strings, NumPy arrays,
//! bytes, dicts) or an `LsysError`. The Python half (`pailou/__init__.py`)
//! re-exports these and adds nothing that builds.
//!
//! * `args.rs`: defines dicts, paths and options from Python values;
//! * `errors.rs`: `LsysError` and its `.diagnostics`;
//! * `grammar.rs`: `Grammar` (compile, derive, steps, build, pickling);
//! * `derived.rs`: `Derived` and the `steps()` iterator;
//! * `scene.rs`: `Scene` (arrays without copying, GLB, files, stats);
//! * `viewer.rs`: a scene's interactive view in a notebook;
//! * `pailou.rs`: `pailou(style=..., graph=...)`;
//! * `batch.rs`: `generate(spec)`, one batch item.

use pyo3::prelude::*;

mod args;
mod batch;
mod derived;
mod errors;
mod grammar;
mod pailou;
mod scene;
mod viewer;

/// Runs `f` on a thread with the compiler's deep stack, as the `lsys`
/// binary does: the parser, resolver and folding recurse as deep as the
/// parser's limits allow, which a Python thread's stack may not hold.
pub fn on_worker<T: Send>(f: impl FnOnce() -> T + Send) -> PyResult<T> {
    std::thread::scope(|s| {
        let worker = std::thread::Builder::new()
            .name("lsys".into())
            .stack_size(lsys::driver::WORKER_STACK)
            .spawn_scoped(s, f)
            .map_err(|e| {
                pyo3::exceptions::PyOSError::new_err(format!("cannot start lsys's thread: {e}"))
            })?;
        worker.join().map_err(|_| {
            pyo3::exceptions::PyRuntimeError::new_err(
                "lsys stopped on a bug; please report it with the grammar",
            )
        })
    })
}

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
