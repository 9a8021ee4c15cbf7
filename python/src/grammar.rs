//! `pailou.Grammar`: a grammar compiled at once from text or a path (or
//! `std:NAME`) with `-D`-style defines and a seed. Input: the source and
//! its options; output: derived strings (as `lsys derive` prints them),
//! a step iterator, and built scenes (through the driver, as `lsys build`
//! builds them). A grammar pickles as its source, defines and seed, so a
//! worker process compiles it again.

use std::sync::Arc;

use lsys::driver::{Input, Job};
use lsys::{Diagnostics, Numbers};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::args::{define_pairs, options, PathOrStr};
use crate::derived::{Derived, StepIter};
use crate::errors::lsys_error;
use crate::on_worker;
use crate::scene::Scene;

/// Where a grammar's text comes from.
#[derive(Clone, Debug)]
pub enum Source {
    /// Text given in memory, named `name` in diagnostics.
    Text { name: String, text: String },
    /// A file, or `std:NAME`, read when compiled (again in a worker that
    /// unpickles it: the path must be readable there).
    Path(String),
}

impl Source {
    pub fn name(&self) -> &str {
        match self {
            Source::Text { name, .. } => name,
            Source::Path(p) => p,
        }
    }

    /// The driver's input for a build.
    pub fn input(&self) -> Input {
        match self {
            Source::Text { name, text } => Input::Text {
                name: name.clone(),
                text: text.clone(),
            },
            Source::Path(p) => match p.strip_prefix("std:") {
                Some(n) => Input::Std(n.to_string()),
                None => Input::Path(p.into()),
            },
        }
    }
}

/// A compiled L-system grammar.
#[pyclass(module = "pailou", frozen)]
pub struct Grammar {
    pub source: Source,
    pub defines: Vec<(String, String)>,
    pub seed: Option<u64>,
    pub inner: Arc<lsys::Grammar>,
}

impl Grammar {
    pub fn compile(
        py: Python<'_>,
        source: Source,
        defines: Vec<(String, String)>,
        seed: Option<u64>,
    ) -> PyResult<Grammar> {
        let opts = options(&defines, seed);
        let compiled = py.detach(|| {
            on_worker(|| match &source {
                Source::Text { name, text } => opts.from_str(name, text),
                Source::Path(p) => opts.from_path(p),
            })
        })?;
        match compiled {
            Ok(g) => Ok(Grammar {
                source,
                defines,
                seed,
                inner: Arc::new(g),
            }),
            Err(d) => Err(lsys_error(py, source.name(), &d)),
        }
    }

    fn steps_or_default(&self, n: Option<u32>) -> u32 {
        n.unwrap_or(self.inner.derivation_length())
    }
}

#[pymethods]
impl Grammar {
    /// Compiles `text`, named `name` in diagnostics (a name ending in `.l`
    /// reads it as a cpfg model). Raises `LsysError` on any error.
    #[staticmethod]
    #[pyo3(signature = (name, text, defines=None, seed=None))]
    fn from_str(
        py: Python<'_>,
        name: String,
        text: String,
        defines: Option<&Bound<'_, PyDict>>,
        seed: Option<u64>,
    ) -> PyResult<Grammar> {
        Grammar::compile(
            py,
            Source::Text { name, text },
            define_pairs(defines)?,
            seed,
        )
    }

    /// Compiles a grammar file, or `std:NAME` from the standard library.
    #[staticmethod]
    #[pyo3(signature = (path, defines=None, seed=None))]
    fn from_path(
        py: Python<'_>,
        path: PathOrStr,
        defines: Option<&Bound<'_, PyDict>>,
        seed: Option<u64>,
    ) -> PyResult<Grammar> {
        Grammar::compile(py, Source::Path(path.0), define_pairs(defines)?, seed)
    }

    /// The grammar's name in diagnostics (its path, or the name given).
    #[getter]
    fn name(&self) -> &str {
        self.source.name()
    }

    /// `derivation length:` of the file.
    #[getter]
    fn derivation_length(&self) -> u32 {
        self.inner.derivation_length()
    }

    /// The string after `n` steps (the file's derivation length when
    /// `None`); `str()` of it is what `lsys derive -n N` prints.
    #[pyo3(signature = (n=None))]
    fn derive(&self, py: Python<'_>, n: Option<u32>) -> PyResult<Derived> {
        let steps = self.steps_or_default(n);
        let g = &self.inner;
        let got = py.detach(|| {
            on_worker(|| -> Result<(String, u32, usize), Diagnostics> {
                let mut d = g.derivation(steps)?;
                d.run(&mut |_, _| {})?;
                d.finish()?;
                let mut out = Vec::new();
                // Writing to memory cannot fail.
                let _ = d.write_current(Numbers::Shortest, &mut out);
                let text = String::from_utf8_lossy(&out).into_owned();
                let modules = count_modules(&text);
                Ok((text, d.step_number(), modules))
            })
        })?;
        match got {
            Ok((text, step, modules)) => Ok(Derived {
                text,
                step,
                modules,
            }),
            Err(d) => Err(lsys_error(py, self.source.name(), &d)),
        }
    }

    /// The axiom and the string after each step, up to `n` (the file's
    /// derivation length when `None`), each as `lsys derive --every`
    /// prints its lines.
    #[pyo3(signature = (n=None))]
    fn steps(&self, n: Option<u32>) -> StepIter {
        StepIter::new(
            self.inner.clone(),
            self.source.name().to_string(),
            self.steps_or_default(n),
        )
    }

    /// Derives `n` steps and builds the model, as `lsys build -n N` does.
    #[pyo3(signature = (n=None))]
    fn build(&self, py: Python<'_>, n: Option<u32>) -> PyResult<Scene> {
        let opts = options(&self.defines, self.seed).steps(n);
        let job = Job::new(self.source.input(), self.source.name(), opts);
        Scene::from_job(py, &job, self.source.name())
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let g = slf.get();
        let restore = py
            .import("pailou._native")?
            .getattr("_grammar_from_state")?;
        let (kind, name, text) = match &g.source {
            Source::Text { name, text } => ("text", name.clone(), Some(text.clone())),
            Source::Path(p) => ("path", p.clone(), None),
        };
        let args = (kind, name, text, g.defines.clone(), g.seed);
        PyTuple::new(py, [restore.into_any(), args.into_pyobject(py)?.into_any()])
    }

    fn __repr__(&self) -> String {
        format!(
            "Grammar({:?}, {} rules, derivation length {})",
            self.source.name(),
            self.inner.rule_count(),
            self.inner.derivation_length()
        )
    }
}

/// Unpickles a [`Grammar`]: compiles its source again.
#[pyfunction]
#[pyo3(signature = (kind, name, text, defines, seed))]
pub fn _grammar_from_state(
    py: Python<'_>,
    kind: &str,
    name: String,
    text: Option<String>,
    defines: Vec<(String, String)>,
    seed: Option<u64>,
) -> PyResult<Grammar> {
    let source = match (kind, text) {
        ("text", Some(text)) => Source::Text { name, text },
        _ => Source::Path(name),
    };
    Grammar::compile(py, source, defines, seed)
}

/// Modules in a printed string: lsys prints one space between modules
/// and none inside a module's parameters.
fn count_modules(text: &str) -> usize {
    text.split_ascii_whitespace().count()
}
