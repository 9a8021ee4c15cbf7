//! Light: cpfg's `chiba` environmental program (vlab `ENVIRO/chiba/`,
//! after Chiba et al.). Every `?E` with one or at least four parameters is
//! a sphere (radius `p1` when positive, else `radius:`) centred at the
//! turtle's position; each receives light from sky samples (the centroids
//! of a subdivided octahedron's triangles, `number of samples:`, upper
//! and lower hemisphere weighted by `lower to upper ratio:`) or from
//! `source direction: x y z intensity` lines, each ray attenuated by the
//! other spheres it meets. The reply is `p1 = ` the light received and,
//! with four or more parameters, `p2..p4 =` the normalised direction of
//! most light.
//!
//! The spheres a ray meets are found as the vlab program finds them: by
//! walking a voxel grid (`grid size:`) from the sphere's centre, each
//! voxel listing the spheres near it, each sphere counted once per ray.
//! That walk places voxel centres without the grid's origin, so when the
//! grid does not start at 0 it can step past a voxel and miss a sphere
//! that a brute-force test would find; lsys walks it the same way, so
//! that models derive the strings cpfg derives (`docs/environments.md`).
//! Arithmetic is in `f32` where the program's is, `f64` where C promotes.

use std::f64::consts::PI;

use miette::SourceSpan;

use super::communication::{lines, number, switch};
use super::error::EnvironmentError;
use super::{EnvironmentalProgram, Query, Reply};

/// The specification file's settings, with the program's defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// `lower to upper ratio:` (0.7).
    pub lower_to_upper: f32,
    /// `transmittance:` of a sphere (0.6).
    pub transmittance: f32,
    /// `radius:` of a sphere whose `?E` gives none (25).
    pub radius: f32,
    /// `beam radius:` (0; 1 with `estimate intersection area: on`).
    pub beam_radius: f32,
    /// `number of samples:` of the sky (20; rounded up to 8·4^k).
    pub samples: u32,
    /// `estimate intersection area:` (off).
    pub estimate_area: bool,
    /// `use CIE formula: yes` (an overcast sky instead of the ratio).
    pub cie_sky: bool,
    /// `source direction: x y z intensity` lines (replace the sky).
    pub sources: Vec<([f32; 3], f32)>,
    /// `grid size: XxYxZ` of the voxel grid the rays walk (1x1x1).
    pub grid: [i32; 3],
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            lower_to_upper: 0.7,
            transmittance: 0.6,
            radius: 25.0,
            beam_radius: 0.0,
            samples: 20,
            estimate_area: false,
            cie_sky: false,
            sources: Vec::new(),
            grid: [1, 1, 1],
        }
    }
}

impl Settings {
    pub(super) fn read(
        text: &str,
        bad: impl Fn(&str, SourceSpan, String) -> Box<EnvironmentError>,
    ) -> Result<Settings, Box<EnvironmentError>> {
        let mut s = Settings::default();
        for line in lines(text) {
            let num = |what: &str| {
                number(line.value)
                    .ok_or_else(|| bad(&line.key, line.span, format!("{what} is not a number")))
            };
            match line.key.as_str() {
                "lower to upper ratio" => s.lower_to_upper = num("the ratio")? as f32,
                "transmittance" => s.transmittance = num("the transmittance")? as f32,
                "radius" => s.radius = num("the radius")? as f32,
                "beam radius" => s.beam_radius = num("the beam radius")? as f32,
                "number of samples" => {
                    let n = num("the number of samples")?;
                    if !(1.0..=1e6).contains(&n) {
                        return Err(bad(
                            &line.key,
                            line.span,
                            "give 1 to 1000000 samples".into(),
                        ));
                    }
                    s.samples = n as u32;
                }
                "estimate intersection area" => s.estimate_area = switch(line.value),
                "grid size" => {
                    let v: Vec<f64> = line
                        .value
                        .split(['x', ',', ';', ' ', '\t'])
                        .filter(|w| !w.is_empty())
                        .filter_map(number)
                        .collect();
                    for (k, n) in v.iter().take(3).enumerate() {
                        if !(1.0..=1024.0).contains(n) {
                            return Err(bad(
                                &line.key,
                                line.span,
                                "each side of the grid is 1 to 1024 voxels".into(),
                            ));
                        }
                        s.grid[k] = *n as i32;
                    }
                }
                "use cie formula" => {
                    s.cie_sky = line.value.split_whitespace().next() == Some("yes")
                }
                "source direction" => {
                    let v: Vec<f32> = line
                        .value
                        .split([',', ';', ' ', '\t'])
                        .filter(|w| !w.is_empty())
                        .map_while(|w| number(w).map(|x| x as f32))
                        .collect();
                    let dir = [0, 1, 2].map(|i| v.get(i).copied().unwrap_or(0.0));
                    s.sources.push((dir, v.get(3).copied().unwrap_or(1.0)));
                }
                _ => {}
            }
        }
        if s.estimate_area {
            s.beam_radius = 1.0;
        }
        Ok(s)
    }
}

/// A direction light comes from, and how much.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    dir: [f32; 3],
    intensity: f32,
}

/// The program.
pub struct Light {
    settings: Settings,
    samples: Vec<Sample>,
}

fn normalize(v: &mut [f32; 3]) {
    let len = ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) as f64).sqrt() as f32;
    if len > 0.0 {
        v.iter_mut().for_each(|c| *c /= len);
    }
}

/// The triangles of an octahedron subdivided `level - 1` times, their
/// vertices on the unit sphere (in f64, then stored as f32), in the
/// order of Jon Leech's `sphere` program that chiba uses.
fn sphere_triangles(level: u32) -> Vec<[[f32; 3]; 3]> {
    let (x, nx, y, ny, z, nz) = (
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    );
    // The octahedron, each triangle's vertex order reversed.
    let mut tris: Vec<[[f64; 3]; 3]> = [
        [x, z, y],
        [y, z, nx],
        [nx, z, ny],
        [ny, z, x],
        [x, y, nz],
        [y, nx, nz],
        [nx, ny, nz],
        [ny, x, nz],
    ]
    .into_iter()
    .map(|[a, b, c]| [c, b, a])
    .collect();
    let mid = |a: [f64; 3], b: [f64; 3]| {
        let m = [
            (a[0] + b[0]) * 0.5,
            (a[1] + b[1]) * 0.5,
            (a[2] + b[2]) * 0.5,
        ];
        let mag = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
        if mag == 0.0 {
            return m;
        }
        let k = 1.0 / mag.sqrt();
        [m[0] * k, m[1] * k, m[2] * k]
    };
    for _ in 1..level {
        let mut next = Vec::with_capacity(tris.len() * 4);
        for t in &tris {
            let a = mid(t[0], t[2]);
            let b = mid(t[0], t[1]);
            let c = mid(t[1], t[2]);
            next.extend([[t[0], b, a], [b, t[1], c], [a, b, c], [a, c, t[2]]]);
        }
        tris = next;
    }
    tris.iter()
        .map(|t| t.map(|v| v.map(|c| c as f32)))
        .collect()
}

impl Light {
    pub fn new(settings: Settings) -> Light {
        let samples = if settings.sources.is_empty() {
            sky(&settings)
        } else {
            let total: f32 = settings.sources.iter().map(|s| s.1).sum();
            settings
                .sources
                .iter()
                .map(|&(d, i)| {
                    let mut dir = d;
                    normalize(&mut dir);
                    Sample {
                        dir,
                        intensity: i / total,
                    }
                })
                .collect()
        };
        Light { settings, samples }
    }
}

/// The sky: centroids of the subdivided octahedron's triangles.
fn sky(s: &Settings) -> Vec<Sample> {
    let level = ((s.samples as f64 / 8.0).ln() / 4f64.ln()).ceil() as i64 + 1;
    let level = level.clamp(1, 12) as u32;
    let mut out: Vec<Sample> = sphere_triangles(level)
        .iter()
        .map(|t| {
            let mut dir = [0, 1, 2].map(|c| ((t[0][c] + t[1][c] + t[2][c]) as f64 / 3.0) as f32);
            normalize(&mut dir);
            Sample {
                dir,
                intensity: 0.0,
            }
        })
        .collect();
    let n = out.len();
    if s.cie_sky {
        // The CIE overcast sky, by the angle from the zenith.
        let mut total = 0f32;
        for smp in &mut out {
            if smp.dir[1] > 0.0 {
                let d = smp.dir;
                let cos = d[1] as f64 / ((d[0] * d[0] + d[1] * d[1]) as f64).sqrt();
                smp.intensity = ((1.0 + cos) / 3.0 * (8.6 * cos + 0.123) / 0.203) as f32;
                total += smp.intensity;
            }
        }
        out.iter_mut().for_each(|smp| smp.intensity /= total);
    } else {
        let up = out.iter().filter(|smp| smp.dir[1] >= 0.0).count();
        let ratio = s.lower_to_upper as f64;
        for smp in &mut out {
            smp.intensity = if smp.dir[1] >= 0.0 {
                (1.0 / up as f32 as f64 / (1.0 + ratio)) as f32
            } else {
                (ratio / (n - up) as f32 as f64 / (1.0 + ratio)) as f32
            };
        }
    }
    out
}

/// A sphere of the pass.
#[derive(Clone, Copy, Debug)]
struct Sphere {
    pos: [f32; 3],
    radius: f32,
    area: f32,
}

/// The area of the query's disc (radius `r`, at `pt`) covered by the
/// disc of `other` seen along `dir`; 0 when `other` is behind.
fn covered_area(pt: [f32; 3], dir: [f32; 3], other: &Sphere, r: f32) -> f32 {
    let v = [
        pt[0] - other.pos[0],
        pt[1] - other.pos[1],
        pt[2] - other.pos[2],
    ];
    let along = dir[0] * v[0] + dir[1] * v[1] + dir[2] * v[2];
    if along > 0.0 {
        return 0.0;
    }
    let d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - along * along;
    let reach = other.radius + r;
    if d2 >= reach * reach {
        return 0.0;
    }
    let (r1, r2) = if other.radius < r {
        (r, other.radius)
    } else {
        (other.radius, r)
    };
    let (r1s, r2s) = (r1 * r1, r2 * r2);
    let d = (d2 as f64).sqrt() as f32;
    if d + r2 <= r1 {
        return (PI * r2s as f64) as f32;
    }
    let x1 = (r1s + d * d - r2s) / (2.0 * d);
    let x2 = (r2s + d * d - r1s) / (2.0 * d);
    let y = ((r2s - x2 * x2) as f64).sqrt() as f32;
    (r1s as f64 * ((x1 / r1) as f64).acos() + r2s as f64 * ((x2 / r2) as f64).acos()
        - (y * d) as f64) as f32
}

/// The length of the ray from `pt` along `dir` inside `other` grown by
/// `beam` (0 when it misses or the sphere is behind).
fn chord(pt: [f32; 3], dir: [f32; 3], other: &Sphere, grow: f32) -> f32 {
    let v = [
        pt[0] - other.pos[0],
        pt[1] - other.pos[1],
        pt[2] - other.pos[2],
    ];
    let along = dir[0] * v[0] + dir[1] * v[1] + dir[2] * v[2];
    let reach = other.radius + grow;
    let disc = along * along - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + reach * reach;
    if disc < 0.0 {
        return 0.0;
    }
    let s = (disc as f64).sqrt() as f32;
    if -along + s <= 0.0 {
        return 0.0;
    }
    if -along - s >= 0.0 {
        2.0 * s
    } else {
        -along + s
    }
}

impl EnvironmentalProgram for Light {
    fn respond(&mut self, queries: &[Query]) -> Vec<Reply> {
        let s = &self.settings;
        // The spheres: queries with 1 or at least 4 parameters and a
        // position; others get no reply.
        let spheres: Vec<Option<Sphere>> = queries
            .iter()
            .map(|q| {
                let n = q.params.len();
                if n != 1 && n < 4 {
                    return None;
                }
                let pos = q.position?;
                let p1 = q.params[0] as f32;
                let radius = if p1 > 0.0 { p1 } else { s.radius };
                Some(Sphere {
                    pos,
                    radius,
                    area: (PI * radius as f64 * radius as f64) as f32,
                })
            })
            .collect();
        let lit: Vec<Sphere> = spheres.iter().flatten().copied().collect();
        let grid = Grid::new(s.grid, &lit, s.beam_radius);
        let mut rays = Rays {
            ray: 0,
            seen: vec![0; lit.len()],
        };
        let mut k = 0;
        spheres
            .iter()
            .zip(queries)
            .map(|(me, q)| {
                let mut reply = vec![None; q.params.len()];
                if me.is_none() {
                    return reply;
                }
                let lv = k;
                k += 1;
                let mut sum = 0f32;
                let mut best = [0f32; 3];
                for smp in &self.samples {
                    let a = self.received(lv, smp, &lit, &grid, &mut rays);
                    sum += a;
                    for (b, d) in best.iter_mut().zip(smp.dir) {
                        *b += a * d;
                    }
                }
                reply[0] = Some(sum as f64);
                if q.params.len() >= 4 {
                    normalize(&mut best);
                    for (r, b) in reply[1..4].iter_mut().zip(best) {
                        *r = Some(b as f64);
                    }
                }
                reply
            })
            .collect()
    }
}

/// Which spheres the current ray has met (chiba's ray signatures): one
/// array for the whole pass instead of one per ray.
struct Rays {
    ray: u64,
    seen: Vec<u64>,
}

/// The voxel grid of one pass, enclosing every sphere.
struct Grid {
    size: [i32; 3],
    pos: [f32; 3],
    range: [f32; 3],
    /// Per voxel (x fastest), the spheres near it in the order they were
    /// added; chiba prepends to its lists, so rays read them backwards.
    cells: Vec<Vec<usize>>,
}

impl Grid {
    /// The grid around `spheres` (in query order), each voxel listing the
    /// spheres within reach of its centre.
    fn new(size: [i32; 3], spheres: &[Sphere], beam: f32) -> Grid {
        let mut pos = [0f32; 3];
        let mut range = [0f32; 3];
        let mut max_r = 0f32;
        for (k, sp) in spheres.iter().enumerate() {
            for c in 0..3 {
                if k == 0 {
                    pos[c] = sp.pos[c] - sp.radius;
                    range[c] = 2.0 * sp.radius;
                } else {
                    let aux = pos[c] - (sp.pos[c] - sp.radius);
                    if aux > 0.0 {
                        pos[c] -= aux;
                        range[c] += aux;
                    }
                    let aux = (sp.pos[c] + sp.radius) - (pos[c] + range[c]);
                    if aux > 0.0 {
                        range[c] += aux;
                    }
                }
            }
            if k == 0 || sp.radius > max_r {
                max_r = sp.radius;
            }
        }
        let n = (size[0] * size[1] * size[2]) as usize;
        let mut grid = Grid {
            size,
            pos,
            range,
            cells: vec![Vec::new(); n],
        };
        let mut half = 0f32;
        for c in 0..3 {
            let aux = range[c] / size[c] as f32;
            half += aux * aux;
        }
        let half = (0.5 * (half as f64).sqrt()) as f32;
        let centre = |c: usize, i: i32| {
            (pos[c] as f64 + (i as f64 + 0.5) / size[c] as f32 as f64 * range[c] as f64) as f32
        };
        for (lv, sp) in spheres.iter().enumerate() {
            let reach = sp.radius + max_r * beam;
            let mut lo = [0i32; 3];
            let mut hi = [0i32; 3];
            for c in 0..3 {
                let l = ((sp.pos[c] - reach - pos[c]) / range[c] * size[c] as f32).floor() - 1.0;
                lo[c] = l.max(0.0) as i32;
                let h = 1.0 + ((sp.pos[c] + reach - pos[c]) / range[c] * size[c] as f32).floor();
                hi[c] = if h >= size[c] as f32 {
                    size[c] - 1
                } else {
                    h as i32
                };
            }
            let limit = (reach + half) * (reach + half);
            for z in lo[2]..=hi[2] {
                let pz = centre(2, z);
                for y in lo[1]..=hi[1] {
                    let py = centre(1, y);
                    for x in lo[0]..=hi[0] {
                        let px = centre(0, x);
                        let d = [sp.pos[0] - px, sp.pos[1] - py, sp.pos[2] - pz];
                        if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= limit {
                            let i = grid.index([x, y, z]);
                            grid.cells[i].push(lv);
                        }
                    }
                }
            }
        }
        grid
    }

    /// The voxel `node`, clamped into the grid.
    fn index(&self, node: [i32; 3]) -> usize {
        let n = [0, 1, 2].map(|c| node[c].clamp(0, self.size[c] - 1));
        (n[2] * self.size[1] * self.size[0] + n[1] * self.size[0] + n[0]) as usize
    }
}

impl Light {
    /// The light sphere `lv` receives from `smp`: the ray from its centre
    /// walks the grid, and every other sphere listed in a voxel it visits
    /// that the ray meets reduces it (each sphere once).
    fn received(
        &self,
        lv: usize,
        smp: &Sample,
        spheres: &[Sphere],
        grid: &Grid,
        rays: &mut Rays,
    ) -> f32 {
        if smp.intensity == 0.0 {
            return 0.0;
        }
        let s = &self.settings;
        let me = &spheres[lv];
        let pt = me.pos;
        let size = grid.size;
        let mut step = [1i64, size[0] as i64, (size[0] * size[1]) as i64];
        let mut node_size = [0f32; 3];
        for c in 0..3 {
            node_size[c] = (0.5 * grid.range[c] as f64 / size[c] as f32 as f64) as f32;
            if smp.dir[c] < 0.0 {
                node_size[c] = -node_size[c];
                step[c] = -step[c];
            }
        }
        let mut node = [0i32; 3];
        let mut middle = [0f32; 3];
        for c in 0..3 {
            node[c] = ((pt[c] - grid.pos[c]) / grid.range[c] * size[c] as f32).floor() as i32;
            // As chiba computes it: without the grid's origin.
            middle[c] =
                ((node[c] as f64 + 0.5) / size[c] as f32 as f64 * grid.range[c] as f64) as f32;
        }
        let mut cell = grid.index(node) as i64;
        // A new ray: every sphere unseen but this one.
        rays.ray += 1;
        let ray = rays.ray;
        rays.seen[lv] = ray;
        let mut reduction = 1f32;
        let red = s.transmittance;
        loop {
            let list = usize::try_from(cell).ok().and_then(|i| grid.cells.get(i));
            for &o in list.into_iter().flatten().rev() {
                if rays.seen[o] == ray {
                    continue;
                }
                let other = &spheres[o];
                if s.estimate_area {
                    let a = covered_area(pt, smp.dir, other, me.radius);
                    if a > 0.0 {
                        rays.seen[o] = ray;
                        reduction *= 1.0 - (1.0 - red) * a / me.area;
                    }
                } else {
                    let a = chord(pt, smp.dir, other, s.beam_radius * me.radius);
                    if a > 0.0 {
                        rays.seen[o] = ray;
                        let e =
                            a as f64 / (2.0 * (other.radius + s.beam_radius * me.radius) as f64);
                        reduction = (reduction as f64 * (red as f64).powf(e)) as f32;
                    }
                }
            }
            // The face of the voxel the ray leaves through.
            let mut smallest = (middle[0] + node_size[0] - pt[0]).abs();
            let mut ind = 0;
            for c in 1..3 {
                let aux = middle[c] + node_size[c] - pt[c];
                if (aux * smp.dir[ind]).abs() < (smallest * smp.dir[c]).abs() {
                    smallest = aux;
                    ind = c;
                }
            }
            middle[ind] += 2.0 * node_size[ind];
            cell += step[ind];
            node[ind] += if smp.dir[ind] > 0.0 { 1 } else { -1 };
            if node[ind] < 0 || node[ind] >= size[ind] {
                return smp.intensity * reduction;
            }
        }
    }
}
