//! The structural check's roof rules (issue 37): the Part boxes of
//! [`super::check`] -> problems where roofs at one height meet, a pillar
//! rises out of a roof, or a roof is held by nothing.

use super::{Part, Problem, TOLERANCE};

/// A part whose top is within this of a roof's bottom may hold the roof
/// (a Toukung row, a lintel, a pillar's top), in model units.
pub const HOLD_GAP: f32 = 0.1;

fn is_roof(p: &Part) -> bool {
    matches!(p.kind.as_deref(), Some("eaves_roof" | "clipped_roof"))
}

/// A suspended pillar that passes through a roof, its foot under the roof's
/// bottom, its top over the roof's top and its whole section inside the
/// roof's footprint, is joined with it: the pillars of an entrance above
/// stand on the lintel inside the roof of the entrance under it and rise
/// through that roof (issue 37, defect 2). A roof whose end runs into a
/// pillar is still reported.
pub(super) fn passes_through(a: &Part, b: &Part) -> bool {
    let through = |p: &Part, r: &Part| {
        p.kind.as_deref() == Some("suspended_pillar")
            && is_roof(r)
            && p.lo.y <= r.lo.y + TOLERANCE
            && p.hi.y >= r.hi.y - TOLERANCE
            && p.lo.x >= r.lo.x - TOLERANCE
            && p.hi.x <= r.hi.x + TOLERANCE
            && p.lo.z >= r.lo.z - TOLERANCE
            && p.hi.z <= r.hi.z + TOLERANCE
    };
    through(a, b) || through(b, a)
}

/// The roofs' own rules (issue 37): roofs at one height must not meet, a
/// pillar must not rise out of a roof, and a roof must have something
/// under both its ends.
pub(super) fn roofs(parts: &[Part], out: &mut Vec<Problem>) {
    let roofs: Vec<&Part> = parts.iter().filter(|p| is_roof(p)).collect();
    for (n, a) in roofs.iter().enumerate() {
        for b in &roofs[n + 1..] {
            let o = a.hi.min(b.hi) - a.lo.max(b.lo);
            let same_height = o.y > 0.5 * (a.hi.y - a.lo.y).min(b.hi.y - b.lo.y);
            // Touching or overlapping (a deeper overlap is also reported
            // as interpenetrating), along x, their footprints side by side.
            if same_height && o.z > TOLERANCE && o.x > -TOLERANCE {
                let x = 0.5 * (a.hi.x.min(b.hi.x) + a.lo.x.max(b.lo.x));
                out.push(Problem::RoofsMeet {
                    a: a.name.clone(),
                    b: b.name.clone(),
                    x,
                });
            }
        }
    }
    for p in parts {
        if p.kind.as_deref() != Some("suspended_pillar") {
            continue;
        }
        let centre = (p.lo + p.hi) * 0.5;
        let roof = roofs.iter().find(|r| {
            (r.lo.x..=r.hi.x).contains(&centre.x)
                && (r.lo.z..=r.hi.z).contains(&centre.z)
                && p.lo.y > r.lo.y + TOLERANCE
                && p.lo.y < r.hi.y + TOLERANCE
        });
        if let Some(r) = roof {
            out.push(Problem::PillarOnRoof {
                part: p.name.clone(),
                roof: r.name.clone(),
                depth: r.hi.y - p.lo.y,
            });
        }
    }
    for r in &roofs {
        // What may hold a roof: a part (not a roof) reaching up to within
        // [HOLD_GAP] under the roof's bottom and not above its middle,
        // its footprint under the roof's.
        let mid = (r.lo.y + r.hi.y) * 0.5;
        let holds = |q: &&Part, x0: f32, x1: f32| {
            !is_roof(q)
                && q.lo.x < x1
                && q.hi.x > x0
                && q.hi.z > r.lo.z
                && q.lo.z < r.hi.z
                && q.hi.y > r.lo.y - HOLD_GAP
                && q.lo.y < mid
        };
        let c = (r.lo.x + r.hi.x) * 0.5;
        // Held under its middle (a Toukung row, a lintel, a pillar's top),
        // or at both ends (between two pillars, as the paper's clipped
        // roofs sit between suspended pillars).
        let under_middle = parts.iter().any(|q| holds(&q, c - 1e-3, c + 1e-3));
        let left = parts.iter().any(|q| holds(&q, r.lo.x, c));
        let right = parts.iter().any(|q| holds(&q, c, r.hi.x));
        if !(under_middle || left && right) {
            let (side, x) = match (left, right) {
                (true, _) => ("right", (c + r.hi.x) * 0.5),
                (_, true) => ("left", (r.lo.x + c) * 0.5),
                _ => ("either", c),
            };
            out.push(Problem::RoofOverNothing {
                part: r.name.clone(),
                side,
                x,
            });
        }
    }
}
