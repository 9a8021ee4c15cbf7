//! Tubes: a turtle [`Chain`] -> a generalized cylinder. Consecutive
//! segments share one ring, oriented in the bisecting plane and carried
//! along the curve by parallel transport so that tubes do not twist; a
//! straight run (no turn, no change of width) is one segment with a ring at
//! each end only. How tubes join each other and how they are capped is
//! decided by [`super::tubes`], which calls `piece` per piece of a chain.

use std::f32::consts::TAU;

use glam::Vec3;

use super::scene::TriMesh;
use crate::turtle::drawing::{Chain, TubePoint};

/// Turns sharper than this (cosine between segments) end one tube and
/// start the next: a ring in the bisecting plane would pinch.
pub(super) const SPLIT_COS: f32 = -0.2;

/// Two segments closer to parallel than this (cosine) are one straight run.
const STRAIGHT_COS: f32 = 1.0 - 1e-6;

/// A ring already in the mesh: `sides` vertices from `first` on, around
/// `pos` in the plane normal to `tangent`, the first one along `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    pub first: u32,
    pub sides: u32,
    pub pos: Vec3,
    pub radius: f32,
    pub tangent: Vec3,
    pub axis: Vec3,
}

/// How one end of a piece is closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cap {
    /// A flat disc with vertices of its own, so that the rim shades sharply.
    Flat,
    /// A fan over the ring's own vertices: no new vertices, for tubes too
    /// thin for the shading of their ends to show.
    Fan,
    /// Open: another tube continues from this ring.
    Open,
}

/// One piece of a chain: its points, where it starts and how its ends close.
pub struct Piece<'a> {
    pub points: &'a [TubePoint],
    /// Index of `points[0]` in the whole chain (for `Piece::keep`).
    pub offset: usize,
    pub sides: u32,
    /// A ring to start from instead of a new one (with its own orientation).
    pub start: Option<Ring>,
    pub caps: [Cap; 2],
}

/// Appends the tube for `chain` with `sides` facets around to `mesh`, with
/// flat caps and no sharing: the tube of one chain on its own.
pub fn tube(chain: &Chain, sides: u32, mesh: &mut TriMesh) {
    if chain.points.len() < 2 {
        return;
    }
    let mut scratch = Scratch::default();
    let mut dirs = Vec::new();
    directions(&chain.points, &mut dirs);
    for_each_piece(&dirs, |range, _, _| {
        piece(
            &Piece {
                points: &chain.points[range.clone()],
                offset: range.start,
                sides,
                start: None,
                caps: [Cap::Flat, Cap::Flat],
            },
            &dirs[range.start..range.end - 1],
            |_| false,
            |_, _| {},
            &mut scratch,
            mesh,
        );
    });
}

/// The unit direction of each segment of `pts` (zero where two points
/// coincide) into `dirs`: computed once per chain, then read by the split,
/// the straight-run test and the ring tangents, which each normalised the
/// same differences again.
pub(super) fn directions(pts: &[TubePoint], dirs: &mut Vec<Vec3>) {
    dirs.clear();
    dirs.extend(
        pts.windows(2)
            .map(|w| (w[1].pos - w[0].pos).normalize_or_zero()),
    );
}

/// Calls `f(range, is_first, is_last)` for each piece of the chain whose
/// segment directions are `dirs` (from [`directions`]): the chain split at
/// every turn sharper than [`SPLIT_COS`] (the two pieces share the turning
/// point).
pub(super) fn for_each_piece(dirs: &[Vec3], mut f: impl FnMut(std::ops::Range<usize>, bool, bool)) {
    let mut start = 0;
    for i in 1..dirs.len() {
        if dirs[i - 1].dot(dirs[i]) < SPLIT_COS {
            f(start..i + 1, start == 0, false);
            start = i;
        }
    }
    f(start..dirs.len() + 1, start == 0, true);
}

/// True when `b` lies on the straight line from `a` on to `c` with the
/// same width at all three: its ring would add nothing.
pub(super) fn straight(a: &TubePoint, b: &TubePoint, c: &TubePoint) -> bool {
    a.radius == b.radius
        && b.radius == c.radius
        && straight_dirs(
            (b.pos - a.pos).normalize_or_zero(),
            (c.pos - b.pos).normalize_or_zero(),
        )
}

fn straight_dirs(d0: Vec3, d1: Vec3) -> bool {
    d0.dot(d1) >= STRAIGHT_COS
}

/// Space `piece` reuses from one call to the next.
#[derive(Default)]
pub struct Scratch {
    /// Indices of the points that get a ring.
    kept: Vec<usize>,
    /// Unit direction from each kept point to the next.
    kdirs: Vec<Vec3>,
    /// (sin, cos) of each facet's angle.
    around: Vec<(f32, f32)>,
}

impl Scratch {
    /// The angle table for `sides` facets, made once per facet count in a
    /// row (a drawing's tubes mostly share one).
    fn tables(&mut self, sides: u32) {
        if self.around.len() == sides as usize {
            return;
        }
        self.around.clear();
        self.around
            .extend((0..sides).map(|k| (TAU * k as f32 / sides as f32).sin_cos()));
    }
}

/// Appends the side wall between the rings of `sides` vertices from `a`
/// (the earlier) and `b`: per facet k, (a_k, a_k+1, b_k) and
/// (a_k+1, b_k+1, b_k), six indices at a time (mapped from a table of
/// (ring, facet) pairs, W2's walls took 44 M more instructions).
fn wall(a: u32, b: u32, sides: u32, indices: &mut Vec<u32>) {
    indices.reserve(6 * sides as usize);
    for k in 0..sides {
        let k1 = if k + 1 == sides { 0 } else { k + 1 };
        indices.extend_from_slice(&[a + k, a + k1, b + k, a + k1, b + k1, b + k]);
    }
}

/// Appends one piece to `mesh`. `dirs` are the directions of its segments.
/// Points in a straight run are skipped unless `keep(chain index)` says
/// another tube starts there; `visit(chain index, ring)` sees every ring
/// of the piece.
pub(super) fn piece(
    p: &Piece,
    dirs: &[Vec3],
    keep: impl Fn(usize) -> bool,
    mut visit: impl FnMut(usize, Ring),
    scratch: &mut Scratch,
    mesh: &mut TriMesh,
) {
    let pts = p.points;
    if pts.len() < 2 {
        return;
    }
    let sides = p.sides.max(3);
    scratch.tables(sides);
    let Scratch {
        kept,
        kdirs,
        around,
    } = scratch;
    let n = pts.len();
    kept.clear();
    kept.push(0);
    for i in 1..n - 1 {
        let last = kept[kept.len() - 1];
        let (a, b, c) = (&pts[last], &pts[i], &pts[i + 1]);
        let run = a.radius == b.radius && b.radius == c.radius && {
            // The direction from the last kept point: the segment's own
            // when that point is the one before.
            let d0 = if last + 1 == i {
                dirs[last]
            } else {
                (b.pos - a.pos).normalize_or_zero()
            };
            straight_dirs(d0, dirs[i])
        };
        if !run || keep(p.offset + i) {
            kept.push(i);
        }
    }
    kept.push(n - 1);
    let m = kept.len();
    kdirs.clear();
    kdirs.extend(kept.windows(2).map(|w| {
        if w[0] + 1 == w[1] {
            dirs[w[0]]
        } else {
            (pts[w[1]].pos - pts[w[0]].pos).normalize_or_zero()
        }
    }));
    let tangent = |j: usize| {
        let t = if j == 0 {
            kdirs[0]
        } else if j == m - 1 {
            kdirs[m - 2]
        } else {
            (kdirs[j - 1] + kdirs[j]).normalize_or_zero()
        };
        if t == Vec3::ZERO {
            Vec3::Y
        } else {
            t
        }
    };
    // Every ring but a shared first one is new: room for all at once.
    let new_rings = m - usize::from(p.start.is_some());
    mesh.positions.reserve(new_rings * sides as usize);
    mesh.normals.reserve(new_rings * sides as usize);
    mesh.indices.reserve((m - 1) * 6 * sides as usize);
    let mut rings = [None::<Ring>; 2];
    let mut prev: Option<Ring> = None;
    for (j, &point) in kept.iter().enumerate() {
        let ring = match (j, p.start) {
            (0, Some(start)) => start,
            _ => new_ring(&pts[point], tangent(j), prev, around, mesh),
        };
        if let Some(r0) = prev {
            wall(r0.first, ring.first, sides, &mut mesh.indices);
        }
        visit(p.offset + point, ring);
        if j == 0 {
            rings[0] = Some(ring);
        }
        if j == m - 1 {
            rings[1] = Some(ring);
        }
        prev = Some(ring);
    }
    for (end, ring) in rings.into_iter().enumerate() {
        let Some(ring) = ring else { continue };
        cap(ring, p.caps[end], end == 0, mesh);
    }
}

/// Appends a ring of `around.len()` vertices at `q`, in the plane normal
/// to `t`: its first vertex along the turtle's up vector at a tube's
/// first ring, else along `prev`'s axis carried into this plane (parallel
/// transport, so that the tube does not twist).
fn new_ring(
    q: &TubePoint,
    t: Vec3,
    prev: Option<Ring>,
    around: &[(f32, f32)],
    mesh: &mut TriMesh,
) -> Ring {
    let seed = prev.map_or(q.up, |r| r.axis);
    let mut a = (seed - t * seed.dot(t)).normalize_or_zero();
    if a == Vec3::ZERO {
        a = t.any_orthonormal_vector();
    }
    let b = t.cross(a);
    let first = mesh.positions.len() as u32;
    let from = mesh.normals.len();
    mesh.normals
        .extend(around.iter().map(|&(s, c)| a * c + b * s));
    let (pos, radius) = (q.pos, q.radius);
    mesh.positions.extend(
        mesh.normals[from..]
            .iter()
            .map(|&normal| pos + normal * radius),
    );
    Ring {
        first,
        sides: around.len() as u32,
        pos: q.pos,
        radius: q.radius,
        tangent: t,
        axis: a,
    }
}

/// [`piece`] for a piece of one segment, `a` to `b` in direction `dir`:
/// the same rings, walls and caps, without the search for straight runs
/// and the lists it keeps. Most chains of a branching plant are one `F`
/// (each of W2's 262,143 is), and `piece`'s bookkeeping was most of their
/// cost. Returns the two rings.
pub(super) fn segment(
    ends: [&TubePoint; 2],
    dir: Vec3,
    sides: u32,
    start: Option<Ring>,
    caps: [Cap; 2],
    scratch: &mut Scratch,
    mesh: &mut TriMesh,
) -> [Ring; 2] {
    let sides = sides.max(3);
    scratch.tables(sides);
    let around = &scratch.around[..];
    let t = if dir == Vec3::ZERO { Vec3::Y } else { dir };
    let new_rings = 2 - usize::from(start.is_some());
    mesh.positions.reserve(new_rings * sides as usize);
    mesh.normals.reserve(new_rings * sides as usize);
    mesh.indices.reserve(6 * sides as usize);
    let r0 = match start {
        Some(ring) => ring,
        None => new_ring(ends[0], t, None, around, mesh),
    };
    let r1 = new_ring(ends[1], t, Some(r0), around, mesh);
    wall(r0.first, r1.first, sides, &mut mesh.indices);
    cap(r0, caps[0], true, mesh);
    cap(r1, caps[1], false, mesh);
    [r0, r1]
}

/// Closes `ring`, facing back along the tube at its start (`start`) or on
/// along it at its end.
fn cap(ring: Ring, kind: Cap, start: bool, mesh: &mut TriMesh) {
    if ring.radius <= 0.0 || kind == Cap::Open {
        return;
    }
    let sides = ring.sides;
    // Triangles (centre, k, k+1) wind so that their front faces out of
    // the tube at this end.
    let tri = |c: u32, a: u32, b: u32, mesh: &mut TriMesh| {
        if start {
            mesh.triangle(c, b, a);
        } else {
            mesh.triangle(c, a, b);
        }
    };
    match kind {
        Cap::Flat => {
            let normal = if start { -ring.tangent } else { ring.tangent };
            let centre = mesh.vertex(ring.pos, normal);
            let rim = mesh.positions.len() as u32;
            for k in 0..sides {
                let p = mesh.positions[(ring.first + k) as usize];
                mesh.vertex(p, normal);
            }
            for k in 0..sides {
                tri(centre, rim + k, rim + (k + 1) % sides, mesh);
            }
        }
        Cap::Fan => {
            let f = ring.first;
            for k in 1..sides - 1 {
                tri(f, f + k, f + k + 1, mesh);
            }
        }
        Cap::Open => {}
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use std::collections::HashMap;

    pub(in crate::mesh) fn chain(points: &[Vec3], radius: f32) -> Chain {
        Chain {
            colour: 0,
            points: points
                .iter()
                .map(|&pos| TubePoint {
                    pos,
                    radius,
                    up: Vec3::Z,
                })
                .collect(),
        }
    }

    /// Every edge of the welded mesh is shared by exactly two triangles with
    /// opposite directions: closed and consistently oriented.
    pub(in crate::mesh) fn assert_watertight(m: &TriMesh) {
        let key = |v: Vec3| ((v * 1e4).round().as_ivec3()).to_array();
        let mut ids = HashMap::new();
        let weld: Vec<usize> = m
            .positions
            .iter()
            .map(|&p| {
                let n = ids.len();
                *ids.entry(key(p)).or_insert(n)
            })
            .collect();
        let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
        for t in m.indices.chunks_exact(3) {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let (a, b) = (weld[a as usize], weld[b as usize]);
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1, "edge {a}-{b} used {count} times one way");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
    }

    #[test]
    fn bent_tube_shares_rings_and_is_watertight() {
        let mut m = TriMesh::default();
        let c = chain(&[Vec3::ZERO, Vec3::Y, Vec3::new(1.0, 2.0, 0.0)], 0.1);
        tube(&c, 8, &mut m);
        // three shared rings + two caps (centre + rim copy)
        assert_eq!(m.vertex_count(), 3 * 8 + 2 * 9);
        assert_eq!(m.triangle_count(), 2 * 8 * 2 + 2 * 8);
        assert_watertight(&m);
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
            let face = (b - a).cross(c - a);
            if face.length() > 1e-9 {
                assert!(face.dot(m.normals[t[0] as usize]) > 0.0, "inward face");
            }
        }
    }

    #[test]
    fn a_reversal_splits_the_tube() {
        let mut m = TriMesh::default();
        let c = chain(&[Vec3::ZERO, Vec3::Y, Vec3::new(0.0, 0.5, 0.0)], 0.1);
        tube(&c, 6, &mut m);
        // two pieces of two rings each, each capped twice
        assert_eq!(m.vertex_count(), 2 * (2 * 6 + 2 * 7));
    }

    #[test]
    fn a_straight_run_is_one_segment() {
        let mut m = TriMesh::default();
        let pts: Vec<Vec3> = (0..5).map(|i| Vec3::new(0.0, i as f32, 0.0)).collect();
        tube(&chain(&pts, 0.1), 6, &mut m);
        // two rings + two caps, whatever the number of F
        assert_eq!(m.vertex_count(), 2 * 6 + 2 * 7);
        assert_watertight(&m);
    }

    #[test]
    fn a_segment_is_the_piece_of_one_segment() {
        let ends = [
            (Vec3::ZERO, Vec3::new(0.3, 1.0, -0.2)),
            (Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 3.0)),
            (Vec3::ZERO, Vec3::Z),
        ];
        let caps = [Cap::Flat, Cap::Fan, Cap::Open];
        for (a, b) in ends {
            let c = chain(&[a, b], 0.1);
            for (c0, c1) in caps.iter().flat_map(|&x| caps.iter().map(move |&y| (x, y))) {
                for shared in [false, true] {
                    let mut before = TriMesh::default();
                    let start = shared.then(|| {
                        let mut scratch = Scratch::default();
                        segment(
                            [&c.points[0], &c.points[0]],
                            Vec3::X,
                            6,
                            None,
                            [Cap::Open; 2],
                            &mut scratch,
                            &mut before,
                        )[1]
                    });
                    let mut by_piece = before.clone();
                    let mut by_segment = before;
                    let mut dirs = Vec::new();
                    directions(&c.points, &mut dirs);
                    let mut seen = Vec::new();
                    piece(
                        &Piece {
                            points: &c.points,
                            offset: 0,
                            sides: 6,
                            start,
                            caps: [c0, c1],
                        },
                        &dirs,
                        |_| false,
                        |_, ring| seen.push(ring),
                        &mut Scratch::default(),
                        &mut by_piece,
                    );
                    let rings = segment(
                        [&c.points[0], &c.points[1]],
                        dirs[0],
                        6,
                        start,
                        [c0, c1],
                        &mut Scratch::default(),
                        &mut by_segment,
                    );
                    assert_eq!(by_segment, by_piece, "{a} {b} {c0:?} {c1:?} {shared}");
                    assert_eq!(rings.to_vec(), seen);
                }
            }
        }
    }

    #[test]
    fn fan_caps_close_the_tube_without_new_vertices() {
        let mut m = TriMesh::default();
        let c = chain(&[Vec3::ZERO, Vec3::Y, Vec3::new(1.0, 2.0, 0.0)], 0.1);
        let mut scratch = Scratch::default();
        let mut dirs = Vec::new();
        directions(&c.points, &mut dirs);
        piece(
            &Piece {
                points: &c.points,
                offset: 0,
                sides: 5,
                start: None,
                caps: [Cap::Fan, Cap::Fan],
            },
            &dirs,
            |_| false,
            |_, _| {},
            &mut scratch,
            &mut m,
        );
        assert_eq!(m.vertex_count(), 3 * 5);
        assert_eq!(m.triangle_count(), 2 * 5 * 2 + 2 * 3);
        assert_watertight(&m);
    }
}
