//! The glTF document of a [`Scene`]: each component becomes one glTF mesh
//! shared by all its placements (one node each, named `<symbol>#<n>`, with
//! its transform as a matrix); all strokes become one mesh with a primitive
//! per material in a node named `strokes`. Output: the JSON root and its
//! binary buffer, which `mod.rs` wraps in a GLB or a `.gltf` file.

use std::collections::HashMap;

use glam::{Mat3, Mat4, Vec3, Vec4};
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use json::mesh::{Mode, Primitive, Semantic};
use json::validation::Checked::Valid;
use json::{Accessor, Index};

use super::ExportError;

mod bin;
mod instancing;
use crate::mesh::scene::Nested;
use crate::mesh::{Component, Instance, Scene, TriMesh};
pub(super) use bin::Bin;
use bin::Piece;

/// The document and the layout of its binary buffer (padded to 4 bytes;
/// empty when the scene draws nothing, and then the document has no
/// buffer), whose bytes are encoded as they are written.
pub(super) fn build(scene: &Scene) -> Result<(json::Root, Bin<'_>), ExportError> {
    let mut b = Builder {
        scene,
        root: json::Root::default(),
        bin: Bin::default(),
        materials: vec![None; scene.materials.len()],
        parts: HashMap::new(),
        meshes: HashMap::new(),
        ids: HashMap::new(),
        distinct: Vec::new(),
        nested_parts: HashMap::new(),
    };
    let mut nodes = Vec::new();
    nodes.extend(b.strokes()?);
    let mut each = scene.instances.iter().collect::<Vec<_>>();
    if scene.gpu_instancing {
        let (instanced, rest) = b.instanced(&scene.instances)?;
        if !instanced.is_empty() {
            let name = instancing::EXTENSION.to_string();
            b.root.extensions_used.push(name.clone());
            b.root.extensions_required.push(name);
        }
        nodes.extend(instanced);
        each = rest;
    }
    for instance in each {
        nodes.push(b.instance(instance)?);
    }
    let mut root = b.root;
    if nodes.is_empty() {
        // glTF forbids an empty `nodes` list and lets a scene omit it, but
        // readers built on gltf-json (the `gltf` crate, Bevy) require the
        // field; one empty node keeps an empty model loadable everywhere.
        nodes.push(root.push(json::Node {
            name: Some("empty".into()),
            ..Default::default()
        }));
    }
    let bin = b.bin;
    if !bin.is_empty() {
        root.push(json::Buffer {
            byte_length: bin.len().into(),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
    }
    root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: None,
        nodes,
    });
    root.scene = Some(Index::new(0));
    root.asset = json::Asset {
        generator: Some(format!("lsys {}", env!("CARGO_PKG_VERSION"))),
        ..Default::default()
    };
    Ok((root, bin))
}

/// The accessors of one triangle mesh written to the buffer.
#[derive(Clone, Copy)]
struct Geometry {
    positions: Index<Accessor>,
    normals: Index<Accessor>,
    indices: Index<Accessor>,
}

struct Builder<'s> {
    scene: &'s Scene,
    root: json::Root,
    /// The binary buffer's layout, encoded when the file is written.
    bin: Bin<'s>,
    /// glTF material per scene material, created on first use so that unused
    /// colours do not clutter the file.
    materials: Vec<Option<Index<json::Material>>>,
    /// Per (component id, part), its geometry (None: empty part), written
    /// once however many meshes and placements use it.
    parts: HashMap<(usize, usize), Option<Geometry>>,
    /// Per (component id, placement material when some part takes it), the
    /// shared mesh (None: the component draws nothing).
    meshes: HashMap<(usize, Option<usize>), Option<Index<json::Mesh>>>,
    /// Component ids (see [`Builder::id`]) by address, and each id's component.
    ids: HashMap<usize, usize>,
    distinct: Vec<&'s Component>,
    /// Per (nested component's address, part), its own parts' geometry.
    nested_parts: HashMap<(usize, usize), Option<Geometry>>,
}

impl<'s> Builder<'s> {
    fn strokes(&mut self) -> Result<Option<Index<json::Node>>, ExportError> {
        let scene = self.scene;
        let mut primitives = Vec::new();
        for stroke in &scene.strokes {
            if let Some(g) = self.geometry("the strokes", &stroke.mesh, None)? {
                primitives.push(self.primitive(g, stroke.material)?);
            }
        }
        if primitives.is_empty() {
            return Ok(None);
        }
        let mesh = self.mesh("strokes".into(), primitives);
        Ok(Some(self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some("strokes".into()),
            ..Default::default()
        })))
    }

    fn instance(&mut self, instance: &Instance) -> Result<Index<json::Node>, ExportError> {
        let scene = self.scene;
        let component = &scene.components[instance.component];
        let name = format!("{}#{}", component.name, instance.number);
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
                Some(nested) => (None, matrix, Some(self.nested(nested, material, &name)?)),
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
        outer: &str,
    ) -> Result<Vec<Index<json::Node>>, ExportError> {
        let mut children = Vec::new();
        let mut primitives = Vec::new();
        for (i, part) in nested.parts.iter().enumerate() {
            let key = (nested as *const Nested as usize, i);
            let geometry = match self.nested_parts.get(&key) {
                Some(&done) => done,
                None => {
                    let g = self.geometry(outer, &part.mesh, None)?;
                    self.nested_parts.insert(key, g);
                    g
                }
            };
            if let Some(g) = geometry {
                primitives.push(self.primitive(g, part.material.unwrap_or(material))?);
            }
        }
        if !primitives.is_empty() {
            let name = format!("{outer}/strokes");
            let mesh = self.mesh(name.clone(), primitives);
            children.push(self.root.push(json::Node {
                mesh: Some(mesh),
                name: Some(name),
                ..Default::default()
            }));
        }
        for inner in &nested.instances {
            let component = &nested.components[inner.component];
            let name = format!("{outer}/{}#{}", component.name, inner.number);
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
            name: Some(format!("{outer}/frame")),
            children: Some(children),
            ..Default::default()
        })])
    }

    /// The canonical id of `component`: components loaded twice (the same
    /// model inside two grammar components) share one, so their meshes are
    /// written once.
    fn id(&mut self, component: &'s Component) -> usize {
        let address = component as *const Component as usize;
        if let Some(&id) = self.ids.get(&address) {
            return id;
        }
        let same = |a: &Component, b: &Component| {
            a.name == b.name
                && a.origin == b.origin
                && a.parts.len() == b.parts.len()
                && a.parts
                    .iter()
                    .zip(&b.parts)
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

    /// The mesh every placement of the component with this material shares.
    fn shared_mesh(
        &mut self,
        component: &'s Component,
        material: usize,
    ) -> Result<Option<Index<json::Mesh>>, ExportError> {
        let scene = self.scene;
        let colour = component.uses_placement_colour().then_some(material);
        let key = (self.id(component), colour);
        if let Some(&mesh) = self.meshes.get(&key) {
            return Ok(mesh);
        }
        let primitives = self.primitives(component, material, None)?;
        let mesh = (!primitives.is_empty()).then(|| {
            let name = match colour {
                Some(m) => {
                    let colour = scene.materials.get(m).map_or("?", |m| m.name.as_str());
                    format!("{}/{colour}", component.name)
                }
                None => component.name.clone(),
            };
            self.mesh(name, primitives)
        });
        self.meshes.insert(key, mesh);
        Ok(mesh)
    }

    /// One primitive per non-empty part of the placed component: with the
    /// component's shared geometry, or, for a placement to bake (named, with
    /// its transform), with geometry of its own transformed here (glTF
    /// cannot hold its transform as a node matrix).
    fn primitives(
        &mut self,
        component: &'s Component,
        material: usize,
        baked: Option<(&str, Mat4)>,
    ) -> Result<Vec<Primitive>, ExportError> {
        let id = self.id(component);
        let mut primitives = Vec::new();
        for (i, part) in component.parts.iter().enumerate() {
            let geometry = match baked {
                Some((name, transform)) => self.geometry(name, &part.mesh, Some(transform))?,
                None => match self.parts.get(&(id, i)) {
                    Some(&done) => done,
                    None => {
                        let g = self.geometry(&component.name, &part.mesh, None)?;
                        self.parts.insert((id, i), g);
                        g
                    }
                },
            };
            if let Some(g) = geometry {
                primitives.push(self.primitive(g, part.material.unwrap_or(material))?);
            }
        }
        Ok(primitives)
    }

    fn mesh(&mut self, name: String, primitives: Vec<Primitive>) -> Index<json::Mesh> {
        self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name),
            primitives,
            weights: None,
        })
    }

    fn primitive(&mut self, g: Geometry, material: usize) -> Result<Primitive, ExportError> {
        Ok(Primitive {
            attributes: [
                (Valid(Semantic::Positions), g.positions),
                (Valid(Semantic::Normals), g.normals),
            ]
            .into(),
            extensions: None,
            extras: Default::default(),
            indices: Some(g.indices),
            material: Some(self.material(material)?),
            mode: Valid(Mode::Triangles),
            targets: None,
        })
    }

    fn material(&mut self, index: usize) -> Result<Index<json::Material>, ExportError> {
        let scene = self.scene;
        let Some(m) = scene.materials.get(index) else {
            return Err(ExportError::InvalidGeometry {
                name: format!("material {index}"),
                detail: format!("the scene has {} materials", scene.materials.len()),
            });
        };
        if let Some(done) = self.materials[index] {
            return Ok(done);
        }
        let [r, g, b] = m.rgb.map(srgb_to_linear);
        let done = self.root.push(json::Material {
            name: Some(m.name.clone()),
            double_sided: false,
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor([r, g, b, 1.0]),
                metallic_factor: StrengthFactor(0.0),
                roughness_factor: StrengthFactor(0.8),
                ..Default::default()
            },
            ..Default::default()
        });
        self.materials[index] = Some(done);
        Ok(done)
    }

    /// Lays out positions, unit normals and indices of `mesh`, transformed
    /// by `bake` if given, in the buffer (encoded when the file is
    /// written); `None` for a mesh without triangles (glTF forbids empty
    /// primitives).
    fn geometry(
        &mut self,
        name: &str,
        mesh: &'s TriMesh,
        bake: Option<Mat4>,
    ) -> Result<Option<Geometry>, ExportError> {
        check(name, mesh)?;
        if mesh.is_empty() {
            return Ok(None);
        }
        let transform = bake.unwrap_or(Mat4::IDENTITY);
        let n = mesh.positions.len();

        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for &p in &mesh.positions {
            let p = transform.transform_point3(p);
            if !p.is_finite() {
                return Err(ExportError::InvalidGeometry {
                    name: name.into(),
                    detail: "a vertex position is not finite".into(),
                });
            }
            (lo, hi) = (lo.min(p), hi.max(p));
        }
        let start = self.bin.push(Piece::Positions(mesh, transform));
        let view = self.view(start, Target::ArrayBuffer);
        let positions = self.accessor(view, n, ComponentType::F32, Type::Vec3, Some((lo, hi)));

        let linear = Mat3::from_mat4(transform);
        let normal_matrix = linear.inverse().transpose();
        let repair = mesh
            .normals
            .iter()
            .any(|&v| (normal_matrix * v).normalize_or_zero() == Vec3::ZERO);
        let start = self.bin.push(Piece::Normals(mesh, linear, repair));
        let view = self.view(start, Target::ArrayBuffer);
        let normals = self.accessor(view, n, ComponentType::F32, Type::Vec3, None);

        // A mirroring transform turns counter-clockwise triangles clockwise;
        // swap two corners to keep the front faces in front. (A node matrix
        // needs no such care: glTF viewers flip the winding themselves.)
        let flip = transform.determinant() < 0.0;
        // u16 when it fits: 65535 is the primitive restart value, never an index.
        let small = n <= usize::from(u16::MAX);
        let start = self.bin.push(Piece::Indices { mesh, flip, small });
        let view = self.view(start, Target::ElementArrayBuffer);
        let kind = if small {
            ComponentType::U16
        } else {
            ComponentType::U32
        };
        let indices = self.accessor(view, mesh.indices.len(), kind, Type::Scalar, None);
        Ok(Some(Geometry {
            positions,
            normals,
            indices,
        }))
    }

    /// A view of the bytes laid out since `start`. Each accessor has a view
    /// of its own, tightly packed, so no byteStride is needed.
    fn view(&mut self, start: usize, target: Target) -> Index<json::buffer::View> {
        self.root.push(json::buffer::View {
            buffer: Index::new(0),
            byte_length: (self.bin.end() - start).into(),
            byte_offset: Some(start.into()),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    fn accessor(
        &mut self,
        view: Index<json::buffer::View>,
        count: usize,
        component: ComponentType,
        kind: Type,
        bounds: Option<(Vec3, Vec3)>,
    ) -> Index<Accessor> {
        // POSITION must declare min and max (the exact stored values).
        let (min, max) = match bounds {
            Some((lo, hi)) => (
                Some(serde_json::json!(lo.to_array())),
                Some(serde_json::json!(hi.to_array())),
            ),
            None => (None, None),
        };
        self.root.push(Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: count.into(),
            component_type: Valid(GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(kind),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }
}

/// Rejects meshes the glTF file could not represent validly; the scene
/// builder should never produce them.
pub(crate) fn check(name: &str, mesh: &TriMesh) -> Result<(), ExportError> {
    let n = mesh.positions.len();
    let detail = if mesh.normals.len() != n {
        format!("{} normals for {n} vertices", mesh.normals.len())
    } else if mesh.indices.len() % 3 != 0 {
        format!("{} indices do not form triangles", mesh.indices.len())
    } else if let Some(i) = mesh.indices.iter().find(|&&i| i as usize >= n) {
        format!("index {i} refers past the {n} vertices")
    } else {
        return Ok(());
    };
    Err(ExportError::InvalidGeometry {
        name: name.into(),
        detail,
    })
}

enum Placement {
    /// A node matrix (`None` for the identity, which glTF wants omitted).
    Matrix(Option<[f32; 16]>),
    /// Not expressible as translation * rotation * scale, which glTF
    /// requires of node matrices (shear, projection, zero scale).
    Bake,
    /// Not finite.
    Invalid,
}

/// How a placement transform goes into the file.
fn placement(m: Mat4) -> Placement {
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

/// Unit normals of `mesh` after the vertices are mapped by `linear`, into
/// `out`. Normals map by the inverse transpose and are renormalised; one
/// that is zero, not finite, or collapses under the map is replaced by the
/// average normal of the faces around its vertex (or +Y if those are
/// degenerate too), since glTF requires unit length.
pub(crate) fn unit_normals(mesh: &TriMesh, linear: Mat3, out: &mut Vec<Vec3>) {
    let normal_matrix = linear.inverse().transpose();
    out.clear();
    out.extend(
        mesh.normals
            .iter()
            .map(|&n| (normal_matrix * n).normalize_or_zero()),
    );
    if !out.contains(&Vec3::ZERO) {
        return;
    }
    // Rare: only for broken input, so the extra pass costs nothing usually.
    let mirror = if linear.determinant() < 0.0 {
        -1.0
    } else {
        1.0
    };
    let mut sums = vec![Vec3::ZERO; out.len()];
    for t in mesh.indices.chunks_exact(3) {
        let [p, q, r] = [0, 1, 2].map(|k| linear * mesh.positions[t[k] as usize]);
        let face = (q - p).cross(r - p) * mirror;
        for &i in t {
            sums[i as usize] += face;
        }
    }
    for (n, sum) in out.iter_mut().zip(sums) {
        if *n == Vec3::ZERO {
            *n = sum.try_normalize().unwrap_or(Vec3::Y);
        }
    }
}

/// glTF colour factors are linear; lsys colours are sRGB.
fn srgb_to_linear(c: f32) -> f32 {
    // glTF requires factors in 0..=1; NaN would make the file invalid.
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
