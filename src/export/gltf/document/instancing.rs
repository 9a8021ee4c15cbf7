//! `EXT_mesh_gpu_instancing`: the placements of a scene whose
//! [`Scene::gpu_instancing`](crate::mesh::Scene) is set -> one node per
//! shared mesh (component and placement colour) with the placements'
//! translations, rotations and scales as accessors (40 bytes each), instead
//! of a node of its own per placement. Placements that glTF cannot hold as
//! translation · rotation · scale are left to the caller to bake.

use std::collections::BTreeMap;

use glam::{Quat, Vec3};
use gltf_json as json;
use json::accessor::{ComponentType, Type};
use json::buffer::Target;
use json::Index;
use serde_json::{json as value, Map};

use super::bin::{f32_bytes, Piece};
use super::{placement, Builder, Placement};
use crate::export::gltf::ExportError;
use crate::mesh::Instance;

/// The extension's name, also listed in `extensionsUsed` and
/// `extensionsRequired` (a viewer without it would draw one copy only).
pub(super) const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// Translation, rotation, scale.
type Trs = (Vec3, Quat, Vec3);

impl Builder<'_> {
    /// One node per shared mesh for `instances`; returns the nodes and the
    /// instances written as nodes of their own (to bake, or nested).
    pub(super) fn instanced<'i>(
        &mut self,
        instances: &'i [Instance],
    ) -> Result<(Vec<Index<json::Node>>, Vec<&'i Instance>), ExportError> {
        // Per shared mesh (in the order the meshes were made), every TRS
        // in placement order.
        let mut groups: BTreeMap<u32, Vec<Trs>> = BTreeMap::new();
        let mut rest = Vec::new();
        let scene = self.scene;
        for instance in instances {
            let component = &scene.components[instance.component];
            match placement(instance.transform) {
                // A nested component keeps its hierarchy (each smaller mesh
                // once): it goes to the caller as a node of its own.
                Placement::Matrix(_) if component.nested.is_none() => {
                    let Some(mesh) = self.shared_mesh(component, instance.material)? else {
                        continue;
                    };
                    let (s, r, t) = instance.transform.to_scale_rotation_translation();
                    groups
                        .entry(mesh.value() as u32)
                        .or_default()
                        .push((t, r.normalize(), s));
                }
                _ => rest.push(instance),
            }
        }
        let mut nodes = Vec::new();
        for (mesh, trs) in groups {
            let count = trs.len();
            let accessor = |b: &mut Self, kind: Type, put: &dyn Fn(&mut Vec<u8>, &Trs)| {
                let mut bytes = Vec::with_capacity(count * 16);
                for x in &trs {
                    put(&mut bytes, x);
                }
                let start = b.bin.push(Piece::Bytes(bytes));
                let view = b.view(start, Target::ArrayBuffer);
                b.accessor(view, count, ComponentType::F32, kind, None)
            };
            let translation = accessor(self, Type::Vec3, &|b, x| f32_bytes(b, x.0.to_array()));
            let rotation = accessor(self, Type::Vec4, &|b, x| f32_bytes(b, x.1.to_array()));
            let scale = accessor(self, Type::Vec3, &|b, x| f32_bytes(b, x.2.to_array()));
            let mut others = Map::new();
            others.insert(
                EXTENSION.into(),
                value!({ "attributes": {
                    "TRANSLATION": translation.value(),
                    "ROTATION": rotation.value(),
                    "SCALE": scale.value(),
                }}),
            );
            let name = self.root.meshes[mesh as usize]
                .name
                .clone()
                .unwrap_or_default();
            nodes.push(self.root.push(json::Node {
                mesh: Some(Index::new(mesh)),
                name: Some(format!("{name} x{count}")),
                extensions: Some(json::extensions::scene::Node { others }),
                ..Default::default()
            }));
        }
        Ok((nodes, rest))
    }
}
