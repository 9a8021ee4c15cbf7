//! One document's analysis. Input: the document's text and path (and the
//! server's compile options); output: an [`Analysis`] with every file the
//! model read (root, includes, the standard library), the syntax [`Index`]
//! of every named occurrence, the compiler's result (a compiled grammar or
//! its [`Diagnostics`], exactly as `lsys check` gets them) and the URI of
//! each file.
//!
//! The text is compiled as if it were the file at its path
//! ([`Input::Edited`]), so `#include "x"` resolves beside it. Included
//! files that are open in the editor are read from their unsaved text (the
//! server passes them in the options), the others from disk. Standard
//! library files have no path: they are written once to a cache folder so
//! that an editor can open them.

use std::path::{Path, PathBuf};

use lsp_types::Url;

use super::index::Index;
use crate::diag::Diagnostics;
use crate::load::{self, Input};
use crate::parse::ast::Item;
use crate::pipeline::{self, Compilation};
use crate::source::{FileId, Origin, SourceMap, Span};

/// The root document is always file 0.
pub const ROOT: FileId = 0;

pub struct Analysis {
    pub uri: Url,
    /// The document's text as the editor has it. For a cpfg model (`.l`)
    /// the root in [`Analysis::sources`] is the preprocessor's output
    /// instead: the same lines, but columns move after an expanded macro.
    pub doc: String,
    pub sources: SourceMap,
    pub items: Vec<(FileId, Item)>,
    /// Each loaded `#include` path's span and the file it loaded.
    pub includes: Vec<(Span, FileId)>,
    pub index: Index,
    pub result: Result<Compilation, Diagnostics>,
    pub profile: crate::lang::Profile,
    /// The code lenses, derived once per analysis (the editor asks again
    /// after every edit and on scrolling).
    pub lenses: std::cell::OnceCell<Vec<lsp_types::CodeLens>>,
    uris: Vec<Option<Url>>,
}

impl Analysis {
    /// Loads and compiles `text` as the document `uri`.
    pub fn new(uri: &Url, text: &str, opts: &load::Options) -> Analysis {
        let input = match uri.to_file_path() {
            Ok(path) => Input::Edited {
                path,
                text: text.to_string(),
            },
            Err(()) => Input::Text {
                name: uri.to_string(),
                text: text.to_string(),
            },
        };
        let (sources, items, includes, profile, result) =
            match load::load(&input, &pipeline::own_options(opts)) {
                Ok(l) => (
                    l.sources.clone(),
                    l.items.clone(),
                    l.includes.clone(),
                    l.profile,
                    pipeline::compile_loaded(l, opts),
                ),
                Err(e) => (
                    SourceMap::new(),
                    Vec::new(),
                    Vec::new(),
                    crate::lang::Profile::decide("", text, opts.dialect),
                    Err(Diagnostics::input(e)),
                ),
            };
        let index = Index::build(&items, &includes, &profile);
        let uris = sources
            .files()
            .iter()
            .enumerate()
            .map(|(i, f)| {
                if i == ROOT as usize {
                    return Some(uri.clone());
                }
                match &f.origin {
                    Origin::Disk(p) => Url::from_file_path(absolute(p)).ok(),
                    Origin::Std(name) => std_file(name).and_then(|p| Url::from_file_path(p).ok()),
                    Origin::Memory => None,
                }
            })
            .collect();
        Analysis {
            uri: uri.clone(),
            doc: text.to_string(),
            sources,
            items,
            includes,
            index,
            result,
            profile,
            lenses: Default::default(),
            uris,
        }
    }

    /// The URI of a loaded file, if an editor can open it.
    pub fn uri_of(&self, file: FileId) -> Option<&Url> {
        self.uris.get(file as usize)?.as_ref()
    }

    /// Whether the model read the file at `uri` (itself or an include).
    pub fn reads(&self, uri: &Url) -> bool {
        self.uris.iter().any(|u| u.as_ref() == Some(uri))
    }

    /// The loaded file a diagnostic names (miette gives the source's name).
    pub fn file_named(&self, name: &str) -> Option<FileId> {
        self.sources
            .files()
            .iter()
            .position(|f| f.name == name)
            .map(|i| i as FileId)
    }

    /// A loaded file's text ("" when the model could not be loaded).
    pub fn text(&self, file: FileId) -> &str {
        self.sources
            .files()
            .get(file as usize)
            .map_or("", |f| f.text.as_str())
    }

    /// The `#include` line (span in the root file) through which `file`
    /// was loaded, following nested includes up to the root.
    pub fn root_include(&self, mut file: FileId) -> Option<Span> {
        for _ in 0..self.includes.len() {
            let &(span, _) = self.includes.iter().find(|(_, f)| *f == file)?;
            if span.file == ROOT {
                return Some(span);
            }
            file = span.file;
        }
        None
    }

    /// The compiled program, when the grammar compiles.
    pub fn program(&self) -> Option<&crate::resolve::Program> {
        self.result.as_ref().ok().map(|c| &c.program)
    }
}

fn absolute(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    })
}

/// The standard library file `name` as a file on disk, written to a cache
/// folder (per lsys version) the first time it is asked for.
/// Checked and written once per process: every analysis (every keystroke)
/// asks for the URIs of the library files the model reads.
pub fn std_file(name: &str) -> Option<PathBuf> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static WRITTEN: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let written = WRITTEN.get_or_init(Default::default);
    if let Some(p) = written.lock().ok()?.get(name) {
        return Some(p.clone());
    }
    let text = crate::stdlib::get(name)?;
    let dir = std::env::temp_dir().join(format!("lsys-std-{}", env!("CARGO_PKG_VERSION")));
    let path = dir.join(format!("{}.lsys", name.trim_end_matches(".lsys")));
    if std::fs::read_to_string(&path).ok().as_deref() != Some(text) {
        std::fs::create_dir_all(&dir).ok()?;
        std::fs::write(&path, text).ok()?;
    }
    written.lock().ok()?.insert(name.to_string(), path.clone());
    Some(path)
}
