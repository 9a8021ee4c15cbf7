//! Tubes: a turtle [`Chain`] -> a capped generalized cylinder. Consecutive
//! segments share one ring, oriented in the bisecting plane and carried
//! along the curve by parallel transport so that tubes do not twist.

use std::f32::consts::TAU;

use glam::Vec3;

use super::scene::TriMesh;
use crate::turtle::drawing::{Chain, TubePoint};

/// Turns sharper than this (cosine between segments) end one tube and
/// start the next: a ring in the bisecting plane would pinch.
const SPLIT_COS: f32 = -0.2;

/// Appends the tube for `chain` with `sides` facets around to `mesh`.
pub fn tube(chain: &Chain, sides: u32, mesh: &mut TriMesh) {
    let pts = &chain.points;
    let mut start = 0;
    for i in 1..pts.len().saturating_sub(1) {
        let d0 = (pts[i].pos - pts[i - 1].pos).normalize_or_zero();
        let d1 = (pts[i + 1].pos - pts[i].pos).normalize_or_zero();
        if d0.dot(d1) < SPLIT_COS {
            piece(&pts[start..=i], sides, mesh);
            start = i;
        }
    }
    piece(&pts[start..], sides, mesh);
}

fn any_perpendicular(t: Vec3) -> Vec3 {
    t.any_orthonormal_vector()
}

fn piece(pts: &[TubePoint], sides: u32, mesh: &mut TriMesh) {
    if pts.len() < 2 {
        return;
    }
    let n = pts.len();
    let dir = |i: usize| (pts[i + 1].pos - pts[i].pos).normalize_or_zero();
    let tangent = |i: usize| {
        let t = if i == 0 {
            dir(0)
        } else if i == n - 1 {
            dir(n - 2)
        } else {
            (dir(i - 1) + dir(i)).normalize_or_zero()
        };
        if t == Vec3::ZERO {
            Vec3::Y
        } else {
            t
        }
    };
    let sides = sides.max(3);
    let first_ring = mesh.positions.len() as u32;
    let mut a = Vec3::ZERO;
    for (i, p) in pts.iter().enumerate() {
        let t = tangent(i);
        // Start from the turtle's up vector, then transport the previous
        // ring's axis: project it into this ring's plane.
        let seed = if i == 0 { p.up } else { a };
        a = (seed - t * seed.dot(t)).normalize_or_zero();
        if a == Vec3::ZERO {
            a = any_perpendicular(t);
        }
        let b = t.cross(a);
        for k in 0..sides {
            let (s, c) = (TAU * k as f32 / sides as f32).sin_cos();
            let normal = a * c + b * s;
            mesh.vertex(p.pos + normal * p.radius, normal);
        }
    }
    for i in 0..n as u32 - 1 {
        let r0 = first_ring + i * sides;
        let r1 = r0 + sides;
        for k in 0..sides {
            let k1 = (k + 1) % sides;
            mesh.triangle(r0 + k, r0 + k1, r1 + k);
            mesh.triangle(r0 + k1, r1 + k1, r1 + k);
        }
    }
    // Flat caps, with their own vertices so that the rim shades sharply.
    for (end, ring) in [
        (0usize, first_ring),
        (n - 1, first_ring + (n as u32 - 1) * sides),
    ] {
        if pts[end].radius <= 0.0 {
            continue;
        }
        let normal = if end == 0 {
            -tangent(0)
        } else {
            tangent(n - 1)
        };
        let centre = mesh.vertex(pts[end].pos, normal);
        let rim = mesh.positions.len() as u32;
        for k in 0..sides {
            let p = mesh.positions[(ring + k) as usize];
            mesh.vertex(p, normal);
        }
        for k in 0..sides {
            let k1 = (k + 1) % sides;
            if end == 0 {
                mesh.triangle(centre, rim + k1, rim + k);
            } else {
                mesh.triangle(centre, rim + k, rim + k1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn chain(points: &[Vec3], radius: f32) -> Chain {
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
    fn assert_watertight(m: &TriMesh) {
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
}
