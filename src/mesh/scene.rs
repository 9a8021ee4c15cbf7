//! The scene: what the turtle builds and every exporter reads. Input: meshes,
//! materials and component placements added by the turtle; output: a
//! [`Scene`] with each distinct component mesh stored once, placements as
//! transforms, and all strokes (tubes, polygons, spheres) merged per material.

use std::collections::BTreeMap;

use glam::{Mat3, Mat4, Vec2, Vec3};

pub use super::component::{Component, Later, Nested};

/// An indexed triangle mesh with one normal per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Three indices per triangle, counter-clockwise seen from the front.
    pub indices: Vec<u32>,
    /// Texture coordinates, one per vertex, in a textured material's mesh
    /// (glTF's: (0, 0) the image's top left); empty in every other.
    pub uvs: Vec<Vec2>,
}

impl TriMesh {
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Adds a vertex and returns its index.
    pub fn vertex(&mut self, position: Vec3, normal: Vec3) -> u32 {
        let i = self.positions.len() as u32;
        self.positions.push(position);
        self.normals.push(normal);
        i
    }

    /// Adds a textured vertex and returns its index.
    pub fn vertex_uv(&mut self, position: Vec3, normal: Vec3, uv: Vec2) -> u32 {
        self.uvs.push(uv);
        self.vertex(position, normal)
    }

    pub fn triangle(&mut self, a: u32, b: u32, c: u32) {
        self.indices.extend_from_slice(&[a, b, c]);
    }

    /// Appends `other`, renumbering its indices.
    pub fn append(&mut self, other: &TriMesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.uvs.extend_from_slice(&other.uvs);
        self.indices.extend(other.indices.iter().map(|i| i + base));
    }

    /// Smallest box holding every vertex, or `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        bounds_of(self.positions.iter().copied())
    }

    /// An axis-aligned box from `min` to `max` with flat-shaded faces
    /// (24 vertices, 12 triangles).
    pub fn cuboid(min: Vec3, max: Vec3) -> TriMesh {
        let mut m = TriMesh::default();
        // (normal, two in-plane axes chosen so that u x v = normal)
        let faces = [
            (Vec3::X, Vec3::Y, Vec3::Z),
            (Vec3::NEG_X, Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::Z, Vec3::X),
            (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            (Vec3::Z, Vec3::X, Vec3::Y),
            (Vec3::NEG_Z, Vec3::Y, Vec3::X),
        ];
        let centre = (min + max) * 0.5;
        let half = (max - min) * 0.5;
        for (n, u, v) in faces {
            let corner = |su: f32, sv: f32| centre + (n + u * su + v * sv) * half;
            let a = m.vertex(corner(-1.0, -1.0), n);
            let b = m.vertex(corner(1.0, -1.0), n);
            let c = m.vertex(corner(1.0, 1.0), n);
            let d = m.vertex(corner(-1.0, 1.0), n);
            m.triangle(a, b, c);
            m.triangle(a, c, d);
        }
        m
    }
}

/// Smallest box around `points`.
pub fn bounds_of(points: impl Iterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    bounds_from(None, points)
}

/// Smallest box around `start` and `points`, grown a point at a time in
/// order (so that measuring meshes one by one gives the box, to the sign
/// of a zero, that measuring them appended would).
pub fn bounds_from(
    start: Option<(Vec3, Vec3)>,
    points: impl Iterator<Item = Vec3>,
) -> Option<(Vec3, Vec3)> {
    points.fold(start, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

/// A surface colour. `rgb` is sRGB, each channel in 0..=1.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub rgb: [f32; 3],
    /// A texture of [`Scene::textures`] over the colour (`@Tex`): exporters
    /// that carry images draw it, the others the colour.
    pub texture: Option<usize>,
}

/// One piece of a component with a single material.
#[derive(Clone, Debug)]
pub struct Part {
    pub mesh: TriMesh,
    /// The component's own material (from its `.mtl`), or `None` to take the
    /// turtle's colour at each placement.
    pub material: Option<usize>,
}

/// One placement of a component.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Index into [`Scene::components`].
    pub component: usize,
    /// Component space to world space.
    pub transform: Mat4,
    /// The turtle's colour at the placement, for parts without their own.
    pub material: usize,
    /// 0-based count of earlier placements of the same component, so that
    /// exporters can name nodes `<symbol>#<n>`.
    pub number: u32,
}

/// Strokes of one material, merged into one mesh in world space.
#[derive(Clone, Debug)]
pub struct Stroke {
    pub material: usize,
    pub mesh: TriMesh,
}

/// Everything one build produces.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub materials: Vec<Material>,
    /// The images textured materials name (`texture i:` headers that a
    /// `@Tex` used), in order of first use.
    pub textures: Vec<crate::resolve::ir::Texture>,
    pub components: Vec<Component>,
    pub instances: Vec<Instance>,
    /// At most one entry per material, in order of first use.
    pub strokes: Vec<Stroke>,
    /// Exporters that can (glTF) write all placements of one component
    /// mesh as one node with `EXT_mesh_gpu_instancing` instead of a node
    /// each (`lsys build --instanced`; see [`super::MeshOptions::instanced`]).
    pub gpu_instancing: bool,
}

impl Scene {
    /// Vertices as drawn: strokes plus every instance's copy of its component.
    pub fn vertex_count(&self) -> usize {
        self.strokes
            .iter()
            .map(|s| s.mesh.vertex_count())
            .sum::<usize>()
            + self
                .instances
                .iter()
                .map(|i| self.components[i.component].vertex_count())
                .sum::<usize>()
    }

    /// Triangles as drawn: strokes plus every instance's copy of its component.
    pub fn triangle_count(&self) -> usize {
        self.strokes
            .iter()
            .map(|s| s.mesh.triangle_count())
            .sum::<usize>()
            + self
                .instances
                .iter()
                .map(|i| self.components[i.component].triangle_count())
                .sum::<usize>()
    }

    /// Placements per component symbol, sorted by symbol.
    pub fn instance_counts(&self) -> BTreeMap<String, usize> {
        let mut counts = BTreeMap::new();
        for i in &self.instances {
            *counts
                .entry(self.components[i.component].name.clone())
                .or_insert(0) += 1;
        }
        counts
    }

    /// World-space bounds of everything drawn, or `None` for an empty scene.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut out: Option<(Vec3, Vec3)> = None;
        let mut grow = |b: Option<(Vec3, Vec3)>| {
            if let Some((lo, hi)) = b {
                out = Some(match out {
                    None => (lo, hi),
                    Some((a, b)) => (a.min(lo), b.max(hi)),
                });
            }
        };
        for s in &self.strokes {
            grow(s.mesh.bounds());
        }
        for i in &self.instances {
            for p in self.components[i.component].parts() {
                grow(bounds_of(
                    p.mesh
                        .positions
                        .iter()
                        .map(|&v| i.transform.transform_point3(v)),
                ));
            }
        }
        out
    }

    /// A deterministic text summary (snapshot tests, the REPL's `:stats`):
    /// materials, strokes, components, instance counts, totals and bounds
    /// to three decimals.
    pub fn summary(&self) -> String {
        use std::fmt::Write;
        let mut out = String::new();
        for (i, m) in self.materials.iter().enumerate() {
            let [r, g, b] = m.rgb.map(|c| (c * 255.0).round() as u8);
            let _ = writeln!(out, "material {i} {} #{r:02x}{g:02x}{b:02x}", m.name);
        }
        for s in &self.strokes {
            let _ = writeln!(
                out,
                "strokes material {}: {} vertices, {} triangles",
                s.material,
                s.mesh.vertex_count(),
                s.mesh.triangle_count()
            );
        }
        for c in &self.components {
            let _ = writeln!(
                out,
                "component {} ({}): parts {}, {} triangles",
                c.name,
                c.origin,
                c.parts().len(),
                c.triangle_count()
            );
        }
        for (name, n) in self.instance_counts() {
            let _ = writeln!(out, "instances {name}: {n}");
        }
        let _ = writeln!(
            out,
            "total: {} vertices, {} triangles",
            self.vertex_count(),
            self.triangle_count()
        );
        match self.bounds() {
            Some((lo, hi)) => {
                let f = |v: Vec3| {
                    let c = |x: f32| {
                        let s = format!("{x:.3}");
                        if s == "-0.000" {
                            "0.000".to_string()
                        } else {
                            s
                        }
                    };
                    format!("({},{},{})", c(v.x), c(v.y), c(v.z))
                };
                let _ = writeln!(out, "bounds: {} .. {}", f(lo), f(hi));
            }
            None => out.push_str("bounds: empty\n"),
        }
        out
    }

    /// Calls `f(a, b, c, normals, material)` for every world-space triangle
    /// drawn, strokes first, then instances in placement order.
    pub fn for_each_triangle(&self, mut f: impl FnMut([Vec3; 3], [Vec3; 3], usize)) {
        for s in &self.strokes {
            emit(&s.mesh, Mat4::IDENTITY, s.material, &mut f);
        }
        for i in &self.instances {
            for p in self.components[i.component].parts() {
                emit(
                    &p.mesh,
                    i.transform,
                    p.material.unwrap_or(i.material),
                    &mut f,
                );
            }
        }
    }
}

fn emit(
    mesh: &TriMesh,
    transform: Mat4,
    material: usize,
    f: &mut impl FnMut([Vec3; 3], [Vec3; 3], usize),
) {
    // Normals transform by the inverse transpose; a zero scale never reaches
    // here (the turtle skips such placements), but guard anyway.
    let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
    let p = |i: u32| transform.transform_point3(mesh.positions[i as usize]);
    let n = |i: u32| (normal_matrix * mesh.normals[i as usize]).normalize_or_zero();
    for t in mesh.indices.chunks_exact(3) {
        f(
            [p(t[0]), p(t[1]), p(t[2])],
            [n(t[0]), n(t[1]), n(t[2])],
            material,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_faces_wind_outward() {
        let m = TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5));
        assert_eq!((m.vertex_count(), m.triangle_count()), (24, 12));
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
            let face_normal = (b - a).cross(c - a).normalize();
            assert!(face_normal.dot(m.normals[t[0] as usize]) > 0.99);
            // outward: the normal points away from the centre
            assert!(face_normal.dot((a + b + c) / 3.0) > 0.0);
        }
    }

    #[test]
    fn scene_counts_and_bounds_include_instances() {
        let mut s = Scene::default();
        s.materials.push(Material {
            name: "m".into(),
            rgb: [1.0, 0.0, 0.0],
            texture: None,
        });
        s.components.push(Component::new(
            "B",
            "test",
            vec![Part {
                mesh: TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5)),
                material: None,
            }],
        ));
        for x in [0.0, 10.0] {
            s.instances.push(Instance {
                component: 0,
                transform: Mat4::from_translation(Vec3::new(x, 0.0, 0.0)),
                material: 0,
                number: x as u32 / 10,
            });
        }
        assert_eq!(s.triangle_count(), 24);
        assert_eq!(s.instance_counts()["B"], 2);
        let (lo, hi) = s.bounds().unwrap();
        assert_eq!(lo, Vec3::new(-0.5, -0.5, -0.5));
        assert_eq!(hi, Vec3::new(10.5, 0.5, 0.5));
    }
}
