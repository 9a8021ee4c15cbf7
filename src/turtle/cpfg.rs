//! cpfg's line widths and sub-L-system scale: a turtle state and the
//! arguments of `#`, `!`, `?(n, s)` or `$` in, the state's scale and line
//! width out; and a finished drawing's pixel widths turned into units.
//! cpfg multiplies step lengths and widths by the scale of the sub-L-system
//! the turtle is in (interpret.c, `UpdateCurrentLsystem`), so a
//! sub-L-system written at its own size is drawn at its caller's.

use super::drawing::Drawing;
use super::interp::State;

/// cpfg's smallest line width (interpret.c's `MinWidth`).
const MIN_WIDTH: f32 = 1e-7;

/// How many pixels cpfg's window spans across the model: a width of one
/// pixel is this fraction of the drawing's largest extent.
const WINDOW_PIXELS: f32 = 600.0;

/// `#(w)` and `!(w)` both set the width to `w` (times the scale); without
/// a parameter `#` adds the view file's increment and `!` takes it away.
pub(super) fn set_width(s: &mut State, increase: bool, args: &[f64], increment: f32) {
    s.width = match args.first() {
        Some(&w) => w as f32 * s.scale,
        None if increase => s.width + increment * s.scale,
        None => s.width - increment * s.scale,
    }
    .max(MIN_WIDTH);
}

/// cpfg draws pixel-wide lines whatever the model's size; as tubes they
/// keep that look at [`WINDOW_PIXELS`] across the drawing.
pub(super) fn pixels_to_units(d: &mut Drawing) {
    let mut lo = glam::Vec3::splat(f32::INFINITY);
    let mut hi = glam::Vec3::splat(f32::NEG_INFINITY);
    let points = d.chains.iter().flat_map(|c| c.points.iter().map(|p| p.pos));
    for p in points.chain(d.polygons.iter().flat_map(|p| p.points.iter().copied())) {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let extent = (hi - lo).max_element();
    if !extent.is_finite() || extent <= 0.0 {
        return;
    }
    let unit = extent / WINDOW_PIXELS;
    for c in &mut d.chains {
        for p in &mut c.points {
            p.radius *= unit;
        }
    }
}

/// `?(n, s)`: remember the scale, multiply it by `s` (1 when absent), and
/// the line width with it.
pub(super) fn enter_sub(stack: &mut Vec<f32>, s: &mut State, args: &[f64]) {
    let before = s.scale;
    stack.push(before);
    if let Some(&k) = args.get(1) {
        s.scale = before * k as f32;
    }
    rescale_width(s, before);
}

/// `$`: back to the scale before the matching `?(n, s)`. An unmatched `$`
/// is ignored, as cpfg ignores it.
pub(super) fn leave_sub(stack: &mut Vec<f32>, s: &mut State) {
    let Some(outer) = stack.pop() else {
        return;
    };
    let before = s.scale;
    s.scale = outer;
    rescale_width(s, before);
}

fn rescale_width(s: &mut State, before: f32) {
    if before != 0.0 {
        s.width *= s.scale / before;
    }
}
