//! Rasterisation: triangles in sample coordinates -> the samples they cover,
//! with depth and colour interpolated; and a band of samples -> 8-bit sRGB
//! pixels (box filter over each pixel's supersamples, averaged in linear
//! light).

use glam::Vec2;

/// Fractional bits of the fixed-point vertex positions. Edge functions are
/// evaluated exactly in integers, so triangles sharing an edge neither leave
/// gaps nor cover a sample twice.
const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;

/// Projected coordinates must lie within this many samples of the origin.
/// With 8 fractional bits that keeps every edge function below 2^59,
/// far from i64 overflow. Auto-framing keeps real vertices inside the image,
/// so only garbage (huge or non-finite coordinates) is rejected.
pub(super) const COORD_LIMIT: f32 = (1 << 20) as f32;

/// Per-vertex values interpolated across a triangle: depth, then linear
/// red, green and blue.
pub(super) type Attrs = [f32; 4];

/// Rows `y0..y0 + rows` of the supersampled image: depth (larger is nearer,
/// `-inf` where nothing was drawn) and linear RGB, kept apart so the depth
/// test reads densely packed values. Large images are drawn one band at a
/// time to bound memory.
pub(super) struct Band {
    pub width: usize,
    pub y0: usize,
    pub rows: usize,
    pub depth: Vec<f32>,
    pub rgb: Vec<[f32; 3]>,
}

impl Band {
    pub(super) fn new(width: usize) -> Band {
        Band {
            width,
            y0: 0,
            rows: 0,
            depth: Vec::new(),
            rgb: Vec::new(),
        }
    }

    /// Clears the band to `background` and moves it to rows `y0..y0 + rows`,
    /// reusing the allocation.
    pub(super) fn reset(&mut self, y0: usize, rows: usize, background: [f32; 3]) {
        self.y0 = y0;
        self.rows = rows;
        let n = self.width * rows;
        self.depth.clear();
        self.depth.resize(n, f32::NEG_INFINITY);
        self.rgb.clear();
        self.rgb.resize(n, background);
    }

    pub(super) fn clip(&self) -> Clip {
        Clip {
            width: self.width as i64,
            y0: self.y0 as i64,
            y1: (self.y0 + self.rows) as i64,
        }
    }
}

/// The sample rectangle that may be written: columns `0..width`, rows
/// `y0..y1`. Sample indices passed to callbacks are relative to `y0`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Clip {
    pub width: i64,
    pub y0: i64,
    pub y1: i64,
}

impl Clip {
    #[inline]
    fn contains(&self, x: i64, y: i64) -> bool {
        x >= 0 && x < self.width && y >= self.y0 && y < self.y1
    }

    #[inline]
    fn index(&self, x: i64, y: i64) -> usize {
        ((y - self.y0) * self.width + x) as usize
    }
}

/// What [`triangle`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Coverage {
    /// Zero area after snapping: nothing to draw.
    Degenerate,
    /// Positive area but no sample centre inside, anywhere in the image
    /// (not just the clip): a sliver or speck for [`sliver`] to draw.
    Missed,
    /// At least one sample centre inside (perhaps outside the clip).
    Covered,
}

/// Twice the signed area of (a, b, p): the edge function of a->b, positive
/// on the inside of a triangle with positive area.
#[inline]
fn orient(a: [i64; 2], b: [i64; 2], p: [i64; 2]) -> i64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

#[inline]
fn ceil_div(a: i64, b: i64) -> i64 {
    -(-a).div_euclid(b)
}

/// Calls `cover(index, attrs)` for every sample inside the clip whose centre
/// `(x + 0.5, y + 0.5)` lies in the triangle `v` (sample coordinates, either
/// winding), with `attrs` interpolated. Samples on an edge shared by two
/// triangles go to exactly one of them (top-left rule). Coordinates must be
/// finite and within [`COORD_LIMIT`].
pub(super) fn triangle(
    v: [Vec2; 3],
    attrs: [Attrs; 3],
    clip: &Clip,
    mut cover: impl FnMut(usize, Attrs),
) -> Coverage {
    // Truncating `x + 0.5` rounds to nearest for the non-negative values
    // seen in practice (and merely widens the bucket at 0 otherwise): what
    // matters for watertightness is only that a shared vertex always snaps
    // the same way. `f32::round` is a libm call on baseline x86-64 and took
    // over a tenth of all instructions executed.
    let snap = |c: f32| (c * ONE as f32 + 0.5) as i64;
    let mut q = [
        [snap(v[0].x), snap(v[0].y)],
        [snap(v[1].x), snap(v[1].y)],
        [snap(v[2].x), snap(v[2].y)],
    ];
    let mut a = attrs;
    let mut area = orient(q[0], q[1], q[2]);
    if area == 0 {
        return Coverage::Degenerate;
    }
    // Back faces are drawn too: turn every triangle positive.
    if area < 0 {
        q.swap(1, 2);
        a.swap(1, 2);
        area = -area;
    }

    let (mut lo, mut hi) = (q[0], q[0]);
    for p in &q[1..] {
        lo = [lo[0].min(p[0]), lo[1].min(p[1])];
        hi = [hi[0].max(p[0]), hi[1].max(p[1])];
    }
    // Sample centres inside the bounding box. Columns are clipped (nothing
    // real lies beside the image); rows are not, so that a triangle whose
    // samples all fall in another band still counts as covered.
    let x_lo = ceil_div(lo[0] - HALF, ONE).max(0);
    let x_hi = (hi[0] - HALF).div_euclid(ONE).min(clip.width - 1);
    let y_lo = ceil_div(lo[1] - HALF, ONE);
    let y_hi = (hi[1] - HALF).div_euclid(ONE);
    if x_lo > x_hi || y_lo > y_hi {
        return Coverage::Missed;
    }

    // Edge k is opposite vertex k, so its edge function divided by the area
    // is vertex k's barycentric weight.
    let start = [x_lo * ONE + HALF, y_lo * ONE + HALF];
    let mut row = [0i64; 3];
    let mut step_x = [0i64; 3];
    let mut step_y = [0i64; 3];
    for k in 0..3 {
        let (s, e) = (q[(k + 1) % 3], q[(k + 2) % 3]);
        let (dx, dy) = (e[0] - s[0], e[1] - s[1]);
        // Top-left rule (y down, positive area): a left edge goes up the
        // screen, a top edge is horizontal and goes right. Samples exactly
        // on other edges belong to the neighbour, so bias those by one.
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        row[k] = orient(s, e, start) - i64::from(!top_left);
        step_x[k] = -dy * ONE;
        step_y[k] = dx * ONE;
    }

    let inv_area = 1.0 / area as f32;
    let d1: Attrs = std::array::from_fn(|i| a[1][i] - a[0][i]);
    let d2: Attrs = std::array::from_fn(|i| a[2][i] - a[0][i]);
    let mut covered = false;
    for y in y_lo..=y_hi {
        if y >= clip.y0 && y < clip.y1 {
            let mut w = row;
            for x in x_lo..=x_hi {
                if (w[0] | w[1] | w[2]) >= 0 {
                    covered = true;
                    let l1 = w[1] as f32 * inv_area;
                    let l2 = w[2] as f32 * inv_area;
                    let at = std::array::from_fn(|i| a[0][i] + d1[i] * l1 + d2[i] * l2);
                    cover(clip.index(x, y), at);
                }
                for k in 0..3 {
                    w[k] += step_x[k];
                }
            }
        } else if !covered {
            // Outside the band: only whether any sample is covered matters.
            let mut w = row;
            for _ in x_lo..=x_hi {
                if (w[0] | w[1] | w[2]) >= 0 {
                    covered = true;
                    break;
                }
                for k in 0..3 {
                    w[k] += step_x[k];
                }
            }
        }
        for k in 0..3 {
            row[k] += step_y[k];
        }
    }
    if covered {
        Coverage::Covered
    } else {
        Coverage::Missed
    }
}

/// Draws a triangle that covers no sample centre as a one-sample-wide line
/// along its longer screen axis: for each sample column (or row) it spans,
/// the sample nearest the middle of its cross-section. A tube thinner than
/// the sample spacing is a chain of such slivers; without this it would
/// break into dashes or vanish. The cost is that thin geometry is drawn at
/// least one sample (a fraction of a pixel) wide.
pub(super) fn sliver(
    v: [Vec2; 3],
    attrs: [Attrs; 3],
    clip: &Clip,
    mut cover: impl FnMut(usize, Attrs),
) {
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    let extent = hi - lo;
    // Axis 0 is x, 1 is y; walk along the major one.
    let (major, minor) = if extent.x >= extent.y { (0, 1) } else { (1, 0) };
    let mut first = (lo[major] - 0.5).ceil();
    let mut last = (hi[major] - 0.5).floor();
    if first > last {
        // Shorter than the spacing: the one column (row) it lies in.
        first = ((lo[major] + hi[major]) * 0.5).floor();
        last = first;
    }
    for i in first as i64..=last as i64 {
        let c = (i as f32 + 0.5).clamp(lo[major], hi[major]);
        // The triangle's cross-section at `c` along the minor axis.
        let (mut a, mut b) = (f32::INFINITY, f32::NEG_INFINITY);
        for k in 0..3 {
            let (p, q) = (v[k], v[(k + 1) % 3]);
            let (pm, qm) = (p[major], q[major]);
            if pm == c {
                a = a.min(p[minor]);
                b = b.max(p[minor]);
            }
            if (pm - c) * (qm - c) < 0.0 {
                let m = p[minor] + (c - pm) / (qm - pm) * (q[minor] - p[minor]);
                a = a.min(m);
                b = b.max(m);
            }
        }
        if a > b {
            continue;
        }
        let m = (a + b) * 0.5;
        let j = m.floor() as i64;
        let (x, y, point) = if major == 0 {
            (i, j, Vec2::new(c, m))
        } else {
            (j, i, Vec2::new(m, c))
        };
        if clip.contains(x, y) {
            cover(clip.index(x, y), interpolate(v, &attrs, point));
        }
    }
}

/// Attributes at `p` from clamped float barycentrics (for [`sliver`], where
/// `p` may sit a hair outside the triangle).
fn interpolate(v: [Vec2; 3], a: &[Attrs; 3], p: Vec2) -> Attrs {
    let (e1, e2, ep) = (v[1] - v[0], v[2] - v[0], p - v[0]);
    let area = e1.perp_dot(e2);
    let (mut l1, mut l2) = if area != 0.0 {
        (ep.perp_dot(e2) / area, e1.perp_dot(ep) / area)
    } else {
        (1.0 / 3.0, 1.0 / 3.0)
    };
    l1 = l1.max(0.0);
    l2 = l2.max(0.0);
    if l1 + l2 > 1.0 {
        let s = l1 + l2;
        l1 /= s;
        l2 /= s;
    }
    std::array::from_fn(|i| a[0][i] + (a[1][i] - a[0][i]) * l1 + (a[2][i] - a[0][i]) * l2)
}

/// sRGB-encoded channel (0..=1) -> linear light.
pub(super) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light (0..=1) -> sRGB-encoded channel.
pub(super) fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear light -> 8-bit sRGB, clamped (NaN becomes 0).
fn encode(c: f32) -> u8 {
    (linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
}

/// Averages each `ss` x `ss` block of the band into one 8-bit sRGB pixel of
/// `out` (`band.rows / ss` rows of `band.width / ss` pixels).
pub(super) fn resolve(band: &Band, ss: usize, out: &mut [u8]) {
    let out_width = band.width / ss;
    let norm = 1.0 / (ss * ss) as f32;
    // Neighbouring pixels are often identical (background, flat faces):
    // reuse the last encoding rather than paying three powf each.
    let mut last: Option<([f32; 3], [u8; 3])> = None;
    for (oy, row) in out.chunks_exact_mut(out_width * 3).enumerate() {
        for (ox, px) in row.chunks_exact_mut(3).enumerate() {
            let mut sum = [0.0f32; 3];
            for sy in 0..ss {
                let start = (oy * ss + sy) * band.width + ox * ss;
                for rgb in &band.rgb[start..start + ss] {
                    for (total, c) in sum.iter_mut().zip(rgb) {
                        *total += c;
                    }
                }
            }
            let rgb = match last {
                Some((l, rgb)) if l == sum => rgb,
                _ => {
                    let rgb = sum.map(|c| encode(c * norm));
                    last = Some((sum, rgb));
                    rgb
                }
            };
            px.copy_from_slice(&rgb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A clip over a plain `width` x `rows` band, and the band's size.
    fn whole(width: usize, rows: usize) -> (Clip, usize) {
        let clip = Clip {
            width: width as i64,
            y0: 0,
            y1: rows as i64,
        };
        (clip, width * rows)
    }

    /// Counts how often each sample of a `w` x `h` grid is covered.
    fn coverage(w: usize, h: usize, tris: &[[Vec2; 3]]) -> Vec<u32> {
        let (clip, n) = whole(w, h);
        let mut count = vec![0u32; n];
        for &t in tris {
            triangle(t, [[0.0; 4]; 3], &clip, |i, _| count[i] += 1);
        }
        // back to row-major
        (0..w * h)
            .map(|i| count[clip.index((i % w) as i64, (i / w) as i64)])
            .collect()
    }

    /// A fan around an off-grid centre point, its rim through awkward
    /// fractional positions and some vertices exactly on sample centres.
    fn fan(centre: Vec2, n: usize, radius: f32) -> Vec<[Vec2; 3]> {
        let rim: Vec<Vec2> = (0..n)
            .map(|k| {
                let t = k as f32 / n as f32 * std::f32::consts::TAU;
                centre + Vec2::new(t.cos(), t.sin()) * radius * (1.0 + 0.3 * (3.0 * t).sin())
            })
            .collect();
        (0..n).map(|k| [centre, rim[k], rim[(k + 1) % n]]).collect()
    }

    #[test]
    fn shared_edges_cover_each_sample_exactly_once() {
        // A fan of 37 triangles, alternately wound: every sample strictly
        // inside the fan's rim must be hit exactly once, none twice.
        let mut tris = fan(Vec2::new(20.3, 19.5), 37, 15.0);
        for (k, t) in tris.iter_mut().enumerate() {
            if k % 2 == 1 {
                t.swap(1, 2);
            }
        }
        let count = coverage(40, 40, &tris);
        assert!(count.iter().all(|&c| c <= 1), "a sample was covered twice");
        // inner disc of radius 15 * 0.7 minus a margin is fully covered
        for y in 0..40 {
            for x in 0..40 {
                let d = Vec2::new(x as f32 + 0.5, y as f32 + 0.5).distance(Vec2::new(20.3, 19.5));
                if d < 9.0 {
                    assert_eq!(count[y * 40 + x], 1, "gap at {x},{y}");
                }
            }
        }
        // A grid of unit squares split into two triangles, vertices exactly
        // on sample centres and edges: still exactly once everywhere inside.
        let mut grid = Vec::new();
        for j in 0..8 {
            for i in 0..8 {
                let p = |a: f32, b: f32| {
                    Vec2::new(2.5 + 3.0 * (i as f32 + a), 2.5 + 3.0 * (j as f32 + b))
                };
                grid.push([p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
                grid.push([p(0.0, 0.0), p(0.0, 1.0), p(1.0, 1.0)]);
            }
        }
        let count = coverage(30, 30, &grid);
        for y in 0..30 {
            for x in 0..30 {
                // centres on the left and top edges count, on the right and bottom not
                let inside = (2..26).contains(&x) && (2..26).contains(&y);
                assert_eq!(count[y * 30 + x], u32::from(inside), "at {x},{y}");
            }
        }
    }

    #[test]
    fn interpolation_reproduces_vertex_values() {
        let (clip, n) = whole(10, 10);
        // vertices on sample centres, so those samples carry vertex values
        let v = [
            Vec2::new(0.5, 0.5),
            Vec2::new(8.5, 0.5),
            Vec2::new(0.5, 8.5),
        ];
        let attrs = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 8.0, 0.0, 0.0],
            [0.0, 0.0, 8.0, 0.0],
        ];
        let mut seen = vec![None; n];
        triangle(v, attrs, &clip, |i, a| seen[i] = Some(a));
        assert_eq!(seen[clip.index(0, 0)], Some([1.0, 0.0, 0.0, 0.0]));
        let a = seen[clip.index(2, 3)].unwrap();
        assert!(
            (a[1] - 2.0).abs() < 1e-4 && (a[2] - 3.0).abs() < 1e-4,
            "{a:?}"
        );
    }

    #[test]
    fn slivers_draw_a_continuous_line() {
        let (clip, n) = whole(50, 20);
        // A diagonal needle at most 0.01 samples wide along y = 2.5 + x / 4:
        // at every column centre its y is 1/8 or more from a row centre.
        let v = [
            Vec2::new(2.0, 3.0),
            Vec2::new(42.0, 13.0),
            Vec2::new(42.0, 13.01),
        ];
        assert_eq!(
            triangle(v, [[0.0; 4]; 3], &clip, |_, _| panic!()),
            Coverage::Missed
        );
        let mut hits = vec![0; n];
        sliver(v, [[0.0; 4]; 3], &clip, |i, _| hits[i] += 1);
        let column = |x: i64| (0..20).map(|y| hits[clip.index(x, y)]).sum::<i32>();
        assert!((2..42).all(|x| column(x) == 1));
        assert_eq!(hits.iter().sum::<i32>(), 40);
        // a speck smaller than a sample still leaves one
        let mut n = 0;
        let speck = [
            Vec2::new(5.1, 5.1),
            Vec2::new(5.3, 5.1),
            Vec2::new(5.1, 5.3),
        ];
        sliver(speck, [[0.0; 4]; 3], &clip, |i, _| {
            assert_eq!(i, clip.index(5, 5));
            n += 1
        });
        assert_eq!(n, 1);
    }

    #[test]
    fn srgb_round_trips() {
        for i in 0..=255u8 {
            let c = i as f32 / 255.0;
            assert_eq!(encode(srgb_to_linear(c)), i);
        }
    }
}
