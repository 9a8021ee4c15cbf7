//! Mesh: a turtle [`Drawing`](crate::turtle::Drawing) in, a [`Scene`] out.
//! Tubes for strokes (sharing rings where chains meet, or instanced
//! internodes), triangles for polygons, spheres and discs, and components
//! (OBJ models, roofs, cpfg surfaces, grammars) loaded once and placed by
//! transform; plus the structural check of a Scene's placed parts.
pub mod assemble;
pub mod component;
pub mod components;
pub mod distortion;
pub mod error;
pub mod internodes;
pub mod obj_options;
pub mod palette;
mod ring_slots;
pub mod roof;
pub mod scene;
pub mod shapes;
pub mod subgrammar;
pub mod surface;
pub mod tube;
pub mod tubes;
pub mod widths;
pub use assemble::{assemble_scene, MeshOptions};
pub use components::ComponentSearch;
pub use error::MeshError;
pub use palette::Palette;
pub use scene::{Component, Instance, Material, Part, Scene, Stroke, TriMesh};
pub use subgrammar::{GrammarComponents, NoGrammars, Wanted};
