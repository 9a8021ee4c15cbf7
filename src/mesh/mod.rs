//! Mesh: turtle output -> triangle meshes. Tubes for strokes, polygons,
//! spheres and discs, and components loaded once and placed by transform.
pub mod scene;
pub use scene::{Component, Instance, Material, Part, Scene, Stroke, TriMesh};
pub mod shapes;
pub mod tube;
