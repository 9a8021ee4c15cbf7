//! Mass–spring editing of guides (seed 002, §4.2 and §5.6): a scene's
//! guides, one vertex dragged to a point and the vertices held in place in;
//! every guide's vertices at the springs' rest out.
//!
//! The paper's system: the guides' vertices are particles, their edges
//! springs whose rest lengths are their lengths before the drag, with
//! diagonal springs that keep each guide's shape; guides snapped together
//! share the particles of the vertices they share; links are stiff
//! springs between the guides they join, so the two edges of a link keep
//! their places relative to each other. The dragged particle follows the
//! mouse and the others take the system's equilibrium.
//!
//! Here: vertices closer than [`SNAP`] × the scene's size are one particle;
//! every edge is a spring, and so is every vertex to the one two along
//! (the diagonals of a quadrilateral; for longer polygons the springs
//! that keep each corner's angle); every link joins its two edges' end
//! points with stiff springs (unless they are shared). The equilibrium,
//! the least energy Σ k (|xa − xb| − rest)², is reached by moving one
//! particle at a time to its best place with the others still (a
//! Gauss–Seidel sweep of projective dynamics' local-global steps, each of
//! which lowers the energy) until no particle moves more than 10⁻⁹ × the
//! scene's size: when the drag can be met with every spring at rest it is
//! (a free structure translates and turns as a whole), and otherwise the
//! springs share the stretch, the stiff ones least. Held particles never
//! move.

use std::collections::{BTreeMap, HashMap};

use glam::DVec2;

use super::scene::SceneSpec;

/// Vertices this close (× the scene's size) are one particle.
pub const SNAP: f64 = 1e-6;

/// Stiffness of a guide's edges, of its shape-keeping springs and of a
/// link's springs (a link is a hard tie between two guides).
const EDGE: f64 = 1.0;
const SHAPE: f64 = 0.5;
const LINK: f64 = 4.0;

/// Sweeps at most (the solver stops sooner when nothing moves), and
/// spring updates at most over all sweeps: the largest scene the studio
/// takes (500 guides of 200 points) still answers in about a second.
const MAX_SWEEPS: usize = 20_000;
const MAX_WORK: usize = 50_000_000;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    pub a: usize,
    pub b: usize,
    pub rest: f64,
    pub stiffness: f64,
}

/// A scene's guides as particles and springs.
#[derive(Clone, Debug)]
pub struct Springs {
    /// Particle positions before the drag.
    pub particles: Vec<DVec2>,
    pub springs: Vec<Spring>,
    /// Per guide, per vertex: its particle.
    pub vertex: Vec<Vec<usize>>,
    /// The scene's size (the diagonal of the box around every guide).
    pub size: f64,
}

impl Springs {
    /// The springs of `spec`'s guides and links, at rest as they stand.
    pub fn new(spec: &SceneSpec) -> Springs {
        let (lo, hi) = spec
            .guides
            .iter()
            .flat_map(|g| g.points.iter())
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let size = if lo.x.is_finite() {
            (hi - lo).length().max(1e-9)
        } else {
            1.0
        };
        let snap = SNAP * size;
        let mut particles: Vec<DVec2> = Vec::new();
        // Particles by grid cell of the snap distance: a vertex looks in
        // its cell and the eight around it, not at every particle.
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        let cell = |p: DVec2| ((p.x / snap).floor() as i64, (p.y / snap).floor() as i64);
        let mut vertex: Vec<Vec<usize>> = Vec::new();
        for g in &spec.guides {
            let mut v = Vec::new();
            for p in &g.points {
                let (cx, cy) = cell(*p);
                let near = (-1..=1)
                    .flat_map(|dx| (-1..=1).map(move |dy| (cx + dx, cy + dy)))
                    .filter_map(|c| cells.get(&c))
                    .flatten()
                    .copied()
                    .filter(|&i| particles[i].distance(*p) <= snap)
                    .min();
                v.push(near.unwrap_or_else(|| {
                    particles.push(*p);
                    cells.entry((cx, cy)).or_default().push(particles.len() - 1);
                    particles.len() - 1
                }));
            }
            vertex.push(v);
        }
        let mut by_pair: BTreeMap<(usize, usize), f64> = BTreeMap::new();
        let mut add = |a: usize, b: usize, k: f64| {
            if a != b {
                let e = by_pair.entry((a.min(b), a.max(b))).or_insert(k);
                *e = e.max(k);
            }
        };
        for v in &vertex {
            let n = v.len();
            for i in 0..n {
                add(v[i], v[(i + 1) % n], EDGE);
                if n >= 4 {
                    add(v[i], v[(i + 2) % n], SHAPE);
                }
            }
        }
        for link in &spec.links {
            let ends = |g: usize, k: usize| {
                let v = &vertex[g];
                [v[k % v.len()], v[(k + 1) % v.len()]]
            };
            for a in ends(link.from, link.from_edge) {
                for b in ends(link.to, link.to_edge) {
                    add(a, b, LINK);
                }
            }
        }
        let springs = by_pair
            .into_iter()
            .map(|((a, b), stiffness)| Spring {
                a,
                b,
                rest: particles[a].distance(particles[b]),
                stiffness,
            })
            .collect();
        Springs {
            particles,
            springs,
            vertex,
            size,
        }
    }

    /// The particle of guide `g`'s vertex `k`.
    pub fn particle(&self, g: usize, k: usize) -> Option<usize> {
        self.vertex.get(g)?.get(k).copied()
    }

    /// The particles after `dragged` is moved to `to` with `held` fixed:
    /// the equilibrium described in the module's docs, and the sweeps it
    /// took.
    pub fn relax(&self, dragged: usize, to: DVec2, held: &[usize]) -> (Vec<DVec2>, usize) {
        let mut fixed = vec![false; self.particles.len()];
        let n = fixed.len();
        for &h in held.iter().filter(|&&h| h < n) {
            fixed[h] = true;
        }
        let mut x = self.particles.clone();
        if dragged >= x.len() {
            return (x, 0);
        }
        // Nothing held: the whole structure follows the drag, which is
        // where a free system comes to rest. Held particles: the others
        // start where they were.
        if !fixed.iter().any(|f| *f) {
            let delta = to - x[dragged];
            x.iter_mut().for_each(|p| *p += delta);
        }
        fixed[dragged] = true;
        x[dragged] = to;
        let tolerance = 1e-9 * self.size;
        // Each spring seen from both of its ends.
        let mut around: Vec<Vec<(usize, f64, f64)>> = vec![Vec::new(); x.len()];
        for s in &self.springs {
            around[s.a].push((s.b, s.rest, s.stiffness));
            around[s.b].push((s.a, s.rest, s.stiffness));
        }
        let sweeps = MAX_SWEEPS
            .min(MAX_WORK / (2 * self.springs.len()).max(1))
            .max(1);
        for sweep in 1..=sweeps {
            let mut moved: f64 = 0.0;
            for i in 0..x.len() {
                if fixed[i] || around[i].is_empty() {
                    continue;
                }
                // The particle's best place with its neighbours still and
                // its springs' directions kept: the stiffness-weighted mean
                // of where each spring alone would put it. Each such move
                // lowers the springs' energy (a local-global step of
                // projective dynamics), so the sweeps settle.
                let (mut sum, mut weight) = (DVec2::ZERO, 0.0);
                for &(j, rest, k) in &around[i] {
                    let d = x[i] - x[j];
                    let len = d.length();
                    let dir = if len > 1e-12 * self.size {
                        d / len
                    } else {
                        (self.particles[i] - self.particles[j]).normalize_or_zero()
                    };
                    sum += (x[j] + dir * rest) * k;
                    weight += k;
                }
                let next = sum / weight;
                moved = moved.max(next.distance(x[i]));
                x[i] = next;
            }
            if moved <= tolerance {
                return (x, sweep);
            }
        }
        (x, sweeps)
    }

    /// Every guide's vertices at the particles `x`.
    pub fn guide_points(&self, x: &[DVec2]) -> Vec<Vec<DVec2>> {
        self.vertex
            .iter()
            .map(|v| v.iter().map(|&p| x[p]).collect())
            .collect()
    }

    /// Where a point of guide `g` goes when the particles move to `x`: the
    /// point with the same mean value coordinates (Floater's generalised
    /// barycentric coordinates) in the moved guide as it had in the guide
    /// before. A guide moved whole carries it exactly, a point on an edge
    /// stays on that edge at the same fraction, a corner stays the corner.
    pub fn carry_point(&self, g: usize, x: &[DVec2], p: DVec2) -> DVec2 {
        let Some(v) = self.vertex.get(g).filter(|v| v.len() >= 3) else {
            return p;
        };
        let old: Vec<DVec2> = v.iter().map(|&i| self.particles[i]).collect();
        let new: Vec<DVec2> = v.iter().map(|&i| x[i]).collect();
        let n = old.len();
        let eps = 1e-12 * self.size;
        // On an edge (or at a corner): along the moved edge.
        for k in 0..n {
            let (a, b) = (old[k], old[(k + 1) % n]);
            let (q, t) = super::geometry::closest_on_segment(p, a, b);
            if q.distance(p) <= eps {
                return new[k].lerp(new[(k + 1) % n], t);
            }
        }
        let d: Vec<DVec2> = old.iter().map(|&o| o - p).collect();
        let r: Vec<f64> = d.iter().map(|d| d.length()).collect();
        // tan(α/2) of the angle each edge subtends at p, signed.
        let half_tan = |k: usize| {
            let (a, b) = (d[k], d[(k + 1) % n]);
            let cross = a.x * b.y - a.y * b.x;
            cross / (r[k] * r[(k + 1) % n] + a.dot(b))
        };
        let mut sum = DVec2::ZERO;
        let mut weight = 0.0;
        for k in 0..n {
            let w = (half_tan((k + n - 1) % n) + half_tan(k)) / r[k];
            sum += new[k] * w;
            weight += w;
        }
        if weight.abs() <= 1e-300 || !sum.is_finite() {
            return p;
        }
        sum / weight
    }

    /// A seed of guide `g` at `p` heading `heading` (degrees) when the
    /// particles move to `x`: its point carried by [`Springs::carry_point`],
    /// its heading turned as the guide's edge nearest to it turns (a seed
    /// on an edge keeps its angle to that edge; a guide moved whole turns
    /// its seeds with it). The map's own turn near an edge is not used: a
    /// guide whose far side moves would tilt a seed on a still edge.
    pub fn carry(&self, g: usize, x: &[DVec2], p: DVec2, heading: f64) -> (DVec2, f64) {
        let q = self.carry_point(g, x, p);
        let Some(v) = self.vertex.get(g).filter(|v| v.len() >= 3) else {
            return (q, heading);
        };
        let n = v.len();
        let edge = |pos: &dyn Fn(usize) -> DVec2, k: usize| pos(v[(k + 1) % n]) - pos(v[k]);
        let old = |i: usize| self.particles[i];
        let new = |i: usize| x[i];
        let nearest = (0..n)
            .min_by(|&a, &b| {
                let d = |k: usize| {
                    super::geometry::distance_to_segment(p, old(v[k]), old(v[(k + 1) % n]))
                };
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(0);
        let (e0, e1) = (edge(&old, nearest), edge(&new, nearest));
        let turn = super::geometry::signed_angle(e0, e1);
        (q, heading + turn)
    }

    /// How far the springs are from rest at `x`: the largest stretch or
    /// squeeze, as a fraction of the spring's rest length.
    pub fn strain(&self, x: &[DVec2]) -> f64 {
        self.springs
            .iter()
            .map(|s| (x[s.a].distance(x[s.b]) - s.rest).abs() / s.rest.max(1e-12))
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guided::scene;

    const TWO: &str = r#"
steps = 1
[[guide]]
name = "a"
grammar = "x.lsys"
points = [[0, 0], [2, 0], [2, 1], [0, 1]]
[[guide]]
name = "b"
grammar = "x.lsys"
points = [[2, 0], [4, 0], [4, 1], [2, 1]]
[[guide]]
name = "c"
grammar = "x.lsys"
points = [[0, 3], [1, 3], [1, 4], [0, 4]]
[[link]]
from = "a"
from_edge = 2
to = "c"
to_edge = 0
continuity = "C1"
"#;

    fn springs() -> Springs {
        Springs::new(&scene::read("two.toml", TWO).unwrap())
    }

    #[test]
    fn snapped_guides_share_particles_and_links_are_springs() {
        let s = springs();
        // a and b share their common edge's two vertices: 4 + 2 + 4.
        assert_eq!(s.particles.len(), 10);
        assert_eq!(s.vertex[0][1], s.vertex[1][0]);
        assert_eq!(s.vertex[0][2], s.vertex[1][3]);
        // a's top edge (vertices 2, 3) joined to c's bottom edge (0, 1).
        let joined = |p: usize, q: usize| {
            s.springs
                .iter()
                .any(|x| (x.a, x.b) == (p.min(q), p.max(q)) && x.stiffness == LINK)
        };
        assert!(joined(s.vertex[0][2], s.vertex[2][0]));
        assert!(joined(s.vertex[0][3], s.vertex[2][1]));
    }

    #[test]
    fn a_free_structure_follows_the_drag_whole() {
        let s = springs();
        let p = s.vertex[2][2];
        let to = s.particles[p] + DVec2::new(5.0, -1.0);
        let (x, _) = s.relax(p, to, &[]);
        assert!(s.strain(&x) < 1e-6, "strain {}", s.strain(&x));
        assert!(x[0].distance(DVec2::new(5.0, -1.0)) < 1e-6);
    }

    #[test]
    fn held_vertices_stay_and_the_rest_relaxes() {
        let s = springs();
        // Hold b's right edge; drag c's top-left corner 1 to the left.
        let held = [s.vertex[1][1], s.vertex[1][2]];
        let p = s.vertex[2][3];
        let to = s.particles[p] + DVec2::new(-1.0, 0.0);
        let (x, sweeps) = s.relax(p, to, &held);
        assert!(sweeps < MAX_SWEEPS);
        for h in held {
            assert_eq!(x[h], s.particles[h]);
        }
        assert_eq!(x[p], to);
        // The chain a-c moved toward the drag: c's bottom edge went left.
        assert!(x[s.vertex[2][0]].x < 0.0 - 1e-3);
        // ... and a, tied to c by the link and to b by shared vertices,
        // is pulled too, but less.
        let a_moved = x[s.vertex[0][3]].distance(s.particles[s.vertex[0][3]]);
        let c_moved = x[s.vertex[2][0]].distance(s.particles[s.vertex[2][0]]);
        assert!(a_moved > 1e-3 && a_moved < c_moved, "{a_moved} {c_moved}");
        // A point of a guide moved whole goes with it, turned as it is.
        let s2 = springs();
        let p = s2.vertex[2][2];
        let c = s2.particles[p];
        let (x2, _) = s2.relax(p, c + DVec2::new(1.0, 1.0), &[]);
        let (q, heading) = s2.carry(2, &x2, DVec2::new(0.5, 3.5), 30.0);
        assert!(q.distance(DVec2::new(1.5, 4.5)) < 1e-6, "{q}");
        assert!((heading - 30.0).abs() < 1e-6, "{heading}");
        // A point on an edge stays on it at the same fraction, though the
        // guide is bent: c's top edge, a quarter along, after the drag
        // above (c's top-left corner moved, its bottom did not).
        let on_top = s.carry_point(2, &x, DVec2::new(0.75, 4.0));
        let (a, b) = (x[s.vertex[2][2]], x[s.vertex[2][3]]);
        assert!(on_top.distance(a.lerp(b, 0.25)) < 1e-9, "{on_top}");
        // Inside, a bent guide's point moves less than the corner did.
        let inner = s.carry_point(2, &x, DVec2::new(0.5, 3.5));
        let corner = s.vertex[2][3];
        assert!(inner.distance(DVec2::new(0.5, 3.5)) < x[corner].distance(s.particles[corner]));
        // The points of every guide are read back in the file's order.
        let pts = s.guide_points(&x);
        assert_eq!(pts[2][3], to);
        assert_eq!(pts[0][1], pts[1][0]);
    }
}
