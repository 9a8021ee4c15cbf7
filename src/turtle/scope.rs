//! Scopes and splits (docs/shapes.md). Input: the turtle's frame, the
//! scope's size and a split command's parameters; output: the sub-scopes
//! each following branch is drawn in, or a [`Misfit`] that says which
//! sizes did not fit and by how much. The scope is turtle state: its
//! origin is the turtle's position, its axes are x = H × U, y = H, z = U,
//! so splits need no derivation-time knowledge of sizes (why the splits
//! live here rather than in derive: docs/shapes.md, "Where splits run").

use glam::DVec3;

use super::frame::Frame;
use crate::lang::builtins::REL_BASE;
use crate::lang::scope_commands::Axis;

/// Sizes within this fraction of the scope are equal: floating-point
/// slack, including `rel(f)`'s encoding (about 1e-10).
const EPS: f64 = 1e-6;

/// One size of a subdivision split.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Size {
    Absolute(f64),
    /// Shares what the absolute and relative sizes leave, by weight.
    Floating(f64),
    /// A fraction of the scope.
    Relative(f64),
}

impl Size {
    /// `flo(w)` and `rel(f)` arrive as negative numbers (lang::builtins).
    pub fn decode(v: f64) -> Size {
        if v >= 0.0 {
            Size::Absolute(v)
        } else if v <= -REL_BASE {
            Size::Relative(-v - REL_BASE)
        } else {
            Size::Floating(-v)
        }
    }

    pub fn text(self) -> String {
        match self {
            Size::Absolute(s) => num(s),
            Size::Floating(w) => format!("flo({})", num(w)),
            Size::Relative(f) => format!("rel({})", num(f)),
        }
    }
}

/// Why a split cannot be laid out.
#[derive(Clone, Debug, PartialEq)]
pub struct Misfit {
    /// What was asked, e.g. `2 + 3 + 2 = 7 along x`.
    pub asked: String,
    /// The scope's size along the split axis.
    pub scope: f64,
    /// What is wrong and by how much.
    pub problem: String,
    pub help: String,
}

pub(crate) fn num(x: f64) -> String {
    num_places(x, 3)
}

/// `x` with at most `places` decimals, trailing zeros dropped.
pub(crate) fn num_places(x: f64, places: usize) -> String {
    // Sizes far from 1 (a 1e308 scope, a denormal piece) in exponent form:
    // three decimals would print 309 digits, or 0.
    if x != 0.0 && x.is_finite() && !(1e-3..1e15).contains(&x.abs()) {
        return format!("{x:e}");
    }
    let s = format!("{x:.places$}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// The piece sizes of `@SX(s1,...)` over a scope `total` long.
pub fn subdivide(total: f64, raw: &[f64], axis: Axis) -> Result<Vec<f64>, Misfit> {
    let sizes: Vec<Size> = raw.iter().map(|&v| Size::decode(v)).collect();
    let fixed: f64 = sizes
        .iter()
        .map(|s| match *s {
            Size::Absolute(a) => a,
            Size::Relative(f) => f * total,
            Size::Floating(_) => 0.0,
        })
        .sum();
    let weight: f64 = sizes
        .iter()
        .map(|s| match *s {
            Size::Floating(w) => w,
            _ => 0.0,
        })
        .sum();
    let rest = total - fixed;
    let asked = format!(
        "{} along {}",
        sizes
            .iter()
            .map(|s| s.text())
            .collect::<Vec<_>>()
            .join(" + "),
        axis.name()
    );
    let fixed_text = num(fixed);
    if rest < -EPS * total.max(1.0) {
        return Err(Misfit {
            asked,
            scope: total,
            problem: format!(
                "the fixed sizes add up to {fixed_text}, {} more than the scope's {}",
                num(-rest),
                num(total)
            ),
            help: "make the absolute sizes smaller, or give the scope more room".into(),
        });
    }
    if weight <= 0.0 && rest > EPS * total.max(1.0) {
        return Err(Misfit {
            asked,
            scope: total,
            problem: format!(
                "the sizes add up to {fixed_text}, leaving {} of the scope's {} unfilled",
                num(rest),
                num(total)
            ),
            help: "make one size floating, e.g. flo(1), to take up what is left".into(),
        });
    }
    Ok(sizes
        .iter()
        .map(|s| match *s {
            Size::Absolute(a) => a,
            Size::Relative(f) => f * total,
            Size::Floating(w) => rest.max(0.0) * w / weight,
        })
        .collect())
}

/// The most pieces one repeat (`@RX`, or each side of `@RSX`) lays out.
/// Checked before the pieces are allocated: a tiny or denormal piece in a
/// large scope asked for 10^8 to 10^300 of them and aborted the run.
pub const MAX_COPIES: usize = 100_000;

/// The refusal of a repeat of `n` (a float: it may be infinite) copies.
fn too_many(asked: String, total: f64, n: f64) -> Misfit {
    let count = if !n.is_finite() {
        "infinitely many".to_string()
    } else if n < 1e15 {
        format!("{n:.0}")
    } else {
        format!("{n:e}")
    };
    Misfit {
        asked,
        scope: total,
        problem: format!(
            "it would lay out {count} copies, more than the {MAX_COPIES} one repeat may"
        ),
        help: "make the piece larger or the scope smaller (docs/limits.md)".into(),
    }
}

/// `@RX(s)`: as many copies as fit (at least one), stretched to fill.
pub fn repeat(total: f64, size: f64, axis: Axis) -> Result<Vec<f64>, Misfit> {
    if size <= 0.0 {
        return Err(Misfit {
            asked: format!("copies of size {} along {}", num(size), axis.name()),
            scope: total,
            problem: "a repeated piece needs a size above 0".into(),
            help: "give @R a positive size".into(),
        });
    }
    let n = (total / size + EPS).floor();
    if n.is_nan() || n > MAX_COPIES as f64 {
        let asked = format!("copies of size {} along {}", num(size), axis.name());
        return Err(too_many(asked, total, n));
    }
    if n < 1.0 {
        return Err(Misfit {
            asked: format!("copies of size {} along {}", num(size), axis.name()),
            scope: total,
            problem: format!(
                "not even one fits: the piece is {} longer than the scope's {}",
                num(size - total),
                num(total)
            ),
            help: "make the piece smaller or the scope larger".into(),
        });
    }
    let n = n as usize;
    Ok(vec![total / n as f64; n])
}

/// Which branch a symmetric repeat draws in each piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    End,
    Bay,
    Centre,
}

/// `@RSX(e,s,c)`: end, n bays, centre, n bays, end, with n the most bays
/// of about s that fit on each side (the same on both sides, so the
/// centre stays in the middle). With no room for a bay the centre widens.
pub fn symmetric(
    total: f64,
    end: f64,
    bay: f64,
    centre: f64,
    axis: Axis,
) -> Result<Vec<(Role, f64)>, Misfit> {
    let asked = format!(
        "ends {e} + bays of about {b} + centre {c} + bays + ends {e} along {}",
        axis.name(),
        e = num(end),
        b = num(bay),
        c = num(centre)
    );
    let inner = total - 2.0 * end - centre;
    if inner < -EPS * total.max(1.0) {
        return Err(Misfit {
            asked,
            scope: total,
            problem: format!(
                "the two ends and the centre need {}, {} more than the scope's {}",
                num(2.0 * end + centre),
                num(-inner),
                num(total)
            ),
            help: "make the ends or the centre smaller, or the scope wider".into(),
        });
    }
    if bay <= 0.0 {
        return Err(Misfit {
            asked,
            scope: total,
            problem: "the bay size must be above 0".into(),
            help: "give the bays a positive size".into(),
        });
    }
    let inner = inner.max(0.0);
    let n = (inner / (2.0 * bay) + EPS).floor();
    if n.is_nan() || n > MAX_COPIES as f64 {
        return Err(too_many(asked, total, n));
    }
    let n = n as usize;
    let (b, c) = if n == 0 {
        (0.0, centre + inner)
    } else {
        (inner / (2 * n) as f64, centre)
    };
    let mut out = vec![(Role::End, end)];
    out.extend(std::iter::repeat((Role::Bay, b)).take(n));
    out.push((Role::Centre, c));
    out.extend(std::iter::repeat((Role::Bay, b)).take(n));
    out.push((Role::End, end));
    Ok(out)
}

/// The scope's axes in a frame: x = H × U, y = H, z = U.
pub fn axes(f: &Frame) -> [DVec3; 3] {
    [f.h.cross(f.u), f.h, f.u]
}

/// A frame whose scope axes are `x`, `y`, `z` (right-handed) at `origin`,
/// keeping the frame's handedness.
pub fn frame_from(f: &Frame, origin: DVec3, x: DVec3, y: DVec3, z: DVec3) -> Frame {
    Frame {
        pos: origin,
        h: y,
        u: z,
        l: -x * f.hand,
        hand: f.hand,
    }
}

/// The faces of a box scope for `@Comp`, in branch order (front, back,
/// left, right, top, bottom): each a frame at the face's corner with z
/// along its outward normal, and the face's size (depth 0).
pub fn faces(f: &Frame, size: DVec3) -> Vec<(Frame, DVec3)> {
    let [x, y, z] = axes(f);
    let o = f.pos;
    let (sx, sy, sz) = (size.x, size.y, size.z);
    vec![
        (frame_from(f, o + z * sz, x, y, z), DVec3::new(sx, sy, 0.0)),
        (
            frame_from(f, o + x * sx, -x, y, -z),
            DVec3::new(sx, sy, 0.0),
        ),
        (frame_from(f, o, z, y, -x), DVec3::new(sz, sy, 0.0)),
        (
            frame_from(f, o + x * sx + z * sz, -z, y, x),
            DVec3::new(sz, sy, 0.0),
        ),
        (
            frame_from(f, o + y * sy + z * sz, x, -z, y),
            DVec3::new(sx, sz, 0.0),
        ),
        (frame_from(f, o, x, z, -y), DVec3::new(sx, sz, 0.0)),
    ]
}

/// `@Rot(ax,ay,az)`: the frame turned about the scope's centre by ax
/// degrees about its x axis, then ay about its (new) y, then az about its
/// z, each counter-clockwise seen from the axis's tip (right-handed).
pub fn rotate(f: &Frame, size: DVec3, degrees: [f64; 3]) -> Frame {
    let mut ax = axes(f);
    let centre = f.pos + (ax[0] * size.x + ax[1] * size.y + ax[2] * size.z) / 2.0;
    for (k, d) in degrees.into_iter().enumerate() {
        if d != 0.0 {
            let q = glam::DQuat::from_axis_angle(ax[k].normalize(), d.to_radians());
            ax = ax.map(|v| q * v);
        }
    }
    let origin = centre - (ax[0] * size.x + ax[1] * size.y + ax[2] * size.z) / 2.0;
    frame_from(f, origin, ax[0], ax[1], ax[2])
}

/// The frame and size of piece `[start, start + len)` along `axis`.
pub fn piece(f: &Frame, size: DVec3, axis: Axis, start: f64, len: f64) -> (Frame, DVec3) {
    let k = axis.index();
    let mut frame = *f;
    frame.pos += axes(f)[k] * start;
    let mut s = size;
    s[k] = len;
    (frame, s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floating_sizes_share_the_rest_by_weight() {
        let s = subdivide(10.0, &[2.0, -1.0, -3.0, -REL_BASE - 0.2], Axis::X).unwrap();
        let want = [2.0, 1.5, 4.5, 2.0];
        assert!(
            s.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-9),
            "{s:?}"
        );
    }

    #[test]
    fn rotate_turns_about_the_centre() {
        let size = DVec3::new(4.0, 2.0, 1.0);
        let f = rotate(&Frame::default(), size, [0.0, 90.0, 0.0]);
        let [x, y, z] = axes(&f);
        // A quarter turn about y: x goes to -z, z to x; the centre stays.
        assert!((x - DVec3::NEG_Z).length() < 1e-12, "{x}");
        assert!((y - DVec3::Y).length() < 1e-12 && (z - DVec3::X).length() < 1e-12);
        let centre = f.pos + (x * 4.0 + y * 2.0 + z * 1.0) / 2.0;
        assert!(
            (centre - DVec3::new(2.0, 1.0, 0.5)).length() < 1e-12,
            "{centre}"
        );
    }

    #[test]
    fn repeats_past_the_limit_are_refused_before_allocating() {
        for (total, size) in [
            (2.0, 1e-320),
            (1e308, 3.0),
            (f64::INFINITY, 1.0),
            (1.0, 1e-6),
        ] {
            let e = repeat(total, size, Axis::X).unwrap_err();
            assert!(
                e.problem.contains("copies, more than the 100000"),
                "{}",
                e.problem
            );
        }
        assert_eq!(repeat(1.0, 1e-5, Axis::X).unwrap().len(), 100_000);
        let e = symmetric(1e308, 1.0, 1.0, 1.0, Axis::X).unwrap_err();
        assert!(e.problem.contains("more than the 100000"), "{}", e.problem);
    }

    #[test]
    fn repeat_fits_whole_copies_and_stretches_them() {
        assert_eq!(repeat(10.0, 3.0, Axis::X).unwrap(), vec![10.0 / 3.0; 3]);
        assert!(repeat(2.0, 3.0, Axis::X).is_err());
    }

    #[test]
    fn symmetric_keeps_the_same_bays_on_both_sides() {
        let s = symmetric(20.0, 1.0, 3.0, 5.0, Axis::X).unwrap();
        let roles: Vec<Role> = s.iter().map(|r| r.0).collect();
        use Role::*;
        assert_eq!(roles, vec![End, Bay, Bay, Centre, Bay, Bay, End]);
        assert!((s.iter().map(|r| r.1).sum::<f64>() - 20.0).abs() < 1e-9);
    }
}
