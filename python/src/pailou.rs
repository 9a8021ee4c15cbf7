//! `pailou.pailou(style=..., type=..., graph=...)`: a Pailou gateway's
//! scene from a style (`NP-NE-NR`) or a component graph (`.toml`), built
//! by the driver's Pailou job as `lsys pailou` builds it.

use lsys::driver::{Pailou, PailouType};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{define_pairs, options, PathOrStr};
use crate::errors::LsysError;
use crate::scene::Scene;

/// A Pailou's scene: `style="4-3-7"` with `type="ridge"` or `"pillar"`,
/// or `graph="file.toml"`; `defines` and `seed` as for a grammar.
#[pyfunction]
#[pyo3(signature = (style=None, r#type="ridge", graph=None, defines=None, seed=None))]
pub fn pailou(
    py: Python<'_>,
    style: Option<String>,
    r#type: &str,
    graph: Option<PathOrStr>,
    defines: Option<&Bound<'_, PyDict>>,
    seed: Option<u64>,
) -> PyResult<Scene> {
    let kind = match r#type {
        "ridge" => PailouType::Ridge,
        "pillar" => PailouType::Pillar,
        other => {
            return Err(PyValueError::new_err(format!(
                "type={other:?}: a Pailou is of type \"ridge\" or \"pillar\""
            )))
        }
    };
    let p = match (style, graph) {
        (Some(s), None) => Pailou::style(&s, kind),
        (None, Some(g)) => Pailou::graph_file(std::path::Path::new(&g.0), None),
        _ => {
            return Err(PyValueError::new_err(
                "give either style=\"NP-NE-NR\" (e.g. \"4-3-7\") or graph=\"file.toml\"",
            ))
        }
    };
    let p = p.map_err(|e| LsysError::new_err(e.to_string()))?;
    let job = p.job(options(&define_pairs(defines)?, seed));
    let name = job.name.clone();
    Scene::from_job(py, &job, &name)
}
