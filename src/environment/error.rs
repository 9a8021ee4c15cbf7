//! Errors of the environment stage: a communication or specification file
//! that names a program lsys does not have, or a value it cannot read.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

type Src = NamedSource<crate::source::SourceText>;

#[derive(Debug, Error, Diagnostic)]
pub enum EnvironmentError {
    #[error("no environmental program `{name}` in lsys")]
    #[diagnostic(
        code(lsys::environment::unknown_program),
        severity(Warning),
        help("lsys runs these environmental programs natively: {known}; the model derives as if `?E` had no environment")
    )]
    UnknownProgram {
        name: String,
        known: String,
        #[source_code]
        src: Src,
        #[label("this program")]
        span: SourceSpan,
    },

    #[error("the communication file names no program")]
    #[diagnostic(
        code(lsys::environment::no_program),
        help("write `executable: PROGRAM SPECFILE`, e.g. `executable: honda81 density.spec`")
    )]
    NoProgram {
        #[source_code]
        src: Src,
        #[label("no `executable:` line in this file")]
        span: SourceSpan,
    },

    #[error("`{key}`: {why}")]
    #[diagnostic(code(lsys::environment::bad_value))]
    BadValue {
        key: String,
        why: String,
        #[source_code]
        src: Src,
        #[label("here")]
        span: SourceSpan,
        #[help]
        help: Option<String>,
    },
}
