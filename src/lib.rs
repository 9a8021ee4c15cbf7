//! `lsys`: a compiler and interpreter for parametric L-systems.
//!
//! ```text
//! source (.lsys, #include'd files, std library embedded in the binary)
//!   -> load       every file the model reads: root, includes (cpfg .l through
//!                 the C preprocessor), view and function files; each parsed
//!   -> parse      pest grammar (grammar/lsys.pest) -> AST with spans
//!   -> resolve    #define, alphabet, names, arity, constant folding (no I/O)
//!   -> bytecode   productions -> documented instructions (+ spans), disassembler
//!   -> derive     parallel rewriting over a flat module store
//!   -> turtle     module string -> strokes, polygons and component placements
//!   -> mesh       tubes, polygons, components (OBJ via tobj) -> a Scene
//!   -> export     Scene -> glTF/GLB, OBJ+MTL, PNG pictures (atomic writes)
//! ```
//!
//! Around the pipeline: [`cli`] (the binary's commands, `watch` among
//! them), [`repl`] (`lsys repl`: step, edit, inspect a grammar
//! interactively) and [`progress`] (progress bars on standard error).

pub mod build;
pub mod bytecode;
pub mod cli;
pub mod derive;
pub mod diag;
pub mod export;
pub mod lang;
pub mod load;
pub mod mesh;
pub mod pailou;
pub mod parse;
pub mod pipeline;
pub mod preprocess;
pub mod progress;
pub mod repl;
pub mod resolve;
pub mod simulation;
pub mod source;
pub mod stdlib;
pub mod turtle;
