//! Turtle: the command table that the checker, help text and (later) the
//! 3D turtle VM all read. Input: symbol names; output: what each means.
pub mod commands;
pub use commands::{lookup, Command, COMMANDS};
