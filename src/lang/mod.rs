//! The language itself, shared by every stage and importing none of them:
//! the profile (which notation a model is written in and every behaviour
//! that follows), the turtle command table (shape-grammar commands
//! included), the built-in functions, cpfg's function files and contour
//! curves, and the random generator. Input: names, and the text of cpfg's
//! function and curve files; output: tables and small values the pipeline
//! reads.

pub mod builtins;
pub mod commands;
pub mod curve;
pub mod profile;
pub mod rng;
pub mod scope_commands;
pub mod spline;

pub use commands::{all, lookup, Command, COMMANDS};
pub use profile::{Dialect, Profile};
