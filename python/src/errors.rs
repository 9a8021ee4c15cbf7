//! lsys's diagnostics -> a Python `LsysError`: its `str()` is what `lsys
//! check` prints (each diagnostic rendered without colour, then a count),
//! its `.diagnostics` a list of dicts (`code`, `severity`, `file`, `line`,
//! `column`, `message`, `help`).

use lsys::{Diagnostics, Message};
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

pyo3::create_exception!(
    pailou,
    LsysError,
    PyException,
    "A grammar, graph or scene that lsys refuses; `.diagnostics` lists why."
);

/// One diagnostic as a dict.
pub fn message_dict<'py>(py: Python<'py>, m: &Message) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("code", m.code.as_deref())?;
    d.set_item("severity", m.severity.as_str())?;
    d.set_item("file", m.file.as_deref())?;
    d.set_item("line", m.line)?;
    d.set_item("column", m.column)?;
    d.set_item("message", &m.message)?;
    d.set_item("help", m.help.as_deref())?;
    Ok(d)
}

/// `diagnostics` of the grammar (or graph, or scene) `name` as an
/// `LsysError`.
pub fn lsys_error(py: Python<'_>, name: &str, diagnostics: &Diagnostics) -> PyErr {
    let mut text = diagnostics.render(false);
    let errors = diagnostics.error_count();
    if errors > 0 {
        text.push_str(&format!(
            "{name}: {errors} error{}\n",
            if errors == 1 { "" } else { "s" }
        ));
    }
    let err = LsysError::new_err(text.trim_end().to_string());
    let list = diagnostics
        .messages()
        .map(|m| message_dict(py, &m))
        .collect::<PyResult<Vec<_>>>()
        .and_then(|v| PyList::new(py, v));
    match list {
        Ok(list) => {
            if let Err(e) = err.value(py).setattr("diagnostics", list) {
                return e;
            }
            err
        }
        Err(e) => e,
    }
}
