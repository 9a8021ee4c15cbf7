//! Recognition: a shape tree -> the same tree with each node labelled from
//! the seed's vocabulary (platform, stairs, column, bay, door, window,
//! wall, lintel, bracket, rafter, roof, ridge, other), and each drawn
//! column, door, window and bracket set made one leaf.
//!
//! Seed 003 labels nodes with an MRF over component priors. Its priors are
//! what decides here, written as rules instead of learned potentials, from
//! the top level down (Section 3's order of a hall, bottom to top:
//! platform, columns and walls, bracket sets, rafters, roof, ridge):
//!
//! - the **body** is the tallest band with columns (regions at least 0.7
//!   of the band's height and three times taller than wide, standing
//!   apart);
//! - bands under it are the **platform** (the middle piece drawn as stacked
//!   steps is the **stairs**);
//! - above it, from the top: a band under a third of the next one's height,
//!   or a plain one (two regions at most) lower than the next one that
//!   holds ten regions or more, is the **ridge**, the highest other band
//!   the **roof**, and between the
//!   body and the roof the first band is the **bracket** layer and the
//!   second the **rafter** layer, each piece with something drawn in it one
//!   bracket set or rafter (unless the pieces are the back between the
//!   elements: sets hanging between closed back, rafters closed into posts
//!   of ink or narrow between wider back; `layers.rs`);
//! - in the body, pieces that are a column are **columns**, the pieces
//!   between them **bays**; a bay's top piece under 0.3 of its height is its
//!   **lintel**; under it, what is drawn inside the wall is a **door** when
//!   it stands on the bay's floor and is at least 0.4 of its height, a
//!   **window** otherwise; undrawn strips and plain narrow side strips
//!   are **wall**; pieces with a door or window in them one above the
//!   other under the lintel are one element.

mod layers;
mod ornaments;

use super::regions::Region;
use super::tree::{Axis, Node};
use layers::row_of;
use ornaments::ornaments;

/// A column is this much of its band's height, at least.
const COLUMN_HEIGHT: f64 = 0.7;
/// ... and this many times taller than wide.
const COLUMN_SLENDER: f64 = 3.0;

/// Labels `root` in place. Returns the boxes of the regions drawn in
/// nodes that no rule could name.
pub fn recognise(root: &mut Node, regions: &[Region]) -> Vec<[i32; 4]> {
    if root.split == Some(Axis::Y) {
        rejoin_pinched_bands(root, regions);
    }
    let bands: Vec<usize> = if root.split == Some(Axis::Y) {
        (0..root.children.len()).collect()
    } else {
        Vec::new()
    };
    if bands.is_empty() {
        // One band: a body with nothing above or below.
        body(root, regions);
        return unlabelled(root, regions);
    }
    let columns = |n: &Node| spaced_columns(n, regions);
    // The body: the tallest band with columns standing apart (two gaps
    // at least), else the tallest band. Not the band with most columns:
    // a row of tall rafter ends passes the column test too, and beats the
    // body, whose door stiles and side walls stand close to its columns.
    let body_at = (0..root.children.len())
        .max_by_key(|&i| (columns(&root.children[i]) >= 2, root.children[i].h()))
        .unwrap_or(0);
    for c in &mut root.children[body_at + 1..] {
        platform(c);
    }
    body(&mut root.children[body_at], regions);
    let mut above: Vec<usize> = (0..body_at).collect();
    // Ornaments on the ridge's ends (chiwen): a band over the ridge drawn
    // only at its two ends. Read as the ridge, it shifted every layer down
    // one (issue 37's hall: the ridge read as the roof).
    if above.len() >= 3 && ornaments(&root.children[above[0]], root.w(), regions) {
        collapse(&mut root.children[above[0]], "ornament");
        above.remove(0);
    }
    if let Some((&top, rest)) = above.split_first() {
        let mut roof_at = top;
        if let Some(&next) = rest.first() {
            // Thin over the roof, or one plain block over the roof's many
            // rows of tiles (a tall ridge over a low roof).
            let (t, n) = (&root.children[top], &root.children[next]);
            let thin = (t.h() as f64) < n.h() as f64 / 3.0;
            let plain = t.regions.len() <= 2 && n.regions.len() >= 10 && t.h() < n.h();
            if thin || plain {
                collapse(&mut root.children[top], "ridge");
                roof_at = next;
            }
        }
        collapse(&mut root.children[roof_at], "roof");
        let between: Vec<usize> = (roof_at + 1..body_at).rev().collect();
        for (k, &i) in between.iter().enumerate() {
            let kind = match k {
                0 => "bracket",
                1 => "rafter",
                _ => "other",
            };
            row_of(&mut root.children[i], kind, regions);
        }
    }
    unlabelled(root, regions)
}

/// Bands cut along x at the same places, one above the other, are one band
/// cut across where a shaky hand pinched its strips shut: a roof's tile
/// rows come in three bands, and the ridge above is then read as the roof.
fn rejoin_pinched_bands(root: &mut Node, regions: &[Region]) {
    let cuts = |a: &Node| -> Vec<i32> {
        let n = a.children.len();
        a.children
            .iter()
            .take(n.saturating_sub(1))
            .map(|c| c.bbox[2])
            .collect()
    };
    // Most of each band's cuts have one in the other within a shift.
    let matched = |a: &[i32], b: &[i32]| {
        a.iter()
            .filter(|&&x| b.iter().any(|&y| (x - y).abs() <= PINCHED_SHIFT))
            .count()
            * 5
            >= a.len() * 4
    };
    let same_cuts = |a: &Node, b: &Node| {
        let (ca, cb) = (cuts(a), cuts(b));
        a.split == Some(Axis::X)
            && b.split == Some(Axis::X)
            && ca.len().min(cb.len()) + 1 >= PINCHED_MIN_PIECES
            && matched(&ca, &cb)
            && matched(&cb, &ca)
    };
    let mut k = 0;
    while k + 1 < root.children.len() {
        if !same_cuts(&root.children[k], &root.children[k + 1]) {
            k += 1;
            continue;
        }
        // The upper band's pieces, taken down through the lower one; each
        // region of the lower one goes to the piece over its middle.
        let lower = root.children.remove(k + 1);
        let upper = &mut root.children[k];
        upper.bbox = union(upper.bbox, lower.bbox);
        upper.regions.extend(lower.regions.iter().copied());
        upper.fills.clear();
        let (y0, y1) = (upper.bbox[1], upper.bbox[3]);
        for p in &mut upper.children {
            p.bbox[1] = y0;
            p.bbox[3] = y1;
            p.fills.clear();
            p.children.clear();
            p.split = None;
        }
        for r in lower.regions {
            let mid = (regions[r].bbox[0] + regions[r].bbox[2]) / 2;
            if let Some(p) = upper.children.iter_mut().find(|p| mid < p.bbox[2]) {
                p.regions.push(r);
            } else if let Some(p) = upper.children.last_mut() {
                p.regions.push(r);
            }
        }
    }
}

/// See [`rejoin_pinched_bands`]: the fewest pieces (a roof has dozens of
/// tile rows), and how far two cuts may stand apart and still be one.
const PINCHED_MIN_PIECES: usize = 8;
const PINCHED_SHIFT: i32 = 2;

fn union(a: [i32; 4], b: [i32; 4]) -> [i32; 4] {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

/// Column-like regions of `band` that stand apart: the gap to the next one
/// is at least [`COLUMN_APART`] times its width. Columns stand a bay apart;
/// a roof's tile rows, as tall and thin, stand about their own width apart.
fn spaced_columns(band: &Node, regions: &[Region]) -> usize {
    let mut xs: Vec<(i32, i32)> = band
        .content()
        .filter(|&r| is_column(&regions[r], band.h()))
        .map(|r| (regions[r].bbox[0], regions[r].bbox[2]))
        .collect();
    xs.sort_unstable();
    xs.windows(2)
        .filter(|w| (w[1].0 - w[0].1) as f64 >= COLUMN_APART * (w[0].1 - w[0].0) as f64)
        .count()
}

/// See [`spaced_columns`].
const COLUMN_APART: f64 = 4.0;

fn is_column(r: &Region, band_h: i32) -> bool {
    r.h() as f64 >= COLUMN_HEIGHT * band_h as f64 && r.h() as f64 >= COLUMN_SLENDER * r.w() as f64
}

/// A plain piece: what is drawn inside it besides its own outline is
/// small (a corner cut off by a stray line).
pub(super) fn is_plain(c: &Node, regions: &[Region]) -> bool {
    let inner: u64 = c.content().map(|r| regions[r].area as u64).sum();
    inner * 5 < (c.w().max(0) as u64 * c.h().max(0) as u64)
}

/// Makes `node` one leaf labelled `label`.
pub(super) fn collapse(node: &mut Node, label: &'static str) {
    node.label = label;
    node.children.clear();
    node.split = None;
}

/// The box around the regions drawn in `node` other than its fills, or
/// its own box when there are none.
fn content_box(node: &Node, regions: &[Region]) -> [i32; 4] {
    let mut b = [i32::MAX, i32::MAX, i32::MIN, i32::MIN];
    for r in node.content() {
        let rb = regions[r].bbox;
        b = [
            b[0].min(rb[0]),
            b[1].min(rb[1]),
            b[2].max(rb[2]),
            b[3].max(rb[3]),
        ];
    }
    if b[0] > b[2] {
        node.bbox
    } else {
        b
    }
}

fn platform(band: &mut Node) {
    band.label = "platform";
    if band.split != Some(Axis::X) {
        band.children.clear();
        band.split = None;
        return;
    }
    // The stairs: a middle piece drawn as steps stacked up.
    let n = band.children.len();
    for (k, c) in band.children.iter_mut().enumerate() {
        let stacked = c.split == Some(Axis::Y) && c.children.len() >= 2;
        let middle = k > 0 && k + 1 < n;
        collapse(
            c,
            if stacked && middle {
                "stairs"
            } else {
                "platform"
            },
        );
    }
}

/// The body: columns and the bays between them.
fn body(band: &mut Node, regions: &[Region]) {
    band.label = "other";
    if band.split != Some(Axis::X) {
        bay(band, regions);
        return;
    }
    let h = band.h();
    let is_col: Vec<bool> = band
        .children
        .iter()
        .map(|c| {
            // A piece as tall as a column and as thin, with a column
            // drawn in it (a round column's outline may hold several
            // regions between its shading lines).
            c.h() as f64 >= COLUMN_SLENDER * c.w() as f64
                && c.content()
                    .chain(c.fills.iter().copied())
                    .any(|r| regions[r].h() as f64 >= COLUMN_HEIGHT * h as f64)
        })
        .collect();
    // Columns are all about as thin: a bay as narrow as the test above
    // (an end bay under a tall wall) is wider than the thinnest column.
    let thinnest = band
        .children
        .iter()
        .zip(&is_col)
        .filter(|(_, &col)| col)
        .map(|(c, _)| c.w())
        .min()
        .unwrap_or(0);
    let is_col: Vec<bool> = band
        .children
        .iter()
        .zip(is_col)
        .map(|(c, col)| col && c.w() as f64 <= 1.5 * thinnest as f64 + 2.0)
        .collect();
    // An end column drawn flush with the wall's end is one piece with it,
    // wider than the other columns: when a bay lies between the outermost
    // piece and the first column found, that piece is the end column.
    let mut is_col = is_col;
    let slender = |c: &Node| c.h() as f64 >= COLUMN_SLENDER * c.w() as f64;
    let n = band.children.len();
    if n >= 3 {
        if is_col.iter().position(|&b| b).is_some_and(|f| f >= 2) && slender(&band.children[0]) {
            is_col[0] = true;
        }
        if is_col.iter().rposition(|&b| b).is_some_and(|l| l + 2 < n)
            && slender(&band.children[n - 1])
        {
            is_col[n - 1] = true;
        }
    }
    let first = is_col.iter().position(|&b| b);
    let last = is_col.iter().rposition(|&b| b);
    let mut widths = Vec::new();
    for (k, c) in band.children.iter_mut().enumerate() {
        if is_col[k] {
            collapse(c, "column");
            c.bbox = content_box(c, regions);
        } else if first.is_some_and(|f| k < f) || last.is_some_and(|l| k > l) {
            // Outside the outer columns: the wall's end, or paper when
            // nothing is drawn there (the roof's overhang above it).
            if c.regions.is_empty() {
                collapse(c, "other");
            } else if c.w() * 4 < h {
                collapse(c, "wall");
            } else {
                bay(c, regions);
                widths.push(c.w());
            }
        } else {
            bay(c, regions);
            widths.push(c.w());
        }
    }
    // The bays repeat when most of them are alike.
    widths.sort_unstable();
    let median = widths.get(widths.len() / 2).copied().unwrap_or(0);
    let alike = widths
        .iter()
        .filter(|&&w| (w - median).abs() as f64 <= 0.08 * median as f64)
        .count();
    band.repeat = alike >= 3;
}

fn bay(node: &mut Node, regions: &[Region]) {
    node.label = "bay";
    let (floor, height) = (node.bbox[3], node.h());
    let mut rest_from = 0;
    if node.split == Some(Axis::Y) && node.children.len() >= 2 {
        let top = &mut node.children[0];
        if (top.h() as f64) < 0.3 * height as f64 {
            collapse(top, "lintel");
            rest_from = 1;
        }
    }
    if rest_from == 0 {
        let mut whole = std::mem::replace(node, placeholder());
        elements(&mut whole, regions, floor, height, false);
        let label = whole.label;
        *node = whole;
        if label == "wall" {
            // A bay with nothing drawn in it stays a bay (a leaf).
            node.label = "bay";
        } else if node.children.is_empty() {
            // The element fills the bay: keep the bay as its parent.
            let element = node.clone();
            node.label = "bay";
            node.children = vec![element];
            node.split = Some(Axis::Y);
        } else {
            node.label = "bay";
        }
        return;
    }
    // A piece under the lintel with no region in it, and no region of the
    // bay's around it, is ink (`inked`); next to a door or window it is
    // part of it: a shaky hand closed a fine lattice's cells in some rows.
    let inked: Vec<bool> = node
        .children
        .iter()
        .map(|c| inked(node, c, regions))
        .collect();
    for c in &mut node.children[rest_from..] {
        elements(c, regions, floor, height, false);
    }
    // Pieces with a door or window in them, one above the other under the
    // lintel, are one element: a shaky hand pinches a lattice's cells shut
    // along a line, and the window comes in two rows (or in rows of ink).
    let found: Vec<bool> = node
        .children
        .iter()
        .enumerate()
        .map(|(k, c)| {
            k >= rest_from
                && c.leaves()
                    .iter()
                    .any(|l| matches!(l.label, "door" | "window"))
        })
        .collect();
    let mut ink_beside = ink_beside(&inked[rest_from..], &found[rest_from..]);
    ink_beside.splice(0..0, vec![false; rest_from]);
    let element: Vec<bool> = found
        .iter()
        .zip(&ink_beside)
        .map(|(f, i)| *f || *i)
        .collect();
    let rest: Vec<(Node, bool, bool)> = node
        .children
        .drain(rest_from..)
        .zip(element.into_iter().skip(rest_from))
        .zip(inked.into_iter().skip(rest_from))
        .map(|((c, e), i)| (c, e, i))
        .collect();
    let mut run: Vec<(Node, bool)> = Vec::new();
    let flush = |run: &mut Vec<(Node, bool)>, children: &mut Vec<Node>| match run.len() {
        0 => {}
        1 if !run[0].1 => children.push(run.remove(0).0),
        _ => children.push(merged(
            &std::mem::take(run),
            Axis::Y,
            regions,
            floor,
            height,
        )),
    };
    for (c, is_element, ink) in rest {
        if !is_element {
            flush(&mut run, &mut node.children);
            node.children.push(c);
        } else {
            run.push((c, ink));
        }
    }
    flush(&mut run, &mut node.children);
}

/// Whether `piece`, a child of `node`, is ink: nothing drawn in it, and
/// no region of `node`'s around it (a wall drawn as one ring round its
/// window covers the strips beside the window). A lattice so fine that
/// thickening the lines by `--gap` closed its cells leaves such pieces,
/// and a shaky line closes more of them.
fn inked(node: &Node, piece: &Node, regions: &[Region]) -> bool {
    let b = piece.bbox;
    let (cx, cy) = ((b[0] + b[2]) / 2, (b[1] + b[3]) / 2);
    piece.regions.is_empty()
        && !node.regions.iter().any(|&r| {
            let o = regions[r].bbox;
            o[0] <= cx && cx < o[2] && o[1] <= cy && cy < o[3]
        })
}

/// The pieces that are ink (`inked`) in an unbroken run of ink between an
/// element (`found`) and another piece: not the first or last piece,
/// where ink is the strip between two lines close together (a window's
/// frame and the column beside it), closed up by `--gap`.
fn ink_beside(inked: &[bool], found: &[bool]) -> Vec<bool> {
    let n = inked.len();
    let mut out = vec![false; n];
    for k in (1..n.saturating_sub(1)).filter(|&k| inked[k]) {
        let up = (0..k).rev().find(|&j| !inked[j]).is_some_and(|j| found[j]);
        let down = (k + 1..n).find(|&j| !inked[j]).is_some_and(|j| found[j]);
        out[k] = up || down;
    }
    out
}

/// One door or window, a leaf, of the pieces `run`, side by side (`axis`
/// x) or one above the other (y); those flagged are ink, and only add
/// their extent along `axis`.
fn merged(run: &[(Node, bool)], axis: Axis, regions: &[Region], floor: i32, height: i32) -> Node {
    let mut m = run[0].0.clone();
    for (r, _) in &run[1..] {
        m.bbox = union(m.bbox, r.bbox);
        m.regions.extend(r.regions.iter().copied());
    }
    m.fills.clear();
    m.children.clear();
    m.split = None;
    let mut b = content_box(&m, regions);
    let (lo, hi) = if axis == Axis::X { (0, 2) } else { (1, 3) };
    for (r, _) in run.iter().filter(|(_, ink)| *ink) {
        b[lo] = b[lo].min(r.bbox[lo]);
        b[hi] = b[hi].max(r.bbox[hi]);
    }
    element_at(&mut m, b, floor, height);
    m
}

pub(super) fn placeholder() -> Node {
    Node {
        label: "other",
        bbox: [0; 4],
        split: None,
        repeat: false,
        children: Vec::new(),
        regions: Vec::new(),
        fills: Vec::new(),
    }
}

/// The doors and windows in `node`, part of a bay whose floor is at `floor`
/// and whose height is `height`; the rest is wall.
///
/// `nested` is false for the part of the bay under its lintel, where a
/// region filling the node is the wall itself, and true for the pieces cut
/// out of that wall, where a region filling a piece is a drawn outline (a
/// door or window drawn as a plain rectangle).
fn elements(node: &mut Node, regions: &[Region], floor: i32, height: i32, nested: bool) {
    let plain = node.content().next().is_none();
    if node.regions.is_empty() || (plain && !nested) {
        collapse(node, "wall");
        return;
    }
    let Some(axis) = node.split else {
        element(node, regions, floor, height);
        return;
    };
    // Walls: undrawn pieces, and along x plain narrow strips at the sides.
    let n = node.children.len();
    let wall: Vec<bool> = node
        .children
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let side = k == 0 || k + 1 == n;
            let plain = is_plain(c, regions);
            c.regions.is_empty() || (axis == Axis::X && side && plain && c.w() * 4 < node.w())
        })
        .collect();
    let drawn: Vec<usize> = (0..n).filter(|&k| !wall[k]).collect();
    // Ink beside a drawn piece is part of it (`inked`).
    let inked: Vec<bool> = node
        .children
        .iter()
        .map(|c| inked(node, c, regions))
        .collect();
    let found: Vec<bool> = wall.iter().map(|w| !w).collect();
    let ink = ink_beside(&inked, &found);
    if drawn.len() == 1 && !ink.contains(&true) {
        for (k, c) in node.children.iter_mut().enumerate() {
            if wall[k] {
                collapse(c, "wall");
            } else {
                elements(c, regions, floor, height, true);
            }
        }
        node.label = "other";
        return;
    }
    // Several drawn pieces next to each other make one element; a wall
    // between them separates two.
    let mut children = Vec::new();
    let mut run: Vec<(Node, bool)> = Vec::new();
    let flush = |run: &mut Vec<(Node, bool)>, children: &mut Vec<Node>| {
        if !run.is_empty() {
            children.push(merged(run, axis, regions, floor, height));
            run.clear();
        }
    };
    // A narrow undrawn strip between two drawn pieces (the joint between a
    // double door's leaves, its lines merged by blur) does not part them.
    let size = |c: &Node| if axis == Axis::X { c.w() } else { c.h() };
    let joint: Vec<bool> = (0..n)
        .map(|k| {
            k > 0
                && k + 1 < n
                && wall[k]
                && !wall[k - 1]
                && !wall[k + 1]
                && (size(&node.children[k]) as f64)
                    < 0.3 * size(&node.children[k - 1]).min(size(&node.children[k + 1])) as f64
        })
        .collect();
    for (k, mut c) in std::mem::take(&mut node.children).into_iter().enumerate() {
        if wall[k] && !joint[k] && !ink[k] {
            flush(&mut run, &mut children);
            collapse(&mut c, "wall");
            children.push(c);
        } else {
            run.push((c, ink[k]));
        }
    }
    flush(&mut run, &mut children);
    if children.len() == 1 {
        *node = children.pop().unwrap_or_else(placeholder);
    } else {
        node.children = children;
        node.label = "other";
    }
}

/// A door or a window, by where it stands.
fn element(node: &mut Node, regions: &[Region], floor: i32, height: i32) {
    element_at(node, content_box(node, regions), floor, height);
}

/// A door or a window drawn over `b`, by where it stands.
fn element_at(node: &mut Node, b: [i32; 4], floor: i32, height: i32) {
    let on_floor = (floor - b[3]) as f64 <= 0.04 * height as f64;
    let tall = (b[3] - b[1]) as f64 >= 0.4 * height as f64;
    collapse(node, if on_floor && tall { "door" } else { "window" });
    node.bbox = b;
}

/// Boxes of drawn regions in leaves still labelled `other`, where the
/// drawing had something the rules could not name.
pub fn unlabelled(root: &Node, regions: &[Region]) -> Vec<[i32; 4]> {
    let mut out = Vec::new();
    for leaf in root.leaves() {
        if leaf.label == "other" && leaf.content().next().is_some() {
            out.push(content_box(leaf, regions));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A band over `y0..y1` cut along x at `cuts` (0 and 100 are its ends).
    fn band(y0: i32, y1: i32, cuts: &[i32]) -> Node {
        let mut xs = vec![0];
        xs.extend_from_slice(cuts);
        xs.push(100);
        let mut b = placeholder();
        b.bbox = [0, y0, 100, y1];
        b.split = Some(Axis::X);
        b.children = xs
            .windows(2)
            .map(|w| Node {
                bbox: [w[0], y0, w[1], y1],
                ..placeholder()
            })
            .collect();
        b
    }

    fn root(bands: Vec<Node>) -> Node {
        let mut r = placeholder();
        r.bbox = [0, 0, 100, 60];
        r.split = Some(Axis::Y);
        r.children = bands;
        r
    }

    #[test]
    fn a_band_pinched_in_two_is_joined_and_other_bands_are_not() {
        let tiles: Vec<i32> = (1..10).map(|k| k * 10).collect();
        // The lower half's cuts wander by up to 2 pixels and one is lost.
        let shaken: Vec<i32> = (1..10)
            .filter(|&k| k != 5)
            .map(|k| k * 10 + k % 3 - 1)
            .collect();
        let mut r = root(vec![
            band(0, 10, &tiles),
            band(10, 25, &shaken),
            band(25, 40, &[30, 70]),
        ]);
        rejoin_pinched_bands(&mut r, &[]);
        assert_eq!(r.children.len(), 2);
        assert_eq!(r.children[0].bbox, [0, 0, 100, 25]);
        assert_eq!(r.children[0].children.len(), 10);
        assert!(r.children[0]
            .children
            .iter()
            .all(|p| p.bbox[1] == 0 && p.bbox[3] == 25));
        // Rafters at another pitch under the tiles stay apart.
        let rafters: Vec<i32> = (1..13).map(|k| k * 8 - 3).collect();
        let mut r = root(vec![band(0, 10, &tiles), band(10, 25, &rafters)]);
        rejoin_pinched_bands(&mut r, &[]);
        assert_eq!(r.children.len(), 2);
    }

    /// A bay 0..60 x 0..100 under a lintel 0..10: a wall strip with its
    /// own region 10..20, then the window's pieces one above the other,
    /// `rows` (with or without a cell of the lattice left open in them),
    /// then a wall strip with its own region down to the floor.
    fn bay_of(rows: &[(i32, i32, bool)]) -> (Node, Vec<Region>) {
        let mut regions = vec![
            Region {
                bbox: [0, 10, 60, 20],
                area: 400,
            },
            Region {
                bbox: [0, 80, 60, 100],
                area: 800,
            },
        ];
        let mut b = placeholder();
        b.bbox = [0, 0, 60, 100];
        b.split = Some(Axis::Y);
        b.regions = vec![0, 1];
        b.children = vec![
            Node {
                bbox: [0, 0, 60, 10],
                ..placeholder()
            },
            Node {
                bbox: [0, 10, 60, 20],
                regions: vec![0],
                fills: vec![0],
                ..placeholder()
            },
        ];
        for &(y0, y1, open) in rows {
            let mut piece = Node {
                bbox: [0, y0, 60, y1],
                ..placeholder()
            };
            if open {
                // Three cells of the lattice, side by side.
                for x in [10, 25, 40] {
                    piece.regions.push(regions.len());
                    b.regions.push(regions.len());
                    regions.push(Region {
                        bbox: [x, y0, x + 10, y1],
                        area: 40,
                    });
                }
            }
            b.children.push(piece);
        }
        b.children.push(Node {
            bbox: [0, 80, 60, 100],
            regions: vec![1],
            fills: vec![1],
            ..placeholder()
        });
        (b, regions)
    }

    fn windows(n: &Node) -> Vec<[i32; 4]> {
        n.leaves()
            .into_iter()
            .filter(|l| l.label == "window")
            .map(|l| l.bbox)
            .collect()
    }

    #[test]
    fn rows_of_ink_beside_a_window_are_part_of_it() {
        // A shaky hand closed the lattice's cells but in the middle row.
        let (mut b, regions) = bay_of(&[(20, 40, false), (40, 60, true), (60, 80, false)]);
        bay(&mut b, &regions);
        assert_eq!(windows(&b), vec![[10, 20, 50, 80]]);
        // Every row open: the same window, from its cells.
        let (mut b, regions) = bay_of(&[(20, 40, true), (40, 60, true), (60, 80, true)]);
        bay(&mut b, &regions);
        assert_eq!(windows(&b), vec![[10, 20, 50, 80]]);
        // A wall drawn as one region round the window covers the strips
        // next to it: they stay wall, and the window is its cells.
        let (mut b, mut regions) = bay_of(&[(20, 40, false), (40, 60, true), (60, 80, false)]);
        b.regions.push(regions.len());
        regions.push(Region {
            bbox: [0, 10, 60, 100],
            area: 2000,
        });
        bay(&mut b, &regions);
        assert_eq!(windows(&b), vec![[10, 40, 50, 60]]);
    }
}
