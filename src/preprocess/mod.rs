//! The C preprocessor that cpfg runs over every `.l` file, rewritten so
//! that line structure survives. Input: the root file, a [`Resolver`] for
//! `#include` names and [`Options`]. Output: one preprocessed text per file
//! read ([`Output`]), each with exactly as many lines as its original, plus
//! errors and warnings pointing into the original texts.
//!
//! How lines are kept:
//! - directive lines become empty lines, except `#include`, which stays
//!   (normalised to `#include "name"` / `#include <name>`) so the loader can
//!   splice the included file's statements there ([`OutFile::includes`]);
//! - a backslash-newline joins the next line onto the first one; the
//!   following lines are left empty;
//! - a function-like macro invocation whose arguments span lines is
//!   expanded onto the line of its name, followed by the rest of the line
//!   of its `)` (as GNU cpp prints it: cpfg reads a production per line);
//!   the lines it consumed are left empty;
//! - `/* */` comments become a space (their newlines are kept), `//`
//!   comments are removed to the end of the line.
//!
//! Only a `#` that is the first non-blank character of a line, followed by
//! a name, a number or nothing, starts a directive: cpfg's `#(w)` turtle
//! command is ordinary text, even at the start of a line (GNU cpp would
//! reject that line as an invalid directive; real cpfg models have it).
//!
//! Compared with GNU cpp in its default mode (all 111 cpfg models of the
//! shared corpus give the same tokens, except two whose `#(` lines GNU
//! cpp rejects):
//! - `'` does not start a character literal (cpfg's `'` is a turtle
//!   command; macros between two `'` are expanded) and `$` is not part of
//!   identifiers;
//! - in a function-like body, `#` not followed by a parameter is kept as
//!   text (cpfg's `#(w)`), and a `##` whose result is not one token keeps
//!   the tokens, instead of errors;
//! - `#if` arithmetic is signed 64-bit, wrapping; no `'c'` constants, no
//!   unsigned arithmetic; floats are an error;
//! - no predefined macros (`__STDC__`, `unix`, ...) except `__LINE__` and
//!   `__FILE__`; no `__COUNTER__`, `__DATE__`, `_Pragma`;
//! - a directive inside a macro's argument list ends it
//!   (`unterminated_call`); GNU cpp would process the directive;
//! - `#line`, `#pragma`, `#ident` are ignored, `#include_next` and
//!   `#import` are `#include`; a `#include` that cannot be read is reported
//!   and its line left empty.
//!
//! Stages: `lexer` (text -> logical lines of tokens), `macros`
//! (`#define` -> macro), `expand` (tokens -> expanded tokens),
//! `conditional` and `if_expr` (`#if` groups), `driver` (directives,
//! includes, one file at a time), `render` (tokens -> lines of text).

mod conditional;
mod driver;
mod error;
mod expand;
mod if_expr;
mod lexer;
mod macros;
mod overrides;
mod render;
mod token;

#[cfg(test)]
mod tests;

use std::path::PathBuf;

pub use error::{ErrorKind, PreprocessDiagnostic, PreprocessError};

/// Inclusions one run may make, the root file counted: an include tree
/// can grow exponentially (each file including the next twice, 31 deep,
/// is 2^31 inclusions within the depth limit). The `.lsys` loader keeps
/// the same limits (docs/limits.md).
pub const MAX_FILES: usize = 10_000;
/// Bytes of all files one run may read, counted at each inclusion (a file
/// read twice counts twice): the size limit of one grammar file.
pub const MAX_TOTAL_BYTES: usize = 64 << 20;

/// Settings of one preprocessor run.
#[derive(Debug, Clone)]
pub struct Options {
    /// `-D NAME=VALUE`, defined before the root file is read. `NAME` may be
    /// `F(x)` for a function-like macro; an empty value defines it as empty.
    pub defines: Vec<(String, String)>,
    /// How deeply `#include`s may nest (default 64; at most 256 is used, so
    /// the recursion over files stays within any thread's stack).
    pub max_include_depth: usize,
    /// How deeply macro arguments may nest inside one another during
    /// expansion (default 200; at most 256 is used, which fits a 2 MiB
    /// thread stack even in debug builds).
    pub max_expansion_depth: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            defines: Vec::new(),
            max_include_depth: 64,
            max_expansion_depth: 200,
        }
    }
}

/// One file as read by the resolver.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RawFile {
    /// Display name, used in messages and `__FILE__`.
    pub name: String,
    /// Canonical identity, used to recognise include cycles.
    pub key: PathBuf,
    pub text: String,
}

/// How `#include` names are found; the loader implements it (relative to
/// the including file's folder, confinement, the std library for `<...>`).
pub trait Resolver {
    /// The file `name` (written `"name"`, or `<name>` when `angled`)
    /// included from `including`, or why it cannot be read, e.g.
    /// "no such file: x (searched: ...)".
    fn resolve(&mut self, including: &RawFile, name: &str, angled: bool)
        -> Result<RawFile, String>;
}

/// One file after preprocessing.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutFile {
    pub raw: RawFile,
    /// Preprocessed text, with exactly as many lines as `raw.text`
    /// (counted as `split('\n')`; CRLF becomes LF).
    pub text: String,
    /// The `#include` lines of this file that were read, in order.
    pub includes: Vec<IncludeSite>,
}

/// An `#include` line kept in a file's output text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IncludeSite {
    /// 1-based line in the including file.
    pub line: usize,
    /// Index into [`Output::files`].
    pub file: usize,
}

/// All files read, the root first; a file included twice appears twice
/// (its text may differ, since the macros in effect may differ).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Output {
    pub files: Vec<OutFile>,
}

/// Preprocesses `root` and everything it includes. Never panics; errors
/// and warnings (see [`PreprocessError::warning`]) are returned beside
/// whatever output could be made.
pub fn preprocess(
    root: RawFile,
    resolver: &mut dyn Resolver,
    opts: &Options,
) -> (Output, Vec<PreprocessError>) {
    driver::run(root, resolver, opts)
}
