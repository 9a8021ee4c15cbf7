//! The tubes of a whole drawing: turtle [`Chain`]s -> tubes in the stroke
//! meshes, joined where they meet. A chain that starts at a point of an
//! earlier chain (a branch leaving its parent, or the parent going on after
//! a branch) with the same colour and width, and in a direction close to
//! the tube there, starts from the ring the earlier chain has at that point
//! instead of a ring and a cap of its own; an end that a later chain goes on
//! from is left open. How many facets a tube gets follows from its width
//! against the size of the whole drawing and `--detail` ([`Facets`]).

use std::f32::consts::PI;

use glam::Vec3;

use super::assemble::MeshOptions;
use super::ring_slots::{slots, Slots, NONE};
use super::scene::{bounds_of, TriMesh};
use super::tube::{directions, for_each_piece, piece, segment, Cap, Piece, Ring, Scratch};
use crate::turtle::drawing::{Chain, Origin};

/// A tube starts from an earlier tube's ring only when its first segment
/// leaves within about 45 degrees of that ring's axis: further round, the
/// ring (normal to the earlier tube) would flatten the new tube's base.
const SHARE_COS: f32 = 0.7;

/// Chord error, in pixels, allowed between a round tube and its facets.
const TOLERANCE_PX: f32 = 0.5;

/// Facets of each tube: the most (`--facets`, 8 by default) unless the
/// tube is so thin against the whole drawing that fewer facets look the
/// same. "Look the same" means: with the whole drawing shown across a
/// view of 512 (detail 0), 2048 (detail 1) or 8192 pixels (detail 2), the
/// facets stay within `TOLERANCE_PX` of the round tube.
#[derive(Clone, Copy, Debug)]
pub struct Facets {
    max: u32,
    min: u32,
    /// Pixels per unit of length; 0 when facets do not adapt.
    px_per_unit: f32,
}

impl Facets {
    pub fn new(opts: &MeshOptions, chains: &[Chain]) -> Facets {
        let max = opts.sides.max(3);
        let min = if opts.detail == 0 { 3 } else { 4 }.min(max);
        let mut px_per_unit = 0.0;
        if opts.adaptive {
            let points = chains.iter().flat_map(|c| c.points.iter().map(|p| p.pos));
            if let Some((lo, hi)) = bounds_of(points) {
                let extent = (hi - lo).max_element();
                let view = [512.0, 2048.0, 8192.0][usize::from(opts.detail.min(2))];
                if extent.is_finite() && extent > 0.0 {
                    px_per_unit = view / extent;
                }
            }
        }
        Facets {
            max,
            min,
            px_per_unit,
        }
    }

    /// The most facets a tube gets.
    pub fn max(&self) -> u32 {
        self.max
    }

    /// Facets for a tube of `radius`.
    pub fn sides(&self, radius: f32) -> u32 {
        if self.px_per_unit == 0.0 {
            return self.max;
        }
        let r = radius * self.px_per_unit;
        if r.is_nan() || r <= TOLERANCE_PX {
            return self.min;
        }
        // A chord of a circle of radius r over angle 2π/n lies
        // r·(1 − cos(π/n)) inside it.
        let n = (PI / (1.0 - TOLERANCE_PX / r).acos()).ceil();
        if n.is_finite() {
            (n as u32).clamp(self.min, self.max)
        } else {
            self.max
        }
    }
}

/// The first chain that starts at a slot.
#[derive(Clone, Copy)]
struct Start {
    chain: usize,
    dir: Vec3,
    sides: u32,
}

/// Drawings of this many chains work out their facets and room on a second
/// core while the slots are found.
const PARALLEL_FROM: usize = 1 << 16;

/// Each chain's facets, and per colour the most vertices and indices its
/// tubes can take.
struct Sizes {
    facets: Facets,
    sides: Vec<u32>,
    room: Vec<(u32, usize, usize)>,
}

impl Sizes {
    fn new(chains: &[Chain], opts: &MeshOptions) -> Sizes {
        let facets = Facets::new(opts, chains);
        let sides: Vec<u32> = chains.iter().map(|c| facets.sides(max_radius(c))).collect();
        let mut room: Vec<(u32, usize, usize)> = Vec::new();
        for (c, &n) in chains.iter().zip(&sides) {
            // A ring at every point and flat caps: the most a chain takes.
            let (n, k) = (n.max(3) as usize, c.points.len());
            let (v, i) = (k * n + 2 * (n + 1), k.saturating_sub(1) * 6 * n + 6 * n);
            match room.iter_mut().find(|r| r.0 == c.colour) {
                Some(r) => (r.1, r.2) = (r.1 + v, r.2 + i),
                None => room.push((c.colour, v, i)),
            }
        }
        Sizes {
            facets,
            sides,
            room,
        }
    }
}

/// Most vertices or indices reserved up front for one stroke mesh (16 M:
/// 192 MB of positions and normals).
const MAX_ROOM: usize = 1 << 24;

/// Builds the tubes of one drawing's chains, in order.
pub struct Tubes {
    facets: Facets,
    /// Each chain's facet count (by its widest point).
    sides: Vec<u32>,
    /// Per slot (a point where some chain starts), the first chain that
    /// starts there.
    starts: Vec<Start>,
    /// Per slot, the ring there once meshed.
    rings: Vec<Option<Ring>>,
    /// The slot of every point of every chain (`NONE` where no chain
    /// starts), chain after chain (see `ring_slots`): found in one pass
    /// before meshing; looked up one at a time, between meshing, each
    /// waited for its cache miss (five a point: most of the meshing time).
    point_slots: Vec<u32>,
    /// Where each chain's points begin in `point_slots`.
    first_point: Vec<usize>,
    /// Per colour, the most vertices and indices its tubes can take.
    room: Vec<(u32, usize, usize)>,
    /// Scratch: the directions of its segments.
    dirs: Vec<Vec3>,
    scratch: Scratch,
}

impl Tubes {
    /// The tubes of `chains`, whose `origins` the turtle may know.
    pub fn new(chains: &[Chain], origins: &[Option<Origin>], opts: &MeshOptions) -> Tubes {
        // Facets and room read the chains only, as the slots do: for a big
        // drawing they are worked out on the second core meanwhile (a third
        // of setting up W2's tubes).
        let (
            Sizes {
                facets,
                sides,
                room,
            },
            slots,
        ) = if chains.len() >= PARALLEL_FROM && crate::derive::threads() >= 2 {
            std::thread::scope(|scope| {
                let sizes = scope.spawn(|| Sizes::new(chains, opts));
                let slots = slots(chains, origins);
                match sizes.join() {
                    Ok(sizes) => (sizes, slots),
                    Err(panic) => std::panic::resume_unwind(panic),
                }
            })
        } else {
            (Sizes::new(chains, opts), slots(chains, origins))
        };
        let Slots {
            first_chain,
            point_slots,
            first_point,
        } = slots;
        let starts: Vec<Start> = first_chain
            .into_iter()
            .map(|i| {
                let (a, b) = (chains[i].points[0], chains[i].points[1]);
                Start {
                    chain: i,
                    dir: (b.pos - a.pos).normalize_or_zero(),
                    sides: sides[i],
                }
            })
            .collect();
        Tubes {
            room,
            facets,
            sides,
            rings: vec![None; starts.len()],
            starts,
            point_slots,
            first_point,
            dirs: Vec::new(),
            scratch: Scratch::default(),
        }
    }

    /// Makes room in `mesh`, the empty stroke mesh of `colour`, for all its
    /// tubes at once: growing it as it fills copied it (and faulted the
    /// copies in) about once more. Straight runs take fewer rings than
    /// this bound; past [`MAX_ROOM`] elements the mesh grows as needed.
    pub fn reserve(&self, colour: u32, mesh: &mut TriMesh) {
        if let Some(&(_, v, i)) = self.room.iter().find(|r| r.0 == colour) {
            mesh.positions.reserve(v.min(MAX_ROOM));
            mesh.normals.reserve(v.min(MAX_ROOM));
            mesh.indices.reserve(i.min(MAX_ROOM));
        }
    }

    /// Appends the tube of `chains[index]` to `mesh`, the stroke mesh of
    /// its colour.
    pub fn add(&mut self, index: usize, chain: &Chain, mesh: &mut TriMesh) {
        let pts = &chain.points;
        if pts.len() < 2 {
            return;
        }
        let sides = self.sides[index];
        // Thin tubes close their ends over the ring: their shading is
        // not seen.
        let closed = if sides < self.facets.max() {
            Cap::Fan
        } else {
            Cap::Flat
        };
        let Tubes {
            starts,
            rings,
            point_slots,
            first_point,
            dirs,
            scratch,
            ..
        } = self;
        let point_slots = &point_slots[first_point[index]..first_point[index + 1]];
        // One segment (most chains of a branching plant) needs no list of
        // directions and no pieces.
        let (dir0, last_dir) = match &pts[..] {
            [a, b] => {
                let dir = (b.pos - a.pos).normalize_or_zero();
                (dir, dir)
            }
            _ => {
                directions(pts, dirs);
                (dirs[0], dirs[dirs.len() - 1])
            }
        };
        let start = rings[point_slots[0] as usize]
            .filter(|r| r.sides == sides && r.tangent.dot(dir0) >= SHARE_COS);
        let end_slot = point_slots[pts.len() - 1];
        let goes_on = end_slot != NONE && {
            let s = &starts[end_slot as usize];
            s.chain > index && s.sides == sides && s.dir.dot(last_dir) >= SHARE_COS
        };
        // The caps of a piece that is the chain's first and/or last.
        let caps = |first: bool, last: bool| {
            [
                if first && start.is_some() {
                    Cap::Open
                } else {
                    closed
                },
                if last && goes_on { Cap::Open } else { closed },
            ]
        };
        // The ring at point `i` of the chain, for the chains that start there.
        let mut keep = |i: usize, ring: Ring| {
            let slot = point_slots[i];
            if slot != NONE {
                rings[slot as usize] = Some(ring);
            }
        };
        if let [a, b] = &pts[..] {
            let ends = segment([a, b], dir0, sides, start, caps(true, true), scratch, mesh);
            keep(0, ends[0]);
            keep(1, ends[1]);
            return;
        }
        let dirs = &dirs[..];
        for_each_piece(dirs, |range, first, last| {
            piece(
                &Piece {
                    points: &pts[range.clone()],
                    offset: range.start,
                    sides,
                    start: if first { start } else { None },
                    caps: caps(first, last),
                },
                &dirs[range.start..range.end - 1],
                |i| point_slots[i] != NONE,
                &mut keep,
                scratch,
                mesh,
            );
        });
    }
}

fn max_radius(c: &Chain) -> f32 {
    c.points.iter().map(|p| p.radius).fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::tube::tests::{assert_watertight, chain};

    fn mesh(chains: &[Chain], opts: &MeshOptions) -> TriMesh {
        let mut m = TriMesh::default();
        let mut tubes = Tubes::new(chains, &[], opts);
        for (i, c) in chains.iter().enumerate() {
            tubes.add(i, c, &mut m);
        }
        m
    }

    fn turned(degrees: f32) -> Vec3 {
        let a = degrees.to_radians();
        Vec3::new(a.sin(), 1.0 + a.cos(), 0.0)
    }

    #[test]
    fn a_branch_goes_on_from_its_parents_end_ring() {
        let chains = [
            chain(&[Vec3::ZERO, Vec3::Y], 0.1),
            chain(&[Vec3::Y, turned(25.0)], 0.1),
        ];
        let m = mesh(&chains, &MeshOptions::default());
        // parent: two rings and its start cap; branch: one ring and its
        // end cap. Before: 2 x (2 rings + 2 caps).
        assert_eq!(m.vertex_count(), 2 * 8 + 9 + 8 + 9);
        assert_watertight(&m);
    }

    #[test]
    fn a_second_branch_shares_the_ring_inside_its_parent() {
        // The first branch carries on the parent's chain (as the turtle
        // draws `F[+F][-F]`); the second starts at its middle point.
        let chains = [
            chain(&[Vec3::ZERO, Vec3::Y, turned(25.0)], 0.1),
            chain(&[Vec3::Y, turned(-25.0)], 0.1),
        ];
        let m = mesh(&chains, &MeshOptions::default());
        assert_eq!(m.vertex_count(), 3 * 8 + 2 * 9 + 8 + 9);
    }

    #[test]
    fn a_wide_turn_or_another_width_starts_a_tube_of_its_own() {
        for (second, radius) in [(turned(90.0), 0.1), (turned(25.0), 0.05)] {
            let chains = [
                chain(&[Vec3::ZERO, Vec3::Y], 0.1),
                chain(&[Vec3::Y, second], radius),
            ];
            let m = mesh(&chains, &MeshOptions::default());
            assert_eq!(m.vertex_count(), 2 * (2 * 8 + 2 * 9));
        }
    }

    #[test]
    fn thin_tubes_take_fewer_facets_unless_told_otherwise() {
        // 0.01 wide on a drawing 100 long: 0.2 pixels at detail 1.
        let chains = [chain(&[Vec3::ZERO, Vec3::Y * 100.0], 0.005)];
        let m = mesh(&chains, &MeshOptions::default());
        // 4 facets, fan caps over the rings
        assert_eq!(
            (m.vertex_count(), m.triangle_count()),
            (2 * 4, 2 * 4 + 2 * 2)
        );
        assert_watertight(&m);
        let fixed = MeshOptions {
            adaptive: false,
            ..MeshOptions::default()
        };
        let m = mesh(&chains, &fixed);
        assert_eq!(m.vertex_count(), 2 * 8 + 2 * 9);
        let f = |detail, radius| {
            let opts = MeshOptions {
                detail,
                ..MeshOptions::default()
            };
            Facets::new(&opts, &chains).sides(radius)
        };
        assert_eq!(f(0, 0.005), 3);
        // 2048 px over 100 units: radius 0.2 is 4.1 px, 7 facets keep
        // within half a pixel; 8192 px: 16.4 px, 13 capped at 8.
        assert_eq!(f(1, 0.2), 7);
        assert_eq!(f(2, 0.2), 8);
        assert_eq!(f(1, 5.0), 8);
    }
}
