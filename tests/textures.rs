//! Textures (docs/shapes.md, "Textures"): `texture i: "file"` headers and
//! `@Tex` projections -> a GLB with the image embedded, a textured
//! material and texture coordinates that place the crop on the faces
//! that face the projection; an OBJ with `vt` and `map_Kd`; and located
//! errors for images that are missing, outside the folder, not images,
//! given twice, or never declared.

mod common;

use std::path::Path;

const PNG: &[u8] = include_bytes!("../examples/painting/villa_front.png");

fn codes(d: &lsys::Diagnostics) -> Vec<String> {
    d.iter()
        .filter_map(|e| e.code().map(|c| c.to_string()))
        .collect()
}

fn folder(grammar: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("photo.png"), PNG).unwrap();
    std::fs::write(dir.path().join("g.lsys"), grammar).unwrap();
    dir
}

fn build(dir: &Path) -> Result<lsys::Scene, lsys::Diagnostics> {
    lsys::Grammar::from_path(dir.join("g.lsys"))?.build(1)
}

/// A 4 x 3 block whose front shows the crop (0.2, 0.2)..(0.8, 0.8) of the
/// photo, and a cylinder, which never takes a texture.
const WALL: &str = "texture 1: \"photo.png\"\nderivation length: 1\n\
                    Axiom: @Scope(4, 3, 1) @Tex(1, 0.2, 0.2, 0.8, 0.8) @Block @Cyl\n";

#[test]
fn a_projected_texture_is_in_the_glb_on_the_faces_toward_it() {
    let dir = folder(WALL);
    let glb = build(dir.path()).unwrap().to_glb().unwrap();
    let gltf = gltf::Gltf::from_slice(&glb).unwrap();
    assert_eq!(gltf.images().count(), 1);
    let image = gltf.images().next().unwrap();
    match image.source() {
        gltf::image::Source::View { view, mime_type } => {
            assert_eq!(mime_type, "image/png");
            assert_eq!(view.length(), PNG.len(), "the file's bytes, embedded");
        }
        gltf::image::Source::Uri { .. } => panic!("the image is embedded"),
    }
    let textured: Vec<_> = gltf
        .materials()
        .filter(|m| m.pbr_metallic_roughness().base_color_texture().is_some())
        .collect();
    assert_eq!(textured.len(), 1, "one textured material");
    assert_eq!(
        textured[0].pbr_metallic_roughness().base_color_factor(),
        [1.0; 4]
    );
    let sampler = gltf.textures().next().unwrap().sampler();
    assert_eq!(sampler.wrap_s(), gltf::texture::WrappingMode::ClampToEdge);

    // The textured primitive: the block's front (z = 1) only, both sides
    // of its two triangles, with the crop's corners at the face's corners.
    let blob = gltf.blob.as_deref().unwrap();
    let mut faces = 0;
    for mesh in gltf.meshes() {
        for p in mesh.primitives() {
            let reader = p.reader(|_| Some(blob));
            let uvs: Option<Vec<[f32; 2]>> =
                reader.read_tex_coords(0).map(|t| t.into_f32().collect());
            let textured = p
                .material()
                .pbr_metallic_roughness()
                .base_color_texture()
                .is_some();
            assert_eq!(
                uvs.is_some(),
                textured,
                "texture coordinates exactly where a texture is"
            );
            let Some(uvs) = uvs else { continue };
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            for (p, uv) in positions.iter().zip(&uvs) {
                assert_eq!(p[2], 1.0, "only the face toward the projection: {p:?}");
                // x 0..4 -> u 0.2..0.8; y 0..3 -> v 0.8..0.2 (glTF's v down).
                let u = 0.2 + p[0] / 4.0 * 0.6;
                let v = 1.0 - (0.2 + p[1] / 3.0 * 0.6);
                assert!(
                    (uv[0] - u).abs() < 1e-5 && (uv[1] - v).abs() < 1e-5,
                    "{p:?} -> {uv:?}"
                );
            }
            faces += positions.len();
        }
    }
    assert_eq!(faces, 8, "one face, both sides, four corners each");
}

#[test]
fn the_obj_names_the_image_and_carries_texture_coordinates() {
    let dir = folder(WALL);
    let scene = build(dir.path()).unwrap();
    scene.write_obj(dir.path().join("out.obj")).unwrap();
    let obj = std::fs::read_to_string(dir.path().join("out.obj")).unwrap();
    let mtl = std::fs::read_to_string(dir.path().join("out.mtl")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("vt ")).count(), 8);
    assert!(obj
        .lines()
        .any(|l| l.starts_with("f ") && l.matches('/').count() == 6 && !l.contains("//")));
    assert!(mtl.contains("map_Kd photo.png"), "{mtl}");
}

#[test]
fn off_switches_it_off_and_branches_keep_it() {
    // `@Tex(0)` before the second block: only the first is textured.
    let dir = folder(
        "texture 1: \"photo.png\"\nderivation length: 1\n\
         Axiom: @Scope(1, 1, 1) @Tex(1) [@Block] @Tex(0) @M(2, 0, 0) @Block\n",
    );
    let glb = build(dir.path()).unwrap().to_glb().unwrap();
    let gltf = gltf::Gltf::from_slice(&glb).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    let textured: usize = gltf
        .meshes()
        .flat_map(|m| m.primitives().collect::<Vec<_>>())
        .filter_map(|p| {
            p.reader(|_| Some(blob))
                .read_tex_coords(0)
                .map(|t| t.into_f32().count())
        })
        .sum();
    assert_eq!(textured, 8, "the first block's front only");
}

#[test]
fn a_wrong_texture_is_a_located_error() {
    // The grammar in a subfolder: `../photo.png` is outside its folder.
    let dir = folder("");
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    std::fs::write(sub.join("photo.png"), PNG).unwrap();
    std::fs::write(
        sub.join("g.lsys"),
        "texture 1: \"missing.png\"\ntexture 2: \"g.lsys\"\ntexture 3: \"photo.png\"\n\
         texture 3: \"photo.png\"\ntexture 4: \"../photo.png\"\nAxiom: F\n",
    )
    .unwrap();
    let e = build(&sub).unwrap_err();
    assert_eq!(
        codes(&e),
        [
            "lsys::resolve::bad_value",
            "lsys::resolve::bad_value",
            "lsys::resolve::duplicate_header",
            "lsys::resolve::bad_value",
        ],
        "{}",
        e.render_plain()
    );
    let text = e.render_plain();
    assert!(
        text.contains("cannot read") && text.contains("missing.png"),
        "{text}"
    );
    assert!(
        text.contains("g.lsys is neither a PNG nor a JPEG image"),
        "{text}"
    );
    assert!(text.contains("is outside"), "{text}");
    // A projection of a texture no header gives.
    let dir = folder("derivation length: 1\nAxiom: @Scope(1, 1, 1) @Tex(2) @Block\n");
    let e = build(dir.path()).unwrap_err();
    assert_eq!(
        codes(&e),
        ["lsys::turtle::no_texture"],
        "{}",
        e.render_plain()
    );
    // From memory there is no folder to read it from.
    let e =
        lsys::Grammar::from_str("mem.lsys", "texture 1: \"photo.png\"\nAxiom: F\n").unwrap_err();
    assert!(
        e.render_plain().contains("is not a file on disk"),
        "{}",
        e.render_plain()
    );
}

/// A grammar named without a folder (`lsys build g.lsys` in its folder)
/// finds its texture beside it.
#[test]
fn a_grammar_given_by_its_bare_name_finds_its_texture() {
    let dir = folder(WALL);
    common::lsys_ok(dir.path(), &["build", "g.lsys", "-o", "g.glb"]);
    let gltf = gltf::Gltf::open(dir.path().join("g.glb")).unwrap();
    assert_eq!(gltf.images().count(), 1);
}

/// The image is read again when it changes (the compiler keeps images
/// between compilations while their size and time stay the same).
#[test]
fn a_changed_image_is_read_again() {
    let dir = folder(WALL);
    let mime = |dir: &Path| {
        let glb = build(dir).unwrap().to_glb().unwrap();
        let gltf = gltf::Gltf::from_slice(&glb).unwrap();
        let image = gltf.images().next().unwrap();
        match image.source() {
            gltf::image::Source::View { mime_type, view } => (mime_type.to_string(), view.length()),
            gltf::image::Source::Uri { .. } => panic!("embedded"),
        }
    };
    assert_eq!(mime(dir.path()), ("image/png".to_string(), PNG.len()));
    // The same name, now a (tiny) JPEG.
    std::fs::write(dir.path().join("photo.png"), b"\xff\xd8\xff\xe0 a jpeg").unwrap();
    assert_eq!(mime(dir.path()), ("image/jpeg".to_string(), 11));
}
