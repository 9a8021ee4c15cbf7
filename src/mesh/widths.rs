//! Line widths out of scale with the model. Widths are in the model's
//! units; ABOP and cpfg give them in pixels (`!(10)` for a trunk ten
//! pixels wide), so an ABOP grammar typed into a `.lsys` file with steps
//! of 1 draws tubes wider than the whole plant: a blob. (cpfg `.l` files
//! are read with cpfg's pixel widths, docs/cpfg.md.) Input: the drawing's
//! tube chains; output: a warning when the widths dwarf the model.

use super::error::MeshError;
use crate::resolve::Program;
use crate::turtle::Drawing;

/// The widest line may be at most this part of the model's largest side
/// (of its centre lines)…
pub const WIDEST: f32 = 0.75;
/// …and the typical one (the median over drawn length) this part. The
/// corpus's lamps have a base half as wide as the lamp, and its
/// generalized cylinders and Ulam fractals lines a tenth to a quarter of
/// the model: all drawn as meant, none warned.
pub const TYPICAL: f32 = 0.3;

/// The warning for `drawing`, if its line widths dwarf it. Runs on every
/// build: one pass for the bounds and the widest line, and the segments
/// are only collected and sorted for the median when the widest line is
/// wide enough for the median to matter (almost never).
pub fn wide_lines(program: &Program, drawing: &Drawing) -> Option<MeshError> {
    let mut lo = glam::Vec3::splat(f32::INFINITY);
    let mut hi = glam::Vec3::splat(f32::NEG_INFINITY);
    let mut widest = 0.0f32;
    for c in &drawing.chains {
        for p in &c.points {
            lo = lo.min(p.pos);
            hi = hi.max(p.pos);
        }
        for pair in c.points.windows(2) {
            widest = widest.max(pair[0].radius + pair[1].radius);
        }
    }
    let size = (hi - lo).max_element();
    // The typical line is no wider than the widest: below TYPICAL there
    // is nothing to say (and no chains at all gives a size of -inf).
    if size.is_nan() || size <= 0.0 || widest <= TYPICAL * size {
        return None;
    }
    // (width, drawn length) of every segment.
    let mut segments: Vec<(f32, f32)> = drawing
        .chains
        .iter()
        .flat_map(|c| {
            c.points
                .windows(2)
                .map(|p| (p[0].radius + p[1].radius, p[0].pos.distance(p[1].pos)))
        })
        .collect();
    let typical = weighted_median(&mut segments)?;
    if widest <= WIDEST * size && typical <= TYPICAL * size {
        return None;
    }
    let (src, span) = super::assemble::symbol_source(program, program.symbols.get("!"));
    Some(MeshError::WideLines(Box::new(super::error::WideLines {
        widest: short(widest),
        typical: short(typical),
        size: short(size),
        ratio: format!("{:.2}", widest / size),
        src,
        span,
    })))
}

/// The width at half the drawn length, segments sorted by width.
fn weighted_median(segments: &mut [(f32, f32)]) -> Option<f32> {
    segments.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f32 = segments.iter().map(|s| s.1).sum();
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let mut run = 0.0;
    segments.iter().find_map(|&(w, l)| {
        run += l;
        (run >= total / 2.0).then_some(w)
    })
}

fn short(x: f32) -> String {
    crate::turtle::scope::num(f64::from(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_is_over_drawn_length() {
        let mut s = [(1.0, 1.0), (5.0, 10.0), (2.0, 1.0)];
        assert_eq!(weighted_median(&mut s), Some(5.0));
        let mut s = [(1.0, 10.0), (5.0, 1.0)];
        assert_eq!(weighted_median(&mut s), Some(1.0));
    }
}
