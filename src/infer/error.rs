//! The inference stage's one error enum: a drawing that cannot be read,
//! is not a line drawing, is too big, has nothing to build from, or whose
//! separator strokes do not fit it.

use miette::Diagnostic;
use thiserror::Error;

/// Largest drawing accepted, in pixels (width times height).
pub const MAX_PIXELS: u64 = 40_000_000;
/// Largest width or height accepted, in pixels.
pub const MAX_SIDE: u32 = 16384;

#[derive(Debug, Error, Diagnostic)]
pub enum InferError {
    #[error("{path}: cannot read the drawing: {reason}")]
    #[diagnostic(
        code(lsys::infer::unreadable),
        help("give a PNG image or an SVG drawing (dark lines on white) of the elevation")
    )]
    Unreadable { path: String, reason: String },

    #[error("{path}: {width} x {height} pixels is too big to read")]
    #[diagnostic(
        code(lsys::infer::too_big),
        help("scale the drawing down to at most 16384 pixels a side and 40 million in all; 1000 to 3000 pixels across is plenty")
    )]
    TooBig {
        path: String,
        width: u32,
        height: u32,
    },

    #[error("{path}: this is not a line drawing: {reason}")]
    #[diagnostic(
        code(lsys::infer::not_a_line_drawing),
        help("`lsys infer` reads elevations drawn as dark lines on a light background (a scan, an export from a drawing program, or `lsys render --style lines --view front`); photographs and filled pictures are not read")
    )]
    NotALineDrawing { path: String, reason: String },

    #[error("{path}: the separator strokes are {width} x {height} pixels, the drawing {drawing_width} x {drawing_height}")]
    #[diagnostic(
        code(lsys::infer::strokes_size),
        help("draw the strokes on a copy of the drawing, or on a layer of its size, and export that at the drawing's size")
    )]
    StrokesSize {
        path: String,
        width: usize,
        height: usize,
        drawing_width: usize,
        drawing_height: usize,
    },

    #[error("{path}: the drawing has no closed regions")]
    #[diagnostic(
        code(lsys::infer::no_regions),
        help("the lines must close around areas (a column's outline, a window's frame); if they almost do, raise --gap to bridge wider breaks")
    )]
    NoRegions { path: String },

    #[error("{path}: read as a Pailou front, but {reason}")]
    #[diagnostic(
        code(lsys::infer::not_a_pailou),
        help("the drawing's ground pillars stand free, so it was read as a Pailou; draw a hall's bays closed (walls, doors, windows) to have it read as a hall")
    )]
    NotPailou { path: String, reason: String },

    #[error("\"{label}\" is not a label of the shape tree")]
    #[diagnostic(code(lsys::infer::unknown_label), help("a node is one of: {known}"))]
    UnknownLabel { label: String, known: String },
}
