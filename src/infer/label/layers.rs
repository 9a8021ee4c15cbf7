//! The bracket and rafter layers: a band between the body and the roof
//! -> its pieces labelled, each drawn element one leaf, the layer's back
//! `other`. Sets drawn as stacked parts, quartered blocks, plain outlines,
//! hanging arms or blocks hanging between closed back, and rafter ends
//! drawn with an inside or closed up into posts of ink by `--gap`, are
//! each read here (see `docs/drawing.md`).

use super::super::regions::Region;
use super::super::tree::{Axis, Node};
use super::posts::posts;
use super::{collapse, is_plain, placeholder};

/// A bracket or rafter layer: each piece with something drawn is one
/// element; the others are the layer's back.
pub(super) fn row_of(band: &mut Node, kind: &'static str, regions: &[Region]) {
    band.label = "other";
    if kind == "bracket" {
        broken_back(band, regions);
    }
    // A layer narrower than the band (the bracket layer under a wider
    // roof) is the one drawn piece between two empty margins.
    let mut band = band;
    while band.split.is_some()
        && band
            .children
            .iter()
            .filter(|c| !c.regions.is_empty())
            .count()
            == 1
        && band.children.len() > 1
    {
        for c in &mut band.children {
            if c.regions.is_empty() {
                collapse(c, "other");
            }
        }
        let inner = band.children.iter().position(|c| !c.regions.is_empty());
        match inner {
            Some(i) => band = &mut band.children[i],
            None => break,
        }
        band.label = "other";
    }
    // A layer that goes round the corners: at each end of the front's
    // row, a side face's first element seen end-on, cut off from the
    // row by a line of its own. Those ends are elements; the row is the
    // one drawn piece wider than half the band, read as a layer itself.
    if band.split == Some(Axis::X) {
        let drawn = |c: &Node| !c.regions.is_empty();
        let wide: Vec<usize> = (0..band.children.len())
            .filter(|&k| drawn(&band.children[k]) && band.children[k].w() * 2 > band.w())
            .collect();
        let ends = band.children.iter().filter(|c| drawn(c)).count() - wide.len();
        if wide.len() == 1 && (1..=2).contains(&ends) {
            for (k, c) in band.children.iter_mut().enumerate() {
                if k != wide[0] {
                    let label = if drawn(c) { kind } else { "other" };
                    collapse(c, label);
                }
            }
            row_of(&mut band.children[wide[0]], kind, regions);
            return;
        }
    }
    if band.split == Some(Axis::Y) {
        // Elements drawn as stacked parts (a bracket set's arm over its
        // block) are cut into rows first: take the layer by columns.
        by_columns(band, regions);
    }
    if band.split != Some(Axis::X) {
        if band.content().next().is_some() {
            collapse(band, kind);
        }
        return;
    }
    if kind == "rafter" {
        if let Some(n) = posts(band, regions, kind) {
            band.repeat = n >= 3;
            return;
        }
    }
    // Corner sets: a side face's first set seen end-on at each end of the
    // row, narrow, with a narrow piece of back beside it (the front row's
    // margin). The sets are set aside (their regions hidden from the rules
    // below) and are sets; the margins are back.
    let (corners, margins) = if kind == "bracket" {
        corner_sets(band)
    } else {
        Default::default()
    };
    for k in margins {
        let c = &mut band.children[k];
        c.regions.clear();
        c.fills.clear();
    }
    // Kept by box: merging detailed runs below renumbers the pieces.
    let hidden: Vec<([i32; 4], Vec<usize>)> = corners
        .iter()
        .map(|&k| {
            let c = &mut band.children[k];
            (c.bbox, std::mem::take(&mut c.regions))
        })
        .collect();
    // When the bracket sets stand from the beam to the eave, the layer's
    // back between them is cut into closed pieces too: an unbroken run of
    // an odd number of drawn pieces alternates sets and back. Which are
    // the sets: the run's end pieces are margins of back when they are
    // not as wide as the others of their parity (a margin is whatever was
    // left at the layer's end), sets otherwise (sets repeat exactly).
    // (Rafter rows were read by `posts` above.)
    let drawn: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let unbroken = drawn.windows(2).all(|w| w[1] == w[0] + 1);
    let mut alternate: Option<Vec<bool>> = if kind == "bracket" {
        hanging_sets(band, &drawn, regions)
    } else {
        None
    };
    if kind == "bracket"
        && alternate.is_none()
        && unbroken
        && drawn.len() >= 5
        && drawn.len() % 2 == 1
    {
        let even: Vec<i32> = drawn
            .iter()
            .step_by(2)
            .map(|&k| band.children[k].w())
            .collect();
        let mut inner = even[1..even.len() - 1].to_vec();
        inner.sort_unstable();
        let med = inner[inner.len() / 2] as f64;
        let off = |w: i32| (w as f64 - med).abs() > 0.2 * med + 1.0;
        let ends_are_back = off(even[0]) || off(even[even.len() - 1]);
        // The ends' parity, unless its pieces are not all plain and the
        // other parity's are: sets hanging from the layer's top (a block
        // under the rafters) leave the back between them closed, as wide
        // as a set, and the row's margins are then as wide as the back.
        let preferred = usize::from(!ends_are_back);
        let backs_plain = |parity: usize| {
            drawn
                .iter()
                .skip(parity)
                .step_by(2)
                .all(|&k| is_plain(&band.children[k], regions))
        };
        alternate = [preferred, 1 - preferred]
            .into_iter()
            .find(|&p| backs_plain(p))
            .map(|p| {
                let f = drawn[0];
                (0..band.children.len())
                    .map(|k| k >= f && (k - f) % 2 == p)
                    .collect()
            });
    }
    // Bracket sets drawn with inner lines (a block quartered by its arms)
    // are cut into several pieces, each with something drawn inside; the
    // back's pieces between them are plain: a run of adjacent detailed
    // pieces is one set.
    if kind == "bracket" && alternate.is_none() {
        merge_detailed_runs(band, regions);
    }
    // A drawn sliver under a third of the sets' median width is a piece of
    // back closed off by a line drawn close beside a set; inside the row
    // (not at its ends, where a corner set seen end-on is narrow too),
    // under half of it.
    let mut widths: Vec<i32> = band
        .children
        .iter()
        .filter(|c| !c.regions.is_empty())
        .map(|c| c.w())
        .collect();
    widths.sort_unstable();
    let median = widths.get(widths.len() / 2).copied().unwrap_or(0);
    let drawn_at: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let inner = |k: usize| drawn_at.first() < Some(&k) && drawn_at.last() > Some(&k);
    let sliver = |k: usize, c: &Node| {
        let limit = if inner(k) { 2 } else { 3 };
        kind == "bracket" && c.w() * limit < median && is_plain(c, regions)
    };
    let mut n = 0;
    for (k, c) in band.children.iter_mut().enumerate() {
        let back = sliver(k, c) || alternate.as_ref().is_some_and(|back| back[k]);
        if c.regions.is_empty() || back {
            collapse(c, "other");
            // The layer's back, not something left unrecognised.
            c.regions.clear();
            c.fills.clear();
        } else {
            collapse(c, kind);
            n += 1;
        }
    }
    for (bbox, regions) in hidden {
        if let Some(c) = band.children.iter_mut().find(|c| c.bbox == bbox) {
            c.regions = regions;
            collapse(c, kind);
            n += 1;
        }
    }
    band.repeat = n >= 3;
}

/// The back of a row of hanging sets broken into pieces: the channel
/// under each set, between its bottom and the beam, is a few pixels high,
/// and a shaky line (a scan's jitter) pinches it shut where the two come
/// close, so that the one region around every set (the layer's back)
/// falls into several, each around a set or a few, and the shape tree cut
/// the layer between them, through the sets. Each such piece reaches from
/// the layer's top to its bottom and holds a set (a region at most half
/// its width, inside it along x). When two such pieces or more reach from
/// top to bottom and one holds a set, every region reaching from top to
/// bottom is back: they become the band's fills, and the band is cut again
/// without them, as the tree cuts an unbroken back: a row of the sets over
/// an empty strip when they all hang, the row by columns.
fn broken_back(band: &mut Node, regions: &[Region]) {
    let [x0, y0, x1, y1] = band.bbox;
    let slack = reach_slack(band);
    let full = |r: usize| {
        let b = regions[r].bbox;
        f64::from(b[1] - y0) <= slack && f64::from(y1 - b[3]) <= slack
    };
    let holds_set = |r: usize| {
        let b = regions[r].bbox;
        band.content().any(|s| {
            let c = regions[s].bbox;
            s != r && !full(s) && c[0] >= b[0] && c[2] <= b[2] && 2 * (c[2] - c[0]) <= b[2] - b[0]
        })
    };
    let backs: Vec<usize> = band.content().filter(|&r| full(r)).collect();
    if backs.len() < 2 || !backs.iter().any(|&r| holds_set(r)) {
        return;
    }
    band.fills.extend(backs);
    let sets: Vec<usize> = band.content().collect();
    let bottom = sets.iter().map(|&r| regions[r].bbox[3]).max().unwrap_or(y1);
    if f64::from(y1 - bottom) <= slack {
        by_columns(band, regions);
        return;
    }
    let mut row = Node {
        bbox: [x0, y0, x1, bottom],
        regions: sets,
        ..placeholder()
    };
    by_columns(&mut row, regions);
    let strip = Node {
        bbox: [x0, bottom, x1, y1],
        ..placeholder()
    };
    band.children = vec![row, strip];
    band.split = Some(Axis::Y);
}

/// How far (pixels) a region's box may stop from the layer's top or bottom
/// and still reach it: an eighth of the layer's height, and at least 2.5,
/// as a line that wobbles a pixel (a scan's jitter) moves a box's edge by
/// one and the line next to it the other way.
fn reach_slack(band: &Node) -> f64 {
    (f64::from(band.h()) / 8.0).max(2.5)
}

/// Bracket sets hanging from the layer's top (a block under the rafters,
/// as `hall.lsys` draws them) leave the back between them closed, from
/// the layer's top to its bottom, and about as wide as a set: which pieces
/// are back is then seen from their height, not their parity (the corner
/// set seen end-on at each end of the row hangs too, next to the front's
/// first set). When every drawn piece either hangs (its regions start at
/// the layer's top and stop short of its bottom by more than an eighth of
/// its height) or reaches from top to bottom, at least two of each, and
/// those reaching are all plain, they are the back: one flag per piece,
/// or None.
fn hanging_sets(band: &Node, drawn: &[usize], regions: &[Region]) -> Option<Vec<bool>> {
    let [_, y0, _, y1] = band.bbox;
    let slack = reach_slack(band);
    let reach = |k: usize, bottom: bool| {
        band.children[k].regions.iter().map(move |&r| {
            let b = regions[r].bbox;
            f64::from(b[1] - y0) <= slack && (f64::from(y1 - b[3]) <= slack) == bottom
        })
    };
    // Every region of a piece reaching from top to bottom, or every one
    // hanging from the top (a set drawn in parts one above the other, a
    // quartered block, is neither: the rule is not for that row).
    let full = |k: usize| reach(k, true).all(|ok| ok);
    let hangs = |k: usize| reach(k, false).all(|ok| ok);
    if !drawn.iter().all(|&k| full(k) || hangs(k)) {
        return None;
    }
    let (backs, sets): (Vec<usize>, Vec<usize>) = drawn.iter().partition(|&&k| full(k));
    let plain = backs.iter().all(|&k| is_plain(&band.children[k], regions));
    if backs.len() < 2 || sets.len() < 2 || !plain {
        return None;
    }
    Some(
        (0..band.children.len())
            .map(|k| backs.contains(&k))
            .collect(),
    )
}

/// The two corner sets of a bracket row and the margins of back beside
/// them, if the row has them: at each end the first two drawn pieces are
/// adjacent and both under 0.8 of the median width of the pieces between.
fn corner_sets(band: &Node) -> (Vec<usize>, Vec<usize>) {
    let drawn: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let n = drawn.len();
    if n < 7 {
        return Default::default();
    }
    let mut widths: Vec<i32> = drawn[2..n - 2]
        .iter()
        .map(|&k| band.children[k].w())
        .collect();
    widths.sort_unstable();
    let median = widths[widths.len() / 2] as f64;
    let narrow = |k: usize| (band.children[k].w() as f64) < 0.8 * median;
    let (a, b, y, z) = (drawn[0], drawn[1], drawn[n - 2], drawn[n - 1]);
    if b == a + 1 && z == y + 1 && [a, b, y, z].into_iter().all(narrow) {
        (vec![a, z], vec![b, y])
    } else {
        Default::default()
    }
}

/// In a layer with both plain and detailed drawn pieces, joins each run
/// of adjacent detailed pieces into one piece; the plain ones become
/// undrawn back.
fn merge_detailed_runs(band: &mut Node, regions: &[Region]) {
    let detailed: Vec<bool> = band
        .children
        .iter()
        .map(|c| !c.regions.is_empty() && !is_plain(c, regions))
        .collect();
    let plain_drawn = band
        .children
        .iter()
        .zip(&detailed)
        .any(|(c, &d)| !d && !c.regions.is_empty());
    if !plain_drawn || !detailed.windows(2).any(|w| w[0] && w[1]) {
        return;
    }
    let mut out: Vec<Node> = Vec::new();
    let mut last_detailed = false;
    for (c, d) in std::mem::take(&mut band.children).into_iter().zip(detailed) {
        match out.last_mut() {
            Some(prev) if d && last_detailed => {
                prev.bbox[2] = c.bbox[2];
                prev.regions.extend(c.regions);
                prev.children.clear();
                prev.split = None;
                prev.fills.clear();
            }
            _ if d => out.push(c),
            _ => out.push(Node {
                bbox: c.bbox,
                ..placeholder()
            }),
        }
        last_detailed = d;
    }
    band.children = out;
}

/// Re-cuts `band` along x where no region drawn in it (other than those
/// filling it, the layer's back) crosses: each cluster of region boxes
/// projected on x is one piece, and the strips between them are pieces
/// with nothing drawn.
fn by_columns(band: &mut Node, regions: &[Region]) {
    let mut spans: Vec<(i32, i32, usize)> = band
        .content()
        .map(|r| (regions[r].bbox[0], regions[r].bbox[2], r))
        .collect();
    if spans.is_empty() {
        return;
    }
    spans.sort_unstable();
    let [x0, y0, x1, y1] = band.bbox;
    let mut pieces: Vec<Node> = Vec::new();
    let mut at = x0;
    let mut k = 0;
    while k < spans.len() {
        let (lo, mut hi, _) = spans[k];
        let mut members = Vec::new();
        while k < spans.len() && spans[k].0 <= hi {
            hi = hi.max(spans[k].1);
            members.push(spans[k].2);
            k += 1;
        }
        if lo > at {
            pieces.push(Node {
                bbox: [at, y0, lo, y1],
                ..placeholder()
            });
        }
        pieces.push(Node {
            bbox: [lo, y0, hi, y1],
            regions: members,
            ..placeholder()
        });
        at = hi;
    }
    if at < x1 {
        pieces.push(Node {
            bbox: [at, y0, x1, y1],
            ..placeholder()
        });
    }
    band.children = pieces;
    band.split = Some(Axis::X);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A layer `y0..y1` from x 0 to a pixel past the last of the regions
    /// `boxes` (its end lines), cut between them
    /// (left to right) at the middle of the ink between each two, one
    /// region to a piece; regions reaching from top to bottom fill their
    /// piece, as the shape tree has it.
    fn row(y0: i32, y1: i32, boxes: &[[i32; 2]], hang: &[usize]) -> (Node, Vec<Region>) {
        let regions: Vec<Region> = boxes
            .iter()
            .enumerate()
            .map(|(k, b)| Region {
                bbox: [
                    b[0],
                    y0,
                    b[1],
                    if hang.contains(&k) {
                        y0 + (y1 - y0) * 7 / 10
                    } else {
                        y1
                    },
                ],
                area: 1,
            })
            .collect();
        let mut cuts = vec![0];
        cuts.extend(boxes.windows(2).map(|w| (w[0][1] + w[1][0]) / 2));
        let end = boxes.last().map_or(1, |b| b[1] + 1);
        cuts.push(end);
        let mut band = Node::leaf("other", [0, y0, end, y1]);
        band.split = Some(Axis::X);
        band.children = cuts
            .windows(2)
            .enumerate()
            .map(|(k, c)| Node {
                regions: vec![k],
                fills: if hang.contains(&k) { vec![] } else { vec![k] },
                ..Node::leaf("other", [c[0], y0, c[1], y1])
            })
            .collect();
        (band, regions)
    }

    fn leaves(band: &Node, kind: &str) -> Vec<[i32; 4]> {
        band.leaves()
            .into_iter()
            .filter(|n| n.label == kind)
            .map(|n| n.bbox)
            .collect()
    }

    #[test]
    fn rafters_closed_into_posts_are_the_ink_between_the_gaps() {
        // Eleven gaps 8 wide between ten posts 5 wide; the row's own lines
        // at its two ends.
        let gaps: Vec<[i32; 2]> = (0..11).map(|k| [1 + 13 * k, 9 + 13 * k]).collect();
        let (mut band, regions) = row(0, 10, &gaps, &[]);
        row_of(&mut band, "rafter", &regions);
        let posts = leaves(&band, "rafter");
        assert_eq!(posts.len(), 10, "{posts:?}");
        assert_eq!(posts[0], [9, 0, 14, 10]);
        assert!(band.repeat);
        // Pieces of one width with plain lines between them are the
        // rafters themselves, each drawn piece one.
        let drawn: Vec<[i32; 2]> = (0..11).map(|k| [1 + 9 * k, 9 + 9 * k]).collect();
        let (mut band, regions) = row(0, 10, &drawn, &[]);
        row_of(&mut band, "rafter", &regions);
        assert_eq!(leaves(&band, "rafter").len(), 11);
    }

    #[test]
    fn rafters_with_an_inside_are_the_narrow_pieces() {
        // Back 9 wide and rafters 4 wide by turns, back at both ends.
        let mut boxes = Vec::new();
        let mut x = 1;
        for k in 0..13 {
            let w = if k % 2 == 0 { 9 } else { 4 };
            boxes.push([x, x + w]);
            x += w + 1;
        }
        let (mut band, regions) = row(0, 10, &boxes, &[]);
        row_of(&mut band, "rafter", &regions);
        let rafters = leaves(&band, "rafter");
        assert_eq!(rafters.len(), 6, "{rafters:?}");
        assert!(rafters.iter().all(|b| b[2] - b[0] <= 6));
    }

    #[test]
    fn hanging_sets_are_told_from_the_back_by_height_with_their_corners() {
        // corner, set, back, set, back, set, back, set, corner: the sets
        // and corners hang from the layer's top, the back reaches its
        // bottom; the corners are as narrow as a margin.
        let widths = [6, 12, 12, 12, 12, 12, 12, 12, 6];
        let mut boxes = Vec::new();
        let mut x = 10;
        for w in widths {
            boxes.push([x, x + w]);
            x += w + 1;
        }
        let hang = [0, 1, 3, 5, 7, 8];
        let (mut band, regions) = row(0, 20, &boxes, &hang);
        row_of(&mut band, "bracket", &regions);
        assert_eq!(leaves(&band, "bracket").len(), 6);
        // Without the heights (every piece reaching the bottom) the parity
        // of the ends decides, and the narrow ends are margins.
        let (mut band, regions) = row(0, 20, &boxes, &[1, 3, 5, 7]);
        row_of(&mut band, "bracket", &regions);
        assert_eq!(leaves(&band, "bracket").len(), 4);
    }

    #[test]
    fn a_back_broken_round_its_sets_still_leaves_one_set_a_piece() {
        // Eight sets 12 wide hanging 0..14 in a layer 0..20, every 20
        // pixels; the back around them broken in three by a shaky line
        // closing the channel under a set: 0..61, 61..121, 121..170.
        let sets: Vec<[i32; 4]> = (0..8).map(|k| [4 + 20 * k, 0, 16 + 20 * k, 14]).collect();
        let backs = [[0, 0, 62, 20], [60, 0, 122, 20], [120, 0, 170, 20]];
        let regions: Vec<Region> = sets
            .iter()
            .chain(&backs)
            .map(|&bbox| Region { bbox, area: 100 })
            .collect();
        // The tree cut the layer between the back's pieces, through a set.
        let mut band = Node::leaf("other", [0, 0, 170, 20]);
        band.regions = (0..regions.len()).collect();
        band.split = Some(Axis::X);
        band.children = [(0, 61), (61, 121), (121, 170)]
            .iter()
            .map(|&(x0, x1)| Node {
                regions: (0..regions.len())
                    .filter(|&r| {
                        let b = regions[r].bbox;
                        (x0..x1).contains(&((b[0] + b[2]) / 2))
                    })
                    .collect(),
                ..Node::leaf("other", [x0, 0, x1, 20])
            })
            .collect();
        row_of(&mut band, "bracket", &regions);
        let got = leaves(&band, "bracket");
        assert_eq!(got.len(), 8, "{got:?}");
        // Each set its own piece, over the empty strip under the row.
        assert!(got.iter().all(|b| b[1] == 0 && b[3] == 14), "{got:?}");
        assert_eq!(got[0], [4, 0, 16, 14]);
    }
}
