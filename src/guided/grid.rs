//! A uniform grid over one guide's elements for one pass: the elements in,
//! the few a query must look at out. Without it every query of every seed
//! scanned every element of its guide, so a scene's time grew with the
//! square of its seeds (5,000 seeds: 20 s; 20,000: over two minutes).
//!
//! Searches return the lexicographic minimum of (score, element index) over
//! the elements they visit, and visit every element that could beat the
//! best found, so the answer is the one a scan of all elements in order
//! gives: ties still go to the first element.

use glam::DVec2;

use super::geometry::EPS;

/// A drawn segment of a guide (after clipping), with the seed that drew it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    pub a: DVec2,
    pub b: DVec2,
    pub seed: usize,
}

/// An element whose bounding box covers more cells than this is checked by
/// every query instead of being listed in each cell.
const WIDE_CELLS: usize = 64;

/// One guide's elements and the grid cells that list them.
pub struct ElementGrid {
    elements: Vec<Element>,
    origin: DVec2,
    cell: f64,
    nx: i64,
    ny: i64,
    /// Row-major: cell (i, j) is `cells[j * nx + i]`.
    cells: Vec<Vec<u32>>,
    /// Elements too long (or too far out) for the cells.
    wide: Vec<u32>,
    /// Slack added around boxes, for points that sit on a cell's border.
    pad: f64,
}

/// The best (score, element) seen so far.
type Best = Option<(f64, usize)>;

fn better(best: Best, score: f64, k: usize) -> bool {
    match best {
        None => true,
        Some((s, i)) => score < s || (score == s && k < i),
    }
}

impl ElementGrid {
    pub fn new(elements: Vec<Element>) -> Self {
        let finite: Vec<&Element> = elements
            .iter()
            .filter(|e| e.a.is_finite() && e.b.is_finite())
            .collect();
        let (lo, hi) = finite.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), e| (lo.min(e.a).min(e.b), hi.max(e.a).max(e.b)),
        );
        let n = finite.len().max(1) as f64;
        let size = if finite.is_empty() {
            DVec2::ONE
        } else {
            (hi - lo).max(DVec2::splat(0.0))
        };
        let longest = size.x.max(size.y).max(EPS);
        // About one element per cell; never more cells than 4n + 16.
        let mut cell = (size.x * size.y / n).sqrt().max(longest / n).max(EPS);
        let count = |cell: f64| {
            (
                (size.x / cell).floor() as i64 + 1,
                (size.y / cell).floor() as i64 + 1,
            )
        };
        while {
            let (nx, ny) = count(cell);
            (nx as f64) * (ny as f64) > 4.0 * n + 16.0
        } {
            cell *= 1.5;
        }
        let (nx, ny) = count(cell);
        let origin = if finite.is_empty() { DVec2::ZERO } else { lo };
        let mut grid = ElementGrid {
            elements: Vec::new(),
            origin,
            cell,
            nx,
            ny,
            cells: vec![Vec::new(); (nx * ny) as usize],
            wide: Vec::new(),
            pad: (cell * 1e-6).max(16.0 * EPS),
        };
        for (k, e) in elements.iter().enumerate() {
            let (i0, j0, i1, j1) = grid.cover(e.a.min(e.b), e.a.max(e.b));
            let cells = ((i1 - i0 + 1) * (j1 - j0 + 1)) as usize;
            if !(e.a.is_finite() && e.b.is_finite()) || i1 < i0 || j1 < j0 || cells > WIDE_CELLS {
                grid.wide.push(k as u32);
                continue;
            }
            for j in j0..=j1 {
                for i in i0..=i1 {
                    grid.cells[(j * nx + i) as usize].push(k as u32);
                }
            }
        }
        grid.elements = elements;
        grid
    }

    pub fn elements(&self) -> &[Element] {
        &self.elements
    }

    /// The (unclamped) cell of a coordinate pair, saturated far outside.
    fn index(&self, p: DVec2) -> (i64, i64) {
        let f = |v: f64| (v / self.cell).floor().clamp(-1e15, 1e15) as i64;
        (f(p.x - self.origin.x), f(p.y - self.origin.y))
    }

    /// The grid cells (clamped) a padded box touches: (i0, j0, i1, j1),
    /// empty (i1 < i0 or j1 < j0) when it misses the grid.
    fn cover(&self, lo: DVec2, hi: DVec2) -> (i64, i64, i64, i64) {
        let (i0, j0) = self.index(lo - self.pad);
        let (i1, j1) = self.index(hi + self.pad);
        (
            i0.max(0),
            j0.max(0),
            i1.min(self.nx - 1),
            j1.min(self.ny - 1),
        )
    }

    fn visit(
        &self,
        list: &[u32],
        best: &mut Best,
        score: &mut impl FnMut(usize, &Element) -> Option<f64>,
    ) {
        for &k in list {
            let k = k as usize;
            // A NaN score (from non-finite input) is no answer.
            if let Some(s) = score(k, &self.elements[k]).filter(|s| !s.is_nan()) {
                if better(*best, s, k) {
                    *best = Some((s, k));
                }
            }
        }
    }

    /// The element nearest `p`: `score` must return the element's distance
    /// from `p` (or `None` to skip it). Cells are searched in rings around
    /// `p` until no unsearched cell can be nearer than the best.
    pub fn nearest(&self, p: DVec2, mut score: impl FnMut(usize, &Element) -> Option<f64>) -> Best {
        let mut best = None;
        self.visit(&self.wide, &mut best, &mut score);
        if !p.is_finite() {
            // No ring bound holds: look at everything.
            for list in &self.cells {
                self.visit(list, &mut best, &mut score);
            }
            return best;
        }
        let (vi, vj) = self.index(p);
        let gap = |v: i64, n: i64| if v < 0 { -v } else { (v - (n - 1)).max(0) };
        let far = |v: i64, n: i64| v.abs().max((v - (n - 1)).abs());
        let first = gap(vi, self.nx).max(gap(vj, self.ny));
        let last = far(vi, self.nx).max(far(vj, self.ny));
        for r in first..=last {
            // Cells of ring r are farther than (r - 1) cells from p.
            if let Some((s, _)) = best {
                if s < (r - 1) as f64 * self.cell {
                    break;
                }
            }
            for j in (vj - r).max(0)..=(vj + r).min(self.ny - 1) {
                let whole = j == vj - r || j == vj + r;
                let row = (j * self.nx) as usize;
                if whole {
                    for i in (vi - r).max(0)..=(vi + r).min(self.nx - 1) {
                        self.visit(&self.cells[row + i as usize], &mut best, &mut score);
                    }
                } else {
                    for i in [vi - r, vi + r] {
                        if (0..self.nx).contains(&i) {
                            self.visit(&self.cells[row + i as usize], &mut best, &mut score);
                        }
                    }
                }
            }
        }
        best
    }

    /// The first element along the segment from `p` in unit direction
    /// `dir` of length `len` (infinite for a ray): `score` must return the
    /// distance along it to the element's hit, or `None`. The line is
    /// walked a cell's length at a time until the best hit is behind.
    pub fn along(
        &self,
        p: DVec2,
        dir: DVec2,
        len: f64,
        mut score: impl FnMut(usize, &Element) -> Option<f64>,
    ) -> Best {
        let mut best = None;
        self.visit(&self.wide, &mut best, &mut score);
        if !(p.is_finite() && dir.is_finite()) {
            for list in &self.cells {
                self.visit(list, &mut best, &mut score);
            }
            return best;
        }
        // Where the line is inside the (padded) grid: slab clipping.
        let lo = self.origin - self.pad;
        let hi = self.origin + DVec2::new(self.nx as f64, self.ny as f64) * self.cell + self.pad;
        let (mut t0, mut t1) = (0.0f64, len);
        for (o, d, l, h) in [(p.x, dir.x, lo.x, hi.x), (p.y, dir.y, lo.y, hi.y)] {
            if d.abs() <= f64::MIN_POSITIVE {
                if o < l || o > h {
                    return best;
                }
            } else {
                let (a, b) = ((l - o) / d, (h - o) / d);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        if t0 > t1 {
            return best;
        }
        let mut t = (t0 - self.cell).max(0.0);
        if t + self.cell <= t || (t1 - t) / self.cell > 4.0 * (self.nx + self.ny) as f64 + 8.0 {
            // A cell is below the rounding of t: walking would not advance.
            for list in &self.cells {
                self.visit(list, &mut best, &mut score);
            }
            return best;
        }
        while t <= t1 {
            let end = (t + self.cell).min(t1.max(t));
            let (a, b) = (p + dir * t, p + dir * end);
            let (i0, j0, i1, j1) = self.cover(a.min(b), a.max(b));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    self.visit(
                        &self.cells[(j * self.nx + i) as usize],
                        &mut best,
                        &mut score,
                    );
                }
            }
            if best.is_some_and(|(s, _)| s <= end) || end >= t1 {
                break;
            }
            t = end;
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::super::geometry;
    use super::*;

    /// A small deterministic generator: the same cases on every run.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        /// Coordinates on a coarse lattice too, so that ties and shared
        /// endpoints occur.
        fn point(&mut self, span: f64) -> DVec2 {
            let mut c = || {
                let v = self.next() * span;
                if self.next() < 0.5 {
                    v.round()
                } else {
                    v
                }
            };
            DVec2::new(c(), c())
        }
    }

    fn scene(rng: &mut Lcg, n: usize, span: f64) -> Vec<Element> {
        (0..n)
            .map(|k| {
                let a = rng.point(span);
                // Mostly short segments, some across the whole scene.
                let b = if k % 17 == 0 {
                    rng.point(span)
                } else {
                    a + (rng.point(4.0) - DVec2::splat(2.0))
                };
                Element { a, b, seed: k }
            })
            .collect()
    }

    fn scan(elements: &[Element], mut score: impl FnMut(&Element) -> Option<f64>) -> Best {
        let mut best = None;
        for (k, e) in elements.iter().enumerate() {
            if let Some(s) = score(e).filter(|s| !s.is_nan()) {
                if better(best, s, k) {
                    best = Some((s, k));
                }
            }
        }
        best
    }

    #[test]
    fn searches_agree_with_a_scan_of_every_element() {
        let mut rng = Lcg(7);
        let mut checked = 0;
        for (n, span) in [(0, 10.0), (1, 10.0), (40, 10.0), (400, 60.0), (2000, 30.0)] {
            let elements = scene(&mut rng, n, span);
            let grid = ElementGrid::new(elements.clone());
            for _ in 0..300 {
                // Query points inside, on and well outside the scene.
                let p = rng.point(span * 1.6) - DVec2::splat(span * 0.3);
                let dir =
                    geometry::direction((rng.next() * 8.0).floor() * 45.0 + rng.next().round());
                let skip = |e: &Element| e.seed % 5 == 3;
                let near =
                    |e: &Element| (!skip(e)).then(|| geometry::distance_to_segment(p, e.a, e.b));
                assert_eq!(
                    grid.nearest(p, |_, e| near(e)),
                    scan(&elements, near),
                    "{n} {p}"
                );
                let ray = |e: &Element| geometry::ray_hit(p, dir, e.a, e.b);
                assert_eq!(
                    grid.along(p, dir, f64::INFINITY, |_, e| ray(e)),
                    scan(&elements, ray),
                    "{n} {p} {dir}"
                );
                let len = rng.next() * span * 0.5;
                let seg = |e: &Element| {
                    let (t, _) = geometry::segment_hit(p, p + dir * len, e.a, e.b)?;
                    (t * len > EPS).then_some(t * len)
                };
                assert_eq!(
                    grid.along(p, dir, len, |_, e| seg(e)),
                    scan(&elements, seg),
                    "{n} {p} {dir} {len}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 1500);
    }

    #[test]
    fn far_and_huge_coordinates_neither_hang_nor_panic() {
        let elements = vec![
            Element {
                a: DVec2::new(-1e308, 0.0),
                b: DVec2::new(1e308, 1.0),
                seed: 0,
            },
            Element {
                a: DVec2::new(0.0, 0.0),
                b: DVec2::new(1e-300, 0.0),
                seed: 1,
            },
            Element {
                a: DVec2::new(f64::NAN, 0.0),
                b: DVec2::ZERO,
                seed: 2,
            },
        ];
        let grid = ElementGrid::new(elements.clone());
        for p in [
            DVec2::new(5e307, -3.0),
            DVec2::new(0.0, -3.0),
            DVec2::new(f64::INFINITY, 0.0),
        ] {
            let near = |e: &Element| Some(geometry::distance_to_segment(p, e.a, e.b));
            assert_eq!(
                grid.nearest(p, |_, e| near(e)),
                scan(&elements, near),
                "{p}"
            );
            let ray = |e: &Element| geometry::ray_hit(p, DVec2::Y, e.a, e.b);
            assert_eq!(
                grid.along(p, DVec2::Y, f64::INFINITY, |_, e| ray(e)),
                scan(&elements, ray),
                "{p}"
            );
        }
        // The short element is found from below.
        let p = DVec2::new(0.0, -3.0);
        let hit = grid.along(p, DVec2::Y, f64::INFINITY, |_, e| {
            geometry::ray_hit(p, DVec2::Y, e.a, e.b)
        });
        assert_eq!(hit.map(|h| h.1), Some(1));
    }
}
