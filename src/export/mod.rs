//! Export: a [`Scene`](crate::mesh::Scene) -> files (glTF/GLB, OBJ+MTL,
//! PNG pictures). Every file is written through [`atomic::AtomicFiles`], so
//! a failed build leaves no partial output and keeps existing files;
//! [`output::write_scene`] picks the format from the file's extension.
pub mod atomic;
pub mod gltf;
pub mod obj;
pub mod output;
pub mod render;
mod write_behind;
