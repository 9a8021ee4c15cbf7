//! Seed 004's automatic correction and the "stands on" configure rule:
//! a painted part and the parts near it -> its edges moved onto theirs
//! (with a sentence for each move), and the part it stands on.

use super::{number, PaintView, Painted, Part};

/// The part whose top edge (in `view`) the rectangle `r` stands on,
/// within `threshold` (at least 1e-6), across the most of its width.
pub(super) fn standing_on(
    parts: &[Part],
    view: PaintView,
    r: &[f64; 4],
    threshold: f64,
) -> Option<usize> {
    let t = threshold.max(1e-6);
    parts
        .iter()
        .enumerate()
        .map(|(i, p)| (i, p.rect(view)))
        .filter(|(_, q)| (q[3] - r[1]).abs() <= t)
        .map(|(i, q)| (i, r[2].min(q[2]) - r[0].max(q[0])))
        .filter(|&(_, shared)| shared > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

pub(super) fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Seed 004's automatic correction: each of the part's four painted
/// edges within `threshold` of an edge of a part near it (their
/// rectangles in the view and their depths within the threshold of each
/// other) moves onto
/// the nearest such edge, unless that would leave the part thinner than
/// the threshold.
pub(super) fn correct(
    part: &mut Part,
    parts: &[Part],
    view: PaintView,
    threshold: f64,
    out: &mut Painted,
) {
    if threshold <= 0.0 {
        return;
    }
    let r = part.rect(view);
    let w = view.axes()[2];
    let (w0, w1) = part.span(w);
    let near: Vec<(usize, [f64; 4])> = parts
        .iter()
        .enumerate()
        // Near in depth too: a window on the far side of the house,
        // seen through in this view, is no edge to meet.
        .filter(|(_, p)| {
            let (a, b) = p.span(w);
            a < w1 + threshold && w0 - threshold < b
        })
        .map(|(i, p)| (i, p.rect(view)))
        .filter(|(_, q)| {
            r[0] - threshold < q[2]
                && q[0] < r[2] + threshold
                && r[1] - threshold < q[3]
                && q[1] < r[3] + threshold
        })
        .collect();
    let mut moved = r;
    // Edges: 0 left, 1 bottom, 2 right, 3 top; an edge meets the other
    // rectangles' edges along the same axis (left or right, bottom or top).
    const EDGE: [&str; 4] = ["left", "bottom", "right", "top"];
    for e in 0..4 {
        let axis = e % 2;
        let best = near
            .iter()
            .flat_map(|(i, q)| [(*i, q[axis], axis), (*i, q[axis + 2], axis + 2)])
            .map(|(i, at, edge)| (i, at, edge, (at - r[e]).abs()))
            .filter(|&(_, _, _, d)| d > 1e-9 && d <= threshold)
            .min_by(|a, b| a.3.total_cmp(&b.3));
        let Some((i, at, edge, _)) = best else {
            continue;
        };
        let mut trial = moved;
        trial[e] = at;
        if trial[axis + 2] - trial[axis] < threshold {
            continue;
        }
        out.corrections.push(format!(
            "its {} edge moved by {} to meet {} {}'s {} edge",
            EDGE[e],
            number(at - r[e]),
            parts[i].component,
            i + 1,
            EDGE[edge]
        ));
        moved = trial;
    }
    let [u, v, _] = view.axes();
    part.set_span(u, (moved[0], moved[2]));
    part.set_span(v, (moved[1], moved[3]));
}
