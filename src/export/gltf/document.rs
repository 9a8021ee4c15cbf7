//! The glTF document of a [`Scene`]: each component becomes one glTF mesh
//! shared by all its placements (one node each, named `<symbol>#<n>`, with
//! its transform as a matrix; a component built of smaller ones becomes a
//! node hierarchy, `nodes.rs`); all strokes become one mesh with a
//! primitive per material in a node named `strokes`. Output: the JSON root
//! and the layout of its binary buffer (`bin.rs`), which `mod.rs` writes as
//! a GLB or a `.gltf` file.

use glam::{Mat3, Mat4, Vec3};
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use json::mesh::{Mode, Primitive, Semantic};
use json::validation::Checked::Valid;
use json::{Accessor, Index};
use rustc_hash::FxHashMap;

use super::ExportError;

mod bin;
mod instancing;
mod nodes;
use crate::mesh::{Component, Scene, TriMesh};
pub(super) use bin::Bin;
use bin::{is_identity, Piece};
use nodes::{placement, Placement};

/// The document and the layout of its binary buffer (padded to 4 bytes;
/// empty when the scene draws nothing, and then the document has no
/// buffer), whose bytes are encoded as they are written.
pub(super) fn build(scene: &Scene) -> Result<(json::Root, Bin<'_>), ExportError> {
    let mut b = Builder {
        scene,
        root: json::Root::default(),
        bin: Bin::default(),
        materials: vec![None; scene.materials.len()],
        textures: vec![None; scene.textures.len()],
        parts: FxHashMap::default(),
        meshes: FxHashMap::default(),
        ids: FxHashMap::default(),
        distinct: Vec::new(),
        nested_meshes: FxHashMap::default(),
        nested_geometry: FxHashMap::default(),
    };
    // Room for every node at once: a Pailou has ~3,600, and growing the
    // list by doubling copied it and touched fresh memory each time.
    let per_component: Vec<usize> = scene.components.iter().map(nodes::bound).collect();
    let placed: usize = scene
        .instances
        .iter()
        .map(|i| per_component[i.component])
        .sum();
    b.root.nodes.reserve(placed + 2);
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
    /// Texture coordinates, for a textured material's mesh.
    uvs: Option<Index<Accessor>>,
}

struct Builder<'s> {
    scene: &'s Scene,
    root: json::Root,
    /// The binary buffer's layout, encoded when the file is written.
    bin: Bin<'s>,
    /// glTF material per scene material, created on first use so that unused
    /// colours do not clutter the file.
    materials: Vec<Option<Index<json::Material>>>,
    /// glTF texture per scene texture, created on first use.
    textures: Vec<Option<Index<json::Texture>>>,
    /// Per (component id, part), its geometry (None: empty part), written
    /// once however many meshes and placements use it.
    parts: FxHashMap<(usize, usize), Option<Geometry>>,
    /// Per (component id, placement material when some part takes it), the
    /// shared mesh (None: the component draws nothing).
    meshes: FxHashMap<(usize, Option<usize>), Option<Index<json::Mesh>>>,
    /// Component ids (see [`Builder::id`]) by address, and each id's component.
    ids: FxHashMap<usize, usize>,
    distinct: Vec<&'s Component>,
    /// Per (nested component's address, placement colour when one of its
    /// own parts takes it), the mesh of its own parts.
    nested_meshes: FxHashMap<(usize, Option<usize>), Option<Index<json::Mesh>>>,
    /// Per own part of a nested component (by address), its geometry.
    nested_geometry: FxHashMap<usize, Option<Geometry>>,
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
        for (i, part) in component.parts().iter().enumerate() {
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
        let mut attributes: std::collections::BTreeMap<_, _> = [
            (Valid(Semantic::Positions), g.positions),
            (Valid(Semantic::Normals), g.normals),
        ]
        .into();
        let textured = self
            .scene
            .materials
            .get(material)
            .is_some_and(|m| m.texture.is_some());
        if let (Some(uvs), true) = (g.uvs, textured) {
            attributes.insert(Valid(Semantic::TexCoords(0)), uvs);
        }
        Ok(Primitive {
            attributes,
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
        // A texture is the surface's colour as photographed: not tinted.
        let (factor, texture) = match m.texture {
            Some(t) => ([1.0; 4], Some(self.texture(t)?)),
            None => ([r, g, b, 1.0], None),
        };
        let done = self.root.push(json::Material {
            name: Some(m.name.clone()),
            double_sided: false,
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor(factor),
                base_color_texture: texture.map(|index| json::texture::Info {
                    index,
                    tex_coord: 0,
                    extensions: None,
                    extras: Default::default(),
                }),
                metallic_factor: StrengthFactor(0.0),
                roughness_factor: StrengthFactor(0.8),
                ..Default::default()
            },
            ..Default::default()
        });
        self.materials[index] = Some(done);
        Ok(done)
    }

    /// The glTF texture of scene texture `index`: its image embedded in the
    /// buffer, sampled with the edges clamped (a face larger than the crop
    /// repeats the image's edge pixels, docs/shapes.md "Textures").
    fn texture(&mut self, index: usize) -> Result<Index<json::Texture>, ExportError> {
        if let Some(done) = self.textures[index] {
            return Ok(done);
        }
        let scene = self.scene;
        let t = &scene.textures[index];
        let start = self.bin.push(Piece::Slice(&t.bytes));
        let view = self.root.push(json::buffer::View {
            buffer: Index::new(0),
            byte_length: (self.bin.end() - start).into(),
            byte_offset: Some(start.into()),
            byte_stride: None,
            name: None,
            target: None,
            extensions: None,
            extras: Default::default(),
        });
        let image = self.root.push(json::Image {
            buffer_view: Some(view),
            mime_type: Some(json::image::MimeType(t.mime.to_string())),
            name: Some(t.name.clone()),
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        use json::texture::{MagFilter, MinFilter, WrappingMode};
        let sampler = self.root.push(json::texture::Sampler {
            mag_filter: Some(Valid(MagFilter::Linear)),
            min_filter: Some(Valid(MinFilter::LinearMipmapLinear)),
            wrap_s: Valid(WrappingMode::ClampToEdge),
            wrap_t: Valid(WrappingMode::ClampToEdge),
            name: None,
            extensions: None,
            extras: Default::default(),
        });
        let done = self.root.push(json::Texture {
            sampler: Some(sampler),
            source: image,
            name: None,
            extensions: None,
            extras: Default::default(),
        });
        self.textures[index] = Some(done);
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

        // The identity maps a finite position p to p + 0 bit for bit, and
        // a position that is not finite to one that is not finite either
        // (see `Bin::write_to`); its normals keep their lengths but for the
        // sign of zero. Most meshes are not baked: the matrix products
        // were a third of the document's time.
        let identity = is_identity(&transform);
        let bounds = if identity {
            bounds(&mesh.positions, |p| p + Vec3::ZERO)
        } else {
            bounds(&mesh.positions, |p| transform.transform_point3(p))
        };
        let Some((lo, hi)) = bounds else {
            return Err(ExportError::InvalidGeometry {
                name: name.into(),
                detail: "a vertex position is not finite".into(),
            });
        };
        let start = self.bin.push(Piece::Positions(mesh, transform));
        let view = self.view(start, Target::ArrayBuffer);
        let positions = self.accessor(view, n, ComponentType::F32, Type::Vec3, Some((lo, hi)));

        let linear = Mat3::from_mat4(transform);
        let normal_matrix = linear.inverse().transpose();
        let repair = if identity {
            mesh.normals.iter().any(|&v| collapses(v))
        } else {
            mesh.normals.iter().any(|&v| collapses(normal_matrix * v))
        };
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
        // Texture coordinates do not move with a transform.
        let uvs = (mesh.uvs.len() == n).then(|| {
            let mut bytes = Vec::with_capacity(n * 8);
            bin::f32_bytes(&mut bytes, mesh.uvs.iter().flat_map(|uv| [uv.x, uv.y]));
            let start = self.bin.push(Piece::Bytes(bytes));
            let view = self.view(start, Target::ArrayBuffer);
            self.accessor(view, n, ComponentType::F32, Type::Vec2, None)
        });
        Ok(Some(Geometry {
            positions,
            normals,
            indices,
            uvs,
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
    } else if let Some(i) = out_of_range(&mesh.indices, n) {
        format!("index {i} refers past the {n} vertices")
    } else {
        return Ok(());
    };
    Err(ExportError::InvalidGeometry {
        name: name.into(),
        detail,
    })
}

/// The smallest and largest of the mapped `positions`; `None` when one is
/// not finite.
fn bounds(positions: &[Vec3], map: impl Fn(Vec3) -> Vec3) -> Option<(Vec3, Vec3)> {
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for &p in positions {
        let p = map(p);
        if !p.is_finite() {
            return None;
        }
        (lo, hi) = (lo.min(p), hi.max(p));
    }
    Some((lo, hi))
}

/// True when `v.normalize_or_zero()` is zero: its length is zero or not
/// finite (glam normalises by `1 / length` when that is finite and
/// positive). Decided on the squared length, without the square root and
/// division the normalisation itself costs.
fn collapses(v: Vec3) -> bool {
    let l2 = v.length_squared();
    !(l2 > 0.0 && l2.is_finite())
}

/// The first index at or past `n`. The largest index is checked first, a
/// loop the compiler vectorises: the search an index at a time cost as
/// much as writing the indices out.
fn out_of_range(indices: &[u32], n: usize) -> Option<u32> {
    let max = indices.iter().copied().max()?;
    if (max as usize) < n {
        return None;
    }
    indices.iter().copied().find(|&i| i as usize >= n)
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
mod collapse_tests {
    use super::*;

    /// `collapses` agrees with glam's normalisation on zero, tiny, huge
    /// and non-finite vectors.
    #[test]
    fn collapses_exactly_when_the_normal_normalises_to_zero() {
        let tiny = f32::from_bits(1);
        for v in [
            Vec3::ZERO,
            Vec3::new(-0.0, 0.0, -0.0),
            Vec3::X,
            Vec3::splat(tiny),
            Vec3::new(1e-20, 0.0, 0.0),
            Vec3::new(1e19, 0.0, 0.0),
            Vec3::new(1e20, 1e20, 0.0),
            Vec3::splat(f32::MAX),
            Vec3::new(f32::INFINITY, 0.0, 0.0),
            Vec3::new(f32::NAN, 1.0, 0.0),
        ] {
            assert_eq!(collapses(v), v.normalize_or_zero() == Vec3::ZERO, "{v:?}");
        }
    }
}
