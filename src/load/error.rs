//! Loading's errors: the root input that cannot be read at all
//! ([`InputError`]), and the diagnostics of files read along the way
//! ([`LoadError`]: includes, the view file and function files). The include
//! errors keep the codes (`lsys::resolve::*`) they had when loading was part
//! of resolve.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

type Src = NamedSource<crate::source::SourceText>;

/// The root input could not be read at all (no diagnostics to point at).
#[derive(Debug, Error, Diagnostic)]
pub enum InputError {
    #[error("cannot read {path}: {cause}")]
    #[diagnostic(
        code(lsys::load::input),
        help("check the path; standard library grammars are named `std:NAME`")
    )]
    NotFound { path: String, cause: String },
    #[error("{path} is a folder, not a grammar")]
    #[diagnostic(code(lsys::load::input_is_folder), help("{help}"))]
    Folder { path: String, help: String },
    #[error("no standard library grammar `std:{name}`")]
    #[diagnostic(code(lsys::load::unknown_std), help("{help}"))]
    UnknownStd { name: String, help: String },
    #[error("{path} is not an L-system source: {why}")]
    #[diagnostic(
        code(lsys::load::input_not_source),
        help(
            "give lsys the grammar (.lsys or cpfg .l) file; a UTF-16 file must be saved as UTF-8"
        )
    )]
    NotSource { path: String, why: String },
}

/// A file included or read beside the model cannot be used.
#[derive(Debug, Error, Diagnostic)]
pub enum LoadError {
    /// The file holds NUL bytes (a binary or UTF-16 file) or is too large
    /// to be a grammar. Its text is never shown in a diagnostic.
    #[error("cannot include \"{path}\": it is not an L-system source ({why})")]
    #[diagnostic(
        code(lsys::load::include_not_source),
        help("include only grammar text files; a UTF-16 file must be saved as UTF-8")
    )]
    IncludeNotSource {
        path: String,
        why: String,
        #[source_code]
        src: Src,
        #[label("included here")]
        span: SourceSpan,
    },

    #[error("cannot include \"{path}\": {cause}")]
    #[diagnostic(code(lsys::load::include_not_found))]
    IncludeNotFound {
        path: String,
        cause: String,
        #[source_code]
        src: Src,
        #[label("included here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("cannot include \"{path}\": it is outside the folder of the top-level grammar")]
    #[diagnostic(code(lsys::load::include_outside))]
    IncludeOutside {
        path: String,
        #[source_code]
        src: Src,
        #[label("included here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("no standard library file <{name}>")]
    #[diagnostic(code(lsys::load::unknown_std))]
    UnknownStd {
        name: String,
        #[source_code]
        src: Src,
        #[label("included here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("include cycle: {chain}")]
    #[diagnostic(
        code(lsys::load::include_cycle),
        help("a file may not include itself, directly or through other files; remove one of the includes in the chain")
    )]
    IncludeCycle {
        chain: String,
        #[source_code]
        src: Src,
        #[label("this include closes the cycle")]
        span: SourceSpan,
    },

    #[error("this include would read {files} files and {bytes} bytes in all, past the limits of one model ({max_files} files, {max_mib} MiB)")]
    #[diagnostic(
        code(lsys::load::include_limit),
        help("nothing more is included. An include tree that reads files more than once grows exponentially (each file including the next twice): include each file once")
    )]
    IncludeLimit {
        files: usize,
        bytes: usize,
        max_files: usize,
        max_mib: usize,
        #[source_code]
        src: Src,
        #[label("this include is past the limit")]
        span: SourceSpan,
    },

    #[error("includes nested deeper than {limit} files (the limit)")]
    #[diagnostic(
        code(lsys::load::include_depth),
        help("this include would be file {} of the chain; look for a file that includes a chain of generated files, or raise the limit with `--max-include-depth N`", limit + 1)
    )]
    IncludeDepth {
        limit: usize,
        #[source_code]
        src: Src,
        #[label("this include is one too many")]
        span: SourceSpan,
    },

    /// A line of the view file names a function file that cannot be read,
    /// or names none.
    #[error("{why}")]
    #[diagnostic(code(lsys::load::view_file))]
    ViewFile {
        why: String,
        #[source_code]
        src: Src,
        #[label("in this line of the view file")]
        span: SourceSpan,
        #[help]
        help: Option<String>,
    },

    /// A cpfg environment file (`.e` or the program's specification)
    /// exists but cannot be read.
    #[error("cannot use the environment file {path}")]
    #[diagnostic(code(lsys::load::environment_file))]
    EnvironmentUnreadable {
        path: String,
        #[help]
        why: String,
    },

    /// The view file exists but cannot be read.
    /// A colour map or material file named in `specifications` that
    /// cannot be used: lsys's palette stands in.
    #[error("cannot use the colour file {path}: {why}")]
    #[diagnostic(
        code(lsys::load::colour_file),
        severity(Warning),
        help("the model is drawn with lsys's palette for the colours this file would give")
    )]
    ColourFile { path: String, why: String },

    /// A view file's `contour:` line whose cross-section cannot be used.
    #[error("cannot use a contour of the view file {view}: {why}")]
    #[diagnostic(
        code(lsys::load::contour_file),
        severity(Warning),
        help("generalized cylinders that select it (`@#`) are drawn round")
    )]
    ContourFile { view: String, why: String },

    /// `angle factor: 0` in a cpfg view file: 360° / 0 is no angle.
    #[error("`angle factor: 0` gives no turning angle (360° / 0), so it is ignored")]
    #[diagnostic(
        code(lsys::load::angle_factor),
        severity(Warning),
        help("the turning angle stays at 90° (or the model's own `angle:`); write the number of turns in a full circle (`angle factor: 8` for 45°), or `angle increment: 45`")
    )]
    ZeroAngleFactor {
        #[source_code]
        src: Src,
        #[label("360° / 0")]
        span: SourceSpan,
    },

    #[error("cannot use the view file {path}")]
    #[diagnostic(code(lsys::load::view_file))]
    ViewUnreadable {
        path: String,
        #[help]
        why: String,
    },

    /// A function file (`.func`, `.fset`) is not in a format lsys reads.
    #[error("cannot read the function file {path}: {why}")]
    #[diagnostic(
        code(lsys::load::function_file),
        help("lsys reads funcedit's `fver 1 1` functions and `funcgalleryver 1 1` galleries")
    )]
    FunctionFile {
        path: String,
        why: String,
        #[source_code]
        src: Src,
        #[label("here")]
        span: SourceSpan,
    },
}
