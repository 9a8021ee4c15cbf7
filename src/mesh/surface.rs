//! cpfg surfaces: the bicubic Bézier patches of a `.s` file (read by load)
//! -> a component. Each patch is evaluated on an (s+1) × (t+1) grid of
//! the view line's precision and drawn with both faces, as cpfg draws
//! surfaces. The component keeps the surface's own size and origin (it is
//! not normalised to the unit box): `~f(k)` draws it at the turtle, x
//! along the turtle's left, y along its heading, z along its up, times k.

use glam::Vec3;

use super::scene::{Component, Part, TriMesh};
use crate::load::{CpfgSurface, SurfacePatch};

/// The component of `surface`, whose patches were read. Its coordinates
/// are those of a placement (see `turtle::interp`'s `place`): the unit
/// box's x along L, y along H with the box's bottom at the turtle, −z
/// along U; so the surface's (x, y, z) is stored as (x, y − ½, −z).
pub fn surface_component(surface: &CpfgSurface, patches: &[SurfacePatch]) -> Component {
    let mut mesh = TriMesh::default();
    for p in patches {
        patch(p, surface.s, surface.t, &mut mesh);
    }
    Component::new(
        surface.name.clone(),
        format!("cpfg surface {}", surface.file),
        vec![Part {
            mesh,
            material: None,
        }],
    )
}

/// The Bernstein weights of a cubic at `u` and their derivatives.
fn bernstein(u: f64) -> ([f64; 4], [f64; 4]) {
    let v = 1.0 - u;
    (
        [v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u],
        [
            -3.0 * v * v,
            3.0 * v * v - 6.0 * u * v,
            6.0 * u * v - 3.0 * u * u,
            3.0 * u * u,
        ],
    )
}

/// Appends patch `p` evaluated on an (s+1) × (t+1) grid, both faces.
fn patch(p: &SurfacePatch, s: u32, t: u32, mesh: &mut TriMesh) {
    let (s, t) = (s.max(1), t.max(1));
    let mut grid = Vec::with_capacity(((s + 1) * (t + 1)) as usize);
    for i in 0..=s {
        let (bs, ds) = bernstein(f64::from(i) / f64::from(s));
        for j in 0..=t {
            let (bt, dt) = bernstein(f64::from(j) / f64::from(t));
            let mut pos = [0.0; 3];
            let mut tan_s = [0.0; 3];
            let mut tan_t = [0.0; 3];
            for a in 0..4 {
                for b in 0..4 {
                    for k in 0..3 {
                        let c = p.points[a][b][k];
                        pos[k] += bs[a] * bt[b] * c;
                        tan_s[k] += ds[a] * bt[b] * c;
                        tan_t[k] += bs[a] * dt[b] * c;
                    }
                }
            }
            let to_vec = |v: [f64; 3]| Vec3::new(v[0] as f32, v[1] as f32, -(v[2] as f32));
            let (pos, ts, tt) = (to_vec(pos), to_vec(tan_s), to_vec(tan_t));
            grid.push((pos + Vec3::new(0.0, -0.5, 0.0), ts.cross(tt)));
        }
    }
    // A degenerate corner (a collapsed edge) takes its neighbours' normal.
    let fallback = grid
        .iter()
        .map(|g| g.1)
        .fold(Vec3::ZERO, |a, n| a + n.normalize_or_zero())
        .normalize_or(Vec3::Z);
    let at = |i: u32, j: u32| (i * (t + 1) + j) as usize;
    for side in [1.0f32, -1.0] {
        let base = mesh.positions.len() as u32;
        for &(pos, n) in &grid {
            mesh.vertex(pos, n.normalize_or(fallback) * side);
        }
        for i in 0..s {
            for j in 0..t {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                    .map(|k| base + k as u32);
                if side > 0.0 {
                    mesh.triangle(a, b, c);
                    mesh.triangle(a, c, d);
                } else {
                    mesh.triangle(a, c, b);
                    mesh.triangle(a, d, c);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_square() -> SurfacePatch {
        let mut points = [[[0.0; 3]; 4]; 4];
        for (i, row) in points.iter_mut().enumerate() {
            for (j, p) in row.iter_mut().enumerate() {
                *p = [i as f64 / 3.0 - 0.5, j as f64 / 3.0, 0.0];
            }
        }
        SurfacePatch {
            name: "sq".into(),
            colours: [0, 0],
            points,
        }
    }

    #[test]
    fn a_patch_is_a_grid_with_both_faces() {
        let surface = CpfgSurface {
            name: "f".into(),
            file: "f.s".into(),
            s: 3,
            t: 2,
            patches: Ok(vec![flat_square()]),
        };
        let c = surface_component(&surface, surface.patches.as_ref().unwrap());
        assert_eq!(c.triangle_count(), 2 * 3 * 2 * 2);
        let (lo, hi) = c.parts()[0].mesh.bounds().unwrap();
        assert!((lo - Vec3::new(-0.5, -0.5, 0.0)).length() < 1e-6, "{lo}");
        assert!((hi - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-6, "{hi}");
        // A flat patch in z = 0: normals along ±z.
        assert!(c.parts()[0].mesh.normals.iter().all(|n| n.z.abs() > 0.999));
    }
}
