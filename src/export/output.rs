//! One output file from a scene: a path whose extension names the format
//! ([`Format`]) -> the model (.glb, .gltf, .obj + .mtl) or a picture (.png)
//! written atomically, and the number of bytes written. `lsys build`,
//! `lsys render`, `lsys watch` and the REPL's `:export` / `:render` all
//! write through [`write_scene`].

use std::io;
use std::path::Path;

use super::atomic::AtomicFiles;
use super::{gltf, obj, render};
use crate::mesh::Scene;

/// The output formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Glb,
    Gltf,
    Obj,
    Png,
}

impl Format {
    /// The format `path`'s extension names (case-insensitive), if any.
    pub fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "glb" => Format::Glb,
            "gltf" => Format::Gltf,
            "obj" => Format::Obj,
            "png" => Format::Png,
            _ => return None,
        })
    }
}

/// Why an output was not written.
#[derive(Debug)]
pub enum WriteError {
    /// The exporter refused the scene (too large for the format, ...).
    Export(Box<dyn miette::Diagnostic + Send + Sync>),
    Io(io::Error),
}

impl From<io::Error> for WriteError {
    fn from(e: io::Error) -> Self {
        WriteError::Io(e)
    }
}

fn export_err<E: miette::Diagnostic + Send + Sync + 'static>(e: E) -> WriteError {
    WriteError::Export(Box::new(e))
}

/// Writes `scene` to `out` in `format` (a picture with `picture`'s camera
/// and size); all files appear at once or not at all. Returns the bytes
/// written.
pub fn write_scene(
    scene: &Scene,
    out: &Path,
    format: Format,
    picture: &render::RenderOptions,
) -> Result<u64, WriteError> {
    let mut files = AtomicFiles::new();
    let bytes: u64;
    match format {
        Format::Glb => {
            // Written straight into the file: no copy of the whole model.
            let mut written = 0;
            files.write(out, |w| -> Result<(), WriteError> {
                written = gltf::write_glb(scene, w).map_err(|e| match e {
                    gltf::ExportError::Io(e) => WriteError::Io(e),
                    e => export_err(e),
                })?;
                Ok(())
            })?;
            bytes = written;
        }
        Format::Gltf => {
            let data = gltf::to_gltf(scene).map_err(export_err)?;
            bytes = data.len() as u64;
            files.write(out, |w| w.write_all(&data))?;
        }
        Format::Obj => {
            let mtl_path = out.with_extension("mtl");
            let mtl_name = mtl_path
                .file_name()
                .map_or("model.mtl".into(), |n| n.to_string_lossy().into_owned());
            // The .mtl is small and goes first: the .obj refers to it. The
            // .obj is written straight into its file (no copy of the model).
            let mut mtl = Vec::new();
            obj::write_mtl_file(scene, &mut mtl)?;
            files.write(&mtl_path, |w| w.write_all(&mtl))?;
            let mut written = 0;
            files.write(out, |w| -> Result<(), WriteError> {
                let mut counted = Counted { inner: w, bytes: 0 };
                obj::write_obj_only(scene, &mtl_name, &mut counted)?;
                written = counted.bytes;
                Ok(())
            })?;
            bytes = written + mtl.len() as u64;
        }
        Format::Png => {
            let image = render::render(scene, picture);
            let mut png = Vec::new();
            render::write_png(&image, &mut png).map_err(export_err)?;
            bytes = png.len() as u64;
            files.write(out, |w| w.write_all(&png))?;
        }
    }
    files.commit()?;
    Ok(bytes)
}

/// `scene` in `format`, in memory: a GLB, a glTF with its buffer
/// embedded, an OBJ whose `mtllib` names `mtl_name` (its materials are
/// not included), or a PNG picture.
pub fn scene_bytes(
    scene: &Scene,
    format: Format,
    picture: &render::RenderOptions,
    mtl_name: &str,
) -> Result<Vec<u8>, Box<dyn miette::Diagnostic + Send + Sync>> {
    Ok(match format {
        Format::Glb => gltf::to_glb(scene)?,
        Format::Gltf => gltf::to_gltf(scene)?,
        Format::Obj => {
            let mut b = Vec::new();
            // Writing to memory fails only when memory does.
            obj::write_obj_only(scene, mtl_name, &mut b).expect("a Vec takes every byte");
            b
        }
        Format::Png => {
            let image = render::render(scene, picture);
            let mut png = Vec::new();
            render::write_png(&image, &mut png)?;
            png
        }
    })
}

/// Counts the bytes that pass through to `inner`.
struct Counted<'w> {
    inner: &'w mut dyn io::Write,
    bytes: u64,
}

impl io::Write for Counted<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.bytes += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}
