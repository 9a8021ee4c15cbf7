//! Preprocessor errors and warnings (`lsys::preprocess::*`). Input: what
//! went wrong and where (a byte span in the original text of one of
//! `Output::files`); output: a plain value, and on request a miette
//! diagnostic carrying that file's text.

use std::ops::Range;
use std::sync::Arc;

use miette::{Diagnostic, LabeledSpan, NamedSource, Severity, SourceCode};

/// What kind of problem a [`PreprocessError`] is; [`ErrorKind::code`] gives
/// its stable diagnostic code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// `#if`/`#ifdef`/`#ifndef` without `#endif` before the end of its file.
    UnterminatedIf,
    /// `#else` without an open `#if`.
    ElseWithoutIf,
    /// `#elif` without an open `#if`.
    ElifWithoutIf,
    /// `#endif` without an open `#if`.
    EndifWithoutIf,
    /// `#else` or `#elif` after the `#else` of the same `#if`.
    ElseAfterElse,
    /// A function-like macro invoked with the wrong number of arguments.
    MacroArgs,
    /// A function-like macro invocation whose `)` never comes.
    UnterminatedCall,
    /// `/*` without `*/`.
    UnterminatedComment,
    /// The resolver could not find an `#include`d file (or the name is malformed).
    IncludeNotFound,
    /// `#include` nested deeper than `Options::max_include_depth` (or a cycle).
    IncludeDepth,
    /// More inclusions, or more bytes in all files read, than one run may
    /// have ([`super::MAX_FILES`], [`super::MAX_TOTAL_BYTES`]).
    IncludeLimit,
    /// An unknown or malformed directive.
    BadDirective,
    /// An `#if`/`#elif` expression that cannot be evaluated.
    IfExpression,
    /// `#error` text.
    ErrorDirective,
    /// Expansion nested deeper than `Options::max_expansion_depth`, or
    /// growing without bound.
    Recursion,
    /// Warning: a macro redefined with a different body (the last one wins).
    Redefined,
    /// A define given as an option that the model never defines or uses.
    UnknownDefine,
    /// Warning: `#warning` text.
    WarningDirective,
}

impl ErrorKind {
    pub fn code(&self) -> &'static str {
        match self {
            ErrorKind::UnterminatedIf => "lsys::preprocess::unterminated_if",
            ErrorKind::ElseWithoutIf => "lsys::preprocess::else_without_if",
            ErrorKind::ElifWithoutIf => "lsys::preprocess::elif_without_if",
            ErrorKind::EndifWithoutIf => "lsys::preprocess::endif_without_if",
            ErrorKind::ElseAfterElse => "lsys::preprocess::else_after_else",
            ErrorKind::MacroArgs => "lsys::preprocess::macro_args",
            ErrorKind::UnterminatedCall => "lsys::preprocess::unterminated_call",
            ErrorKind::UnterminatedComment => "lsys::preprocess::unterminated_comment",
            ErrorKind::IncludeNotFound => "lsys::preprocess::include_not_found",
            ErrorKind::IncludeDepth => "lsys::preprocess::include_depth",
            ErrorKind::IncludeLimit => "lsys::preprocess::include_limit",
            ErrorKind::BadDirective => "lsys::preprocess::bad_directive",
            ErrorKind::IfExpression => "lsys::preprocess::if_expression",
            ErrorKind::ErrorDirective => "lsys::preprocess::error_directive",
            ErrorKind::Recursion => "lsys::preprocess::recursion",
            ErrorKind::Redefined => "lsys::preprocess::redefined",
            ErrorKind::UnknownDefine => "lsys::preprocess::unknown_define",
            ErrorKind::WarningDirective => "lsys::preprocess::warning_directive",
        }
    }

    /// Warnings do not stop the pipeline; everything else is an error.
    pub fn is_warning(&self) -> bool {
        matches!(self, ErrorKind::Redefined | ErrorKind::WarningDirective)
    }
}

/// One preprocessor problem. `span` is a byte range in the ORIGINAL text of
/// `Output::files[file].raw.text` (for errors in `Options::defines` it is
/// `0..0` of the root file).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct PreprocessError {
    pub kind: ErrorKind,
    pub file: usize,
    pub span: Range<usize>,
    pub message: String,
    pub help: Option<String>,
    /// Same as `kind.is_warning()`; here so callers can filter without the enum.
    pub warning: bool,
}

impl PreprocessError {
    pub(crate) fn new(kind: ErrorKind, file: usize, span: Range<usize>, message: String) -> Self {
        PreprocessError {
            kind,
            file,
            span,
            message,
            help: None,
            warning: kind.is_warning(),
        }
    }

    pub(crate) fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// A renderable diagnostic over `name`/`text`, the file this error points into.
    pub fn to_diagnostic(&self, name: &str, text: Arc<String>) -> PreprocessDiagnostic {
        PreprocessDiagnostic {
            error: self.clone(),
            src: NamedSource::new(name, crate::source::SourceText::from(text)),
        }
    }
}

/// A [`PreprocessError`] with its source text, for miette rendering.
#[derive(Debug, thiserror::Error)]
#[error("{}", error.message)]
pub struct PreprocessDiagnostic {
    pub error: PreprocessError,
    src: NamedSource<crate::source::SourceText>,
}

impl Diagnostic for PreprocessDiagnostic {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        Some(Box::new(self.error.kind.code()))
    }

    fn severity(&self) -> Option<Severity> {
        Some(if self.error.warning {
            Severity::Warning
        } else {
            Severity::Error
        })
    }

    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.error
            .help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn std::fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn SourceCode> {
        Some(&self.src)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let s = &self.error.span;
        let len = s.end.saturating_sub(s.start);
        Some(Box::new(std::iter::once(LabeledSpan::new_with_span(
            None,
            (s.start, len),
        ))))
    }
}
