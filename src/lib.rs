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
//! is `docs/architecture.md`. Each stage imports only the stages before it
//! (`tests/architecture.rs` checks). Above them: [`pipeline`] (load to
//! bytecode in one call), [`build`] (simulation to meshes in one call,
//! building grammar components with the same options), [`pailou`] and the
//! public API.
//!
//! # Using the library
//!
//! The public surface is [`Grammar`], [`Derived`], [`Scene`],
//! [`GrammarOptions`] and [`Diagnostics`] (see `docs/library.md`):
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
//! The stage modules are public for tests, benchmarks and tools that go
//! deeper; their items may change between versions.
//!
//! With the default `cli` feature: [`cli`] (the binary's commands, `watch`
//! among them), [`repl`] (`lsys repl`: step, edit, inspect a grammar
//! interactively), [`lsp`] (`lsys lsp`: the language server for editors)
//! and [`progress`] (progress bars on standard error).
//! `default-features = false` builds the library without them (no clap,
//! rustyline, notify, ctrlc, indicatif, dirs, lsp-server, lsp-types).

mod api;

pub use api::{Derivation, Derived, Drawn, Grammar, GrammarOptions, Numbers, Scene, Steps};
pub use diag::{Diagnostics, Level, Message};
pub use lang::Dialect;

pub mod build;
pub mod bytecode;
#[cfg(feature = "cli")]
pub mod cli;
pub mod derive;
pub mod diag;
pub mod driver;
pub mod environment;
#[cfg(feature = "cli")]
pub mod exit_code;
pub mod export;
pub mod guided;
pub mod lang;
pub mod load;
#[cfg(feature = "cli")]
pub mod lsp;
pub mod mesh;
pub mod pailou;
pub mod parse;
pub mod pipeline;
pub mod preprocess;
#[cfg(feature = "cli")]
pub mod progress;
#[cfg(feature = "cli")]
pub mod repl;
pub mod resolve;
pub mod simulation;
pub mod source;
pub mod stdlib;
#[cfg(feature = "studio")]
pub mod studio;
pub mod support;
pub mod turtle;
