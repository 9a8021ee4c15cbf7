//! A drawing as a job (`lsys infer`, the studio's drawing page): a line
//! drawing's path (and its separator strokes') -> the [`Inference`] (shape
//! tree, grammar; a hall's by seed 003's reading, a Pailou's front by
//! synthesis, `infer_pailou.rs`), the grammar
//! compiled once to prove it builds, and both written atomically: the
//! grammar and the tree appear together or not at all.

use std::path::Path;

use crate::export::atomic::AtomicFiles;
use crate::infer;
use crate::Diagnostics;

pub use crate::infer::{
    Correction, InferError, InferOptions, Inference, Ink, Node as InferNode, LABELS as INFER_LABELS,
};

/// Why a drawing gave no grammar.
#[derive(Debug)]
pub enum InferFailure {
    /// The drawing could not be read or is not a line drawing.
    Drawing(InferError),
    /// The inferred grammar does not compile (a bug of ours: the text is
    /// kept so that it can be reported).
    Grammar(Diagnostics),
    /// An output could not be written.
    Write(std::io::Error),
}

/// The vocabulary's spelling of a label the user gave, or why not.
pub fn infer_label(label: &str) -> Result<&'static str, InferError> {
    infer::known_label(label)
}

/// Reads the drawing at `path`, with the separator strokes at `strokes`
/// drawn into it when given, and infers its hall with the user's label
/// `corrections`.
pub fn infer_drawing(
    path: &Path,
    strokes: Option<&Path>,
    corrections: &[Correction],
    opts: &InferOptions,
) -> Result<Inference, InferFailure> {
    let read = |path: &Path| {
        let shown = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| InferError::Unreadable {
            path: shown.clone(),
            reason: e.to_string(),
        })?;
        infer::read_drawing(&bytes, &shown).map(|ink| (ink, shown))
    };
    let (mut ink, shown) = read(path).map_err(InferFailure::Drawing)?;
    if let Some(strokes) = strokes {
        let (lines, strokes_shown) = read(strokes).map_err(InferFailure::Drawing)?;
        infer::add_strokes(&mut ink, &lines, &strokes_shown).map_err(InferFailure::Drawing)?;
    }
    let inference = infer_ink(&ink, &shown, opts, corrections)?;
    crate::Grammar::from_str("inferred.lsys", &inference.grammar).map_err(InferFailure::Grammar)?;
    Ok(inference)
}

/// A Pailou's front is read by synthesis (`infer_pailou`), anything else
/// as a hall (seed 003's reading). A Pailou's tree takes no label
/// corrections: each is reported as missed.
fn infer_ink(
    ink: &Ink,
    shown: &str,
    opts: &InferOptions,
    corrections: &[Correction],
) -> Result<Inference, InferFailure> {
    let gap = opts.gap.min(8);
    let paper = infer::paper(ink, gap);
    let pailou = |ink: &Ink, front: &infer::PailouFront, regions| {
        let mut inference =
            super::infer_pailou::read_pailou(ink, front, regions, shown, opts.scale, gap)
                .map_err(InferFailure::Drawing)?;
        inference.missed = (0..corrections.len()).collect();
        Ok(inference)
    };
    if let Some(front) = infer::pailou_front(ink, &paper.outside) {
        return pailou(ink, &front, paper.regions);
    }
    // A Pailou drawn standing on a ground line: its passages are closed.
    if let Some(open) = infer::without_ground_line(ink, &paper.regions, gap) {
        let cleared = infer::paper(&open, gap);
        if let Some(front) = infer::pailou_front(&open, &cleared.outside) {
            return pailou(&open, &front, cleared.regions);
        }
    }
    infer::infer_regions(ink, paper.regions, shown, opts, corrections)
        .map_err(InferFailure::Drawing)
}

/// Reads a drawing's `bytes` (PNG or SVG), named `shown` in messages: an
/// upload to the studio, or a file of its folder.
pub fn read_drawing(bytes: &[u8], shown: &str) -> Result<Ink, InferFailure> {
    infer::read_drawing(bytes, shown).map_err(InferFailure::Drawing)
}

/// Infers the hall of `ink` (named `shown`) with separator strokes drawn
/// by hand (`lines`: polylines in its pixels) and the user's label
/// `corrections` (the studio's drawing page). Unlike [`infer_drawing`] it
/// does not compile the grammar: the caller builds it, and that build is
/// the proof (one compile, not two, at every edit).
pub fn infer_edited(
    ink: &Ink,
    shown: &str,
    lines: &[Vec<[f32; 2]>],
    corrections: &[Correction],
    opts: &InferOptions,
) -> Result<Inference, InferFailure> {
    let mut ink = ink.clone();
    if !lines.is_empty() {
        let strokes = infer::stroke_lines(ink.width, ink.height, lines);
        infer::add_strokes(&mut ink, &strokes, "the strokes").map_err(InferFailure::Drawing)?;
    }
    infer_ink(&ink, shown, opts, corrections)
}

/// Writes the grammar to `grammar` and, when asked, the tree to `tree`.
pub fn write_inference(
    inference: &Inference,
    grammar: &Path,
    tree: Option<&Path>,
) -> Result<(), InferFailure> {
    let mut files = AtomicFiles::new();
    files
        .write(grammar, |w| w.write_all(inference.grammar.as_bytes()))
        .map_err(InferFailure::Write)?;
    if let Some(tree) = tree {
        let mut text = serde_json::to_string_pretty(&inference.tree_json())
            .map_err(|e| InferFailure::Write(std::io::Error::other(e)))?;
        text.push('\n');
        files
            .write(tree, |w| w.write_all(text.as_bytes()))
            .map_err(InferFailure::Write)?;
    }
    files.commit().map_err(InferFailure::Write)
}
