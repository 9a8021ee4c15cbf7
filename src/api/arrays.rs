//! A built model as plain arrays for numeric code (NumPy, trimesh, a
//! renderer): the drawn triangles as one indexed mesh in world space, with
//! a colour per vertex, and each component placement as a matrix. Input:
//! a [`Scene`]; output: [`Arrays`] and [`Placement`]s.

use glam::{Mat3, Mat4};

use super::Scene;
use crate::mesh::scene::TriMesh;

/// The model's triangles in world space, strokes first, then each instance's
/// parts in placement order (the order of the GLB's nodes). Flat `xyz`
/// triples, so that they are handed to NumPy without copying.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Arrays {
    /// `3 × vertices` coordinates.
    pub positions: Vec<f32>,
    /// `3 × vertices` unit normals.
    pub normals: Vec<f32>,
    /// `3 × triangles` vertex indices, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// `3 × vertices` linear RGB in 0..1, the material's colour.
    pub colors: Vec<f32>,
}

/// One component placement: which component, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The component's name, as the grammar places it (`MCa` for `~MCa`).
    pub component: String,
    /// The placement's transform, column-major (as glTF and glam store it).
    pub matrix: [f32; 16],
}

impl Scene {
    /// The drawn triangles as one indexed mesh ([`Arrays`]); component
    /// instances are expanded, so this is what a picture shows.
    pub fn arrays(&self) -> Arrays {
        let s = &self.built.scene;
        let mut out = Arrays::default();
        let rgb = |m: usize| s.materials.get(m).map_or([0.8; 3], |m| m.rgb);
        for st in &s.strokes {
            append(&mut out, &st.mesh, Mat4::IDENTITY, rgb(st.material));
        }
        for i in &s.instances {
            for p in s.components[i.component].parts() {
                let m = p.material.unwrap_or(i.material);
                append(&mut out, &p.mesh, i.transform, rgb(m));
            }
        }
        out
    }

    /// Every component placement, in placement order.
    pub fn placements(&self) -> Vec<Placement> {
        let s = &self.built.scene;
        s.instances
            .iter()
            .map(|i| Placement {
                component: s.components[i.component].name.clone(),
                matrix: i.transform.to_cols_array(),
            })
            .collect()
    }
}

fn append(out: &mut Arrays, mesh: &TriMesh, transform: Mat4, rgb: [f32; 3]) {
    let base = (out.positions.len() / 3) as u32;
    // Normals transform by the inverse transpose (non-uniform scales).
    let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        out.positions
            .extend_from_slice(&transform.transform_point3(*p).to_array());
        out.normals
            .extend_from_slice(&(normal_matrix * *n).normalize_or_zero().to_array());
        out.colors.extend_from_slice(&rgb);
    }
    out.indices.extend(mesh.indices.iter().map(|i| i + base));
}
