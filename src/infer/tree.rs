//! The shape tree: [`Region`]s -> a tree of boxes made by alternating
//! vertical and horizontal splits from the top down (seed 003, Section 6).
//!
//! A node's box is cut along an axis wherever no region crosses: between
//! the clusters of region boxes projected on that axis, at the middle of
//! the line between them. Regions that fill the node's box (a wall around
//! its window, a bracket layer's back around its bracket sets) belong to
//! the node itself and do not stop a cut. A strip wider than the tolerance
//! with no region in it (the wall beside a window) is a piece of its own,
//! as a hand-written split would have it. Nodes split along y first, then
//! x, then y again; when the preferred axis has no cut the other is tried.

use super::regions::Region;

/// Split axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
}

impl Axis {
    pub fn other(self) -> Axis {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::X,
        }
    }
    fn lo(self, b: &[i32; 4]) -> i32 {
        match self {
            Axis::X => b[0],
            Axis::Y => b[1],
        }
    }
    fn hi(self, b: &[i32; 4]) -> i32 {
        match self {
            Axis::X => b[2],
            Axis::Y => b[3],
        }
    }
    fn with(self, b: &[i32; 4], lo: i32, hi: i32) -> [i32; 4] {
        match self {
            Axis::X => [lo, b[1], hi, b[3]],
            Axis::Y => [b[0], lo, b[2], hi],
        }
    }
}

/// A node of the shape tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub label: &'static str,
    /// `[x0, y0, x1, y1)` in pixels, y down.
    pub bbox: [i32; 4],
    pub split: Option<Axis>,
    /// The children repeat one element (found by the recogniser).
    pub repeat: bool,
    pub children: Vec<Node>,
    /// Indices of the regions drawn inside this node (its own and its
    /// children's).
    pub regions: Vec<usize>,
    /// Indices of the regions that fill this node's box.
    pub fills: Vec<usize>,
}

impl Node {
    /// A node with no children and no regions.
    pub fn leaf(label: &'static str, bbox: [i32; 4]) -> Node {
        Node {
            label,
            bbox,
            split: None,
            repeat: false,
            children: Vec::new(),
            regions: Vec::new(),
            fills: Vec::new(),
        }
    }

    pub fn w(&self) -> i32 {
        self.bbox[2] - self.bbox[0]
    }
    pub fn h(&self) -> i32 {
        self.bbox[3] - self.bbox[1]
    }
    /// Regions drawn inside this node other than those filling it.
    pub fn content(&self) -> impl Iterator<Item = usize> + '_ {
        self.regions
            .iter()
            .copied()
            .filter(|r| !self.fills.contains(r))
    }
    pub fn leaves(&self) -> Vec<&Node> {
        if self.children.is_empty() {
            vec![self]
        } else {
            self.children.iter().flat_map(|c| c.leaves()).collect()
        }
    }
}

/// A region fills a node when its box covers this much of the node's box
/// along both axes.
const FILL: f64 = 0.9;
/// ... or all of it but this many pixels.
const FILL_PIXELS: f64 = 5.0;
/// Splits stop this deep.
const MAX_DEPTH: usize = 14;

/// The shape tree of `regions` inside `bbox`, splitting along y first.
/// `tolerance` is the narrowest empty strip kept as a piece of its own.
pub fn shape_tree(regions: &[Region], bbox: [i32; 4], tolerance: i32) -> Node {
    let all: Vec<usize> = (0..regions.len()).collect();
    split(regions, bbox, all, Axis::Y, tolerance, 0)
}

fn split(
    regions: &[Region],
    bbox: [i32; 4],
    inside: Vec<usize>,
    prefer: Axis,
    tolerance: i32,
    depth: usize,
) -> Node {
    let covers = |r: &Region| {
        let spans = |a: Axis| {
            let lo = a.lo(&r.bbox).max(a.lo(&bbox));
            let hi = a.hi(&r.bbox).min(a.hi(&bbox));
            let extent = (a.hi(&bbox) - a.lo(&bbox)) as f64;
            // Thick or doubled lines eat a few pixels of a narrow piece.
            (hi - lo) as f64 >= extent - ((1.0 - FILL) * extent).max(FILL_PIXELS)
        };
        spans(Axis::X) && spans(Axis::Y)
    };
    let fills: Vec<usize> = inside
        .iter()
        .copied()
        .filter(|&i| covers(&regions[i]))
        .collect();
    let mut node = Node {
        label: "other",
        bbox,
        split: None,
        repeat: false,
        children: Vec::new(),
        regions: inside.clone(),
        fills: fills.clone(),
    };
    let mut rest: Vec<usize> = inside.into_iter().filter(|i| !fills.contains(i)).collect();
    if rest.is_empty() || depth >= MAX_DEPTH {
        return node;
    }
    // First as drawn; then, when nothing can be cut, with the regions that
    // run the node's whole width or height taken as its wall: a wall whose
    // narrow sides beside a window were pinched shut by thick or shaky
    // lines falls into such pieces, and each would stop every cut.
    for attempt in 0..2 {
        if attempt == 1 {
            let spans = |r: &Region, a: Axis| {
                let extent = (a.hi(&bbox) - a.lo(&bbox)) as f64;
                (a.hi(&r.bbox).min(a.hi(&bbox)) - a.lo(&r.bbox).max(a.lo(&bbox))) as f64
                    >= extent - ((1.0 - FILL) * extent).max(FILL_PIXELS)
            };
            let (walls, others): (Vec<usize>, Vec<usize>) = rest
                .iter()
                .partition(|&&i| spans(&regions[i], Axis::X) || spans(&regions[i], Axis::Y));
            if walls.is_empty() || others.is_empty() {
                break;
            }
            node.fills.extend(&walls);
            rest = others;
        }
        for axis in [prefer, prefer.other()] {
            let pieces = cuts(regions, &rest, bbox, axis, tolerance);
            if pieces.len() < 2 {
                continue;
            }
            node.split = Some(axis);
            node.children = pieces
                .into_iter()
                .map(|(lo, hi)| {
                    let piece = axis.with(&bbox, lo, hi);
                    let members = rest
                        .iter()
                        .copied()
                        .filter(|&i| {
                            let c = (axis.lo(&regions[i].bbox) + axis.hi(&regions[i].bbox)) / 2;
                            lo <= c && c < hi
                        })
                        .collect();
                    split(regions, piece, members, axis.other(), tolerance, depth + 1)
                })
                .collect();
            return node;
        }
    }
    node
}

/// The pieces `[lo, hi)` that cuts along `axis` make of `bbox`: one for
/// each cluster of overlapping regions, and one for each empty strip wider
/// than `tolerance`; narrower strips go to their neighbours.
fn cuts(
    regions: &[Region],
    members: &[usize],
    bbox: [i32; 4],
    axis: Axis,
    tolerance: i32,
) -> Vec<(i32, i32)> {
    let slack = (tolerance / 2).clamp(1, 4);
    let (lo, hi) = (axis.lo(&bbox), axis.hi(&bbox));
    let mut spans: Vec<(i32, i32)> = members
        .iter()
        .map(|&i| {
            let b = &regions[i].bbox;
            (axis.lo(b).max(lo), axis.hi(b).min(hi))
        })
        .collect();
    spans.sort();
    let mut clusters: Vec<(i32, i32)> = Vec::new();
    for (a, b) in spans {
        match clusters.last_mut() {
            // Boxes reach the middle of their lines, so neighbours across
            // one line touch or overlap by a pixel, and by a few more where
            // the line wobbles: only a larger overlap joins them.
            Some(last) if a < last.1 - slack => last.1 = last.1.max(b),
            _ => clusters.push((a, b)),
        }
    }
    // Boundaries between consecutive pieces.
    let mut bounds = vec![lo];
    let mut end = lo;
    for (k, &(a, b)) in clusters.iter().enumerate() {
        if k == 0 {
            if a - lo > tolerance {
                bounds.push(a);
            }
        } else if a - end > tolerance {
            // An empty strip between two clusters is a piece of its own.
            bounds.push(end);
            bounds.push(a);
        } else {
            // Cut in the middle of the line between the clusters.
            bounds.push((end + a) / 2);
        }
        end = b;
    }
    if hi - end > tolerance {
        bounds.push(end);
    }
    bounds.push(hi);
    bounds.dedup();
    // Slivers (a wobbling line's two strokes) join the piece before them.
    let min = slack.max(2) + 1;
    let mut kept = vec![lo];
    for &b in &bounds[1..] {
        if b == hi {
            if hi - kept[kept.len() - 1] < min && kept.len() > 1 {
                kept.pop();
            }
            kept.push(hi);
        } else if b - kept[kept.len() - 1] >= min {
            kept.push(b);
        }
    }
    kept.windows(2).map(|w| (w[0], w[1])).collect()
}
