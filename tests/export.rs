//! Exporters end to end: hand-built scenes -> GLB, .gltf and OBJ+MTL bytes,
//! read back with the `gltf` and `tobj` crates (and, when installed, the
//! Khronos glTF-Validator through `scripts/gltf-validate.mjs`).

use std::collections::{BTreeMap, BTreeSet};
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{Mat4, Quat, Vec3};
use lsys::internals::export::gltf::{to_glb, to_gltf};
use lsys::internals::export::obj::write_obj;
use lsys::internals::mesh::scene::bounds_of;
use lsys::internals::mesh::{Component, Instance, Material, Part, Scene, Stroke, TriMesh};

fn unit_box() -> TriMesh {
    TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5))
}

fn material(name: &str, rgb: [f32; 3]) -> Material {
    Material {
        name: name.into(),
        rgb,
        texture: None,
    }
}

fn place(scene: &mut Scene, component: usize, transform: Mat4, material: usize) {
    let number = scene
        .instances
        .iter()
        .filter(|i| i.component == component)
        .count() as u32;
    scene.instances.push(Instance {
        component,
        transform,
        material,
        number,
    });
}

/// Materials 0 wood, 1 "red paint" (not OBJ-safe), 2 gold; component B (a
/// box in the placement colour) placed twice in wood, once rotated and
/// scaled non-uniformly; component L (a gold box with a lid in the
/// placement colour) placed in red, wood, red; strokes in wood and red.
fn sample() -> Scene {
    let mut s = Scene {
        materials: vec![
            material("wood", [0.6, 0.4, 0.2]),
            material("red paint", [0.8, 0.1, 0.1]),
            material("gold", [0.9, 0.8, 0.2]),
        ],
        ..Scene::default()
    };
    s.components.push(Component::new(
        "B",
        "test",
        vec![Part {
            mesh: unit_box(),
            material: None,
        }],
    ));
    s.components.push(Component::new(
        "L",
        "test",
        vec![
            Part {
                mesh: unit_box(),
                material: Some(2),
            },
            Part {
                mesh: TriMesh::cuboid(Vec3::new(-0.3, 0.5, -0.3), Vec3::new(0.3, 0.6, 0.3)),
                material: None,
            },
        ],
    ));
    place(
        &mut s,
        0,
        Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)),
        0,
    );
    let turned = Mat4::from_scale_rotation_translation(
        Vec3::new(2.0, 1.0, 0.5),
        Quat::from_rotation_y(0.6),
        Vec3::new(5.0, 0.0, 0.0),
    );
    place(&mut s, 0, turned, 0);
    for (x, m) in [(-3.0, 1), (-6.0, 0), (-9.0, 1)] {
        place(&mut s, 1, Mat4::from_translation(Vec3::new(x, 0.0, 0.0)), m);
    }
    s.strokes.push(Stroke {
        material: 0,
        mesh: TriMesh::cuboid(Vec3::ZERO, Vec3::new(0.1, 3.0, 0.1)),
    });
    s.strokes.push(Stroke {
        material: 1,
        mesh: TriMesh::cuboid(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, 3.1, 0.2)),
    });
    s
}

/// One component placed with a mirror and with a shear (rotate, then scale
/// non-uniformly), which glTF node matrices cannot hold.
fn skewed() -> Scene {
    let mut s = Scene {
        materials: vec![material("stone", [0.5, 0.5, 0.5])],
        ..Scene::default()
    };
    s.components.push(Component::new(
        "W",
        "test",
        vec![Part {
            mesh: unit_box(),
            material: None,
        }],
    ));
    place(&mut s, 0, Mat4::from_scale(Vec3::new(-1.0, 2.0, 1.0)), 0);
    let shear = Mat4::from_translation(Vec3::X * 4.0)
        * Mat4::from_scale(Vec3::new(3.0, 1.0, 1.0))
        * Mat4::from_rotation_z(0.5);
    place(&mut s, 0, shear, 0);
    s
}

/// A triangle in the xy plane whose normals are zero, NaN and too long.
fn broken_normals() -> TriMesh {
    let mut m = TriMesh::default();
    let a = m.vertex(Vec3::ZERO, Vec3::ZERO);
    let b = m.vertex(Vec3::X, Vec3::new(0.0, 0.0, 5.0));
    let c = m.vertex(Vec3::Y, Vec3::splat(f32::NAN));
    m.triangle(a, b, c);
    m
}

/// [`broken_normals`] as a stroke and as a component placed mirrored in z.
fn repaired() -> Scene {
    let mut s = Scene {
        materials: vec![material("leaf", [0.2, 0.6, 0.1])],
        ..Scene::default()
    };
    s.strokes.push(Stroke {
        material: 0,
        mesh: broken_normals(),
    });
    s.components.push(Component::new(
        "T",
        "test",
        vec![Part {
            mesh: broken_normals(),
            material: None,
        }],
    ));
    place(&mut s, 0, Mat4::from_scale(Vec3::new(1.0, 1.0, -1.0)), 0);
    s
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() <= 1e-5 * (1.0 + a.abs().max(b.abs()).max_element())
}

/// Per node name: (mesh index, world transform, triangles, bounds read from
/// the buffer) of a glTF document, after checking each primitive's data.
fn read_nodes(doc: &gltf::Gltf, bin: &[u8]) -> BTreeMap<String, (Option<usize>, Mat4, usize)> {
    let mut out = BTreeMap::new();
    for node in doc.nodes() {
        let matrix = Mat4::from_cols_array_2d(&node.transform().matrix());
        let mut triangles = 0;
        for prim in node.mesh().iter().flat_map(|m| m.primitives()) {
            let reader = prim.reader(|b| (b.index() == 0).then_some(bin));
            let positions: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
            let bb = prim.bounding_box();
            let (lo, hi) = bounds_of(positions.iter().copied()).unwrap();
            assert_eq!((Vec3::from(bb.min), Vec3::from(bb.max)), (lo, hi));
            for n in reader.read_normals().unwrap() {
                assert!((Vec3::from(n).length() - 1.0).abs() < 1e-6, "normal {n:?}");
            }
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            assert!(indices.iter().all(|&i| (i as usize) < positions.len()));
            assert!(prim.material().index().is_some());
            triangles += indices.len() / 3;
        }
        let name = node.name().unwrap().to_string();
        out.insert(name, (node.mesh().map(|m| m.index()), matrix, triangles));
    }
    out
}

#[test]
fn glb_shares_one_mesh_per_component_and_material() {
    let scene = sample();
    let glb = to_glb(&scene).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(glb.len() % 4, 0);
    let doc = gltf::Gltf::from_slice(&glb).unwrap();
    let bin = doc.blob.clone().unwrap();

    let json = doc.as_json();
    let generator = json.asset.generator.as_deref().unwrap();
    assert_eq!(generator, concat!("lsys ", env!("CARGO_PKG_VERSION")));
    assert_eq!(json.asset.version, "2.0");
    assert_eq!(doc.default_scene().unwrap().index(), 0);
    assert_eq!(doc.scenes().count(), 1);
    assert_eq!(doc.default_scene().unwrap().nodes().count(), 6);
    for view in doc.views() {
        assert_eq!(view.offset() % 4, 0);
        assert!(view.target().is_some());
        assert!(view.stride().is_none());
    }

    let nodes = read_nodes(&doc, &bin);
    let names: Vec<&str> = nodes.keys().map(String::as_str).collect();
    assert_eq!(names, ["B#0", "B#1", "L#0", "L#1", "L#2", "strokes"]);
    // B in wood twice: one mesh; L in red twice and wood once: two meshes.
    assert_eq!(nodes["B#0"].0, nodes["B#1"].0);
    assert_eq!(nodes["L#0"].0, nodes["L#2"].0);
    assert_ne!(nodes["L#0"].0, nodes["L#1"].0);
    assert_eq!(doc.meshes().count(), 4);
    for instance in &scene.instances {
        let symbol = &scene.components[instance.component].name;
        let name = format!("{symbol}#{}", instance.number);
        let (_, matrix, _) = nodes[&name];
        assert!(matrix.abs_diff_eq(instance.transform, 1e-6), "{name}");
    }
    // Strokes: one primitive per material, triangles as in the scene.
    let strokes = doc.meshes().nth(nodes["strokes"].0.unwrap()).unwrap();
    assert_eq!(strokes.primitives().count(), 2);
    assert_eq!(nodes["strokes"].2, 24);
    let total: usize = nodes.values().map(|n| n.2).sum();
    assert_eq!(total, scene.triangle_count());

    // Components stay in their own space: the box's accessor bounds.
    let b = doc.meshes().nth(nodes["B#0"].0.unwrap()).unwrap();
    let bb = b.primitives().next().unwrap().bounding_box();
    assert_eq!((bb.min, bb.max), ([-0.5; 3], [0.5; 3]));

    // Materials: the gold part keeps gold, the lid takes the placement's.
    let l0 = doc.meshes().nth(nodes["L#0"].0.unwrap()).unwrap();
    let material_names: Vec<&str> = l0
        .primitives()
        .map(|p| p.material().name().unwrap())
        .collect();
    assert_eq!(material_names, ["gold", "red paint"]);
    assert_eq!(doc.materials().count(), 3);
    for m in doc.materials() {
        let source = scene
            .materials
            .iter()
            .find(|s| Some(s.name.as_str()) == m.name())
            .unwrap();
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, a] = pbr.base_color_factor();
        let expected = source.rgb.map(srgb_to_linear);
        assert!(close(Vec3::new(r, g, b), Vec3::from(expected)));
        assert_eq!(a, 1.0);
        assert_eq!(pbr.metallic_factor(), 0.0);
        assert_eq!(pbr.roughness_factor(), 0.8);
        assert!(!m.double_sided());
    }
}

/// Decodes standard padded base64 (test helper; the exporter only encodes).
fn unbase64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let mut out = Vec::new();
    for quad in text.as_bytes().chunks(4) {
        let digits: Vec<u32> = quad
            .iter()
            .filter(|&&c| c != b'=')
            .map(|&c| u32::from(value(c)))
            .collect();
        let n = digits.iter().fold(0, |n, d| n << 6 | d) << (6 * (4 - digits.len()));
        out.extend(&n.to_be_bytes()[1..digits.len()]);
    }
    out
}

#[test]
fn gltf_json_embeds_the_same_buffer_as_the_glb() {
    let scene = sample();
    let text = to_gltf(&scene).unwrap();
    let doc = gltf::Gltf::from_slice(&text).unwrap();
    assert!(doc.blob.is_none());
    let buffer = doc.buffers().next().unwrap();
    let gltf::buffer::Source::Uri(uri) = buffer.source() else {
        panic!("the buffer should be a data URI")
    };
    let data = unbase64(
        uri.strip_prefix("data:application/octet-stream;base64,")
            .unwrap(),
    );
    assert_eq!(data.len(), buffer.length());
    let glb = gltf::Gltf::from_slice(&to_glb(&scene).unwrap()).unwrap();
    assert_eq!(Some(&data), glb.blob.as_ref());
    let nodes = read_nodes(&doc, &data);
    assert_eq!(nodes.len(), 6);
    assert!(nodes.contains_key("B#1"));
}

#[test]
fn glb_bakes_sheared_placements_and_keeps_faces_outward() {
    let scene = skewed();
    let doc = gltf::Gltf::from_slice(&to_glb(&scene).unwrap()).unwrap();
    let bin = doc.blob.clone().unwrap();
    let nodes = read_nodes(&doc, &bin);
    // The mirror is a valid node matrix; the shear is baked into its own mesh.
    assert!(nodes["W#0"]
        .1
        .abs_diff_eq(scene.instances[0].transform, 1e-6));
    assert_eq!(nodes["W#1"].1, Mat4::IDENTITY);
    assert_ne!(nodes["W#0"].0, nodes["W#1"].0);
    let baked = doc.meshes().nth(nodes["W#1"].0.unwrap()).unwrap();
    let prim = baked.primitives().next().unwrap();
    let reader = prim.reader(|_| Some(&bin[..]));
    let positions: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
    let normals: Vec<Vec3> = reader.read_normals().unwrap().map(Vec3::from).collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    let world = bounds_of(
        unit_box()
            .positions
            .iter()
            .map(|&p| scene.instances[1].transform.transform_point3(p)),
    );
    assert_eq!(bounds_of(positions.iter().copied()), world);
    assert_faces_agree_with_normals(&positions, &normals, &indices);
}

/// Every triangle's winding (counter-clockwise = front) agrees with its
/// vertex normals, and the normals point away from the mesh centre.
fn assert_faces_agree_with_normals(positions: &[Vec3], normals: &[Vec3], indices: &[u32]) {
    let centre = positions.iter().sum::<Vec3>() / positions.len() as f32;
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| positions[t[k] as usize]);
        let face = (b - a).cross(c - a).normalize();
        assert!(face.dot(normals[t[0] as usize]) > 0.5, "triangle {t:?}");
        assert!(face.dot((a + b + c) / 3.0 - centre) > 0.0, "triangle {t:?}");
    }
}

fn obj_of(scene: &Scene) -> (Vec<tobj::Model>, Vec<tobj::Material>) {
    let (mut obj, mut mtl) = (Vec::new(), Vec::new());
    write_obj(scene, "scene.mtl", &mut obj, &mut mtl).unwrap();
    let (models, materials) = tobj::load_obj_buf(
        &mut Cursor::new(&obj),
        &tobj::LoadOptions::default(),
        |path| {
            assert_eq!(path, Path::new("scene.mtl"));
            tobj::load_mtl_buf(&mut Cursor::new(&mtl))
        },
    )
    .unwrap();
    (models, materials.unwrap())
}

fn vec3s(flat: &[f32]) -> Vec<Vec3> {
    flat.chunks_exact(3).map(Vec3::from_slice).collect()
}

#[test]
fn obj_loads_back_in_world_space_with_materials() {
    let scene = sample();
    let (models, materials) = obj_of(&scene);
    let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["wood", "red_paint", "gold"]);
    assert_eq!(materials[1].diffuse, Some([0.8, 0.1, 0.1]));

    // tobj splits an object at each `usemtl`: strokes 2, B 1 each, L 2 each.
    let model_names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        model_names,
        ["strokes", "strokes", "B#0", "B#1", "L#0", "L#0", "L#1", "L#1", "L#2", "L#2"]
    );
    let used: Vec<&str> = models
        .iter()
        .map(|m| names[m.mesh.material_id.unwrap()])
        .collect();
    assert_eq!(
        used,
        [
            "wood",
            "red_paint",
            "wood",
            "wood",
            "gold",
            "red_paint",
            "gold",
            "wood",
            "gold",
            "red_paint"
        ]
    );
    let triangles: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    assert_eq!(triangles, scene.triangle_count());

    let all = models.iter().flat_map(|m| vec3s(&m.mesh.positions));
    let (lo, hi) = bounds_of(all).unwrap();
    let (want_lo, want_hi) = scene.bounds().unwrap();
    assert!(close(lo, want_lo) && close(hi, want_hi), "{lo} {hi}");
    for m in &models {
        for n in vec3s(&m.mesh.normals) {
            assert!((n.length() - 1.0).abs() < 1e-5, "{n}");
        }
    }
    // B#1 is the rotated, scaled box.
    let b1 = &models[3].mesh;
    let world = bounds_of(
        unit_box()
            .positions
            .iter()
            .map(|&p| scene.instances[1].transform.transform_point3(p)),
    );
    assert_eq!(bounds_of(vec3s(&b1.positions).into_iter()), world);
}

#[test]
fn obj_keeps_faces_outward_under_mirror_and_shear() {
    for model in obj_of(&skewed()).0 {
        let positions = vec3s(&model.mesh.positions);
        let normals = vec3s(&model.mesh.normals);
        // Positions and normals are numbered alike, so one index list serves.
        assert_eq!(model.mesh.indices, model.mesh.normal_indices);
        assert_faces_agree_with_normals(&positions, &normals, &model.mesh.indices);
    }
}

#[test]
fn broken_normals_are_repaired_from_faces() {
    let scene = repaired();
    let doc = gltf::Gltf::from_slice(&to_glb(&scene).unwrap()).unwrap();
    let bin = doc.blob.clone().unwrap();
    // Both meshes in their own space, where the face looks along +z.
    for prim in doc.meshes().flat_map(|m| m.primitives()) {
        let reader = prim.reader(|_| Some(&bin[..]));
        let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        assert_eq!(normals, [[0.0, 0.0, 1.0]; 3]);
    }
    // In world space the mirrored copy looks along -z.
    let (models, _) = obj_of(&scene);
    let normals: Vec<Vec<Vec3>> = models.iter().map(|m| vec3s(&m.mesh.normals)).collect();
    assert_eq!(normals, [[Vec3::Z; 3], [Vec3::NEG_Z; 3]]);
    // ... and its winding was turned to match.
    let p = vec3s(&models[1].mesh.positions);
    let t: Vec<usize> = models[1].mesh.indices.iter().map(|&i| i as usize).collect();
    let face = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    assert!(face.dot(Vec3::NEG_Z) > 0.0);
}

#[test]
fn empty_scene_exports_valid_empty_files() {
    let scene = Scene::default();
    let doc = gltf::Gltf::from_slice(&to_glb(&scene).unwrap()).unwrap();
    assert!(doc.blob.is_none());
    assert_eq!(doc.buffers().count(), 0);
    // One empty node: the `gltf` crate cannot read a scene without nodes.
    let nodes: Vec<_> = doc.default_scene().unwrap().nodes().collect();
    assert_eq!(nodes.len(), 1);
    assert!(nodes[0].mesh().is_none() && nodes[0].children().next().is_none());
    let doc = gltf::Gltf::from_slice(&to_gltf(&scene).unwrap()).unwrap();
    assert_eq!(doc.meshes().count(), 0);
    let (models, materials) = obj_of(&scene);
    // tobj always ends with the model being read, here an empty one.
    assert!(models.iter().all(|m| m.mesh.indices.is_empty()));
    assert!(materials.is_empty());
}

/// The scene `lsys build` makes of a grammar (a path relative to the
/// package, or `std:NAME`).
fn built(arg: &str) -> Scene {
    built_with(arg, &Default::default())
}

/// As [`built`], with `opts`.
fn built_with(arg: &str, opts: &lsys::internals::build::BuildOptions) -> Scene {
    let input = match arg.strip_prefix("std:") {
        Some(_) => lsys::internals::load::Input::from_arg(arg),
        None => lsys::internals::load::Input::Path(Path::new(env!("CARGO_MANIFEST_DIR")).join(arg)),
    };
    let Ok(comp) = lsys::internals::pipeline::compile(&input, &Default::default()) else {
        panic!("{arg} does not compile");
    };
    lsys::internals::build::build(&comp, opts)
        .unwrap_or_else(|e| panic!("{arg}: {}", lsys::internals::diag::render_plain(&e)))
        .scene
}

fn instanced() -> lsys::internals::build::BuildOptions {
    let mut opts = lsys::internals::build::BuildOptions::default();
    opts.mesh.instanced = true;
    opts
}

/// `--instanced`: one node per cylinder mesh with EXT_mesh_gpu_instancing,
/// 40 bytes of TRS per segment, the extension required.
#[test]
fn export_instanced_internodes_use_gpu_instancing() {
    let scene = built_with("examples/abop/fig1_24a.lsys", &instanced());
    let segments = scene.instances.len();
    assert!(segments > 100, "{segments}");
    assert!(scene.strokes.is_empty());
    let glb = to_glb(&scene).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    assert_eq!(doc["extensionsRequired"][0], "EXT_mesh_gpu_instancing");
    let nodes = doc["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 1, "{nodes:?}");
    let attributes = &nodes[0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    let count = |name: &str| {
        let a = attributes[name].as_u64().unwrap() as usize;
        doc["accessors"][a]["count"].as_u64().unwrap() as usize
    };
    assert_eq!(
        [count("TRANSLATION"), count("ROTATION"), count("SCALE")],
        [segments; 3]
    );
    // the cylinder once, then 40 bytes a segment
    let cylinder: usize = scene.components[0]
        .parts()
        .iter()
        .map(|p| p.mesh.positions.len() * 24 + p.mesh.indices.len() * 2)
        .sum();
    assert!(
        glb.len() - json_len < cylinder + 40 * segments + 64,
        "{}",
        glb.len()
    );
}

/// Where the npm package `gltf-validator` is installed, if it is.
fn validator_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("GLTF_VALIDATOR_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target/npm"));
    let package = dir.join("node_modules/gltf-validator/package.json");
    let node = Command::new("node").arg("--version").output();
    (package.is_file() && node.is_ok_and(|o| o.status.success())).then_some(dir)
}

#[test]
fn khronos_validator_accepts_the_exports() {
    let Some(dir) = validator_dir() else {
        assert_ne!(
            std::env::var("CI").as_deref(),
            Ok("true"),
            "CI must install node and gltf-validator (npm install --prefix target/npm gltf-validator)"
        );
        eprintln!(
            "skipped: gltf-validator not installed (npm install --prefix target/npm gltf-validator)"
        );
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (name, scene) in [
        ("sample", sample()),
        ("skewed", skewed()),
        ("repaired", repaired()),
        ("empty", Scene::default()),
        ("bush", built("examples/abop/fig1_24d.lsys")),
        ("leaves", built("examples/plants/bush_3d.lsys")),
        ("toukung", built("std:toukung_side")),
        ("pailou", built("std:pailou")),
        (
            "instanced",
            built_with("examples/plants/bush_3d.lsys", &instanced()),
        ),
        // Instanced cylinders beside placed components, nested ones too.
        ("pailou_instanced", built_with("std:pailou", &instanced())),
        // Shape grammars (docs/shapes.md): primitives, fitted components.
        ("veranda", built("examples/shapes/veranda.lsys")),
        ("verandas", built("examples/shapes/verandas.lsys")),
        ("hall", built("examples/shapes/hall.lsys")),
        ("wall", built("examples/shapes/wall.lsys")),
        ("pailou_board", built("examples/shapes/pailou_board.lsys")),
        ("snap", built("examples/shapes/snap.lsys")),
    ] {
        for (ext, bytes) in [("glb", to_glb(&scene)), ("gltf", to_gltf(&scene))] {
            let path = tmp.path().join(format!("{name}.{ext}"));
            std::fs::write(&path, bytes.unwrap()).unwrap();
            files.push(path);
        }
    }
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("node")
        .arg(manifest.join("scripts/gltf-validate.mjs"))
        .args(&files)
        .env("GLTF_VALIDATOR_DIR", &dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "validator failed:\n{stdout}");
    let reported: BTreeSet<&str> = stdout
        .lines()
        .filter(|l| l.ends_with(": 0 errors, 0 warnings"))
        .collect();
    assert_eq!(reported.len(), files.len(), "{stdout}");
}

/// Every triangle of `doc` in world space (node hierarchy composed), as
/// (centroid, area).
fn world_triangles(doc: &gltf::Gltf, bin: &[u8]) -> Vec<(Vec3, f32)> {
    fn walk(n: gltf::Node, parent: Mat4, bin: &[u8], out: &mut Vec<(Vec3, f32)>) {
        let m = parent * Mat4::from_cols_array_2d(&n.transform().matrix());
        for prim in n.mesh().iter().flat_map(|mesh| mesh.primitives()) {
            let reader = prim.reader(|b| (b.index() == 0).then_some(bin));
            let p: Vec<Vec3> = reader
                .read_positions()
                .unwrap()
                .map(|v| m.transform_point3(Vec3::from(v)))
                .collect();
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            for t in indices.chunks_exact(3) {
                let [a, b, c] = [0, 1, 2].map(|k| p[t[k] as usize]);
                out.push(((a + b + c) / 3.0, (b - a).cross(c - a).length() / 2.0));
            }
        }
        for c in n.children() {
            walk(c, m, bin, out);
        }
    }
    let mut out = Vec::new();
    for s in doc.scenes() {
        for n in s.nodes() {
            walk(n, Mat4::IDENTITY, bin, &mut out);
        }
    }
    out
}

/// Grammar components (the Toukungs) and clipped roofs are written as a
/// hierarchy of nodes placing their smaller components (each stored once):
/// composed, the file draws exactly the scene's triangles, and it is far
/// smaller than the same model with the Toukungs written as single meshes.
#[test]
fn glb_nests_grammar_components_and_draws_the_same_triangles() {
    let scene = built("std:pailou");
    assert!(
        scene
            .components
            .iter()
            .any(|c| c.name == "RC" && c.nested.is_some())
            && scene
                .components
                .iter()
                .any(|c| c.name == "TS" && c.nested.is_some()),
        "std:pailou places a clipped roof and side Toukungs"
    );
    let glb = to_glb(&scene).unwrap();
    let doc = gltf::Gltf::from_slice(&glb).unwrap();
    let bin = doc.blob.clone().unwrap();
    let mut file = world_triangles(&doc, &bin);
    let mut drawn = Vec::new();
    scene.for_each_triangle(|[a, b, c], _, _| {
        drawn.push(((a + b + c) / 3.0, (b - a).cross(c - a).length() / 2.0));
    });
    assert_eq!(file.len(), drawn.len());
    assert_eq!(file.len(), scene.triangle_count());
    let (lo, hi) = scene.bounds().unwrap();
    let tolerance = (hi - lo).max_element() * 1e-4;
    // Each axis of the centroids, and the areas, sorted, agree pairwise.
    for key in 0..4 {
        let pick = |t: &(Vec3, f32)| if key < 3 { t.0[key] } else { t.1 };
        file.sort_by(|a, b| pick(a).total_cmp(&pick(b)));
        drawn.sort_by(|a, b| pick(a).total_cmp(&pick(b)));
        let worst = file
            .iter()
            .zip(&drawn)
            .map(|(a, b)| (pick(a) - pick(b)).abs())
            .fold(0.0, f32::max);
        let limit = if key < 3 {
            tolerance
        } else {
            tolerance * tolerance * 1e4
        };
        assert!(worst < limit, "axis {key}: off by {worst}");
    }
    // Nested, the Toukungs' and tiles' meshes are stored once each.
    let mut flat = scene.clone();
    for c in &mut flat.components {
        c.nested = None;
    }
    let flat = to_glb(&flat).unwrap();
    assert!(
        glb.len() * 2 < flat.len(),
        "nested {} bytes, flat {}",
        glb.len(),
        flat.len()
    );
}
