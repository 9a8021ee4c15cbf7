//! The public surface of the library: grammar text or a file in,
//! derived strings and built models out. Everything a program, a test or
//! a front end (the CLI, the REPL, an editor) needs is here; the stage
//! modules below it are the implementation.
//!
//! ```
//! let g = lsys::Grammar::from_str("koch.lsys", "axiom: F\nF --> F+F-F-F+F\n")?;
//! assert_eq!(g.derive(1)?.to_string(), "F + F - F - F + F");
//! # Ok::<(), lsys::Diagnostics>(())
//! ```

mod arrays;
mod derivation;
mod derived;
mod grammar;
mod options;
mod scene;
mod steps;

pub use arrays::{Arrays, Placement};
pub use derivation::{Derivation, Drawn, Numbers};
pub use derived::Derived;
pub use grammar::Grammar;
pub use options::GrammarOptions;
pub use scene::Scene;
pub(crate) use scene::WriteFailed;
pub use steps::Steps;

#[cfg(test)]
mod tests;
