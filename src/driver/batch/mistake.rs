//! A manifest's mistake as a diagnostic: which line, what is wrong (not
//! JSON, a wrong item, an id used twice) and where, over the manifest's
//! text. Input: what `manifest.rs` found; output: a miette diagnostic
//! with code `lsys::batch::json`, `duplicate_id` or the item's own.

use miette::{Diagnostic, LabeledSpan, NamedSource, SourceSpan};

use super::item::ItemError;

/// One mistake in a manifest, at its place.
#[derive(Debug)]
pub struct ManifestError {
    /// The whole manifest, shared by its mistakes (a manifest may have
    /// many thousand lines).
    pub(super) src: NamedSource<crate::source::SourceText>,
    pub(super) span: SourceSpan,
    /// The line, from 1.
    pub line: usize,
    pub kind: Mistake,
}

/// What the mistake is.
#[derive(Debug)]
pub enum Mistake {
    /// The line is not JSON (serde_json's message).
    Json(String),
    /// The item's fields are wrong.
    Item(ItemError),
    /// The id was already used, at `first` (a line from 1, and the span
    /// of the id there).
    Duplicate {
        id: String,
        first: usize,
        first_span: SourceSpan,
    },
}

impl std::fmt::Display for ManifestError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            Mistake::Json(m) => write!(f, "line {} is not JSON: {m}", self.line),
            Mistake::Item(e) => write!(f, "line {}: {e}", self.line),
            Mistake::Duplicate { id, first, .. } => write!(
                f,
                "line {}: the id `{id}` is already used on line {first}",
                self.line
            ),
        }
    }
}

impl std::error::Error for ManifestError {}

impl Diagnostic for ManifestError {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        match &self.kind {
            Mistake::Json(_) => Some(Box::new("lsys::batch::json")),
            Mistake::Item(e) => e.code(),
            Mistake::Duplicate { .. } => Some(Box::new("lsys::batch::duplicate_id")),
        }
    }

    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        match &self.kind {
            Mistake::Json(_) => Some(Box::new(
                "each line of a manifest is one JSON object, on one line (JSON Lines)",
            )),
            Mistake::Item(e) => e.help(),
            Mistake::Duplicate { .. } => Some(Box::new(
                "an id names its output file and its line in index.jsonl: each must be unique",
            )),
        }
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        Some(&self.src)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let here = match &self.kind {
            Mistake::Json(_) => "here",
            Mistake::Item(ItemError::UnknownKey { .. }) => "this key",
            Mistake::Item(ItemError::MissingKey { .. } | ItemError::NotAnObject { .. }) => {
                "this item"
            }
            Mistake::Item(_) => "this value",
            Mistake::Duplicate { .. } => "used again here",
        };
        let mut labels = vec![LabeledSpan::new_primary_with_span(
            Some(here.into()),
            self.span,
        )];
        if let Mistake::Duplicate { first_span, .. } = &self.kind {
            labels.push(LabeledSpan::new_with_span(
                Some("first used here".into()),
                *first_span,
            ));
        }
        Some(Box::new(labels.into_iter()))
    }
}
