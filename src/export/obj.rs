//! Wavefront OBJ export: a [`Scene`] -> an `.obj` file with all geometry in
//! world space (one object per placement, named `<symbol>#<n>`, and one
//! object `strokes`) plus the `.mtl` file with its materials. OBJ has no
//! instancing, so each placement's copy of its component is written out.

use std::collections::HashSet;
use std::io::{self, BufWriter, Write};

use glam::{Mat3, Mat4, Vec3};

use super::gltf::{check, unit_normals};
use crate::mesh::{Scene, TriMesh};

/// Writes the scene as OBJ to `obj` and its materials to `mtl`;
/// `mtl_file_name` is how the OBJ refers to the MTL file (its `mtllib`), so
/// normally the bare file name when both lie in one directory.
pub fn write_obj(
    scene: &Scene,
    mtl_file_name: &str,
    obj: &mut dyn Write,
    mtl: &mut dyn Write,
) -> io::Result<()> {
    write_mtl_file(scene, mtl)?;
    write_obj_only(scene, mtl_file_name, obj)
}

/// Writes the scene's `.mtl` file (what [`write_obj`] writes to `mtl`).
pub fn write_mtl_file(scene: &Scene, mtl: &mut dyn Write) -> io::Result<()> {
    write_mtl(scene, &material_names(scene), mtl)
}

/// Writes the `.obj` file alone (what [`write_obj`] writes to `obj`),
/// streaming: memory stays at one mesh's normals whatever the model's size.
pub fn write_obj_only(scene: &Scene, mtl_file_name: &str, obj: &mut dyn Write) -> io::Result<()> {
    let names = material_names(scene);
    let mut out = BufWriter::with_capacity(1 << 16, obj);
    writeln!(out, "# lsys {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(out, "mtllib {mtl_file_name}")?;
    let mut w = MeshWriter {
        out: &mut out,
        next: 1,
        next_uv: 1,
        normals: Vec::new(),
    };
    if scene.strokes.iter().any(|s| !s.mesh.is_empty()) {
        w.group("strokes")?;
        for stroke in &scene.strokes {
            if !stroke.mesh.is_empty() {
                w.usemtl(&names, stroke.material)?;
                w.mesh("strokes", &stroke.mesh, Mat4::IDENTITY)?;
            }
        }
    }
    for instance in &scene.instances {
        let component = &scene.components[instance.component];
        let name = format!("{}#{}", component.name, instance.number);
        // Written even when the component draws nothing, so that every
        // placement can be found by name.
        w.group(&name)?;
        for part in component.parts() {
            if !part.mesh.is_empty() {
                w.usemtl(&names, part.material.unwrap_or(instance.material))?;
                w.mesh(&name, &part.mesh, instance.transform)?;
            }
        }
    }
    out.flush()
}

struct MeshWriter<'w> {
    out: &'w mut dyn Write,
    /// The 1-based number of the next vertex; positions and normals are
    /// written in pairs, so one number serves both.
    next: u64,
    /// The 1-based number of the next texture coordinate (textured meshes
    /// only have them).
    next_uv: u64,
    /// Scratch space for one mesh's normals, reused across meshes.
    normals: Vec<Vec3>,
}

impl MeshWriter<'_> {
    /// Starts an object. `o` and `g` both, since importers differ in which
    /// one they split objects on.
    fn group(&mut self, name: &str) -> io::Result<()> {
        writeln!(self.out, "o {name}\ng {name}")
    }

    fn usemtl(&mut self, names: &[String], material: usize) -> io::Result<()> {
        let Some(name) = names.get(material) else {
            return Err(invalid(format!(
                "material {material} does not exist; the scene has {}",
                names.len()
            )));
        };
        writeln!(self.out, "usemtl {name}")
    }

    /// Writes `mesh` mapped by `transform` to world space.
    fn mesh(&mut self, name: &str, mesh: &TriMesh, transform: Mat4) -> io::Result<()> {
        check(name, mesh).map_err(|e| invalid(e.to_string()))?;
        if !mesh
            .positions
            .iter()
            .all(|&p| transform.transform_point3(p).is_finite())
        {
            return Err(invalid(format!("{name}: a vertex position is not finite")));
        }
        // `{}` prints the shortest decimal that reads back as the same f32.
        lines(self.out, &mesh.positions, 1, |p, out| {
            let p = transform.transform_point3(p[0]);
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)
        })?;
        let linear = Mat3::from_mat4(transform);
        unit_normals(mesh, linear, &mut self.normals);
        lines(self.out, &self.normals, 1, |n, out| {
            writeln!(out, "vn {} {} {}", n[0].x, n[0].y, n[0].z)
        })?;
        // A mirroring transform turns the triangles clockwise; swap two
        // corners to keep their front faces in front.
        let flip = linear.determinant() < 0.0;
        let next = self.next;
        if mesh.uvs.len() == mesh.positions.len() && !mesh.uvs.is_empty() {
            // A textured mesh: OBJ's v runs up the image, glTF's down.
            lines(self.out, &mesh.uvs, 1, |t, out| {
                writeln!(out, "vt {} {}", t[0].x, 1.0 - t[0].y)
            })?;
            let uv = self.next_uv;
            lines(self.out, &mesh.indices, 3, |t, out| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| next + u64::from(i));
                let [ta, tb, tc] = [t[0], t[1], t[2]].map(|i| uv + u64::from(i));
                let ((b, tb), (c, tc)) = if flip {
                    ((c, tc), (b, tb))
                } else {
                    ((b, tb), (c, tc))
                };
                writeln!(out, "f {a}/{ta}/{a} {b}/{tb}/{b} {c}/{tc}/{c}")
            })?;
            self.next_uv += mesh.uvs.len() as u64;
        } else {
            lines(self.out, &mesh.indices, 3, |t, out| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| next + u64::from(i));
                let (b, c) = if flip { (c, b) } else { (b, c) };
                writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}")
            })?;
        }
        self.next += mesh.positions.len() as u64;
        Ok(())
    }
}

/// Lines formatted a chunk at a time.
const CHUNK: usize = 1 << 14;

/// Writes one line per `per` items (a vertex, or a triangle's three
/// indices) with `line`. Formatting numbers is most of an OBJ's cost (the
/// 10 M-module forest: 11 s): past two chunks, every other chunk is
/// formatted on a second thread, and the two are written in order.
fn lines<T: Sync>(
    out: &mut dyn Write,
    items: &[T],
    per: usize,
    line: impl Fn(&[T], &mut Vec<u8>) -> io::Result<()> + Sync,
) -> io::Result<()> {
    let format = |chunk: &[T], buf: &mut Vec<u8>| -> io::Result<()> {
        buf.clear();
        chunk.chunks_exact(per).try_for_each(|item| line(item, buf))
    };
    let chunk = CHUNK * per;
    let (mut mine, mut theirs) = (Vec::new(), Vec::new());
    if items.len() < 2 * chunk || crate::derive::threads() < 2 {
        for chunk in items.chunks(chunk) {
            format(chunk, &mut mine)?;
            out.write_all(&mine)?;
        }
        return Ok(());
    }
    for pair in items.chunks(2 * chunk) {
        let (first, second) = pair.split_at(pair.len().min(chunk));
        // A scoped thread, not `rayon::join`: rayon's workers spin after
        // each join and took the core this thread writes on (W2's OBJ
        // 0.79 -> 0.99 s).
        std::thread::scope(|scope| {
            let other = scope.spawn(|| format(second, &mut theirs));
            let done = format(first, &mut mine);
            other
                .join()
                .unwrap_or_else(|_| Err(io::Error::other("formatting the OBJ failed")))
                .and(done)
        })?;
        out.write_all(&mine)?;
        out.write_all(&theirs)?;
    }
    Ok(())
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// OBJ-safe, unique material names: `usemtl` and `newmtl` take the rest of
/// the line, which many readers split at whitespace, and `#` starts a
/// comment in some of them.
fn material_names(scene: &Scene) -> Vec<String> {
    let mut taken = HashSet::new();
    let mut names = Vec::with_capacity(scene.materials.len());
    for (i, m) in scene.materials.iter().enumerate() {
        let mut name: String = m
            .name
            .chars()
            .map(|c| {
                if c.is_whitespace() || c.is_control() || c == '#' {
                    '_'
                } else {
                    c
                }
            })
            .collect();
        if name.is_empty() {
            name = format!("material_{i}");
        }
        // Two names that differ only in unsafe characters (or the same
        // name with two colours) must stay two materials.
        while !taken.insert(name.clone()) {
            name = format!("{name}_{i}");
        }
        names.push(name);
    }
    names
}

fn write_mtl(scene: &Scene, names: &[String], mtl: &mut dyn Write) -> io::Result<()> {
    let mut out = BufWriter::new(mtl);
    writeln!(out, "# lsys {}", env!("CARGO_PKG_VERSION"))?;
    for (m, name) in scene.materials.iter().zip(names) {
        // In range and never NaN, which readers would reject.
        let [r, g, b] = m
            .rgb
            .map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
        // Ka is black: Blender reads the average of Ka as metallic.
        writeln!(
            out,
            "\nnewmtl {name}\nKa 0 0 0\nKd {r} {g} {b}\nKs 0 0 0\nd 1\nillum 1"
        )?;
        // The image by the name the grammar gives it: OBJ readers look for
        // it beside the .mtl (copy it there; the GLB carries it inside).
        if let Some(t) = m.texture.and_then(|t| scene.textures.get(t)) {
            writeln!(out, "map_Kd {}", t.name)?;
        }
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Material;

    #[test]
    fn export_obj_material_names_are_safe_and_unique() {
        let mut scene = Scene::default();
        for name in ["dark red", "dark_red", "", "a#b", "dark red"] {
            scene.materials.push(Material {
                name: name.into(),
                rgb: [0.5; 3],
                texture: None,
            });
        }
        assert_eq!(
            material_names(&scene),
            ["dark_red", "dark_red_1", "material_2", "a_b", "dark_red_4"]
        );
    }

    /// Chunked and threaded or not, the lines are those of one vertex,
    /// normal and triangle at a time; a position that is not finite is an
    /// error before anything of the mesh is written.
    #[test]
    fn lines_in_chunks_are_the_lines_one_at_a_time() {
        let n = 2 * CHUNK + 7;
        let mesh = TriMesh {
            positions: (0..n)
                .map(|i| Vec3::new(i as f32 * 0.1, -0.0, 1e-7))
                .collect(),
            normals: vec![Vec3::Y; n],
            indices: (0..3 * n as u32).map(|i| i % n as u32).collect(),
            uvs: Vec::new(),
        };
        let mut out = Vec::new();
        let mut w = MeshWriter {
            out: &mut out,
            next: 5,
            next_uv: 1,
            normals: Vec::new(),
        };
        w.mesh("m", &mesh, Mat4::IDENTITY).unwrap();
        let mut expected = String::new();
        for p in &mesh.positions {
            // The identity turns -0 into 0, as before.
            let p = Mat4::IDENTITY.transform_point3(*p);
            expected += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        expected += &"vn 0 1 0\n".repeat(n);
        for t in mesh.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| 5 + i);
            expected += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
        }
        assert!(String::from_utf8(out).unwrap() == expected);

        let mut bad = mesh.clone();
        bad.positions[CHUNK + 3].x = f32::NAN;
        let mut out = Vec::new();
        let mut w = MeshWriter {
            out: &mut out,
            next: 1,
            next_uv: 1,
            normals: Vec::new(),
        };
        let e = w.mesh("m", &bad, Mat4::IDENTITY).unwrap_err();
        assert!(
            e.to_string().contains("a vertex position is not finite"),
            "{e}"
        );
        assert!(out.is_empty());
    }
}
