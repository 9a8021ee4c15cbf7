//! Errors and warnings of the derivation. Input: a VM
//! [`Fault`](crate::bytecode::Fault) or a limit overrun plus where it
//! happened (production, step); output: diagnostics with the source, a
//! label on the exact expression and a help sentence.

use std::sync::Arc;

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

/// Shared, so that errors stay small (`Result`s are returned per module).
pub type Src = Arc<NamedSource<crate::source::SourceText>>;

/// Internal error: boxed so that the `Result`s passed per module stay small.
pub(crate) type Fail = Box<DeriveError>;

impl From<Box<DeriveError>> for DeriveError {
    fn from(b: Box<DeriveError>) -> DeriveError {
        *b
    }
}

#[derive(Debug, Error, Diagnostic)]
pub enum DeriveError {
    #[error(
        "the string passed the module limit at step {step}: {reached} modules (limit {limit})"
    )]
    #[diagnostic(
        code(lsys::derive::module_limit),
        help("raise the limit max_modules (`--max-modules N`), or derive fewer steps")
    )]
    ModuleLimit {
        step: u32,
        limit: usize,
        reached: usize,
        #[source_code]
        src: Option<Src>,
        #[label("the limit was passed while applying this production")]
        production: Option<SourceSpan>,
    },

    #[error("the string passed the parameter limit at step {step}: {reached} parameter values (limit {limit})")]
    #[diagnostic(
        code(lsys::derive::param_limit),
        help("raise the limit max_params (`--max-params N`), or derive fewer steps")
    )]
    ParamLimit {
        step: u32,
        limit: usize,
        reached: usize,
        #[source_code]
        src: Option<Src>,
        #[label("the limit was passed while applying this production")]
        production: Option<SourceSpan>,
    },

    #[error("{context} at step {step}: {what}")]
    #[diagnostic(
        code(lsys::derive::table_index),
        help("indices are whole numbers within the ranges of the table's #define (an array's: 0 to its size - 1); guard the production with a condition on the index, or enlarge the table or array")
    )]
    TableIndex {
        /// e.g. "index 4 of table `dec` is outside 1..3".
        what: String,
        context: String,
        step: u32,
        #[source_code]
        src: Src,
        #[label("this lookup")]
        span: SourceSpan,
        #[label("in this production")]
        production: Option<SourceSpan>,
    },

    #[error("{context} at step {step}: loops went round more than {limit} times in the step")]
    #[diagnostic(
        code(lsys::derive::endless_loop),
        help("make the `while` condition become false (is the variable it tests changed in the loop?); the limit counts the rounds of every loop run in one step, for all modules together")
    )]
    EndlessLoop {
        limit: u64,
        context: String,
        step: u32,
        #[source_code]
        src: Src,
        #[label("this loop")]
        span: SourceSpan,
        #[label("in this production")]
        production: Option<SourceSpan>,
    },

    #[error("{context} at step {step}: {what} by zero")]
    #[diagnostic(
        code(lsys::derive::division_by_zero),
        help("guard the production with a condition, or keep the divisor away from zero (e.g. `max(d, 0.001)`)")
    )]
    DivisionByZero {
        /// "division" or "remainder".
        what: &'static str,
        context: String,
        step: u32,
        #[source_code]
        src: Src,
        #[label("the divisor of this is zero")]
        span: SourceSpan,
        #[label("in this production")]
        production: Option<SourceSpan>,
    },

    #[error("{context} at step {step}: module parameter is {value}")]
    #[diagnostic(
        code(lsys::derive::not_finite),
        help("module parameters must be finite numbers; check for sqrt/log of negative numbers, asin/acos outside [-1, 1] or overflowing powers")
    )]
    NotFinite {
        value: f64,
        context: String,
        step: u32,
        #[source_code]
        src: Src,
        #[label("this evaluates to {value}")]
        span: SourceSpan,
        #[label("in this production")]
        production: Option<SourceSpan>,
    },

    #[error("{context} at step {step}: probability is {value}")]
    #[diagnostic(
        code(lsys::derive::bad_probability),
        help("a probability is a relative weight and must be zero or positive")
    )]
    BadProbability {
        value: f64,
        context: String,
        step: u32,
        #[source_code]
        src: Src,
        #[label("this evaluates to {value}")]
        span: SourceSpan,
        #[label("in this production")]
        production: Option<SourceSpan>,
    },

    #[error("step {step} would not fit in memory: about {modules} modules ({bytes} with the string before it), and {available} is available")]
    #[diagnostic(
        code(lsys::derive::too_large),
        help("the size is projected from the growth of the last step; derive fewer steps, count the modules without building the string with `lsys derive --count`, or lower the limit max_modules (`--max-modules`, now {limit}) so that the derivation stops at a size of your choosing")
    )]
    TooLarge {
        step: u32,
        modules: u64,
        bytes: String,
        available: String,
        limit: usize,
    },

    #[error("the program has {count} module symbols; at most {limit} are supported")]
    #[diagnostic(
        code(lsys::derive::too_many_symbols),
        help("use fewer distinct module names")
    )]
    TooManySymbols { count: usize, limit: usize },
}

impl DeriveError {
    /// The derivation step the error happened at, when there is one.
    pub fn step(&self) -> Option<u32> {
        match self {
            DeriveError::ModuleLimit { step, .. }
            | DeriveError::ParamLimit { step, .. }
            | DeriveError::DivisionByZero { step, .. }
            | DeriveError::TableIndex { step, .. }
            | DeriveError::EndlessLoop { step, .. }
            | DeriveError::NotFinite { step, .. }
            | DeriveError::BadProbability { step, .. }
            | DeriveError::TooLarge { step, .. } => Some(*step),
            DeriveError::TooManySymbols { .. } => None,
        }
    }
}

/// A decomposition or homomorphism production still applied at the
/// maximum depth; the module was left as it was.
#[derive(Clone, Debug, Error, Diagnostic)]
#[error("{table} reached its maximum depth {depth} (first at step {step}, {count} time(s)); the modules were left unrewritten")]
#[diagnostic(
    code(lsys::derive::depth_limit),
    severity(Warning),
    help(
        "raise `maximum depth:` of the {table} section, or make the recursion end with a condition"
    )
)]
pub struct DepthWarning {
    /// "decomposition" or "homomorphism".
    pub table: &'static str,
    pub depth: u32,
    /// First step it happened at.
    pub step: u32,
    /// How many times it happened.
    pub count: u64,
    /// Index of the production in its table.
    pub production: usize,
    #[source_code]
    pub src: Src,
    #[label("this production would still apply")]
    pub span: SourceSpan,
}
