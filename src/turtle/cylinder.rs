//! Generalized cylinders: the turtle's state at `@Gs`, `@Gc(n)` and
//! `@Ge(n)` in, tube chains in the drawing out. As in cpfg (general.c,
//! `SetControlPoint`), each control point after the first draws at once
//! the Hermite curve from the previous control point to the turtle, with
//! `n` segments, tangents along the two headings. The previous point is
//! part of the turtle's state, so a branch copies it: the branch's first
//! `@Gc` draws from the branch point, and after `]` the parent goes on
//! from its own last point (cpfg's spline stack). Between control points
//! the turtle usually moves with `f`.

use super::cpfg_contour::{sweep, End};
use super::drawing::{Chain, Drawing, TubePoint};
use super::frame::Frame;
use super::interp::State;
use crate::lang::commands::Action;
use crate::load::Contour;

/// Curve segments between two control points when `@Gc`/`@Ge` give none.
const DEFAULT_SEGMENTS: usize = 8;

/// An open generalized cylinder: its last control point and the chain the
/// last segment drew into (the next segment extends it when it is still
/// that chain's end).
#[derive(Clone, Copy, Debug)]
pub(super) struct Open {
    frame: Frame,
    radius: f32,
    chain: Option<usize>,
    /// The cross-section (`@#`) in force here.
    contour: Option<usize>,
}

/// `@Gs` starts a cylinder at the turtle; `@Gc(n)` adds a control point
/// (starting a cylinder when none is open, as cpfg does); `@Ge(n)` adds
/// the last one and closes it.
pub(super) fn control_point(
    d: &mut Drawing,
    s: &mut State,
    act: Action,
    args: &[f64],
    contours: &[Contour],
) {
    let here = Open {
        frame: s.frame,
        radius: s.width * 0.5,
        chain: None,
        contour: s.contour,
    };
    let prev = match (act, s.cylinder.as_deref()) {
        (Action::CylStart, _) | (_, None) => {
            s.cylinder = Some(Box::new(here));
            return;
        }
        (_, Some(&prev)) => prev,
    };
    let segments = args
        .first()
        .map_or(DEFAULT_SEGMENTS, |&n| (n.max(1.0) as usize).min(1024));
    // A contour other than round: the previous point's, as cpfg starts
    // each segment's rings from it (cpfg blends two different ones; the
    // corpus never changes contour inside a cylinder).
    let chain = match prev.contour.and_then(|c| contours.get(c)) {
        Some(c) => {
            let end = |o: &Open| End {
                pos: o.frame.pos.as_vec3(),
                h: o.frame.h.as_vec3(),
                l: o.frame.l.as_vec3(),
                u: o.frame.u.as_vec3(),
                radius: o.radius,
            };
            sweep(d, &end(&prev), &end(&here), segments, s.colour, c);
            None
        }
        None => draw_segment(d, &prev, &here, segments, s.colour),
    };
    s.cylinder = (act != Action::CylEnd).then(|| Box::new(Open { chain, ..here }));
}

/// Samples the cubic Hermite curve from `a` to `b` (tangents along each
/// heading, scaled by the distance between them) into the drawing: onto
/// the end of `a`'s chain when that chain still ends at `a`, else into a
/// new chain. Returns the chain drawn into.
fn draw_segment(
    d: &mut Drawing,
    a: &Open,
    b: &Open,
    segments: usize,
    colour: u32,
) -> Option<usize> {
    let (ap, bp) = (a.frame.pos.as_vec3(), b.frame.pos.as_vec3());
    let dist = ap.distance(bp);
    if dist < 1e-7 || (a.radius <= 0.0 && b.radius <= 0.0) {
        return a.chain;
    }
    let (ah, bh) = (a.frame.h.as_vec3(), b.frame.h.as_vec3());
    let (au, bu) = (a.frame.u.as_vec3(), b.frame.u.as_vec3());
    let (m0, m1) = (ah * dist, bh * dist);
    let sample = |t: f32| {
        let (t2, t3) = (t * t, t * t * t);
        let pos = ap * (2.0 * t3 - 3.0 * t2 + 1.0)
            + m0 * (t3 - 2.0 * t2 + t)
            + bp * (-2.0 * t3 + 3.0 * t2)
            + m1 * (t3 - t2);
        TubePoint {
            pos,
            radius: a.radius + (b.radius - a.radius) * t,
            up: au.lerp(bu, t).normalize_or(au),
        }
    };
    let points = (1..=segments).map(|k| sample(k as f32 / segments as f32));
    let extends = a.chain.filter(|&c| {
        let ch = &d.chains[c];
        ch.colour == colour && ch.points.last().is_some_and(|p| p.pos.distance(ap) < 1e-7)
    });
    let c = match extends {
        Some(c) => c,
        None => {
            d.chains.push(Chain {
                colour,
                points: smallvec::smallvec![sample(0.0)],
            });
            d.chains.len() - 1
        }
    };
    let chain = &mut d.chains[c].points;
    for p in points {
        if chain
            .last()
            .map_or(true, |q: &TubePoint| q.pos.distance(p.pos) >= 1e-7)
        {
            chain.push(p);
        }
    }
    Some(c)
}
