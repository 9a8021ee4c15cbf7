//! `pailou.Scene`: a built model for Python. Input: a driver job (the
//! same one `lsys build` runs); output: NumPy arrays that own the Rust
//! buffers (positions and normals N×3 float32, indices M×3 uint32, colours
//! N×3 float32), component placements as 4×4 matrices with their names,
//! the GLB bytes, files in any format, and the `--stats` dictionary.
//!
//! The arrays are made when first asked for: expanding every component
//! instance into world space costs more than the build itself for an
//! instanced model (a Pailou: 1.2 M triangles from 78 placements), and a
//! caller who only writes a GLB never needs them.

use lsys::driver::{self, Event, Job};
use lsys::Diagnostics;
use numpy::ndarray::Array2;
use numpy::{PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyList, PyTuple};

use crate::errors::lsys_error;
use crate::on_worker;

/// A built model.
#[pyclass(module = "pailou", frozen)]
pub struct Scene {
    scene: lsys::Scene,
    name: String,
    stats: String,
    warnings: Vec<String>,
    arrays: PyOnceLock<Arrays>,
    instances: PyOnceLock<Py<PyList>>,
}

/// The scene's arrays, made together on first use.
struct Arrays {
    positions: Py<PyArray2<f32>>,
    normals: Py<PyArray2<f32>>,
    indices: Py<PyArray2<u32>>,
    colors: Py<PyArray2<f32>>,
}

/// `v` (a flat list of `k`-tuples) as an `n × k` array that owns `v`.
fn owned<'py, T: numpy::Element>(
    py: Python<'py>,
    v: Vec<T>,
    k: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let n = v.len() / k;
    let a = Array2::from_shape_vec((n, k), v)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    let a = PyArray2::from_owned_array(py, a);
    // Read-only: every caller shares the scene's arrays.
    a.readwrite().make_nonwriteable();
    Ok(a)
}

impl Scene {
    /// Runs `job` (named `name` in errors) and wraps what it built.
    pub fn from_job(py: Python<'_>, job: &Job, name: &str) -> PyResult<Scene> {
        let ran = py.detach(|| {
            on_worker(|| {
                let mut warnings = Vec::new();
                let done = driver::run(job, &mut |e| match e {
                    Event::Warning(w) => {
                        warnings.push(lsys::Message::from_diagnostic(w).rendered().to_string())
                    }
                    Event::Notice(n) => warnings.push(n.to_string()),
                    Event::Stage(_) | Event::Writing(_) => {}
                });
                done.map(|done| (done.stats().to_string(), done.scene, warnings))
                    .map_err(|f| f.diagnostics())
            })
        })?;
        let (stats, scene, warnings) = match ran {
            Ok(x) => x,
            Err(d) => return Err(lsys_error(py, name, &d)),
        };
        Ok(Scene {
            scene,
            name: name.to_string(),
            stats,
            warnings,
            arrays: PyOnceLock::new(),
            instances: PyOnceLock::new(),
        })
    }

    fn arrays(&self, py: Python<'_>) -> PyResult<&Arrays> {
        self.arrays.get_or_try_init(py, || {
            let scene = &self.scene;
            let a = py.detach(|| scene.arrays());
            Ok(Arrays {
                positions: owned(py, a.positions, 3)?.unbind(),
                normals: owned(py, a.normals, 3)?.unbind(),
                indices: owned(py, a.indices, 3)?.unbind(),
                colors: owned(py, a.colors, 3)?.unbind(),
            })
        })
    }

    fn fail(&self, py: Python<'_>, d: &Diagnostics) -> PyErr {
        lsys_error(py, &self.name, d)
    }
}

fn shared<'py, T: numpy::Element>(py: Python<'py>, a: &Py<PyArray2<T>>) -> Bound<'py, PyArray2<T>> {
    a.bind(py).clone()
}

#[pymethods]
impl Scene {
    /// Vertex positions, N×3 float32, world space (instances expanded).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        Ok(shared(py, &self.arrays(py)?.positions))
    }

    /// Unit vertex normals, N×3 float32.
    #[getter]
    fn normals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        Ok(shared(py, &self.arrays(py)?.normals))
    }

    /// Triangles, M×3 uint32 indices into `positions`.
    #[getter]
    fn indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        Ok(shared(py, &self.arrays(py)?.indices))
    }

    /// Linear RGB per vertex in 0..1, N×3 float32.
    #[getter]
    fn colors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        Ok(shared(py, &self.arrays(py)?.colors))
    }

    /// Component placements: `(name, matrix)` with a 4×4 float32 matrix
    /// (`matrix @ [x, y, z, 1]` places a point of the component's model).
    #[getter]
    fn instances<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = self
            .instances
            .get_or_try_init(py, || -> PyResult<Py<PyList>> {
                let list = PyList::empty(py);
                for p in self.scene.placements() {
                    // glam's columns -> a NumPy matrix indexed [row, column].
                    let m = p.matrix;
                    let rows: Vec<f32> = (0..16).map(|i| m[(i % 4) * 4 + i / 4]).collect();
                    let name = p.component.into_pyobject(py)?.into_any();
                    list.append(PyTuple::new(py, [name, owned(py, rows, 4)?.into_any()])?)?;
                }
                Ok(list.unbind())
            })?;
        Ok(list.bind(py).clone())
    }

    /// The `lsys build --stats` figures.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?.call_method1("loads", (&self.stats,))
    }

    /// Warnings of the compiler and the build, rendered.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Triangles in the model.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.scene.triangle_count()
    }

    /// `(min, max)` corners of everything drawn, or `None`.
    #[getter]
    fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        self.scene.bounds()
    }

    /// The bytes `lsys build -o x.glb` writes.
    fn to_glb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let scene = &self.scene;
        match py.detach(|| scene.to_glb()) {
            Ok(b) => Ok(PyBytes::new(py, &b)),
            Err(d) => Err(self.fail(py, &d)),
        }
    }

    /// Writes the model in the format of `path`'s extension (`.glb`,
    /// `.gltf`, `.obj` with its `.mtl`, `.png`), atomically; the bytes
    /// written.
    fn write(&self, py: Python<'_>, path: crate::args::PathOrStr) -> PyResult<u64> {
        let scene = &self.scene;
        match py.detach(|| scene.write_file(&path.0)) {
            Ok(n) => Ok(n),
            Err(d) => Err(self.fail(py, &d)),
        }
    }

    /// A `trimesh.Trimesh` (imports trimesh only now).
    fn to_trimesh<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let trimesh = py.import("trimesh")?;
        let np = py.import("numpy")?;
        let colors = self.colors(py)?.call_method1("__mul__", (255.0,))?;
        let colors = np
            .call_method1("round", (colors,))?
            .call_method1("astype", ("uint8",))?;
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("vertices", self.positions(py)?)?;
        kwargs.set_item("faces", self.indices(py)?)?;
        kwargs.set_item("vertex_normals", self.normals(py)?)?;
        kwargs.set_item("vertex_colors", colors)?;
        kwargs.set_item("process", false)?;
        trimesh.getattr("Trimesh")?.call((), Some(&kwargs))
    }

    /// A `pyvista.PolyData` with the colours as point data `"colors"`
    /// (imports pyvista only now).
    fn to_pyvista<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pv = py.import("pyvista")?;
        let np = py.import("numpy")?;
        let tris = self.indices(py)?;
        let n = tris.len()?;
        let threes = np.call_method1("full", ((n, 1), 3, "int64"))?;
        let faces = np
            .call_method1(
                "hstack",
                ((threes, tris.call_method1("astype", ("int64",))?),),
            )?
            .call_method0("ravel")?;
        let mesh = pv
            .getattr("PolyData")?
            .call1((self.positions(py)?, faces))?;
        mesh.getattr("point_data")?
            .set_item("colors", self.colors(py)?)?;
        mesh.getattr("point_data")?
            .set_item("Normals", self.normals(py)?)?;
        Ok(mesh)
    }

    /// An interactive 3D view in a notebook, from the package's own files.
    fn _repr_html_(&self, py: Python<'_>) -> PyResult<String> {
        crate::viewer::html(
            py,
            &self.positions(py)?,
            &self.normals(py)?,
            &self.indices(py)?,
            &self.colors(py)?,
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}: {} modules, {} triangles, {} instances)",
            self.name,
            self.scene.module_count(),
            self.scene.triangle_count(),
            self.scene.instance_count()
        )
    }
}
