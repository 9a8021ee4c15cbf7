//! Load: one file and, recursively, what it includes. A source file in;
//! its statements (and those of its includes, in include order), the
//! files added to the [`SourceMap`] and the diagnostics of parsing and
//! including out. Cycles and too deep chains are refused here.

use std::path::{Path, PathBuf};

use miette::Report;

use super::error::LoadError;
use super::include::{IncludeFinder, Refused};
use super::{Loaded, Options, SideFiles};
use crate::lang::Profile;
use crate::parse::ast::{Include, Item};
use crate::parse::{self};
use crate::preprocess::{MAX_FILES, MAX_TOTAL_BYTES};
use crate::source::{FileId, Origin, SourceFile, SourceMap, Span};
use crate::stdlib;

pub(super) struct Loader {
    pub(super) loaded: Loaded,
    /// The include chain being loaded: (file, its identity for cycles).
    stack: Vec<(FileId, String)>,
    /// Where includes are found, and the folders they must stay in.
    pub(super) finder: IncludeFinder,
    /// `--max-include-depth`.
    pub(super) max_depth: usize,
    /// `--max-nesting`, `--max-operators`.
    limits: parse::Limits,
    /// A cpfg root's preprocessed files, and which file id holds which.
    pub(super) pre: Option<super::cpfg::Preprocessed>,
    /// Files entered and their bytes, the root's too, against
    /// [`MAX_FILES`] and [`MAX_TOTAL_BYTES`]: the depth limit alone lets a
    /// diamond of includes read 2^30 files.
    files_read: usize,
    bytes_read: usize,
    /// Set once a limit is reached: later includes are skipped unread.
    includes_stopped: bool,
}

impl Loader {
    pub(super) fn new(profile: Profile, finder: IncludeFinder, opts: &Options) -> Loader {
        Loader {
            loaded: Loaded {
                sources: SourceMap::new(),
                items: Vec::new(),
                errors: Vec::new(),
                warnings: Vec::new(),
                broken: Vec::new(),
                failed_includes: Vec::new(),
                includes: Vec::new(),
                preprocessed: false,
                profile,
                side: SideFiles::default(),
                environment: None,
                environment_images: Vec::new(),
            },
            stack: Vec::new(),
            finder,
            max_depth: opts.max_include_depth,
            limits: opts.parse,
            pre: None,
            files_read: 0,
            bytes_read: 0,
            includes_stopped: false,
        }
    }

    /// Loads the root file and everything it includes.
    pub(super) fn root(&mut self, root: SourceFile) {
        self.files_read = 1;
        self.bytes_read = root.text.len();
        let id = self.loaded.sources.add(root);
        if let Some(pre) = &mut self.pre {
            pre.ids.insert(id, 0);
        }
        self.file(id);
    }

    pub(super) fn finish(self) -> Loaded {
        self.loaded
    }

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

    fn error(&mut self, e: LoadError) {
        self.loaded.errors.push(Report::new(e));
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
        self.loaded.broken.extend(ast.broken);
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
        if self.includes_stopped {
            self.loaded.failed_includes.push(span);
            return;
        }
        let base: PathBuf = from.dir().map(Path::to_path_buf).unwrap_or_default();
        let found = self.finder.find(&base, path);
        if found.is_err() {
            self.loaded.failed_includes.push(span);
        }
        let (full, text) = match found {
            Ok(found) => found,
            Err(Refused::Outside { help, .. }) => {
                return self.error(LoadError::IncludeOutside {
                    path: path.to_string(),
                    src: from.named_source(),
                    span: span.into(),
                    help,
                })
            }
            Err(Refused::NotSource { why, .. }) => {
                return self.error(LoadError::IncludeNotSource {
                    path: path.to_string(),
                    why,
                    src: from.named_source(),
                    span: span.into(),
                })
            }
            Err(Refused::NotFound { full, cause }) => {
                let help = if from.dir().is_some() {
                    format!(
                        "the path is relative to the including file's folder (then to each `--include-dir`); lsys looked for {}",
                        full.display()
                    )
                } else {
                    format!("lsys looked for {}", full.display())
                };
                return self.error(LoadError::IncludeNotFound {
                    path: path.to_string(),
                    cause,
                    src: from.named_source(),
                    span: span.into(),
                    help,
                });
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
            None => {
                self.loaded.failed_includes.push(span);
                self.loaded.errors.push(Report::new(LoadError::UnknownStd {
                    name: name.to_string(),
                    src: from.named_source(),
                    span: span.into(),
                    help: stdlib::unknown_help(name, |n| format!("#include <{n}>")),
                }))
            }
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
                .push(Report::new(LoadError::IncludeCycle {
                    chain: chain.join(" -> "),
                    src: from.named_source(),
                    span: span.into(),
                }));
            return;
        }
        if self.includes_stopped {
            self.loaded.failed_includes.push(span);
            return;
        }
        let (files, bytes) = (self.files_read + 1, self.bytes_read + file.text.len());
        if files > MAX_FILES || bytes > MAX_TOTAL_BYTES {
            self.includes_stopped = true;
            self.loaded.failed_includes.push(span);
            return self.error(LoadError::IncludeLimit {
                files,
                bytes,
                max_files: MAX_FILES,
                max_mib: MAX_TOTAL_BYTES >> 20,
                src: from.named_source(),
                span: span.into(),
            });
        }
        (self.files_read, self.bytes_read) = (files, bytes);
        if self.stack.len() >= self.max_depth {
            self.loaded
                .errors
                .push(Report::new(LoadError::IncludeDepth {
                    limit: self.max_depth,
                    src: from.named_source(),
                    span: span.into(),
                }));
            return;
        }
        let id = self.loaded.sources.add(file);
        self.loaded.includes.push((span, id));
        self.file(id);
    }
}
