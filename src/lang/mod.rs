//! The language itself, shared by every stage and importing none of them:
//! the profile (which notation a model is written in and every behaviour
//! that follows), the turtle command table, the built-in functions and
//! cpfg's function files, and the random generator. Input: nothing but
//! names; output: tables and small values the pipeline reads.

pub mod builtins;
pub mod commands;
pub mod curve;
pub mod profile;
pub mod rng;
pub mod scope_commands;
pub mod spline;

pub use commands::{all, lookup, Command, COMMANDS};
pub use profile::{Dialect, Profile};
