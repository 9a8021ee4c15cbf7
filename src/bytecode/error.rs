//! Errors of the bytecode compiler. Input: a resolved program that exceeds
//! an operand width; output: a [`BytecodeError`] diagnostic. Runtime faults
//! of the VM are [`crate::bytecode::Fault`]s, turned into diagnostics by
//! `derive`, which knows the production and the step.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

#[derive(Debug, Error, Diagnostic)]
pub enum BytecodeError {
    #[error("module `{name}` has {count} parameters; at most 255 are supported")]
    #[diagnostic(
        code(lsys::bytecode::too_many_parameters),
        help("split the data over several modules")
    )]
    TooManyParameters {
        name: String,
        count: usize,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this module has {count} parameters")]
        span: SourceSpan,
    },

    #[error("the parameter {value:e} is too large for cpfg's 32-bit parameters: it would be stored as infinity")]
    #[diagnostic(
        code(lsys::bytecode::f32_overflow),
        help("cpfg keeps parameters as 32-bit floats (at most about 3.4e38): scale the value down; the paper's dialect (a `.lsys` file without `dialect: cpfg`) keeps 64-bit parameters")
    )]
    F32Overflow {
        value: f64,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("{value:e} does not fit")]
        span: SourceSpan,
    },

    #[error("the program needs more than {limit} constants")]
    #[diagnostic(
        code(lsys::bytecode::too_many_constants),
        help("the program is too large for the bytecode; split it into sub-grammars")
    )]
    TooManyConstants { limit: u64 },

    #[error("this expression or successor compiles to more than {limit} instructions")]
    #[diagnostic(
        code(lsys::bytecode::chunk_too_long),
        help("split the successor over several productions")
    )]
    ChunkTooLong {
        limit: u64,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("too long")]
        span: SourceSpan,
    },
}
