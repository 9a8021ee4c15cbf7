//! `@Roof(hip, tile, eave, j1, …, jn)`: a Chinese roof fitted to a scope,
//! with the slope seed 003 (Sec 3, Sec 7.1) builds from the timber frame.
//! Input: the parameters and the scope; output: polygons (the shell, its
//! edges or gable walls, and rows of tiles in the next colour).
//!
//! The frame: purlins one bujia apart (horizontally) from the eaves purlin
//! to the ridge; between purlins k-1 and k the rafters rise jujia j_k per
//! unit of run, and the jujia grow toward the ridge, so the slope is
//! concave (steep at the ridge, flat at the eaves). Past the eaves purlin
//! the rafters run on (chuyan) `eave` bujias at the first step's slope.
//! Across the depth (z) the profile rises from both eaves to the ridge at
//! the middle; a hip roof (`hip` = 1) has the same profile up from the two
//! ends (x), so its ridge is shorter than the eaves by the depth and the
//! hips run at 45° in plan; a gable roof (`hip` = 0) has a gable wall
//! under each end. The profile is stretched to the scope: when the scope
//! is 2·(eave + n)·bujia deep and (eave·j1 + Σj)·bujia high (what the
//! hall's rules compute), the slopes are the jujia exactly.

use glam::DVec3;

use super::drawing::Polygon;
use super::scope::axes;
use super::solid::Solid;

/// Most steps (purlins from the eaves to the ridge, one side): 7 gives 15
/// purlins, more than any hall in the seed's sources.
pub const MAX_STEPS: usize = 7;

/// What `@Roof`'s parameters ask for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoofShape {
    pub hip: bool,
    /// Spacing of the rows of tiles (0: a bare shell).
    pub tile: f64,
    /// The eaves' run past the last purlin, in bujias.
    pub eave: f64,
    steps: [f64; MAX_STEPS],
    n: usize,
}

impl RoofShape {
    /// Reads `@Roof(hip, tile, eave, j1, …, jn)`, or says what is wrong.
    pub fn from_args(args: &[f64]) -> Result<RoofShape, String> {
        let [hip, tile, eave, jujia @ ..] = args else {
            return Err(format!(
                "it has {} parameters; it needs hip, tile, eave and at least one jujia",
                args.len()
            ));
        };
        if *hip != 0.0 && *hip != 1.0 {
            return Err(format!(
                "hip is {hip}; it must be 1 (hip roof) or 0 (gable)"
            ));
        }
        if !(tile.is_finite() && *tile >= 0.0) {
            return Err(format!("the tile spacing is {tile}; it must be 0 or more"));
        }
        if !(eave.is_finite() && *eave >= 0.0) {
            return Err(format!("the eaves' run is {eave}; it must be 0 or more"));
        }
        if jujia.is_empty() || jujia.len() > MAX_STEPS {
            return Err(format!(
                "it gives {} jujia; a roof has 1 to {MAX_STEPS} steps",
                jujia.len()
            ));
        }
        if let Some(j) = jujia.iter().find(|j| !(j.is_finite() && **j > 0.0)) {
            return Err(format!("a jujia is {j}; each must be more than 0"));
        }
        let mut steps = [0.0; MAX_STEPS];
        steps[..jujia.len()].copy_from_slice(jujia);
        Ok(RoofShape {
            hip: *hip == 1.0,
            tile: *tile,
            eave: *eave,
            steps,
            n: jujia.len(),
        })
    }

    /// The profile from the eaves (0, 0) to the ridge: (run, rise) at the
    /// eaves purlin and at each purlin above it, in bujias.
    pub fn profile(&self) -> Vec<(f64, f64)> {
        let mut out = vec![(0.0, 0.0)];
        let mut at = (self.eave, self.eave * self.steps[0]);
        if self.eave > 0.0 {
            out.push(at);
        }
        for j in &self.steps[..self.n] {
            at = (at.0 + 1.0, at.1 + j);
            out.push(at);
        }
        out
    }
}

/// The roof's surfaces in scope coordinates: the height of the top at a
/// point of the plan, and where the profile bends.
struct Fit {
    size: DVec3,
    hip: bool,
    /// (distance from the eaves, height of the top), world units.
    knots: Vec<(f64, f64)>,
    /// Shell thickness.
    thick: f64,
    /// Height of a row of tiles above the shell.
    rib: f64,
    /// A hip roof's upturned corners (qiqiao): how far from a corner the
    /// eaves start to rise, and how high the corner rises.
    corner: Option<(f64, f64)>,
}

impl Fit {
    fn new(r: &RoofShape, size: DVec3) -> Fit {
        let profile = r.profile();
        let (run, rise) = *profile.last().expect("the eaves point");
        let thick = 0.03 * size.y.min(size.z / 2.0);
        let rib = if r.tile > 0.0 {
            (0.3 * r.tile).min(0.1 * size.y)
        } else {
            0.0
        };
        let top = size.y - thick - rib;
        let knots: Vec<(f64, f64)> = profile
            .iter()
            .map(|(d, h)| (d / run * size.z / 2.0, thick + h / rise * top))
            .collect();
        // The corners of a hip roof turn up (issue 37: the hall's eaves
        // ran straight into its corners): the eaves rise over the last
        // 2.5 eaves' runs (the chuyan's, or a bujia's without one) to half
        // a run at the corner, and the lift fades up the hip over as far.
        // A gable roof's eaves stay straight, as its ends have no corner
        // rafters to turn up.
        let eave = knots.get(1).map_or(0.0, |k| k.0);
        let corner = (r.hip && eave > 0.0).then(|| {
            let reach = (2.5 * eave).min(size.x / 2.0).min(size.z / 2.0);
            (reach, (0.5 * eave).min(0.25 * size.y))
        });
        Fit {
            size,
            hip: r.hip,
            knots,
            thick,
            rib,
            corner,
        }
    }

    /// How far the corners lift the surface at (x, z): the full rise at a
    /// corner, fading (quadratically) to nothing `reach` from it along the
    /// eaves and up the hip.
    fn lift(&self, x: f64, z: f64) -> f64 {
        let Some((reach, rise)) = self.corner else {
            return 0.0;
        };
        let dx = x.min(self.size.x - x).max(0.0);
        let dz = z.min(self.size.z - z).max(0.0);
        let t = (1.0 - dx.max(dz) / reach).max(0.0);
        rise * t * t
    }

    /// Distance from the nearest eave (the ends count on a hip roof).
    fn dist(&self, x: f64, z: f64) -> f64 {
        let d = z.min(self.size.z - z);
        let d = if self.hip {
            d.min(x).min(self.size.x - x)
        } else {
            d
        };
        d.max(0.0)
    }

    /// Height of the top surface over (x, z).
    fn top(&self, x: f64, z: f64) -> f64 {
        self.profile_at(self.dist(x, z)) + self.lift(x, z)
    }

    /// The profile's height at distance `d` from the eaves.
    fn profile_at(&self, d: f64) -> f64 {
        let k = &self.knots;
        for w in k.windows(2) {
            let ((d0, h0), (d1, h1)) = (w[0], w[1]);
            if d <= d1 {
                return h0 + (h1 - h0) * (d - d0) / (d1 - d0).max(1e-12);
            }
        }
        k.last().expect("knots").1
    }

    /// Grid lines along one axis of length `len`: both ends, the middle and
    /// every bend of the profile measured from either end.
    fn lines(&self, len: f64) -> Vec<f64> {
        let mut v = vec![0.0, len, len / 2.0];
        for (d, _) in &self.knots {
            if *d < len / 2.0 {
                v.extend([*d, len - d]);
            }
        }
        // Enough lines in the corners for the upturn to curve.
        if let Some((reach, _)) = self.corner {
            for k in 1..8 {
                let d = reach * f64::from(k) / 8.0;
                if d < len / 2.0 {
                    v.extend([d, len - d]);
                }
            }
        }
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        v
    }
}

/// Draws roof `r` filling solid `s`'s scope.
pub fn draw(s: &Solid, r: &RoofShape, polys: &mut Vec<Polygon>) {
    let f = Fit::new(r, s.size);
    let [ax, ay, az] = axes(&s.frame);
    let at = |x: f64, y: f64, z: f64| s.frame.pos + ax * x + ay * y + az * z;
    let mut put = |colour: u32, pts: &[DVec3], out: DVec3| {
        let n = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
        let mut pts: Vec<DVec3> = pts.to_vec();
        if n.dot(out) < 0.0 {
            pts.reverse();
        }
        polys.push(Polygon {
            colour,
            points: pts.iter().map(|p| p.as_vec3()).collect(),
            uv: None,
        });
    };
    let (sx, sz) = (s.size.x, s.size.z);
    let xs = if f.hip { f.lines(sx) } else { vec![0.0, sx] };
    let zs = f.lines(sz);
    let c = s.colour;
    let up = ay;
    // Top and underside, each cell cut along the diagonal that follows the
    // hip (the diagonal whose midpoint height is the surface's).
    for i in 0..xs.len() - 1 {
        for j in 0..zs.len() - 1 {
            let (x0, x1, z0, z1) = (xs[i], xs[i + 1], zs[j], zs[j + 1]);
            let h = |x, z| f.top(x, z);
            let mid = h((x0 + x1) / 2.0, (z0 + z1) / 2.0);
            let along_ac = ((h(x0, z0) + h(x1, z1)) / 2.0 - mid).abs()
                <= ((h(x1, z0) + h(x0, z1)) / 2.0 - mid).abs();
            let tris: [[(f64, f64); 3]; 2] = if along_ac {
                [
                    [(x0, z0), (x1, z0), (x1, z1)],
                    [(x0, z0), (x1, z1), (x0, z1)],
                ]
            } else {
                [
                    [(x0, z0), (x1, z0), (x0, z1)],
                    [(x1, z0), (x1, z1), (x0, z1)],
                ]
            };
            for t in tris {
                let top: Vec<DVec3> = t.iter().map(|&(x, z)| at(x, h(x, z), z)).collect();
                put(c, &top, up);
                let under: Vec<DVec3> = t
                    .iter()
                    .map(|&(x, z)| at(x, h(x, z) - f.thick, z))
                    .collect();
                put(c, &under, -up);
            }
        }
    }
    // The edges: the shell's thickness along the eaves; on a gable roof
    // the ends are walls from the scope's floor up to the top.
    for (&z0, &z1) in zs.iter().zip(&zs[1..]) {
        for (x, out) in [(0.0, -ax), (sx, ax)] {
            let low = |z| if f.hip { f.top(x, z) - f.thick } else { 0.0 };
            let pts = [
                at(x, low(z0), z0),
                at(x, low(z1), z1),
                at(x, f.top(x, z1), z1),
                at(x, f.top(x, z0), z0),
            ];
            put(c, &pts, out);
        }
    }
    for (&x0, &x1) in xs.iter().zip(&xs[1..]) {
        for (z, out) in [(0.0, -az), (sz, az)] {
            let pts = [
                at(x0, f.top(x0, z) - f.thick, z),
                at(x1, f.top(x1, z) - f.thick, z),
                at(x1, f.top(x1, z), z),
                at(x0, f.top(x0, z), z),
            ];
            put(c, &pts, out);
        }
    }
    if r.tile > 0.0 {
        tiles(&f, r.tile, c + 1, &at, &mut put);
    }
}

/// Rows of round tiles (here square ribs) down every slope, `tile` apart,
/// from the eaves up to the ridge or to the hip they meet.
fn tiles(
    f: &Fit,
    tile: f64,
    colour: u32,
    at: &dyn Fn(f64, f64, f64) -> DVec3,
    put: &mut dyn FnMut(u32, &[DVec3], DVec3),
) {
    let (sx, sz) = (f.size.x, f.size.z);
    // A row in plan coordinates (u across it, v from the eave inward),
    // mapped to (x, z) by `plan`.
    let mut row = |u: f64, half: f64, v_end: f64, plan: &dyn Fn(f64, f64) -> (f64, f64)| {
        let mut vs: Vec<f64> = f
            .knots
            .iter()
            .map(|k| k.0)
            .filter(|v| *v > 0.0 && *v < v_end)
            .collect();
        vs.insert(0, 0.0);
        vs.push(v_end);
        let point = |u: f64, v: f64, lift: f64| {
            let (x, z) = plan(u, v);
            at(x, f.top(x, z) + lift, z)
        };
        let (mx, mz) = plan(u, 1.0);
        let (ox, oz) = plan(u, 0.0);
        let inward = at(mx, 0.0, mz) - at(ox, 0.0, oz);
        let (sx_, sz_) = plan(u + 1.0, 0.0);
        let side = at(sx_, 0.0, sz_) - at(ox, 0.0, oz);
        let up = at(0.0, 1.0, 0.0) - at(0.0, 0.0, 0.0);
        for w in vs.windows(2) {
            let (a, b) = (w[0], w[1]);
            for (du, out) in [(-half, -side), (half, side)] {
                let pts = [
                    point(u + du, a, 0.0),
                    point(u + du, b, 0.0),
                    point(u + du, b, f.rib),
                    point(u + du, a, f.rib),
                ];
                put(colour, &pts, out);
            }
            let pts = [
                point(u - half, a, f.rib),
                point(u + half, a, f.rib),
                point(u + half, b, f.rib),
                point(u - half, b, f.rib),
            ];
            put(colour, &pts, up);
        }
        let cap = [
            point(u - half, 0.0, 0.0),
            point(u + half, 0.0, 0.0),
            point(u + half, 0.0, f.rib),
            point(u - half, 0.0, f.rib),
        ];
        put(colour, &cap, -inward);
    };
    let rows = |len: f64| {
        let m = ((len / tile).floor() as usize).max(1);
        let pitch = len / m as f64;
        (0..m).map(move |i| ((i as f64 + 0.5) * pitch, 0.2 * pitch))
    };
    let hip_end = |u: f64, len: f64| if f.hip { u.min(len - u) } else { f64::INFINITY };
    for (u, half) in rows(sx) {
        let v_end = (sz / 2.0).min(hip_end(u, sx));
        row(u, half, v_end, &|u, v| (u, v));
        row(u, half, v_end, &|u, v| (u, sz - v));
    }
    if f.hip {
        for (u, half) in rows(sz) {
            let v_end = (sx / 2.0).min(u.min(sz - u));
            row(u, half, v_end, &|u, v| (v, u));
            row(u, half, v_end, &|u, v| (sx - v, u));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(args: &[f64]) -> RoofShape {
        RoofShape::from_args(args).expect("valid")
    }

    #[test]
    fn the_profile_steps_up_by_the_jujia() {
        let r = shape(&[1.0, 0.0, 0.5, 0.5, 0.7, 0.9]);
        let p = r.profile();
        let want = [
            (0.0, 0.0),
            (0.5, 0.25),
            (1.5, 0.75),
            (2.5, 1.45),
            (3.5, 2.35),
        ];
        assert_eq!(p.len(), want.len());
        for (a, b) in p.iter().zip(want) {
            assert!(
                (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12,
                "{p:?}"
            );
        }
    }

    #[test]
    fn bad_parameters_are_named() {
        for (args, says) in [
            (&[1.0, 0.0][..], "needs hip"),
            (&[2.0, 0.0, 0.5, 0.5], "hip is 2"),
            (&[1.0, -1.0, 0.5, 0.5], "tile spacing"),
            (&[1.0, 0.0, 0.5, 0.5, 0.0], "jujia is 0"),
            (
                &[1.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
                "1 to 7",
            ),
        ] {
            let e = RoofShape::from_args(args).unwrap_err();
            assert!(e.contains(says), "{args:?}: {e}");
        }
    }

    /// On a scope sized as the hall's rules size it, the slope between two
    /// purlins is that step's jujia, and a hip roof's ends rise like its
    /// front.
    #[test]
    fn slopes_are_the_jujia_when_the_scope_fits_the_frame() {
        let r = shape(&[1.0, 0.0, 0.5, 0.5, 0.7, 0.9]);
        let b = 1.2; // bujia
        let size = DVec3::new(20.0, 2.35 * b, 2.0 * 3.5 * b);
        let f = Fit::new(&r, size);
        let scale = (size.y - f.thick) / size.y;
        let slope = |z0: f64, z1: f64| (f.top(10.0, z1) - f.top(10.0, z0)) / (z1 - z0);
        for (k, j) in [(0.5, 0.5), (1.5, 0.7), (2.5, 0.9)] {
            let got = slope(k * b + 0.1, k * b + 0.9);
            assert!((got - j * scale).abs() < 1e-9, "step at {k}: {got}");
        }
        // The end slope of a hip roof: the same rise at the same distance.
        assert!((f.top(1.0, 4.0) - f.top(4.0, 1.0)).abs() < 1e-12);
        // The ridge stops short of the ends by half the depth.
        let ridge = f.top(10.0, size.z / 2.0);
        assert!((f.top(size.z / 2.0, size.z / 2.0) - ridge).abs() < 1e-12);
        assert!(f.top(size.z / 2.0 - 0.5, size.z / 2.0) < ridge - 0.1);
    }

    /// A hip roof's corners turn up: the eaves rise toward each corner
    /// (half an eaves' run at the corner, nothing 2.5 runs from it) and
    /// the lift fades up the hip; the middle of an eave and the ridge do
    /// not move. A gable roof's eaves stay straight.
    #[test]
    fn hip_corners_turn_up_and_gable_eaves_stay_straight() {
        let r = shape(&[1.0, 0.0, 0.5, 0.5, 0.7, 0.9]);
        let size = DVec3::new(20.0, 3.0, 8.0);
        let f = Fit::new(&r, size);
        let eave = f.knots[1].0;
        let middle = f.top(10.0, 0.0);
        assert!((f.top(0.0, 0.0) - middle - 0.5 * eave).abs() < 1e-9);
        assert!((f.top(size.x, size.z) - middle - 0.5 * eave).abs() < 1e-9);
        let along = |x: f64| f.top(x, 0.0) - middle;
        assert!(along(0.5 * eave) > along(eave) && along(eave) > along(2.0 * eave));
        assert!(along(2.5 * eave).abs() < 1e-9);
        // Up the hip the lift fades: the surface still falls toward the
        // corner, only less.
        assert!(f.lift(eave, eave) > 0.0 && f.lift(eave, eave) < f.lift(0.0, 0.0));
        assert!((f.top(10.0, 4.0) - 3.0).abs() < 1e-9);
        let g = Fit::new(&shape(&[0.0, 0.0, 0.5, 0.5, 0.7, 0.9]), size);
        assert!((g.top(0.0, 0.0) - g.top(10.0, 0.0)).abs() < 1e-12);
    }

    #[test]
    fn a_gable_roof_keeps_its_ridge_to_the_ends() {
        let r = shape(&[0.0, 0.0, 0.5, 0.5, 0.7, 0.9]);
        let f = Fit::new(&r, DVec3::new(20.0, 3.0, 8.0));
        assert!((f.top(0.0, 4.0) - f.top(10.0, 4.0)).abs() < 1e-12);
        assert!((f.top(0.0, 4.0) - 3.0).abs() < 1e-9);
    }
}
