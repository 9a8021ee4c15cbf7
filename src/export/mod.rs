//! Export: a [`Scene`](crate::mesh::Scene) -> files (glTF/GLB, OBJ+MTL,
//! PNG pictures). Every file is written through [`atomic::AtomicFiles`], so
//! a failed build leaves no partial output and keeps existing files.
pub mod atomic;
pub mod gltf;
pub mod obj;
pub mod render;
