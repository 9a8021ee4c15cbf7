//! A built model as the library hands it out: meshes and component
//! instances, written to GLB, OBJ (+ MTL) or a PNG picture, atomically.

use std::path::Path;

use miette::Diagnostic;
use thiserror::Error;

use crate::build::Built;
use crate::diag::Diagnostics;
use crate::export::output::{scene_bytes, write_scene, Format, WriteError};
use crate::export::render::{RenderOptions, View};

/// A built model ([`Grammar::build`](super::Grammar::build)).
///
/// ```no_run
/// let scene = lsys::Grammar::from_path("std:pailou")?.build(1)?;
/// scene.write_glb("pailou.glb")?;
/// # Ok::<(), lsys::Diagnostics>(())
/// ```
pub struct Scene {
    pub(crate) built: Built,
}

/// A short form: the counts, not the meshes.
impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scene")
            .field("modules", &self.module_count())
            .field("triangles", &self.triangle_count())
            .field("instances", &self.instance_count())
            .finish()
    }
}

/// An output file could not be written.
#[derive(Debug, Error, Diagnostic)]
#[error("cannot write {path}: {cause}")]
#[diagnostic(
    code(lsys::export::write),
    help("check that the folder exists and is writable; nothing was written")
)]
pub struct WriteFailed {
    pub path: String,
    pub cause: String,
}

/// An output path whose extension names no format.
#[derive(Debug, Error, Diagnostic)]
#[error("cannot tell the format of `{path}` from its extension")]
#[diagnostic(
    code(lsys::export::format),
    help("name the output .glb, .gltf, .obj or .png")
)]
pub struct UnknownFormat {
    pub path: String,
}

impl Scene {
    /// Triangles in the model, instances counted in full.
    pub fn triangle_count(&self) -> usize {
        self.built.scene.triangle_count()
    }

    /// Modules of the string the turtle interpreted.
    pub fn module_count(&self) -> usize {
        self.built.modules
    }

    /// Component placements (instances).
    pub fn instance_count(&self) -> usize {
        self.built.scene.instances.len()
    }

    /// The box around everything drawn, `(min, max)` corners; `None`
    /// when nothing is.
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        self.built
            .scene
            .bounds()
            .map(|(lo, hi)| (lo.to_array(), hi.to_array()))
    }

    /// What the shape grammars' constraint rules did, one sentence each
    /// in the order they applied (`@Hole`'s openings, `@Snap`'s moves;
    /// docs/shapes.md); empty for other models.
    pub fn constraints(&self) -> &[String] {
        &self.built.drawing.constraints
    }

    /// The internal meshes, materials and instances, for the crate's own
    /// tests (`lsys::internals`); no API.
    #[doc(hidden)]
    pub fn mesh(&self) -> &crate::mesh::Scene {
        &self.built.scene
    }

    /// The model as a binary glTF file's bytes (what
    /// [`write_glb`](Self::write_glb) writes).
    pub fn to_glb(&self) -> Result<Vec<u8>, Diagnostics> {
        self.to_bytes(Format::Glb, &RenderOptions::default(), "model.mtl")
    }

    /// The model as an OBJ file's text whose `mtllib` names `mtl_name`
    /// (the materials themselves are [`write_obj`](Self::write_obj)'s).
    pub fn to_obj(&self, mtl_name: &str) -> Vec<u8> {
        self.to_bytes(Format::Obj, &RenderOptions::default(), mtl_name)
            .unwrap_or_default()
    }

    /// An isometric picture `width` × `height` pixels, as PNG bytes.
    pub fn to_png(&self, width: u32, height: u32) -> Result<Vec<u8>, Diagnostics> {
        self.to_bytes(Format::Png, &iso(width, height)?, "model.mtl")
    }

    fn to_bytes(
        &self,
        format: Format,
        pic: &RenderOptions,
        mtl_name: &str,
    ) -> Result<Vec<u8>, Diagnostics> {
        scene_bytes(&self.built.scene, format, pic, mtl_name).map_err(Diagnostics::boxed)
    }

    /// Writes a binary glTF file; returns its size in bytes.
    pub fn write_glb(&self, path: impl AsRef<Path>) -> Result<u64, Diagnostics> {
        self.write(path.as_ref(), Format::Glb, &RenderOptions::default())
    }

    /// Writes an OBJ file and its MTL beside it; returns the bytes written.
    pub fn write_obj(&self, path: impl AsRef<Path>) -> Result<u64, Diagnostics> {
        self.write(path.as_ref(), Format::Obj, &RenderOptions::default())
    }

    /// Renders an isometric picture `width` × `height` pixels to a PNG.
    pub fn write_png(
        &self,
        path: impl AsRef<Path>,
        width: u32,
        height: u32,
    ) -> Result<u64, Diagnostics> {
        self.write(path.as_ref(), Format::Png, &iso(width, height)?)
    }

    /// Writes the model in the format its extension names (`.glb`,
    /// `.gltf`, `.obj` with its MTL, `.png` at the default size), as
    /// `lsys build -o PATH` does; returns the bytes written.
    pub fn write_file(&self, path: impl AsRef<Path>) -> Result<u64, Diagnostics> {
        let path = path.as_ref();
        let format = Format::of(path).ok_or_else(|| {
            Diagnostics::one(UnknownFormat {
                path: path.display().to_string(),
            })
        })?;
        self.write(path, format, &RenderOptions::default())
    }

    fn write(&self, path: &Path, format: Format, pic: &RenderOptions) -> Result<u64, Diagnostics> {
        write_scene(&self.built.scene, path, format, pic).map_err(|e| match e {
            WriteError::Export(d) => Diagnostics::boxed(d),
            WriteError::Io(e) => Diagnostics::one(WriteFailed {
                path: path.display().to_string(),
                cause: e.to_string(),
            }),
        })
    }
}

/// An isometric picture's settings at `width` × `height` pixels, checked.
fn iso(width: u32, height: u32) -> Result<RenderOptions, Diagnostics> {
    let pic = RenderOptions {
        view: View::Iso,
        width,
        height,
        ..RenderOptions::default()
    };
    pic.validate().map_err(Diagnostics::one)?;
    Ok(pic)
}
