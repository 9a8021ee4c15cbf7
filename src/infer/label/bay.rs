//! One bay of the body: the pieces between two columns -> its lintel,
//! walls, and each door or window one leaf (pieces of one element drawn
//! side by side, one above the other, or in rows of ink, joined).

use super::super::regions::Region;
use super::super::tree::{Axis, Node};
use super::{collapse, content_box, is_plain, placeholder, union};

pub(super) fn bay(node: &mut Node, regions: &[Region]) {
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

#[cfg(test)]
mod tests {
    use super::*;

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
