//! Placements as glTF nodes: one placement of a component -> its node,
//! with the component's shared mesh, or, for a component built of smaller
//! ones (a Toukung, a tiled roof: [`Nested`]), a node hierarchy placing
//! each smaller mesh, stored once in the file; and which transforms a node
//! matrix can hold.

use glam::{Mat3, Mat4, Vec4};
use gltf_json as json;
use json::Index;

use super::{Builder, ExportError};
use crate::mesh::scene::Nested;
use crate::mesh::{Component, Instance};

/// At most how many nodes one placement of `component` adds (its own, and
/// for a nested component its frame, its strokes and each inner placement's).
pub(super) fn bound(component: &Component) -> usize {
    1 + component.nested.as_ref().map_or(0, |n| {
        2 + n
            .instances
            .iter()
            .map(|i| bound(&n.components[i.component]))
            .sum::<usize>()
    })
}

impl<'s> Builder<'s> {
    pub(super) fn instance(
        &mut self,
        instance: &Instance,
    ) -> Result<Index<json::Node>, ExportError> {
        let scene = self.scene;
        let component = &scene.components[instance.component];
        let name = node_name(&[&component.name], instance.number);
        self.placed(component, instance.transform, instance.material, name)
    }

    /// The node of one placement of `component`: its matrix and the shared
    /// mesh, or, for a component built of smaller ones, a child node per
    /// smaller placement (each smaller mesh stored once in the file).
    fn placed(
        &mut self,
        component: &'s Component,
        transform: Mat4,
        material: usize,
        name: String,
    ) -> Result<Index<json::Node>, ExportError> {
        let (mesh, matrix, children) = match placement(transform) {
            Placement::Matrix(matrix) => match &component.nested {
                Some(nested) => {
                    let children = self.nested(nested, material, &component.name, &name)?;
                    (None, matrix, Some(children))
                }
                None => (self.shared_mesh(component, material)?, matrix, None),
            },
            Placement::Bake => {
                let primitives = self.primitives(component, material, Some((&name, transform)))?;
                let mesh = (!primitives.is_empty()).then(|| self.mesh(name.clone(), primitives));
                (mesh, None, None)
            }
            Placement::Invalid => {
                return Err(ExportError::InvalidGeometry {
                    name,
                    detail: "the placement transform is not finite".into(),
                })
            }
        };
        Ok(self.root.push(json::Node {
            matrix,
            mesh,
            name: Some(name),
            children,
            ..Default::default()
        }))
    }

    /// The children of a placement of a nested component: one node for its
    /// normalisation, holding its own parts and a node per inner placement,
    /// named `<outer>/<inner symbol>#<n>`.
    fn nested(
        &mut self,
        nested: &'s Nested,
        material: usize,
        symbol: &str,
        outer: &str,
    ) -> Result<Vec<Index<json::Node>>, ExportError> {
        let mut children = Vec::new();
        if let Some(mesh) = self.nested_mesh(nested, material, symbol)? {
            children.push(self.root.push(json::Node {
                mesh: Some(mesh),
                name: Some([outer, "/strokes"].concat()),
                ..Default::default()
            }));
        }
        for inner in &nested.instances {
            let component = &nested.components[inner.component];
            let name = node_name(&[outer, "/", &component.name], inner.number);
            let colour = if nested.placement_colour {
                material
            } else {
                inner.material
            };
            children.push(self.placed(component, inner.transform, colour, name)?);
        }
        let Placement::Matrix(matrix) = placement(nested.frame) else {
            return Err(ExportError::InvalidGeometry {
                name: outer.into(),
                detail: "its normalisation is not a scale and a translation".into(),
            });
        };
        Ok(vec![self.root.push(json::Node {
            matrix,
            name: Some([outer, "/frame"].concat()),
            children: Some(children),
            ..Default::default()
        })])
    }

    /// The mesh of a nested component's own parts (its strokes, a roof's
    /// shell), shared by every placement with the same colour; `None` when
    /// it has none.
    fn nested_mesh(
        &mut self,
        nested: &'s Nested,
        material: usize,
        symbol: &str,
    ) -> Result<Option<Index<json::Mesh>>, ExportError> {
        let colour = nested
            .parts
            .iter()
            .any(|p| p.material.is_none())
            .then_some(material);
        let key = (nested as *const Nested as usize, colour);
        if let Some(&mesh) = self.nested_meshes.get(&key) {
            return Ok(mesh);
        }
        let mut primitives = Vec::new();
        for part in &nested.parts {
            // Laid out once, whatever colours its placements take.
            let address = &part.mesh as *const _ as usize;
            let geometry = match self.nested_geometry.get(&address) {
                Some(&done) => done,
                None => {
                    let g = self.geometry(symbol, &part.mesh, None)?;
                    self.nested_geometry.insert(address, g);
                    g
                }
            };
            if let Some(g) = geometry {
                primitives.push(self.primitive(g, part.material.unwrap_or(material))?);
            }
        }
        let mesh =
            (!primitives.is_empty()).then(|| self.mesh(format!("{symbol}/strokes"), primitives));
        self.nested_meshes.insert(key, mesh);
        Ok(mesh)
    }

    /// The canonical id of `component`: components loaded twice (the same
    /// model inside two grammar components) share one, so their meshes are
    /// written once.
    pub(super) fn id(&mut self, component: &'s Component) -> usize {
        let address = component as *const Component as usize;
        if let Some(&id) = self.ids.get(&address) {
            return id;
        }
        let same = |a: &Component, b: &Component| {
            a.name == b.name
                && a.origin == b.origin
                && a.parts().len() == b.parts().len()
                && a.parts()
                    .iter()
                    .zip(b.parts())
                    .all(|(p, q)| p.material == q.material && p.mesh == q.mesh)
        };
        let id = match self.distinct.iter().position(|&c| same(c, component)) {
            Some(id) => id,
            None => {
                self.distinct.push(component);
                self.distinct.len() - 1
            }
        };
        self.ids.insert(address, id);
        id
    }
}

/// `pieces` then `#number`: a placement's node name (`MAn#3`,
/// `TM#2/MAn#3`). Built by hand: `format!` was a third of the node tree's
/// time (thousands of nested names in a Pailou).
fn node_name(pieces: &[&str], number: u32) -> String {
    let mut digits = itoa::Buffer::new();
    let digits = digits.format(number);
    let mut name = String::with_capacity(pieces.iter().map(|p| p.len()).sum::<usize>() + 11);
    pieces.iter().for_each(|p| name.push_str(p));
    name.push('#');
    name.push_str(digits);
    name
}

pub(super) enum Placement {
    /// A node matrix (`None` for the identity, which glTF wants omitted).
    Matrix(Option<[f32; 16]>),
    /// Not expressible as translation * rotation * scale, which glTF
    /// requires of node matrices (shear, projection, zero scale).
    Bake,
    /// Not finite.
    Invalid,
}

/// How a placement transform goes into the file.
pub(super) fn placement(m: Mat4) -> Placement {
    if !m.is_finite() {
        return Placement::Invalid;
    }
    let linear = Mat3::from_mat4(m);
    let [a, b, c] = [linear.x_axis, linear.y_axis, linear.z_axis];
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    if m.row(3) != Vec4::W || la * lb * lc == 0.0 || linear.determinant() == 0.0 {
        return Placement::Bake;
    }
    // T * R * S has orthogonal columns; measure the worst cosine.
    let skew = (a.dot(b) / (la * lb))
        .abs()
        .max((b.dot(c) / (lb * lc)).abs())
        .max((a.dot(c) / (la * lc)).abs());
    if skew > 1e-4 {
        Placement::Bake
    } else if m == Mat4::IDENTITY {
        Placement::Matrix(None)
    } else if skew > 1e-6 {
        // Rounding drift from many turtle rotations: snap to the nearest TRS
        // so that validators decomposing the matrix agree with it.
        let (s, r, t) = m.to_scale_rotation_translation();
        let snapped = Mat4::from_scale_rotation_translation(s, r.normalize(), t);
        Placement::Matrix(Some(snapped.to_cols_array()))
    } else {
        // cos(90°) and the like leave 1e-17s where zeros are meant; zeros
        // are shorter in the JSON and exact.
        Placement::Matrix(Some(m.to_cols_array().map(|x| {
            if x.abs() < 1e-12 {
                0.0
            } else {
                x
            }
        })))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn export_node_names_are_formats() {
        for n in [0, 7, 10, 99, 100, 4_096, u32::MAX] {
            assert_eq!(node_name(&["MAn"], n), format!("MAn#{n}"));
            assert_eq!(node_name(&["TM#2", "/", "MAn"], n), format!("TM#2/MAn#{n}"));
        }
    }

    #[test]
    fn export_placement_keeps_trs_and_bakes_shear() {
        let trs = Mat4::from_scale_rotation_translation(
            Vec3::new(2.0, 0.5, 1.0),
            glam::Quat::from_rotation_y(0.7),
            Vec3::new(1.0, 2.0, 3.0),
        );
        assert!(matches!(placement(trs), Placement::Matrix(Some(m)) if m == trs.to_cols_array()));
        assert!(matches!(placement(Mat4::IDENTITY), Placement::Matrix(None)));
        let mirrored = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        assert!(matches!(placement(mirrored), Placement::Matrix(Some(_))));
        // rotate, then scale non-uniformly: a shear
        let shear = Mat4::from_scale(Vec3::new(3.0, 1.0, 1.0)) * Mat4::from_rotation_z(0.5);
        assert!(matches!(placement(shear), Placement::Bake));
        assert!(matches!(
            placement(Mat4::from_scale(Vec3::ZERO)),
            Placement::Bake
        ));
        assert!(matches!(placement(Mat4::NAN), Placement::Invalid));
        // A drifted rotation is snapped to an exact one.
        let mut drifted = trs;
        drifted.x_axis.y += 2e-5;
        let Placement::Matrix(Some(snapped)) = placement(drifted) else {
            panic!("drift is not shear")
        };
        let snapped = Mat4::from_cols_array(&snapped);
        assert_ne!(snapped, drifted);
        assert!(snapped.abs_diff_eq(drifted, 1e-4));
        assert!(
            snapped
                .x_axis
                .truncate()
                .dot(snapped.y_axis.truncate())
                .abs()
                < 1e-6
        );
    }
}
