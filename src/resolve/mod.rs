//! Resolve: AST of the root file and its includes -> [`Program`].
pub mod ir;
pub use ir::*;
