//! Source files and spans: input is file text (from disk, the embedded
//! standard library or memory), output is a [`SourceMap`] that every later
//! stage points into with [`Span`]s, and that diagnostics render from.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{NamedSource, SourceSpan};

/// Index of a file in a [`SourceMap`].
pub type FileId = u32;

/// A byte range in one source file. Small and `Copy` so that every AST node,
/// IR node and bytecode instruction can carry one.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    pub file: FileId,
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub fn new(file: FileId, start: usize, end: usize) -> Span {
        Span {
            file,
            start: start as u32,
            end: end as u32,
        }
    }

    /// The smallest span covering both (same file assumed).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    pub fn len(self) -> usize {
        (self.end - self.start) as usize
    }

    pub fn is_empty(self) -> bool {
        self.end == self.start
    }
}

impl fmt::Debug for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}@{}..{}", self.file, self.start, self.end)
    }
}

thread_local! {
    /// How spans being deserialized are read (see [`in_file`]).
    static READING: std::cell::Cell<(FileId, u32, i64)> = const { std::cell::Cell::new((0, 0, 0)) };
}

/// Spans are stored without their file: a standard library file's syntax
/// tree is stored once, when the crate is built (`build.rs`), and its file
/// gets its id only when a run loads it. A span read back belongs to the
/// file that [`in_file`] names.
impl serde::Serialize for Span {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serde::Serialize::serialize(&(self.start, self.end), s)
    }
}

impl<'de> serde::Deserialize<'de> for Span {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Span, D::Error> {
        let (start, end) = <(u32, u32)>::deserialize(d)?;
        let (file, from, shift) = READING.with(std::cell::Cell::get);
        let moved =
            |at: u32| u32::try_from(i64::from(at) + shift).map_err(serde::de::Error::custom);
        Ok(if start >= from && shift != 0 {
            Span {
                file,
                start: moved(start)?,
                end: moved(end)?,
            }
        } else {
            Span { file, start, end }
        })
    }
}

/// Runs `read`, which deserializes spans, with those spans in file `file`
/// and the ones that start at `from` or later moved by `shift` bytes (a
/// stored tree's last part, in a text where it stands elsewhere).
pub fn in_file<T>(file: FileId, from: u32, shift: i64, read: impl FnOnce() -> T) -> T {
    let before = READING.with(|r| r.replace((file, from, shift)));
    let out = read();
    READING.with(|r| r.set(before));
    out
}

impl From<Span> for SourceSpan {
    fn from(s: Span) -> SourceSpan {
        SourceSpan::new((s.start as usize).into(), s.len())
    }
}

/// Where a file came from; decides how `#include "x"` inside it is resolved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A file on disk (the path as given, used for display and relative includes).
    Disk(PathBuf),
    /// A standard library file embedded in the binary (`std:NAME`, `#include <NAME>`).
    Std(String),
    /// Text that came from memory (tests, the REPL, `-e`).
    Memory,
}

/// One loaded source file.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// Name shown in diagnostics (`examples/abop/koch.lsys`, `std:toukung_middle`).
    pub name: String,
    pub origin: Origin,
    pub text: Arc<String>,
    line_starts: Arc<Vec<u32>>,
}

impl SourceFile {
    pub fn new(name: impl Into<String>, origin: Origin, text: impl Into<String>) -> SourceFile {
        let text: String = text.into();
        SourceFile {
            name: name.into(),
            origin,
            line_starts: Arc::new(line_starts(&text)),
            text: Arc::new(text),
        }
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: u32) -> (usize, usize) {
        let line = match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.line_starts[line] as usize;
        let end = (offset as usize).min(self.text.len());
        let col = self
            .text
            .get(start..end)
            .map_or(1, |s| s.chars().count() + 1);
        (line + 1, col)
    }

    /// The directory relative includes are resolved against, if any.
    pub fn dir(&self) -> Option<&Path> {
        match &self.origin {
            Origin::Disk(p) => p.parent(),
            _ => None,
        }
    }

    /// The text as miette wants it for a labelled snippet.
    pub fn named_source(&self) -> NamedSource<SourceText> {
        NamedSource::new(
            &self.name,
            SourceText(Arc::new(Lines {
                text: self.text.clone(),
                starts: self.line_starts.clone(),
            })),
        )
    }
}

/// All files of one compilation, the root first, then includes in load order.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    pub fn add(&mut self, file: SourceFile) -> FileId {
        self.files.push(file);
        (self.files.len() - 1) as FileId
    }

    pub fn get(&self, id: FileId) -> &SourceFile {
        &self.files[id as usize]
    }

    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// The files read from disk, in load order: what a model depends on
    /// (text from memory and the standard library is not on disk).
    pub fn disk_paths(&self) -> Vec<PathBuf> {
        self.files
            .iter()
            .filter_map(|f| match &f.origin {
                Origin::Disk(p) => Some(p.clone()),
                _ => None,
            })
            .collect()
    }

    /// The source text a span points into.
    pub fn slice(&self, span: Span) -> &str {
        let f = self.get(span.file);
        f.text
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// `file:line:col` of the start of a span, for one-line messages.
    pub fn location(&self, span: Span) -> String {
        let f = self.get(span.file);
        let (l, c) = f.line_col(span.start);
        format!("{}:{}:{}", f.name, l, c)
    }

    pub fn named_source(&self, span: Span) -> NamedSource<SourceText> {
        self.get(span.file).named_source()
    }
}

/// A file's text for miette, with the starts of its lines. miette's own
/// `SourceCode` for text walks it from the first byte to every label, so
/// a file with thousands of diagnostics was printed in quadratic time
/// (20,000 errors: 12 s, issue 36). This one starts the walk at the first
/// line of the snippet, found by binary search.
///
/// One pointer, as the `Arc<String>` it replaces: diagnostics carry one
/// per label and stay small.
#[derive(Clone, Debug)]
pub struct SourceText(Arc<Lines>);

#[derive(Debug)]
struct Lines {
    text: Arc<String>,
    starts: Arc<Vec<u32>>,
}

impl From<Arc<String>> for SourceText {
    fn from(text: Arc<String>) -> SourceText {
        SourceText(Arc::new(Lines {
            starts: Arc::new(line_starts(&text)),
            text,
        }))
    }
}

impl From<String> for SourceText {
    fn from(text: String) -> SourceText {
        SourceText::from(Arc::new(text))
    }
}

impl miette::SourceCode for SourceText {
    fn read_span<'a>(
        &'a self,
        span: &miette::SourceSpan,
        before: usize,
        after: usize,
    ) -> Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        let Lines { text, starts } = &*self.0;
        let offset = u32::try_from(span.offset()).unwrap_or(u32::MAX);
        let line = match starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        };
        let first = line.saturating_sub(before);
        let base = starts.get(first).map_or(0, |&b| b as usize);
        let base = base.min(text.len()).min(span.offset());
        let shifted = miette::SourceSpan::new((span.offset() - base).into(), span.len());
        let rest: &'a [u8] = &text.as_bytes()[base..];
        let c = rest.read_span(&shifted, before, after)?;
        let first = if base == 0 { 0 } else { first };
        Ok(Box::new(miette::MietteSpanContents::new(
            c.data(),
            miette::SourceSpan::new((c.span().offset() + base).into(), c.span().len()),
            c.line() + first,
            c.column(),
            c.line_count(),
        )))
    }
}

/// The byte offsets at which the lines of `text` start.
fn line_starts(text: &str) -> Vec<u32> {
    let mut starts = vec![0u32];
    starts.extend(
        text.bytes()
            .enumerate()
            .filter(|&(_, b)| b == b'\n')
            .map(|(i, _)| i as u32 + 1),
    );
    starts
}
