//! Rafter rows closed into posts: a band of rafter ends whose insides
//! `--gap` closed -> its posts of ink as the elements, the regions
//! between them the layer's back (see [`posts`]).

use super::super::regions::Region;
use super::super::tree::Node;
use super::collapse;

/// Elements drawn too small to keep an inside: when lines are thickened
/// (`--gap`) a rafter end a few pixels wide closes up into a post of ink,
/// and what the row's regions are is the back between the posts. Read
/// so, a row of n rafters gave n - 1 + its margins "rafters", the gaps.
///
/// The row's longest run of drawn pieces side by side (at least 4, and
/// four in five of the drawn pieces) is of posts when the ink between
/// each two pieces' regions (boxes reach the middle of a plain line, so a
/// line drawn between two pieces leaves a pixel or two) has a median of
/// at least 3 pixels and 0.4 of the regions' median width, and four in
/// five of them are within half of that median. Those are the elements;
/// so is ink of at least half a post between the run's end regions and
/// the nearest drawn region beyond them (or the row's end): the first and
/// last posts have no region of the run on their outer side. Drawn pieces
/// outside the run (a side face's element seen end-on at each corner)
/// are elements too; the pieces of the run are the layer's back.
/// Returns how many elements, or None when the row is not of posts.
pub(super) fn posts(band: &mut Node, regions: &[Region], kind: &'static str) -> Option<usize> {
    let is_drawn = |c: &Node| !c.regions.is_empty();
    let drawn = band.children.iter().filter(|c| is_drawn(c)).count();
    // The longest run of adjacent drawn pieces: [first, last].
    let count = band.children.len();
    let (mut first, mut last, mut start) = (None, 0, None);
    for k in 0..=count {
        let d = k < count && is_drawn(&band.children[k]);
        match (d, start) {
            (true, None) => start = Some(k),
            (false, Some(a)) => {
                if first.map_or(true, |f| k - a > last + 1 - f) {
                    (first, last) = (Some(a), k - 1);
                }
                start = None;
            }
            _ => {}
        }
    }
    let first = first?;
    let run = last + 1 - first;
    if run < 4 || run * 5 < drawn * 4 {
        return None;
    }
    let span = |c: &Node| {
        let lo = c.regions.iter().map(|&r| regions[r].bbox[0]).min();
        let hi = c.regions.iter().map(|&r| regions[r].bbox[2]).max();
        (lo.unwrap_or(c.bbox[0]), hi.unwrap_or(c.bbox[2]))
    };
    let spans: Vec<(i32, i32)> = band.children[first..=last].iter().map(span).collect();
    let widths: Vec<i32> = spans.windows(2).map(|w| w[1].0 - w[0].1).collect();
    let median = |v: &[i32]| {
        let mut v = v.to_vec();
        v.sort_unstable();
        v[v.len() / 2] as f64
    };
    // Pieces of two widths (a rafter's inside and the back between two):
    // the narrow ones are elements. Split at the geometric mean of the
    // lower and upper quartile widths when those differ by a third.
    let piece_widths: Vec<i32> = spans.iter().map(|s| s.1 - s.0).collect();
    let mut sorted = piece_widths.clone();
    sorted.sort_unstable();
    let (q1, q3) = (sorted[run / 4] as f64, sorted[3 * run / 4] as f64);
    let split = (q3 >= 1.3 * q1).then(|| (q1 * q3).sqrt());
    let narrow: Vec<bool> = piece_widths
        .iter()
        .map(|&w| split.is_some_and(|t| (w as f64) < t))
        .collect();
    let wide: Vec<i32> = (0..run)
        .filter(|&k| !narrow[k])
        .map(|k| piece_widths[k])
        .collect();
    // Ink between two pieces as wide as 0.4 of a wide piece is a post.
    let floor = (0.4 * median(&wide)).max(3.0);
    let thick: Vec<i32> = widths
        .iter()
        .copied()
        .filter(|&w| w as f64 >= floor)
        .collect();
    let post = if thick.is_empty() {
        0.0
    } else {
        median(&thick)
    };
    // A rafter does not touch a rafter: ink beside a narrow piece is its
    // outline (and an open strip beyond), not a post.
    let is_post: Vec<bool> = (0..widths.len())
        .map(|i| {
            let w = widths[i] as f64;
            post > 0.0 && w >= 0.5 * post && w <= 1.8 * post && !narrow[i] && !narrow[i + 1]
        })
        .collect();
    let posts = is_post.iter().filter(|&&p| p).count();
    let narrows = narrow.iter().filter(|&&n| n).count();
    // A row of posts (four in five of the gaps between pieces), or of
    // narrow and wide pieces by turns (a third of the pieces narrow at
    // least, no two side by side).
    let of_posts = posts * 5 >= widths.len() * 4;
    let by_turns = narrows * 3 >= run && narrow.windows(2).all(|w| !(w[0] && w[1]));
    if !(of_posts || by_turns) {
        return None;
    }
    // The run's end pieces much wider than its back (1.6 times the median)
    // are a side face's first element seen end-on, at the corner.
    let back = median(&wide);
    let corner = |k: usize| (k == 0 || k + 1 == run) && piece_widths[k] as f64 > 1.6 * back;
    let element_width = if of_posts {
        post
    } else {
        let w: Vec<i32> = (0..run)
            .filter(|&k| narrow[k])
            .map(|k| piece_widths[k])
            .collect();
        median(&w)
    };
    let [x0, y0, x1, y1] = band.bbox;
    let edge = (0.5 * element_width).max(2.5).ceil() as i32;
    let before = band.children[..first]
        .iter()
        .rev()
        .find(|c| is_drawn(c))
        .map_or(x0, |c| span(c).1);
    let after = band.children[last + 1..]
        .iter()
        .find(|c| is_drawn(c))
        .map_or(x1, |c| span(c).0);
    let lead = spans[0].0 - before >= edge;
    let trail = after - spans[run - 1].1 >= edge;
    // An undrawn piece beside the run holds its outer post (the strip
    // between it and the corner is open): it is the element.
    let undrawn = |k: usize| !is_drawn(&band.children[k]);
    let lead_piece = lead && first > 0 && undrawn(first - 1);
    let trail_piece = trail && last + 1 < count && undrawn(last + 1);
    let mut out: Vec<Node> = Vec::new();
    let mut n = 0;
    for (k, mut c) in std::mem::take(&mut band.children).into_iter().enumerate() {
        let in_run = (first..=last).contains(&k);
        let element = (is_drawn(&c) && !in_run)
            || (in_run && (narrow[k - first] || corner(k - first)))
            || (lead_piece && k + 1 == first)
            || (trail_piece && k == last + 1);
        collapse(&mut c, if element { kind } else { "other" });
        if !element {
            // The layer's back, not something left unrecognised.
            c.regions.clear();
            c.fills.clear();
        }
        let mut tail = None;
        if in_run {
            let (lo, hi) = spans[k - first];
            let post_before = if k > first {
                is_post[k - first - 1]
            } else {
                lead && !lead_piece
            };
            if post_before {
                let from = match out.last() {
                    Some(p) if k > first => p.bbox[2],
                    _ => c.bbox[0],
                };
                out.push(Node::leaf(kind, [from, y0, lo, y1]));
                n += 1;
                c.bbox[0] = lo;
            }
            let post_after = if k < last {
                is_post[k - first]
            } else {
                trail && !trail_piece
            };
            if post_after {
                // The post after is cut off the next piece, or at the
                // run's end off this one.
                if k == last {
                    tail = Some(Node::leaf(kind, [hi, y0, c.bbox[2], y1]));
                    n += 1;
                }
                c.bbox[2] = hi;
            }
        }
        n += usize::from(element);
        out.push(c);
        out.extend(tail);
    }
    band.children = out;
    Some(n)
}
