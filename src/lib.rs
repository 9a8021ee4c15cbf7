//! `lsys`: a compiler and interpreter for parametric L-systems.
//!
//! ```text
//! lang        the language profile, turtle command table, built-in
//!             functions, random generator: what every stage shares
//! support     not a stage: memory infrastructure the stages share
//!             (prefault: a second core backing big buffers' fresh pages
//!             ahead of their writer, for the turtle's chains and the
//!             mesher's meshes)
//! source (.lsys, #include'd files, std library embedded in the binary)
//!   -> load       every file the model reads: root, includes (cpfg .l through
//!                 the C preprocessor), view and function files, each parsed
//!                 (parse: pest grammar -> AST with spans); decides the profile
//!   -> resolve    #define, alphabet, names, arity, constant folding (no I/O)
//!   -> bytecode   productions -> documented instructions (+ spans), disassembler
//!   -> derive     parallel rewriting over a flat module store (no turtle)
//!   -> turtle     module string -> strokes, polygons and component placements
//!   -> simulation the loop: derive a step -> environments (the turtle's
//!                 ?P ?H ?L ?U first) answer query modules -> next step; End:
//!   -> mesh       tubes, polygons, components (OBJ via tobj; grammar
//!                 components through a seam the caller implements) -> a Scene
//!   -> export     Scene -> glTF/GLB, OBJ+MTL, PNG pictures (atomic writes)
//! ```
//!
//! The whole map, every folder of `src/` with what goes in and out of it,
//! is `docs/architecture.md` in the repository. Each stage imports only the stages before it
//! (`tests/architecture.rs` checks). Above them: `pipeline` (load to
//! bytecode in one call), `build` (simulation to meshes in one call,
//! building grammar components with the same options), `pailou`, the
//! public API and the [`driver`].
//!
//! # Using the library
//!
//! This is the door every front end uses (the command line, the REPL, the
//! studio): [`Grammar`] (compile, [`derive`](Grammar::derive),
//! [`steps`](Grammar::steps), a [`Derivation`] to drive, [`build`](Grammar::build)),
//! [`GrammarOptions`], [`Derived`], [`Scene`], [`Diagnostics`] of typed
//! [`Message`]s, and the [`driver`]: one [`driver::Job`] from its input to
//! a file or bytes (Pailous from a style or a graph, guided scenes, the
//! structural check, `--stats`). See `docs/library.md`:
//!
//! ```
//! let g = lsys::Grammar::options()
//!     .define("N", 3)
//!     .from_str("koch.lsys", "#define N 1\nderivation length: N\naxiom: F\nF --> F+F-F-F+F\n")?;
//! assert_eq!(g.derive(1)?.to_string(), "F + F - F - F + F");
//! assert_eq!(g.steps().count(), 4); // the axiom and 3 steps
//! # Ok::<(), lsys::Diagnostics>(())
//! ```
//!
//! The stages are private; the crate's own tests, benchmarks and fuzzers
//! reach them through a hidden `internals` module that is no API.
//!
//! With the default `cli` feature: [`cli`] (the binary's commands, `watch`
//! among them, the REPL, the language server and progress bars).
//! `default-features = false` builds the library without them (no clap,
//! rustyline, notify, ctrlc, indicatif, dirs, lsp-server, lsp-types).

mod api;

pub use api::{
    Arrays, Derivation, Derived, Drawn, Grammar, GrammarOptions, Numbers, Placement, Scene, Steps,
};
pub use diag::{Diagnostics, Level, Message};
pub use lang::Dialect;

#[cfg(feature = "cli")]
pub mod cli;
pub mod driver;

// The stages and the layers above them are the implementation: private
// here, reachable by the crate's own tests, benchmarks and fuzzers
// through `internals` (no API; may change in any version).
mod build;
mod bytecode;
mod derive;
mod diag;
mod environment;
#[cfg(feature = "cli")]
mod exit_code;
mod export;
mod guided;
mod infer;
mod lang;
mod load;
#[cfg(feature = "cli")]
mod lsp;
mod mesh;
mod pailou;
mod parse;
mod pipeline;
mod preprocess;
#[cfg(feature = "cli")]
mod progress;
#[cfg(feature = "cli")]
mod repl;
mod resolve;
mod simulation;
mod source;
mod stdlib;
#[cfg(feature = "studio")]
mod studio;
mod support;
mod turtle;

/// The crate's insides for its own tests, benchmarks and fuzzers: every
/// stage and front end, as `lsys::internals::derive::...`. Not part of the
/// API: programs use the crate root and [`driver`].
#[doc(hidden)]
pub mod internals {
    pub mod build {
        pub use crate::build::*;
    }
    pub mod bytecode {
        pub use crate::bytecode::*;
    }
    pub mod derive {
        pub use crate::derive::*;
    }
    pub mod diag {
        pub use crate::diag::*;
    }
    pub mod environment {
        pub use crate::environment::*;
    }
    pub mod export {
        pub use crate::export::*;
    }
    pub mod guided {
        pub use crate::guided::*;
    }
    pub mod infer {
        pub use crate::infer::*;
    }
    pub mod lang {
        pub use crate::lang::*;
    }
    pub mod load {
        pub use crate::load::*;
    }
    pub mod mesh {
        pub use crate::mesh::*;
    }
    pub mod pailou {
        pub use crate::pailou::*;
    }
    pub mod parse {
        pub use crate::parse::*;
    }
    pub mod pipeline {
        pub use crate::pipeline::*;
    }
    pub mod preprocess {
        pub use crate::preprocess::*;
    }
    pub mod resolve {
        pub use crate::resolve::*;
    }
    pub mod simulation {
        pub use crate::simulation::*;
    }
    pub mod source {
        pub use crate::source::*;
    }
    pub mod stdlib {
        pub use crate::stdlib::*;
    }
    pub mod support {
        pub use crate::support::*;
    }
    pub mod turtle {
        pub use crate::turtle::*;
    }
    #[cfg(feature = "cli")]
    pub mod exit_code {
        pub use crate::exit_code::*;
    }
    #[cfg(feature = "cli")]
    pub mod lsp {
        pub use crate::lsp::*;
    }
    #[cfg(feature = "cli")]
    pub mod progress {
        pub use crate::progress::*;
    }
    #[cfg(feature = "cli")]
    pub mod repl {
        pub use crate::repl::*;
    }
    #[cfg(feature = "studio")]
    pub mod studio {
        pub use crate::studio::*;
    }
}
