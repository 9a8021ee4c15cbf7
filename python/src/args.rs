//! Arguments as Python passes them -> lsys's values: `defines` dicts as
//! `-D` pairs, a `str` or `pathlib.Path` as a path, and the grammar
//! options both make.

use lsys::GrammarOptions;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `{"TM.NTL": 3}` as `-D` pairs; values as Python prints them.
pub fn define_pairs(defines: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let Some(d) = defines else {
        return Ok(Vec::new());
    };
    d.iter()
        .map(|(k, v)| {
            let value = if v.is_instance_of::<pyo3::types::PyBool>() {
                // `True`/`False` mean 1/0, as in C.
                if v.is_truthy()? { "1" } else { "0" }.to_string()
            } else {
                v.str()?.to_string()
            };
            Ok((k.extract::<String>()?, value))
        })
        .collect()
}

/// The options of `-D` pairs and a seed.
pub fn options(defines: &[(String, String)], seed: Option<u64>) -> GrammarOptions {
    GrammarOptions::default()
        .defines_from(defines)
        .seed_option(seed)
}

/// A path given as `str` or as a `pathlib.Path`.
pub struct PathOrStr(pub String);

impl<'a, 'py> FromPyObject<'a, 'py> for PathOrStr {
    type Error = PyErr;

    fn extract(ob: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(s) = ob.extract::<String>() {
            return Ok(PathOrStr(s));
        }
        let p: std::path::PathBuf = ob.extract()?;
        Ok(PathOrStr(p.to_string_lossy().into_owned()))
    }
}
