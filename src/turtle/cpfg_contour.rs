//! cpfg's contours: a generalized cylinder segment (two control points)
//! and the cross-section `@#(id)` selected in, the surface swept along the
//! segment's Hermite curve out, as polygons of the drawing (general.c,
//! `make_contour`): each contour point (x, y) is placed at
//! `pos + radius · (x · up − y · left)`, the radius going from one control
//! point's half width to the other's, and neighbouring rings are joined
//! by quadrilaterals. Herb-lily's leaf blade is such a sweep of a
//! leaf-shaped open contour.

use glam::Vec3;

use super::drawing::{Drawing, Polygon};
use crate::load::Contour;

/// One end of the segment: the turtle's frame at a control point and its
/// radius.
pub(super) struct End {
    pub pos: Vec3,
    pub h: Vec3,
    pub l: Vec3,
    pub u: Vec3,
    pub radius: f32,
}

/// Sweeps `contour` from `a` to `b` in `segments` pieces into `d`.
pub(super) fn sweep(
    d: &mut Drawing,
    a: &End,
    b: &End,
    segments: usize,
    colour: u32,
    contour: &Contour,
) {
    let dist = a.pos.distance(b.pos);
    let (m0, m1) = (a.h * dist, b.h * dist);
    let ring = |t: f32| -> Vec<Vec3> {
        let (t2, t3) = (t * t, t * t * t);
        let pos = a.pos * (2.0 * t3 - 3.0 * t2 + 1.0)
            + m0 * (t3 - 2.0 * t2 + t)
            + b.pos * (-2.0 * t3 + 3.0 * t2)
            + m1 * (t3 - t2);
        let tangent = a.pos * (6.0 * t2 - 6.0 * t)
            + m0 * (3.0 * t2 - 4.0 * t + 1.0)
            + b.pos * (-6.0 * t2 + 6.0 * t)
            + m1 * (3.0 * t2 - 2.0 * t);
        let h = tangent.normalize_or(a.h.lerp(b.h, t).normalize_or(a.h));
        let u = a.u.lerp(b.u, t);
        let u = (u - h * u.dot(h)).normalize_or(a.u);
        let l = a.l.lerp(b.l, t);
        let l = (l - h * l.dot(h) - u * l.dot(u)).normalize_or(a.l);
        let r = a.radius + (b.radius - a.radius) * t;
        contour
            .points
            .iter()
            .map(|&[x, y]| pos + (u * x - l * y) * r)
            .collect()
    };
    let mut prev = ring(0.0);
    for k in 1..=segments {
        let next = ring(k as f32 / segments as f32);
        let n = prev.len();
        let pairs = if contour.closed { n } else { n - 1 };
        for i in 0..pairs {
            let j = (i + 1) % n;
            d.polygons.push(Polygon {
                colour,
                points: vec![prev[i], prev[j], next[j], next[i]],
                uv: None,
            });
        }
        prev = next;
    }
}
