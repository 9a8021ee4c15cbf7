//! Loading: the root input -> every source file it includes, parsed, with
//! their statements flattened in include order (an `#include "f"` line is
//! replaced by the statements of `f`, as the C preprocessor would).

use std::path::{Path, PathBuf};

use miette::Report;

use super::error::ResolveError;
use crate::parse::ast::{Include, Item};
use crate::parse::{self};
use crate::source::{FileId, Origin, SourceFile, SourceMap, Span};
use crate::stdlib;

/// Includes nested deeper than this are refused (a runaway generator, not
/// a grammar); `--max-include-depth` changes it.
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// What to compile.
#[derive(Clone, Debug)]
pub enum Input {
    /// A file on disk.
    Path(PathBuf),
    /// `std:NAME`: a standard library file.
    Std(String),
    /// Text from memory (tests, the REPL).
    Text { name: String, text: String },
    /// A file's text as edited in memory (the REPL): named like the file,
    /// with its `#include "..."` resolved beside it.
    Edited { path: PathBuf, text: String },
}

impl Input {
    /// Reads a command-line argument: `std:NAME` or a path.
    pub fn from_arg(arg: &str) -> Input {
        match arg.strip_prefix("std:") {
            Some(name) => Input::Std(name.to_string()),
            None => Input::Path(PathBuf::from(arg)),
        }
    }
}

/// The root input could not be read at all (no diagnostics to point at).
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
pub enum InputError {
    #[error("cannot read {path}: {cause}")]
    #[diagnostic(
        code(lsys::resolve::input),
        help("check the path; standard library grammars are named `std:NAME`")
    )]
    NotFound { path: String, cause: String },
    #[error("no standard library grammar `std:{name}`")]
    #[diagnostic(
        code(lsys::resolve::unknown_std),
        help("the standard library has: {available}")
    )]
    UnknownStd { name: String, available: String },
    #[error("{path} is not an L-system source: {why}")]
    #[diagnostic(
        code(lsys::resolve::input_not_source),
        help(
            "give lsys the grammar (.lsys or cpfg .l) file; a UTF-16 file must be saved as UTF-8"
        )
    )]
    NotSource { path: String, why: String },
}

/// Larger files are not grammars (a log, a disk image): refused unread
/// rather than loaded whole into memory.
pub const MAX_SOURCE_BYTES: u64 = 64 << 20;

/// Reads a source file: its bytes, or why it is not an L-system source
/// (`Ok(Err(..))`), or the I/O error.
fn read_source(path: &Path) -> std::io::Result<Result<Vec<u8>, String>> {
    let len = std::fs::metadata(path)?.len();
    if len > MAX_SOURCE_BYTES {
        return Ok(Err(format!(
            "it is {len} bytes long, more than the {} MiB a grammar file may have",
            MAX_SOURCE_BYTES >> 20
        )));
    }
    let bytes = std::fs::read(path)?;
    if is_binary(&bytes) {
        return Ok(Err(
            "it holds NUL bytes, as binary and UTF-16 files do".to_string()
        ));
    }
    Ok(Ok(bytes))
}

/// Text files never hold NUL bytes; binary and UTF-16 files do. Such a
/// file is refused unread, so that no diagnostic shows its bytes. (Other
/// invalid UTF-8, e.g. Latin-1 comments in old cpfg files, is read lossily.)
fn is_binary(bytes: &[u8]) -> bool {
    bytes.contains(&0)
}

/// Every file of one compilation and their statements in include order.
pub struct Loaded {
    pub sources: SourceMap,
    pub items: Vec<(FileId, Item)>,
    pub errors: Vec<Report>,
    pub warnings: Vec<Report>,
    /// The files went through the C preprocessor (a cpfg `.l` root), which
    /// took the `-D` definitions.
    pub preprocessed: bool,
    /// The language profile, decided here once for the whole model.
    pub profile: crate::lang::Profile,
}

/// Loads `input` and what it includes. A cpfg file (`.l`) goes through the
/// C preprocessor first, with the `-D` definitions defined before its
/// first line.
pub fn load(input: &Input, opts: &super::Options) -> Result<Loaded, InputError> {
    let root = match input {
        Input::Path(p) => {
            let text = read_source(p)
                .map_err(|e| InputError::NotFound {
                    path: p.display().to_string(),
                    cause: e.to_string(),
                })?
                .map_err(|why| InputError::NotSource {
                    path: p.display().to_string(),
                    why,
                })?;
            SourceFile::new(
                p.display().to_string(),
                Origin::Disk(p.clone()),
                String::from_utf8_lossy(&text).into_owned(),
            )
        }
        Input::Std(name) => {
            let text = stdlib::get(name).ok_or_else(|| InputError::UnknownStd {
                name: name.clone(),
                available: stdlib::names().join(", "),
            })?;
            SourceFile::new(format!("std:{name}"), Origin::Std(name.clone()), text)
        }
        Input::Text { name, text } => SourceFile::new(name.clone(), Origin::Memory, text.clone()),
        Input::Edited { path, text } => SourceFile::new(
            path.display().to_string(),
            Origin::Disk(path.clone()),
            text.clone(),
        ),
    };
    let profile = crate::lang::Profile::decide(&root.name, &root.text, opts.dialect);
    // Includes stay inside the top-level file's folder (or, for text and
    // library grammars, the working folder): a grammar from someone else
    // cannot read ../../etc/passwd, nor show its lines in a diagnostic.
    let root_dir = match &root.origin {
        Origin::Disk(p) => p.parent().map(Path::to_path_buf),
        _ => None,
    }
    .filter(|d| !d.as_os_str().is_empty())
    .unwrap_or_else(|| PathBuf::from("."));
    // `--include-dir` folders are allowed roots too (a missing one
    // allows nothing: it cannot be canonicalised, so nothing starts with it).
    let mut roots = vec![std::fs::canonicalize(&root_dir).unwrap_or_else(|_| root_dir.clone())];
    roots.extend(
        opts.include_dirs
            .iter()
            .filter_map(|d| std::fs::canonicalize(d).ok()),
    );
    let mut shown = vec![root_dir];
    shown.extend(opts.include_dirs.iter().cloned());
    let mut loader = Loader {
        loaded: Loaded {
            sources: SourceMap::new(),
            items: Vec::new(),
            errors: Vec::new(),
            warnings: Vec::new(),
            preprocessed: false,
            profile,
        },
        stack: Vec::new(),
        roots,
        roots_shown: shown,
        include_dirs: opts.include_dirs.clone(),
        max_depth: opts.max_include_depth,
        limits: opts.parse,
        pre: None,
    };
    let root = if profile.cpfg_model_file {
        loader.preprocess(root, &opts.defines)
    } else {
        root
    };
    let id = loader.loaded.sources.add(root);
    if let Some(pre) = &mut loader.pre {
        pre.ids.insert(id, 0);
    }
    loader.file(id);
    Ok(loader.loaded)
}

pub(super) struct Loader {
    pub(super) loaded: Loaded,
    /// The include chain being loaded: (file, its identity for cycles).
    stack: Vec<(FileId, String)>,
    /// Every included file must resolve (links followed) inside one of
    /// these: the top-level file's folder, then the `--include-dir`s.
    pub(super) roots: Vec<PathBuf>,
    /// The same folders as the user named them, for messages.
    pub(super) roots_shown: Vec<PathBuf>,
    /// `--include-dir`: searched after the including file's folder.
    pub(super) include_dirs: Vec<PathBuf>,
    /// `--max-include-depth`.
    pub(super) max_depth: usize,
    /// `--max-nesting`, `--max-operators`.
    limits: parse::Limits,
    /// A cpfg root's preprocessed files, and which file id holds which.
    pub(super) pre: Option<super::cpp_load::Preprocessed>,
}

impl Loader {
    fn identity(file: &SourceFile) -> String {
        match &file.origin {
            Origin::Disk(p) => std::fs::canonicalize(p)
                .unwrap_or_else(|_| p.clone())
                .display()
                .to_string(),
            Origin::Std(n) => format!("std:{n}"),
            Origin::Memory => file.name.clone(),
        }
    }

    fn file(&mut self, id: FileId) {
        let file = self.loaded.sources.get(id).clone();
        self.stack.push((id, Self::identity(&file)));
        let (ast, errors) = parse::parse_limited(id, &file, self.limits);
        for e in errors {
            if crate::diag::is_error(&e) {
                self.loaded.errors.push(Report::new(e));
            } else {
                self.loaded.warnings.push(Report::new(e));
            }
        }
        for item in ast.items {
            match item {
                Item::Include(Include::Path { span, .. }) if self.pre.is_some() => {
                    self.include_preprocessed(id, &file, span)
                }
                Item::Include(Include::Path { ref path, span }) => {
                    self.include_path(&file, path, span)
                }
                Item::Include(Include::Std { ref name, span }) => {
                    self.include_std(&file, name, span)
                }
                other => self.loaded.items.push((id, other)),
            }
        }
        self.stack.pop();
    }

    fn include_path(&mut self, from: &SourceFile, path: &str, span: Span) {
        let base: PathBuf = from.dir().map(Path::to_path_buf).unwrap_or_default();
        let mut full = base.join(path);
        // Not beside the including file: the first `--include-dir` that has it.
        if !full.exists() {
            if let Some(found) = self
                .include_dirs
                .iter()
                .map(|d| d.join(path))
                .find(|p| p.exists())
            {
                full = found;
            }
        }
        if let Ok(real) = std::fs::canonicalize(&full) {
            // `real` is only compared, never shown: messages keep the
            // user's own relative paths.
            if !self.roots.iter().any(|r| real.starts_with(r)) {
                let inside = self
                    .roots_shown
                    .iter()
                    .map(|d| d.display().to_string())
                    .collect::<Vec<_>>()
                    .join(" or ");
                self.loaded
                    .errors
                    .push(Report::new(ResolveError::IncludeOutside {
                        path: path.to_string(),
                        src: from.named_source(),
                        span: span.into(),
                        help: format!(
                            "{} is not inside {inside} (links are followed); copy the file into that folder or below it, or allow its folder with `--include-dir DIR`",
                            full.display(),
                        ),
                    }));
                return;
            }
        }
        let text = match read_source(&full) {
            Ok(Err(why)) => {
                self.loaded
                    .errors
                    .push(Report::new(ResolveError::IncludeNotSource {
                        path: path.to_string(),
                        why,
                        src: from.named_source(),
                        span: span.into(),
                    }));
                return;
            }
            Ok(Ok(t)) => String::from_utf8_lossy(&t).into_owned(),
            Err(e) => {
                let help = if from.dir().is_some() {
                    format!(
                        "the path is relative to the including file's folder (then to each `--include-dir`); lsys looked for {}",
                        full.display()
                    )
                } else {
                    format!("lsys looked for {}", full.display())
                };
                self.loaded
                    .errors
                    .push(Report::new(ResolveError::IncludeNotFound {
                        path: path.to_string(),
                        cause: e.to_string(),
                        src: from.named_source(),
                        span: span.into(),
                        help,
                    }));
                return;
            }
        };
        let name = if from.dir().is_some() {
            full.display().to_string()
        } else {
            path.to_string()
        };
        let file = SourceFile::new(name, Origin::Disk(full), text);
        self.enter(from, file, span);
    }

    fn include_std(&mut self, from: &SourceFile, name: &str, span: Span) {
        match stdlib::get(name) {
            Some(text) => {
                let file = SourceFile::new(format!("std:{name}"), Origin::Std(name.into()), text);
                self.enter(from, file, span);
            }
            None => self
                .loaded
                .errors
                .push(Report::new(ResolveError::UnknownStd {
                    name: name.to_string(),
                    src: from.named_source(),
                    span: span.into(),
                    help: format!("the standard library has: {}", stdlib::names().join(", ")),
                })),
        }
    }

    pub(super) fn enter(&mut self, from: &SourceFile, file: SourceFile, span: Span) {
        let ident = Self::identity(&file);
        if let Some(pos) = self.stack.iter().position(|(_, i)| *i == ident) {
            let mut chain: Vec<String> = self.stack[pos..]
                .iter()
                .map(|(id, _)| self.loaded.sources.get(*id).name.clone())
                .collect();
            chain.push(file.name.clone());
            self.loaded
                .errors
                .push(Report::new(ResolveError::IncludeCycle {
                    chain: chain.join(" -> "),
                    src: from.named_source(),
                    span: span.into(),
                }));
            return;
        }
        if self.stack.len() >= self.max_depth {
            self.loaded
                .errors
                .push(Report::new(ResolveError::IncludeDepth {
                    limit: self.max_depth,
                    src: from.named_source(),
                    span: span.into(),
                }));
            return;
        }
        let id = self.loaded.sources.add(file);
        self.file(id);
    }
}
