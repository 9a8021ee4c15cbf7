//! Grammars from elevation drawings (seed 003): a line drawing (PNG or SVG)
//! -> an [`Inference`]: the shape tree with each node labelled, as JSON for
//! `--tree`, and a `.lsys` shape grammar that rebuilds the hall in 3D.
//!
//! ```text
//! drawing.rs   PNG or SVG -> ink bitmap (Otsu threshold; refuses photographs,
//!              filled pictures, blank pages, oversized images)
//! regions.rs   ink -> closed regions (specks erased, gaps bridged)
//! tree.rs      regions -> shape tree (alternating y/x cuts, top down)
//! label/       shape tree -> labelled tree (the seed's priors as rules;
//!              layers.rs: the bracket and rafter layers)
//! pitch/       labelled tree + ink -> the rafter row re-cut at the pitch
//!              its ink repeats at (rafters too small to keep a region;
//!              rafters.rs), and the bracket layer at its sets' pitch
//!              where the regions' count disagrees with it (brackets.rs)
//! outline.rs   labelled tree + ink -> doors and windows out to their drawn
//!              outlines (lines that gap bridging closed up)
//! correct.rs   labelled tree + the user's labels -> corrected tree
//! rules.rs     labelled tree -> measured sizes -> the grammar text
//! ```
//!
//! `docs/drawing.md` describes the method, its choices and the round trip
//! that measures it.

mod correct;
mod drawing;
mod error;
mod front;
mod label;
mod outline;
mod pitch;
mod regions;
mod rules;
mod tree;

use serde_json::{json, Value};

pub use correct::{known_label, Correction, LABELS};
pub use drawing::{binarize, is_svg, read_png, read_svg, stroke_lines, Ink, STROKE_WIDTH};
pub use error::InferError;
pub use front::{pailou_front, without_ground_line, PailouFront};
pub use regions::{paper, regions, Paper, Region};
pub use tree::{Axis, Node};

/// How to read a drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InferOptions {
    /// Line breaks up to twice this many pixels are bridged (0 to 8).
    pub gap: usize,
    /// Metres per pixel; `None` takes the columns as 4.2 m high.
    pub scale: Option<f64>,
}

impl Default for InferOptions {
    fn default() -> Self {
        InferOptions {
            gap: 2,
            scale: None,
        }
    }
}

/// What was read from a drawing.
#[derive(Clone, Debug)]
pub struct Inference {
    pub width: usize,
    pub height: usize,
    pub regions: Vec<Region>,
    pub tree: Node,
    /// Boxes of drawn regions no rule could label (not rebuilt).
    pub unlabelled: Vec<[i32; 4]>,
    /// Indices of the corrections whose box is no node's (not applied).
    pub missed: Vec<usize>,
    pub grammar: String,
    /// What kind of front was read, when not a hall's (a Pailou's: its
    /// style and type), for the reader.
    pub summary: Option<String>,
    /// Defines the grammar is to be built with that it cannot say itself
    /// (a Pailou's Toukung levels, `TM.NTL` and `TS.NTL`); empty for a hall.
    pub build_defines: Vec<(String, String)>,
}

/// Reads the drawing `bytes` (PNG or SVG), named `path` in messages and in
/// the grammar's heading.
pub fn infer(bytes: &[u8], path: &str, opts: &InferOptions) -> Result<Inference, InferError> {
    infer_ink(&read_drawing(bytes, path)?, path, opts)
}

/// Reads `bytes` (PNG or SVG) as an ink bitmap; `path` names it in
/// messages.
pub fn read_drawing(bytes: &[u8], path: &str) -> Result<Ink, InferError> {
    if is_svg(bytes) {
        read_svg(bytes, path)
    } else {
        read_png(bytes, path)
    }
}

/// Draws the separator strokes `strokes` (the seed's user strokes, a
/// picture of the drawing's size with lines where the drawing is
/// ambiguous: a missing line, two parts drawn as one) into `ink`.
/// `strokes_path` names the strokes in messages.
pub fn add_strokes(ink: &mut Ink, strokes: &Ink, strokes_path: &str) -> Result<(), InferError> {
    if (strokes.width, strokes.height) != (ink.width, ink.height) {
        return Err(InferError::StrokesSize {
            path: strokes_path.to_string(),
            width: strokes.width,
            height: strokes.height,
            drawing_width: ink.width,
            drawing_height: ink.height,
        });
    }
    for (a, &b) in ink.ink.iter_mut().zip(&strokes.ink) {
        *a |= b;
    }
    Ok(())
}

/// As [`infer`], from an ink bitmap.
pub fn infer_ink(ink: &Ink, path: &str, opts: &InferOptions) -> Result<Inference, InferError> {
    infer_corrected(ink, path, opts, &[])
}

/// As [`infer_ink`], with the user's `corrections` applied to the
/// recognised tree before the sizes are measured (the studio's drawing
/// page; see [`correct`]).
pub fn infer_corrected(
    ink: &Ink,
    path: &str,
    opts: &InferOptions,
    corrections: &[Correction],
) -> Result<Inference, InferError> {
    infer_regions(
        ink,
        regions::regions(ink, opts.gap.min(8)),
        path,
        opts,
        corrections,
    )
}

/// As [`infer_corrected`], with the drawing's `regions` read already (the
/// driver cleans a drawing once, to tell a Pailou's front from a hall's
/// and to read either).
pub fn infer_regions(
    ink: &Ink,
    regions: Vec<Region>,
    path: &str,
    opts: &InferOptions,
    corrections: &[Correction],
) -> Result<Inference, InferError> {
    let gap = opts.gap.min(8);
    if regions.is_empty() {
        return Err(InferError::NoRegions {
            path: path.to_string(),
        });
    }
    let bbox = regions
        .iter()
        .fold([i32::MAX, i32::MAX, i32::MIN, i32::MIN], |b, r| {
            [
                b[0].min(r.bbox[0]),
                b[1].min(r.bbox[1]),
                b[2].max(r.bbox[2]),
                b[3].max(r.bbox[3]),
            ]
        });
    // Empty strips narrower than this join their neighbours: about two
    // line widths, and at least a hundredth of the drawing.
    let tolerance = ((bbox[2] - bbox[0]).max(bbox[3] - bbox[1]) / 100).max(2 * gap as i32 + 2);
    let mut tree = tree::shape_tree(&regions, bbox, tolerance);
    let mut unlabelled = label::recognise(&mut tree, &regions);
    // Rafters are read from the ink's rhythm where it repeats: thickened
    // lines close them (pitch/rafters.rs).
    // So are bracket sets whose regions a shaky or blurred scan broke up
    // or closed, when the count they give is not the ink's (pitch/brackets.rs).
    let by_pitch = pitch::rafters(&mut tree, ink).is_some();
    if pitch::brackets(&mut tree, ink).is_some() || by_pitch {
        unlabelled = label::unlabelled(&tree, &regions);
    }
    outline::snap(&mut tree, ink);
    // After the snap: the boxes are those the user saw in the tree.
    let missed = correct::apply(&mut tree, corrections)?;
    if !corrections.is_empty() {
        unlabelled = label::unlabelled(&tree, &regions);
    }
    let measured = rules::measure(&tree, opts.scale, ink);
    let name = std::path::Path::new(path)
        .file_name()
        .map_or(path.to_string(), |n| n.to_string_lossy().into_owned());
    let grammar = measured.grammar(&name, unlabelled.len());
    Ok(Inference {
        width: ink.width,
        height: ink.height,
        regions,
        tree,
        unlabelled,
        missed,
        grammar,
        summary: None,
        build_defines: Vec::new(),
    })
}

impl Inference {
    /// `{"width", "height", "root"}`, each node `{"label", "box", "split",
    /// "repeat", "children"}` in drawing pixels with y down.
    pub fn tree_json(&self) -> Value {
        json!({"width": self.width, "height": self.height, "root": node_json(&self.tree)})
    }

    /// What `lsys infer` reports and the studio shows: for columns, bays,
    /// doors, windows, bracket sets and rafters, (label, plural, nodes so
    /// labelled anywhere in the tree: bays are inner nodes).
    pub fn counts(&self) -> Vec<(&'static str, &'static str, usize)> {
        fn nodes(n: &Node, label: &str) -> usize {
            usize::from(n.label == label)
                + n.children.iter().map(|c| nodes(c, label)).sum::<usize>()
        }
        [
            ("column", "columns"),
            ("bay", "bays"),
            ("door", "doors"),
            ("window", "windows"),
            ("bracket", "bracket sets"),
            ("rafter", "rafters"),
        ]
        .into_iter()
        .map(|(l, p)| (l, p, nodes(&self.tree, l)))
        .collect()
    }

    /// Leaves labelled `label`.
    pub fn count(&self, label: &str) -> usize {
        self.tree
            .leaves()
            .iter()
            .filter(|n| n.label == label)
            .count()
    }
}

fn node_json(n: &Node) -> Value {
    json!({
        "label": n.label,
        "box": n.bbox,
        "split": n.split.map(|a| match a { Axis::X => "x", Axis::Y => "y" }),
        "repeat": n.repeat,
        "children": n.children.iter().map(node_json).collect::<Vec<_>>(),
    })
}
