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
            // Only the drawing's bands: lower down, a frame round a
            // lattice is one straddling region that must hold it whole.
            let weak = depth == 0 && axis == Axis::Y;
            let pieces = cuts(regions, &rest, bbox, axis, tolerance, weak);
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

/// A cut is weak when at most one region in [`WEAK_RATIO`] of those on
/// its smaller side straddles it (reaches two pixels past it both ways),
/// and each side has [`WEAK_SIDE`] regions at least.
const WEAK_RATIO: usize = 15;
const WEAK_SIDE: usize = 15;

/// A region's span along the cut axis, and its middle across it.
type Span = (i32, i32, i32);

/// `spans` (sorted) with the few that straddle a weak cut clipped to its
/// side of their middle, so that the cut is made: a shaky line pinches
/// shut where a roof's tile strips meet the rafter row below and bridges
/// them with a handful of regions (an upturned eave corner, a rafter end
/// reaching up), and the roof and the rafters came as one band. Each cut
/// is the position where the fewest regions straddle; the sides are cut
/// again, if they can be. Not where three in four regions under the cut
/// stand under one over it (their middles across within 2 pixels): those are
/// the parts of one row of elements drawn one above the other (a bracket
/// set's arm over its block), held together by a few drawn whole.
fn weak_cuts(spans: Vec<Span>) -> Vec<Span> {
    if spans.len() < 2 * WEAK_SIDE {
        return spans;
    }
    let lo = spans.iter().map(|s| s.0).min().unwrap_or(0);
    let hi = spans.iter().map(|s| s.1).max().unwrap_or(0);
    let mut best: Option<(usize, i32)> = None;
    for c in lo + 2..hi - 1 {
        let straddle = spans.iter().filter(|s| s.0 < c - 1 && s.1 > c + 1).count();
        let above = spans.iter().filter(|s| s.1 <= c + 1).count();
        let below = spans.iter().filter(|s| s.0 >= c - 1).count();
        let side = above.min(below);
        if side >= WEAK_SIDE
            && straddle * WEAK_RATIO <= side
            && best.map_or(true, |(b, _)| straddle < b)
        {
            best = Some((straddle, c));
        }
    }
    let Some((_, c)) = best else {
        return spans;
    };
    let (mut upper, mut lower): (Vec<Span>, Vec<Span>) = (Vec::new(), Vec::new());
    for &(a, b, m) in &spans {
        if a + b < 2 * c {
            upper.push((a, b.min(c), m));
        } else {
            lower.push((a.max(c), b, m));
        }
    }
    let stacked = lower
        .iter()
        .filter(|l| upper.iter().any(|u| (u.2 - l.2).abs() <= 2))
        .count();
    if stacked * 4 >= lower.len() * 3 {
        return spans;
    }
    let mut out = weak_cuts(upper);
    out.extend(weak_cuts(lower));
    out
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
    weak: bool,
) -> Vec<(i32, i32)> {
    let slack = (tolerance / 2).clamp(1, 4);
    let (lo, hi) = (axis.lo(&bbox), axis.hi(&bbox));
    // Each region's span along `axis`, and its middle across it.
    let mut spans: Vec<Span> = members
        .iter()
        .map(|&i| {
            let b = &regions[i].bbox;
            let across = axis.other();
            let middle = (across.lo(b) + across.hi(b)) / 2;
            (axis.lo(b).max(lo), axis.hi(b).min(hi), middle)
        })
        .collect();
    spans.sort();
    // Boxes reach the middle of their lines, so neighbours across one line
    // touch or overlap by a pixel, and by a few more where the line
    // wobbles: only a larger overlap joins them.
    let group = |spans: &[Span]| {
        let mut groups: Vec<Vec<Span>> = Vec::new();
        let mut end = i32::MIN;
        for &(a, b, m) in spans {
            match groups.last_mut() {
                Some(g) if a < end - slack => g.push((a, b, m)),
                _ => groups.push(vec![(a, b, m)]),
            }
            end = if groups.last().is_some_and(|g| g.len() == 1) {
                b
            } else {
                end.max(b)
            };
        }
        groups
    };
    if weak {
        // Each band cut again where only a few regions hold it together.
        spans = group(&spans).into_iter().flat_map(weak_cuts).collect();
        spans.sort();
    }
    let clusters: Vec<(i32, i32)> = group(&spans)
        .iter()
        .map(|g| {
            let lo = g.iter().map(|s| s.0).min().unwrap_or(0);
            (lo, g.iter().map(|s| s.1).max().unwrap_or(lo))
        })
        .collect();
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_held_together_by_a_few_regions_is_cut_at_the_root() {
        // A roof's 60 tile strips over a row of 60 rafter ends, a pixel of
        // overlap between them, and three regions bridging the two (an
        // eave corner each side, a rafter reaching up) by more than the
        // slack.
        let mut boxes: Vec<[i32; 4]> = (0..60).map(|k| [k * 20, 0, k * 20 + 14, 71]).collect();
        boxes.extend((0..60).map(|k| [k * 20, 70, k * 20 + 7, 90]));
        boxes.extend([[0, 62, 20, 76], [1180, 62, 1200, 76], [300, 64, 307, 90]]);
        let regions: Vec<Region> = boxes
            .iter()
            .map(|&bbox| Region { bbox, area: 50 })
            .collect();
        let all: Vec<usize> = (0..regions.len()).collect();
        let bbox = [0, 0, 1200, 90];
        assert_eq!(cuts(&regions, &all, bbox, Axis::Y, 8, false), vec![(0, 90)]);
        assert_eq!(
            cuts(&regions, &all, bbox, Axis::Y, 8, true),
            vec![(0, 70), (70, 90)]
        );
        // Ten bridges are too many: the band stays whole.
        let mut many = boxes.clone();
        many.extend((0..7).map(|k| [k * 40 + 10, 60, k * 40 + 15, 80]));
        let regions: Vec<Region> = many.iter().map(|&bbox| Region { bbox, area: 50 }).collect();
        let all: Vec<usize> = (0..regions.len()).collect();
        assert_eq!(cuts(&regions, &all, bbox, Axis::Y, 8, true), vec![(0, 90)]);
        // Bracket sets drawn as an arm over a block, 20 of them in the
        // back that surrounds them all: the back straddles any cut, but
        // every block stands under its arm, and the layer stays whole.
        let mut sets: Vec<[i32; 4]> = vec![[0, 0, 1200, 30]];
        for k in 0..20 {
            let x = 20 + 55 * k;
            sets.push([x, 4, x + 30, 16]);
            sets.push([x + 8, 15, x + 22, 30]);
        }
        let regions: Vec<Region> = sets.iter().map(|&bbox| Region { bbox, area: 50 }).collect();
        let all: Vec<usize> = (0..regions.len()).collect();
        let layer = [0, 0, 1200, 30];
        assert_eq!(cuts(&regions, &all, layer, Axis::Y, 8, true), vec![(0, 30)]);
        // The same blocks shifted off their arms are a row of their own.
        let shifted: Vec<Region> = sets
            .iter()
            .enumerate()
            .map(|(k, &b)| {
                let dx = if k > 0 && k % 2 == 0 { 20 } else { 0 };
                Region {
                    bbox: [b[0] + dx, b[1], b[2] + dx, b[3]],
                    area: 50,
                }
            })
            .collect();
        assert_eq!(
            cuts(&shifted, &all, layer, Axis::Y, 8, true),
            vec![(0, 15), (15, 30)]
        );
    }
}
