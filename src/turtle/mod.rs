//! Turtle: the command table that the checker, help text and the 3D turtle
//! all read, and the turtle itself. Input: a derived module string; output:
//! strokes, polygons and component placements handed to the mesh builder.
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
pub use interp::{interpret, query_sites, QuerySite, TurtleOptions};
