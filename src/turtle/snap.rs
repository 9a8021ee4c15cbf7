//! The constraint rule "a new part within a threshold of an existing one
//! is resized and aligned to it" (seed 004, Sec 4, automatic correction).
//! Input: the primitives in the order drawn, each with the `@Snap(d)` in
//! force; output: the blocks moved or resized, and one report line per
//! face that moved.
//!
//! Only blocks are snapped, and only to earlier blocks whose axes are the
//! same (parallel and in the same direction): each of the new block's six
//! faces moves onto the nearest face plane of an earlier block along the
//! same axis when it is within d and the two blocks overlap (or nearly)
//! across that axis, so a face snaps to a neighbour, not to a far-away
//! block that happens to share a coordinate.

use glam::DVec3;

use super::scope::{axes, num};
use super::solid::Solid;
use crate::lang::scope_commands::Primitive;

/// The solids after snapping.
pub fn snap(solids: &[Solid], report: &mut Vec<String>) -> Vec<Solid> {
    let mut out: Vec<Solid> = solids.to_vec();
    for i in 0..out.len() {
        let b = out[i];
        if b.kind != Primitive::Block || b.snap <= 0.0 {
            continue;
        }
        let ax = axes(&b.frame);
        // The block as [lo, hi] along its own axes, from its origin.
        let mut lo = DVec3::ZERO;
        let mut hi = b.size;
        for a in out[..i].iter().filter(|a| a.kind == Primitive::Block) {
            let aa = axes(&a.frame);
            if (0..3).any(|k| aa[k].dot(ax[k]) < 1.0 - 1e-9) {
                continue;
            }
            // The earlier block in the new one's coordinates.
            let o = a.frame.pos - b.frame.pos;
            let alo = DVec3::new(o.dot(ax[0]), o.dot(ax[1]), o.dot(ax[2]));
            let ahi = alo + a.size;
            for k in 0..3 {
                // Near each other across the other two axes.
                let near = (0..3)
                    .filter(|&j| j != k)
                    .all(|j| lo[j] < ahi[j] + b.snap && hi[j] > alo[j] - b.snap);
                if !near {
                    continue;
                }
                for high in [false, true] {
                    // The face and the one opposite it: a snap never
                    // squeezes the block thinner than d (so a thin slab
                    // on top of a block does not collapse onto it).
                    let (v, other) = if high { (hi[k], lo[k]) } else { (lo[k], hi[k]) };
                    let target = [alo[k], ahi[k]]
                        .into_iter()
                        .filter(|t| (*t - v).abs() > 1e-9 && (*t - v).abs() <= b.snap)
                        .filter(|t| (*t - other).abs() > b.snap)
                        .min_by(|p, q| (*p - v).abs().total_cmp(&(*q - v).abs()));
                    if let Some(t) = target {
                        let side = if high { "high" } else { "low" };
                        report.push(format!(
                            "block (module {}) within {} of block (module {}): its {} {} face moved by {} to meet it",
                            b.module + 1,
                            num(b.snap),
                            a.module + 1,
                            side,
                            ["x", "y", "z"][k],
                            num(t - v),
                        ));
                        if high {
                            hi[k] = t;
                        } else {
                            lo[k] = t;
                        }
                    }
                }
            }
        }
        let s = &mut out[i];
        s.frame.pos += ax[0] * lo.x + ax[1] * lo.y + ax[2] * lo.z;
        s.size = (hi - lo).max(DVec3::ZERO);
    }
    out
}
