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

mod bay;
mod layers;
mod ornaments;
mod posts;

use super::regions::Region;
use super::tree::{Axis, Node};
use bay::bay;
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
}
