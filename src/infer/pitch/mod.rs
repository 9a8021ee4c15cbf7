//! Rows read by their pitch: a labelled shape tree and its ink -> the same
//! tree with the rafter row (`rafters.rs`) and, where its regions miscount
//! it, the bracket layer (`brackets.rs`) cut where the ink repeats.
//!
//! This file holds what both share: a row's profile, its rhythm (the
//! pitch, from the profile's autocorrelation, refined on peaks at doubling
//! multiples to a hundredth of a pixel), the profile folded at the pitch,
//! the front the rows are measured on, and the re-cut band.

mod brackets;
mod rafters;

pub use brackets::brackets;
pub use rafters::rafters;

use super::drawing::Ink;
use super::tree::Node;

/// The shortest pitch read: 3 pixels (a line, a gap, a line).
const MIN_PITCH: usize = 3;
/// A row is read by its pitch when it has at least this many elements.
pub(super) const MIN_COUNT: usize = 8;
/// The profile's autocorrelation at the pitch, at least: below, the ink
/// does not repeat (0 is noise, 1 a perfect repeat).
const MIN_PERIODICITY: f64 = 0.3;
/// The pitch is the first peak this close to the highest (the highest may
/// be a multiple of it, lines drawn a pixel off).
const NEAR_HIGHEST: f64 = 0.6;

/// A row's reading from its ink: the pitch in pixels, its phase (the
/// first element's centre, from the row's start) and an element's width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rhythm {
    pub pitch: f64,
    pub phase: f64,
    pub width: f64,
    /// The profile's autocorrelation at the pitch.
    pub periodicity: f64,
}

/// Ink per column of `ink` over rows `rows`, for columns `x0..x1`.
fn profile(ink: &Ink, x0: usize, x1: usize, rows: std::ops::Range<usize>) -> Vec<f64> {
    (x0..x1)
        .map(|x| rows.clone().filter(|&y| ink.at(x, y)).count() as f64)
        .collect()
}

/// Normalised autocorrelation of a mean-free profile.
struct Correlation {
    g: Vec<f64>,
    var: f64,
}

impl Correlation {
    fn new(f: &[f64]) -> Option<Correlation> {
        let n = f.len() as f64;
        let mean = f.iter().sum::<f64>() / n;
        let g: Vec<f64> = f.iter().map(|v| v - mean).collect();
        let var = g.iter().map(|v| v * v).sum::<f64>() / n;
        (var > 1e-9).then_some(Correlation { g, var })
    }

    /// At integer lag `l` (0 past the profile's half).
    fn at(&self, l: usize) -> f64 {
        let n = self.g.len();
        if l >= n {
            return 0.0;
        }
        let s: f64 = self.g[..n - l]
            .iter()
            .zip(&self.g[l..])
            .map(|(a, b)| a * b)
            .sum();
        s / (n - l) as f64 / self.var
    }

    /// The peak within `radius` of `lag`, to a fraction of a pixel (a
    /// parabola through the best lag and its neighbours).
    fn peak_near(&self, lag: f64, radius: usize) -> f64 {
        let lo = (lag.round() as usize).saturating_sub(radius).max(1);
        let hi = lag.round() as usize + radius;
        let best = (lo..=hi)
            .max_by(|&a, &b| self.at(a).total_cmp(&self.at(b)))
            .unwrap_or(lo);
        let (a, b, c) = (self.at(best - 1), self.at(best), self.at(best + 1));
        let curve = a - 2.0 * b + c;
        let shift = if curve < 0.0 {
            (0.5 * (a - c) / curve).clamp(-0.5, 0.5)
        } else {
            0.0
        };
        best as f64 + shift
    }
}

/// The rhythm of the profile `f`, if it repeats at least [`MIN_COUNT`]
/// times.
pub fn rhythm(f: &[f64]) -> Option<Rhythm> {
    let n = f.len();
    // Lines a pixel wide at a pitch that is not a whole number of pixels
    // fall a pixel apart from one period to the next: smoothed over three
    // pixels they still overlap at the pitch.
    let smooth: Vec<f64> = (0..n)
        .map(|x| {
            let at = |i: Option<usize>| i.and_then(|i| f.get(i)).copied().unwrap_or(0.0);
            at(x.checked_sub(1)) + 2.0 * f[x] + at(Some(x + 1))
        })
        .collect();
    let corr = Correlation::new(&smooth)?;
    let longest = n / MIN_COUNT;
    if longest <= MIN_PITCH {
        return None;
    }
    let r: Vec<f64> = (0..=longest + 1).map(|l| corr.at(l)).collect();
    let highest = (MIN_PITCH..=longest).map(|l| r[l]).fold(f64::MIN, f64::max);
    if highest < MIN_PERIODICITY {
        return None;
    }
    let first = (MIN_PITCH..=longest)
        .find(|&l| r[l] >= NEAR_HIGHEST * highest && r[l] >= r[l - 1] && r[l] >= r[l + 1])?;
    // Refine on the peaks at 2, 4, 8, ... pitches: each halves the error.
    let mut pitch = first as f64;
    let mut k = 1usize;
    while (2 * k) as f64 * pitch <= n as f64 / 2.0 {
        k *= 2;
        pitch = corr.peak_near(k as f64 * pitch, 2) / k as f64;
    }
    let periodicity = corr.at(pitch.round() as usize);
    let (phase, width) = fold(f, pitch);
    Some(Rhythm {
        pitch,
        phase,
        width,
        periodicity,
    })
}

/// The mean of `f` in each of `bins` equal parts of a period `pitch` long
/// (the period starting at `f`'s start); 0 where no sample falls.
pub(super) fn folded(f: &[f64], pitch: f64, bins: usize) -> Vec<f64> {
    let mut sum = vec![0.0; bins];
    let mut seen = vec![0usize; bins];
    for (x, v) in f.iter().enumerate() {
        let b = (((x as f64 + 0.5) / pitch).fract() * bins as f64) as usize % bins;
        sum[b] += v;
        seen[b] += 1;
    }
    sum.iter()
        .zip(&seen)
        .map(|(s, &k)| if k == 0 { 0.0 } else { s / k as f64 })
        .collect()
}

/// The profile folded at `pitch`: where in a period an element's centre
/// stands and how wide it is. An element is drawn as two lines (its
/// edges) nearer to each other than to the next element's; closed into
/// one post of ink, it is that post.
fn fold(f: &[f64], pitch: f64) -> (f64, f64) {
    let bins = (pitch.round() as usize).max(MIN_PITCH);
    let h = folded(f, pitch, bins);
    let circ = |a: usize, b: usize| {
        let d = (b + bins - a) % bins;
        d.min(bins - d)
    };
    let a = (0..bins)
        .max_by(|&i, &j| h[i].total_cmp(&h[j]))
        .unwrap_or(0);
    // The other edge: the highest bin two or more away from the first.
    let other = (0..bins)
        .filter(|&i| circ(a, i) >= 2)
        .max_by(|&i, &j| h[i].total_cmp(&h[j]));
    let bin = pitch / bins as f64;
    // An edge is a peak standing clear of the lowest bins (half way up).
    let low = h.iter().copied().fold(f64::MAX, f64::min);
    match other.filter(|&b| h[b] - low >= 0.5 * (h[a] - low)) {
        Some(b) => {
            // Each edge where its ink's weight is, over the peak and its
            // two neighbours (a line between two pixels fills both).
            let at = |p: usize| {
                let w = |j: i32| h[(p as i32 + j).rem_euclid(bins as i32) as usize] - low;
                let total = w(-1) + w(0) + w(1);
                p as f64
                    + if total > 0.0 {
                        (w(1) - w(-1)) / total
                    } else {
                        0.0
                    }
            };
            let (pa, pb) = (at(a), at(b));
            // The shorter way round from one edge to the other is inside.
            let forward = (pb - pa).rem_euclid(bins as f64);
            let (start, d) = if forward <= bins as f64 / 2.0 {
                (pa, forward)
            } else {
                (pb, bins as f64 - forward)
            };
            let centre = (start + d / 2.0 + 0.5) * bin;
            (centre.rem_euclid(pitch), d * bin)
        }
        None => ((a as f64 + 0.5) * bin, bin.max(1.0)),
    }
}

/// Re-cuts `band` into back and `kind` elements, one over each of
/// `boxes` (x ranges, left to right), and an element seen end-on at each
/// end when `corners` gives where they stop: from the band's left end to
/// the first, and from the second to its right end.
pub(super) fn lay_out(
    band: &mut Node,
    kind: &'static str,
    boxes: &[(i32, i32)],
    corners: Option<(i32, i32)>,
) {
    let [bx0, y0, bx1, y1] = band.bbox;
    let mut children = Vec::new();
    let mut at = bx0;
    if let Some((start, _)) = corners {
        children.push(Node::leaf(kind, [bx0, y0, start, y1]));
        at = start;
    }
    for &(lo, hi) in boxes {
        let (lo, hi) = (lo.max(at), hi.min(bx1).max(lo.max(at) + 1));
        if lo > at {
            children.push(Node::leaf("other", [at, y0, lo, y1]));
        }
        children.push(Node::leaf(kind, [lo, y0, hi, y1]));
        at = hi;
    }
    let stop = corners.map_or(bx1, |(_, end)| end.max(at));
    if stop > at {
        children.push(Node::leaf("other", [at, y0, stop, y1]));
        at = stop;
    }
    if corners.is_some() && bx1 > at {
        children.push(Node::leaf(kind, [at, y0, bx1, y1]));
    }
    band.children = children;
    band.split = Some(super::tree::Axis::X);
    band.repeat = true;
}

/// The front: from the first column's centre to the last's, where a
/// row's elements on the front face run; None when it is too short to
/// repeat [`MIN_COUNT`] times or lies off the drawing.
pub(super) fn front(root: &Node, ink: &Ink) -> Option<(i32, i32)> {
    let mut columns: Vec<[i32; 4]> = Vec::new();
    collect(root, "column", &mut columns);
    columns.sort_by_key(|b| b[0]);
    let centre = |b: &[i32; 4]| ((b[0] + b[2]) as f64 / 2.0).round() as i32;
    let (x0, x1) = (centre(columns.first()?), centre(columns.last()?));
    let long = x1 - x0 >= (MIN_COUNT * MIN_PITCH) as i32;
    (long && x0 >= 0 && x1 as usize <= ink.width).then_some((x0, x1))
}

pub(super) fn collect(n: &Node, label: &str, out: &mut Vec<[i32; 4]>) {
    if n.label == label {
        out.push(n.bbox);
    }
    for c in &n.children {
        collect(c, label, out);
    }
}

/// How many nodes of `n` (itself included) are labelled `label`.
fn labelled(n: &Node, label: &str) -> usize {
    usize::from(n.label == label) + n.children.iter().map(|c| labelled(c, label)).sum::<usize>()
}
