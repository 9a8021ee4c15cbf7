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

use std::collections::BTreeMap;

use glam::DVec2;

use super::scene::SceneSpec;

/// Vertices this close (× the scene's size) are one particle.
pub const SNAP: f64 = 1e-6;

/// Stiffness of a guide's edges, of its shape-keeping springs and of a
/// link's springs (a link is a hard tie between two guides).
const EDGE: f64 = 1.0;
const SHAPE: f64 = 0.5;
const LINK: f64 = 4.0;

/// Sweeps at most (the solver stops sooner when nothing moves).
const MAX_SWEEPS: usize = 20_000;

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
        let vertex: Vec<Vec<usize>> = spec
            .guides
            .iter()
            .map(|g| {
                g.points
                    .iter()
                    .map(
                        |p| match particles.iter().position(|q| q.distance(*p) <= snap) {
                            Some(i) => i,
                            None => {
                                particles.push(*p);
                                particles.len() - 1
                            }
                        },
                    )
                    .collect()
            })
            .collect();
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
        for sweep in 1..=MAX_SWEEPS {
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
        (x, MAX_SWEEPS)
    }

    /// Every guide's vertices at the particles `x`.
    pub fn guide_points(&self, x: &[DVec2]) -> Vec<Vec<DVec2>> {
        self.vertex
            .iter()
            .map(|v| v.iter().map(|&p| x[p]).collect())
            .collect()
    }

    /// Where a point inside guide `g` goes when the particles move to `x`,
    /// and how far it turns (degrees, counter-clockwise): the similarity
    /// (turn, scale, shift) that best carries the guide's vertices from
    /// where they were to `x`, in the least-squares sense. A guide moved
    /// whole carries its seeds exactly; a bent one, as near as one
    /// similarity can.
    pub fn carry(&self, g: usize, x: &[DVec2], p: DVec2) -> (DVec2, f64) {
        let Some(v) = self.vertex.get(g).filter(|v| !v.is_empty()) else {
            return (p, 0.0);
        };
        let n = v.len() as f64;
        let c0 = v.iter().map(|&i| self.particles[i]).sum::<DVec2>() / n;
        let c1 = v.iter().map(|&i| x[i]).sum::<DVec2>() / n;
        // The best turn-and-scale as one complex number a + ib.
        let (mut a, mut b, mut norm) = (0.0, 0.0, 0.0);
        for &i in v {
            let (p0, p1) = (self.particles[i] - c0, x[i] - c1);
            a += p0.dot(p1);
            b += p0.x * p1.y - p0.y * p1.x;
            norm += p0.length_squared();
        }
        if norm <= 1e-24 {
            return (p + (c1 - c0), 0.0);
        }
        let (a, b) = (a / norm, b / norm);
        let q = p - c0;
        let turned = DVec2::new(a * q.x - b * q.y, b * q.x + a * q.y);
        (c1 + turned, b.atan2(a).to_degrees())
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
        let (q, turn) = s2.carry(2, &x2, DVec2::new(0.5, 3.5));
        assert!(
            q.distance(DVec2::new(1.5, 4.5)) < 1e-6 && turn.abs() < 1e-6,
            "{q} {turn}"
        );
        // The points of every guide are read back in the file's order.
        let pts = s.guide_points(&x);
        assert_eq!(pts[2][3], to);
        assert_eq!(pts[0][1], pts[1][0]);
    }
}
