//! Load: a cpfg file through the C preprocessor. The root `.l` file in,
//! its preprocessed text and that of every file it includes out (the C
//! preprocessor of [`crate::preprocess`]), with the include sites the
//! loader splices.
//!
//! Each preprocessed file keeps its original line count, so everything
//! the later stages report points at the right file and line; the
//! snippet shows the line as the parser saw it (macros expanded).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::Report;

use super::include::IncludeFinder;
use super::loader::Loader;
use crate::preprocess::{self, OutFile, RawFile};
use crate::source::{FileId, Origin, SourceFile, Span};

/// The preprocessor's output and the file id each of its files got.
pub(crate) struct Preprocessed {
    pub out: Vec<OutFile>,
    pub ids: HashMap<FileId, usize>,
}

/// The preprocessor's `#include "x"` files, found by the loader's
/// [`IncludeFinder`]: beside the including file, then in the
/// `--include-dir`s, inside the allowed folders, within the size limit.
struct IncludeFiles<'a>(&'a IncludeFinder);

impl preprocess::Resolver for IncludeFiles<'_> {
    fn resolve(
        &mut self,
        including: &RawFile,
        name: &str,
        _angled: bool,
    ) -> Result<RawFile, String> {
        let base = including
            .key
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let (full, text) = self.0.find(&base, name).map_err(|r| r.message())?;
        Ok(RawFile {
            name: full.display().to_string(),
            key: full,
            text,
        })
    }
}

impl Loader {
    /// Preprocess the root and everything it includes; the root comes back
    /// with its preprocessed text, the rest waits in `self.pre`.
    pub(super) fn preprocess(
        &mut self,
        root: SourceFile,
        defines: &[(String, String)],
    ) -> SourceFile {
        let key = match &root.origin {
            Origin::Disk(p) => p.clone(),
            _ => PathBuf::from(&root.name),
        };
        let raw = RawFile {
            name: root.name.clone(),
            key,
            text: root.text.as_str().to_string(),
        };
        let opts = preprocess::Options {
            defines: defines.to_vec(),
            max_include_depth: self.max_depth,
            ..Default::default()
        };
        let mut files = IncludeFiles(&self.finder);
        let (out, errors) = preprocess::preprocess(raw, &mut files, &opts);
        for e in errors {
            let f = &out.files[e.file.min(out.files.len() - 1)].raw;
            let d = e.to_diagnostic(&f.name, Arc::new(f.text.clone()));
            if e.warning {
                self.loaded.warnings.push(Report::new(d));
            } else {
                self.loaded.errors.push(Report::new(d));
            }
        }
        self.loaded.preprocessed = true;
        let text = out.files[0].text.clone();
        self.pre = Some(Preprocessed {
            out: out.files,
            ids: HashMap::new(),
        });
        SourceFile::new(root.name, root.origin, text)
    }

    /// An `#include` line of a preprocessed file: enter the file the
    /// preprocessor read there.
    pub(super) fn include_preprocessed(&mut self, id: FileId, from: &SourceFile, span: Span) {
        let (line, _) = from.line_col(span.start);
        let Some(pre) = &self.pre else { return };
        let Some(&k) = pre.ids.get(&id) else { return };
        let Some(site) = pre.out[k].includes.iter().find(|s| s.line == line) else {
            // The preprocessor reported why it could not read the file.
            return;
        };
        let child = &pre.out[site.file];
        let file = SourceFile::new(
            child.raw.name.clone(),
            Origin::Disk(child.raw.key.clone()),
            child.text.clone(),
        );
        // `enter` gives the file the next id and parses it at once (its
        // own includes need the mapping); if it refuses the file, the next
        // file to get that id overwrites the entry.
        let j = site.file;
        let next = self.loaded.sources.files().len() as FileId;
        if let Some(pre) = &mut self.pre {
            pre.ids.insert(next, j);
        }
        self.enter(from, file, span);
    }
}
