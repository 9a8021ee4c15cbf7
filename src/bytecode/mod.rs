//! Bytecode: resolved [`Program`](crate::resolve::Program) in, [`Compiled`]
//! chunks out, plus the VM that runs them and a disassembler.
//!
//! Each production compiles to an optional condition chunk, an optional
//! probability chunk and a successor chunk; the axiom compiles to one
//! successor chunk. See [`Op`] for the instruction set.

mod compile;
mod disasm;
mod error;
mod op;
pub mod vm;

pub use compile::compile;
pub use disasm::{disasm, disasm_production, one_line};
pub use error::BytecodeError;
pub use op::{Chunk, Compiled, CondCode, Op, ProdCode};
pub use vm::{Fault, FaultKind, NoSink, Sink};
