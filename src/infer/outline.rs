//! Outlines: a labelled shape tree and its ink -> the same tree with each
//! door and window box reaching the element's drawn outline.
//!
//! Regions are found on lines thickened to bridge gaps, so the narrow
//! strips at a small window's sides (its frame, the first lattice cell)
//! close up and are lost: a 31-pixel window whose frame and bars stand 2 to
//! 4 pixels apart is left as its middle 15 pixels, and the frame goes to
//! the wall beside it. The ink still has those lines. A wall piece beside
//! an element is drawn blank between the line it shares with its
//! neighbour (a column's edge, the bay's side) and the element, so any
//! line crossing it from the element's top to its bottom is the element's
//! own: the element reaches the outermost one, and the wall gives up what
//! it took.

use super::drawing::Ink;
use super::tree::{Axis, Node};

/// A line crosses the element when this much of its span reaches it.
const CROSSING: f64 = 0.8;
/// A line within this many pixels of the wall's far side is the one the
/// wall shares with its neighbour (the wall's box reaches about the middle
/// of it).
const BOUNDARY: i32 = 3;

/// Moves the sides of every door and window in `root` out to their drawn
/// outlines, taking the room from the wall leaves beside them. In a split
/// along y the room between an element and the parent's sides is wall too
/// (a window merged from two rows stands in its bay alone).
pub fn snap(root: &mut Node, ink: &Ink) {
    if let Some(axis) = root.split {
        let (parent, n) = (root.bbox, root.children.len());
        for k in 0..n {
            if !is_element(&root.children[k]) {
                continue;
            }
            for side in [Side::Low, Side::High] {
                let beside = match side {
                    Side::Low => k.checked_sub(1),
                    Side::High => Some(k + 1).filter(|&j| j < n),
                };
                if let Some(j) = beside.filter(|&j| is_wall(&root.children[j])) {
                    let far = edge(&root.children[j].bbox, axis, side);
                    if let Some(e) = outer_line(&root.children[k].bbox, far, axis, side, ink) {
                        set(&mut root.children[k].bbox, axis, side, e);
                        set(&mut root.children[j].bbox, axis, side.other(), e);
                    }
                }
                // Across a split along y only: an element in a row cut
                // along x is as tall as the row, less its own sill lines.
                if axis == Axis::Y {
                    let far = edge(&parent, Axis::X, side);
                    if let Some(e) = outer_line(&root.children[k].bbox, far, Axis::X, side, ink) {
                        set(&mut root.children[k].bbox, Axis::X, side, e);
                    }
                }
            }
        }
    }
    for c in &mut root.children {
        snap(c, ink);
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Side {
    /// The side towards smaller coordinates.
    Low,
    High,
}

impl Side {
    fn other(self) -> Side {
        match self {
            Side::Low => Side::High,
            Side::High => Side::Low,
        }
    }
}

fn is_element(n: &Node) -> bool {
    n.children.is_empty() && matches!(n.label, "door" | "window")
}

fn is_wall(n: &Node) -> bool {
    n.children.is_empty() && n.label == "wall"
}

fn index(axis: Axis, side: Side) -> usize {
    match (axis, side) {
        (Axis::X, Side::Low) => 0,
        (Axis::Y, Side::Low) => 1,
        (Axis::X, Side::High) => 2,
        (Axis::Y, Side::High) => 3,
    }
}

fn edge(b: &[i32; 4], axis: Axis, side: Side) -> i32 {
    b[index(axis, side)]
}

fn set(b: &mut [i32; 4], axis: Axis, side: Side, v: i32) {
    b[index(axis, side)] = v;
}

/// Where the element's `side` along `axis` belongs between its box `b`
/// and `far` (the far side of the wall beside it): the outer edge of the
/// outermost line that crosses the element's whole span, leaving out the
/// line the wall shares with what lies beyond it. `None` when the wall is
/// blank.
///
/// Row by row across the element, so that a line that wanders (a scan, a
/// shaky hand) still counts though no single column of pixels crosses:
/// each row's outermost ink short of the shared line is taken, and the
/// edge is where [`CROSSING`] of the rows reach. Lines a pixel or two apart
/// (a frame's two edges, the frame and the column beside it) stay apart,
/// as they are within each row.
fn outer_line(b: &[i32; 4], far: i32, axis: Axis, side: Side, ink: &Ink) -> Option<i32> {
    let (lo, hi) = match axis {
        Axis::X => (b[1] + 1, b[3] - 1),
        Axis::Y => (b[0] + 1, b[2] - 1),
    };
    if hi <= lo {
        return None;
    }
    let inked = |at: i32, s: i32| {
        let (x, y) = match axis {
            Axis::X => (at, s),
            Axis::Y => (s, at),
        };
        x >= 0
            && y >= 0
            && (x as usize) < ink.width
            && (y as usize) < ink.height
            && ink.at(x as usize, y as usize)
    };
    let (start, end, step) = match side {
        Side::Low => (edge(b, axis, side) - 1, far, -1),
        Side::High => (edge(b, axis, side), far - 1, 1),
    };
    // Each row's outermost ink, as a distance out from the element.
    let mut reach: Vec<i32> = (lo..hi)
        .map(|s| {
            let mut out = 0;
            let mut at = start;
            while (at - end) * step < 0 {
                if inked(at, s) {
                    let mut o = at;
                    while (o + step - end) * step < 0 && inked(o + step, s) {
                        o += step;
                    }
                    if (o + BOUNDARY * step - end) * step >= 0 {
                        break;
                    }
                    out = (o - start) * step + 1;
                    at = o;
                }
                at += step;
            }
            out
        })
        .collect();
    reach.sort_unstable();
    // The distance that CROSSING of the rows reach or pass.
    let d = reach[((1.0 - CROSSING) * reach.len() as f64) as usize];
    (d > 0).then(|| match side {
        Side::Low => start - (d - 1),
        Side::High => start + d,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaf(label: &'static str, bbox: [i32; 4]) -> Node {
        Node::leaf(label, bbox)
    }

    /// Vertical lines at the given columns, rows 0..40, in a 60-wide page.
    fn lines(xs: &[usize]) -> Ink {
        let (width, height) = (60, 40);
        let mut ink = vec![false; width * height];
        for y in 0..height {
            for &x in xs {
                ink[y * width + x] = true;
            }
        }
        Ink { width, height, ink }
    }

    fn row(children: Vec<Node>) -> Node {
        Node {
            label: "other",
            bbox: [0, 0, 60, 40],
            split: Some(Axis::X),
            children,
            ..leaf("other", [0, 0, 60, 40])
        }
    }

    #[test]
    fn a_window_reaches_its_frame_lines_inside_the_walls() {
        // Walls from the bay's sides (0 and 59) to a window read as
        // 20..40 whose frame lines stand at 12 and 47.
        let mut n = row(vec![
            leaf("wall", [0, 0, 20, 40]),
            leaf("window", [20, 0, 40, 40]),
            leaf("wall", [40, 0, 60, 40]),
        ]);
        snap(&mut n, &lines(&[0, 1, 12, 14, 47, 58, 59]));
        let boxes: Vec<[i32; 4]> = n.children.iter().map(|c| c.bbox).collect();
        assert_eq!(boxes, [[0, 0, 12, 40], [12, 0, 48, 40], [48, 0, 60, 40]]);
    }

    #[test]
    fn blank_walls_and_the_bays_sides_leave_the_window_alone() {
        let mut n = row(vec![
            leaf("wall", [0, 0, 20, 40]),
            leaf("window", [20, 0, 40, 40]),
            leaf("wall", [40, 0, 60, 40]),
        ]);
        let before = n.clone();
        snap(&mut n, &lines(&[0, 1, 58, 59]));
        assert_eq!(n, before);
        // A line in the wall that stops short of the window's height (a
        // sill's end) is not its outline.
        let mut ink = lines(&[0, 1, 58, 59]);
        for y in 0..20 {
            ink.ink[y * 60 + 10] = true;
        }
        snap(&mut n, &ink);
        assert_eq!(n, before);
    }

    #[test]
    fn a_shaky_frame_line_still_crosses_and_a_lone_window_reaches_it_across_its_bay() {
        // The frame line at 12 wanders a pixel either way every 5 rows;
        // the window stands alone in a bay split along y (wall above and
        // below), so its x sides are snapped inside the bay.
        let mut ink = lines(&[0, 1, 47, 58, 59]);
        for y in 0..40 {
            ink.ink[y * 60 + (11 + (y / 5) % 3)] = true;
        }
        let mut n = Node {
            split: Some(Axis::Y),
            ..row(vec![
                leaf("wall", [0, 0, 60, 5]),
                leaf("window", [20, 5, 40, 35]),
                leaf("wall", [0, 35, 60, 40]),
            ])
        };
        snap(&mut n, &ink);
        // Every row reaches 13, a third reach 11: the edge is where most
        // rows reach.
        assert_eq!(n.children[1].bbox, [13, 5, 48, 35]);
    }
}
