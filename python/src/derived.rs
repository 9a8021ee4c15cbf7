//! Derived strings for Python: `Derived` (a string after some steps, its
//! `str()` as `lsys derive` prints it) and the iterator `Grammar.steps()`
//! returns, which owns the grammar it derives from (a `self_cell`: the
//! derivation borrows the grammar the cell keeps alive). A derivation may
//! hold environments that are not `Send` (a guided scene's shared world),
//! so the iterator stays on the thread that made it and keeps the GIL
//! while it steps; `Grammar.derive` and `build` release it.

use std::sync::Arc;

use pyo3::prelude::*;
use self_cell::self_cell;

use crate::errors::lsys_error;

/// A derived string.
#[pyclass(module = "pailou", frozen)]
pub struct Derived {
    pub text: String,
    pub step: u32,
    pub modules: usize,
}

#[pymethods]
impl Derived {
    /// The step it is the string of (0: the axiom).
    #[getter]
    fn step(&self) -> u32 {
        self.step
    }

    /// How many modules it has.
    fn __len__(&self) -> usize {
        self.modules
    }

    fn __str__(&self) -> &str {
        &self.text
    }

    fn __repr__(&self) -> String {
        const SHOWN: usize = 60;
        let short: String = self.text.chars().take(SHOWN).collect();
        let more = if self.text.chars().count() > SHOWN {
            " ..."
        } else {
            ""
        };
        format!(
            "Derived(step {}, {} modules: {short}{more})",
            self.step, self.modules
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<Derived>() {
            Ok(o) => {
                let o = o.get();
                o.text == self.text && o.step == self.step
            }
            Err(_) => other.extract::<String>().is_ok_and(|s| s == self.text),
        }
    }
}

type Steps<'g> = lsys::Steps<'g>;

self_cell!(
    struct Cell {
        owner: Arc<lsys::Grammar>,
        #[not_covariant]
        dependent: Steps,
    }
);

/// The iterator of [`Grammar.steps`](crate::grammar::Grammar).
#[pyclass(module = "pailou", unsendable)]
pub struct StepIter {
    cell: Cell,
    name: String,
}

impl StepIter {
    pub fn new(grammar: Arc<lsys::Grammar>, name: String, steps: u32) -> StepIter {
        StepIter {
            cell: Cell::new(grammar, |g| g.steps_to(steps)),
            name,
        }
    }
}

#[pymethods]
impl StepIter {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&mut self, py: Python<'_>) -> PyResult<Option<Derived>> {
        match self.cell.with_dependent_mut(|_, steps| steps.next()) {
            None => Ok(None),
            Some(Ok(d)) => {
                let text = d.to_string();
                Ok(Some(Derived {
                    modules: d.len(),
                    step: d.step(),
                    text,
                }))
            }
            Some(Err(e)) => Err(lsys_error(py, &self.name, &e)),
        }
    }
}
