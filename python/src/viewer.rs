//! A scene's interactive 3D view in a notebook (`Scene._repr_html_`): the
//! arrays as base64 and the package's own WebGL viewer (`pailou/viewer.js`,
//! compiled in), so it works offline and needs no other package.

use numpy::PyArray2;
use pyo3::prelude::*;

const VIEWER: &str = include_str!("../pailou/viewer.js");

/// An id for each view's canvas, unique within a notebook.
static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

fn b64<T: numpy::Element>(py: Python<'_>, a: &Bound<'_, PyArray2<T>>) -> PyResult<String> {
    let bytes = a.call_method0("tobytes")?;
    py.import("base64")?
        .call_method1("b64encode", (bytes,))?
        .call_method0("decode")?
        .extract()
}

pub fn html(
    py: Python<'_>,
    positions: &Bound<'_, PyArray2<f32>>,
    normals: &Bound<'_, PyArray2<f32>>,
    indices: &Bound<'_, PyArray2<u32>>,
    colors: &Bound<'_, PyArray2<f32>>,
) -> PyResult<String> {
    let id = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let data = format!(
        r#"{{"positions":"{}","normals":"{}","indices":"{}","colors":"{}"}}"#,
        b64(py, positions)?,
        b64(py, normals)?,
        b64(py, indices)?,
        b64(py, colors)?
    );
    Ok(format!(
        r#"<div class="pailou-view"><canvas id="pailou-view-{id}" width="640" height="420" style="border:1px solid #ccc;cursor:grab" title="drag to turn, wheel to zoom"></canvas>
<script>{VIEWER}
pailouView(document.getElementById("pailou-view-{id}"), {data});</script></div>"#
    ))
}
