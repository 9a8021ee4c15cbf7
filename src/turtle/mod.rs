//! Turtle: the 3D turtle that carries out a string's commands. Input: a
//! derived module string; output: a [`Drawing`] (strokes in tube chains,
//! polygons, spheres and discs, generalized cylinders and cpfg contours,
//! shape grammars' solids, component placements) handed to the mesh
//! builder, and for the simulation loop the turtle's state at each query
//! module ([`query_sites`]). The command table it reads, with resolve and
//! `lsys commands`, is `lang/commands.rs`'s.
mod chinese_roof;
mod cpfg;
mod cpfg_contour;
mod cylinder;
pub mod drawing;
pub mod error;
pub mod frame;
pub mod interp;
mod placement;
pub mod scope;
mod scope_walk;
mod snap;
pub mod solid;
pub use drawing::Drawing;
pub use error::{BracketOrigin, TurtleError};
pub use interp::{
    interpret, query_sites, QuerySite, TurtleOptions, DEFAULT_MAX_TRIANGLES, MAX_PIECES,
};
