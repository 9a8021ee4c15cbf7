//! Shapes: `@O` spheres, `@o` discs, `@c` circles and `{ . }` polygons ->
//! triangles. Thin surfaces (discs, circles, polygons) get both faces, so
//! that they show from either side in any viewer.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

use super::scene::TriMesh;
use crate::turtle::drawing::{Shape, ShapeKind};

pub fn shape(s: &Shape, sides: u32, mesh: &mut TriMesh) {
    let sides = sides.max(3);
    match s.kind {
        ShapeKind::Sphere => sphere(s.centre, s.radius, sides, mesh),
        ShapeKind::Disc => annulus(s.centre, s.normal, 0.0, s.radius, sides, mesh),
        ShapeKind::Circle => annulus(s.centre, s.normal, s.radius * 0.9, s.radius, sides, mesh),
    }
}

fn sphere(c: Vec3, r: f32, sides: u32, mesh: &mut TriMesh) {
    let rings = (sides / 2).max(2);
    let base = mesh.positions.len() as u32;
    for i in 0..=rings {
        let (st, ct) = (PI * i as f32 / rings as f32).sin_cos();
        for k in 0..=sides {
            let (sp, cp) = (TAU * k as f32 / sides as f32).sin_cos();
            let n = Vec3::new(st * cp, ct, -st * sp);
            mesh.vertex(c + n * r, n);
        }
    }
    let row = sides + 1;
    for i in 0..rings {
        for k in 0..sides {
            let a = base + i * row + k;
            let b = a + row;
            if i != 0 {
                mesh.triangle(a, b, a + 1);
            }
            if i != rings - 1 {
                mesh.triangle(a + 1, b, b + 1);
            }
        }
    }
}

/// A flat ring between `inner` and `outer` radii facing `normal` (a disc
/// when `inner` is 0), both faces.
fn annulus(c: Vec3, normal: Vec3, inner: f32, outer: f32, sides: u32, mesh: &mut TriMesh) {
    let n = normal.normalize_or(Vec3::Y);
    let a = n.any_orthonormal_vector();
    let b = n.cross(a);
    for face in [n, -n] {
        let base = mesh.positions.len() as u32;
        for k in 0..sides {
            let (s, co) = (TAU * k as f32 / sides as f32).sin_cos();
            let d = a * co + b * s;
            mesh.vertex(c + d * inner, face);
            mesh.vertex(c + d * outer, face);
        }
        for k in 0..sides {
            let (i0, o0) = (base + 2 * k, base + 2 * k + 1);
            let k1 = (k + 1) % sides;
            let (i1, o1) = (base + 2 * k1, base + 2 * k1 + 1);
            // a × b = n: increasing k runs counter-clockwise seen from +n.
            if face == n {
                mesh.triangle(i0, o0, o1);
                if inner > 0.0 {
                    mesh.triangle(i0, o1, i1);
                }
            } else {
                mesh.triangle(i0, o1, o0);
                if inner > 0.0 {
                    mesh.triangle(i0, i1, o1);
                }
            }
        }
    }
}

/// Triangulates a (possibly concave) planar outline, both faces. Returns
/// false when the outline is degenerate (collinear or self-overlapping).
pub fn polygon(points: &[Vec3], mesh: &mut TriMesh) -> bool {
    polygon_uv(points, None, mesh)
}

/// [`polygon`], with texture coordinates (one per point) when given.
pub fn polygon_uv(points: &[Vec3], uvs: Option<&[Vec2]>, mesh: &mut TriMesh) -> bool {
    // Newell's method: a robust normal for a non-convex outline.
    let mut n = Vec3::ZERO;
    for (i, p) in points.iter().enumerate() {
        let q = points[(i + 1) % points.len()];
        n += Vec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    let Some(n) = n.try_normalize() else {
        return false;
    };
    let a = n.any_orthonormal_vector();
    let b = n.cross(a);
    let flat: Vec<f64> = points
        .iter()
        .flat_map(|p| [p.dot(a) as f64, p.dot(b) as f64])
        .collect();
    let Ok(tris) = earcutr::earcut(&flat, &[], 2) else {
        return false;
    };
    if tris.is_empty() {
        return false;
    }
    for face in [n, -n] {
        let base = mesh.positions.len() as u32;
        for (k, &p) in points.iter().enumerate() {
            match uvs {
                Some(uv) => mesh.vertex_uv(p, face, uv[k]),
                None => mesh.vertex(p, face),
            };
        }
        for t in tris.chunks_exact(3) {
            let [i, j, k] = [t[0], t[1], t[2]].map(|x| base + x as u32);
            // earcut's winding follows the 2D projection (a, b), whose
            // counter-clockwise side is +n; check rather than assume.
            let (pi, pj, pk) = (points[t[0]], points[t[1]], points[t[2]]);
            let ccw = (pj - pi).cross(pk - pi).dot(face) > 0.0;
            if ccw {
                mesh.triangle(i, j, k);
            } else {
                mesh.triangle(i, k, j);
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn faces_agree_with_normals(m: &TriMesh) {
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
            let f = (b - a).cross(c - a);
            if f.length() > 1e-9 {
                assert!(f.dot(m.normals[t[0] as usize]) > 0.0);
            }
        }
    }

    #[test]
    fn concave_polygon_triangulates_both_faces() {
        // An L shape: 6 corners, 4 triangles per face.
        let pts = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ];
        let mut m = TriMesh::default();
        assert!(polygon(&pts, &mut m));
        assert_eq!(m.triangle_count(), 8);
        faces_agree_with_normals(&m);
        // area of one face = 3
        let area: f32 = m
            .indices
            .chunks_exact(3)
            .take(4)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
                (b - a).cross(c - a).length() / 2.0
            })
            .sum();
        assert!((area - 3.0).abs() < 1e-5);
    }

    #[test]
    fn collinear_polygon_is_rejected() {
        let pts = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        assert!(!polygon(&pts, &mut TriMesh::default()));
    }

    #[test]
    fn shapes_face_outward() {
        for kind in [ShapeKind::Sphere, ShapeKind::Disc, ShapeKind::Circle] {
            let mut m = TriMesh::default();
            let s = Shape {
                kind,
                centre: Vec3::ONE,
                normal: Vec3::X,
                radius: 0.5,
                colour: 0,
            };
            shape(&s, 8, &mut m);
            assert!(!m.is_empty());
            faces_agree_with_normals(&m);
            let (lo, hi) = m.bounds().unwrap();
            assert!((hi - lo).max_element() <= 1.0 + 1e-5);
        }
    }
}
