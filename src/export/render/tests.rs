//! Unit tests of the rasteriser: framing, depth, shading, bands and PNG output.

use glam::{Mat4, Quat};

use super::*;
use crate::mesh::{Component, Instance, Material, Part, Stroke, TriMesh};

const RED: [f32; 3] = [0.9, 0.1, 0.1];
const GREEN: [f32; 3] = [0.1, 0.8, 0.1];
const BLUE: [f32; 3] = [0.1, 0.2, 0.9];

fn material(scene: &mut Scene, rgb: [f32; 3]) -> usize {
    scene.materials.push(Material {
        name: format!("m{}", scene.materials.len()),
        rgb,
        texture: None,
    });
    scene.materials.len() - 1
}

fn stroke(scene: &mut Scene, mesh: TriMesh, rgb: [f32; 3]) {
    let material = material(scene, rgb);
    scene.strokes.push(Stroke { material, mesh });
}

/// One unit-cube component placed once with `transform`.
fn cube_scene(rgb: [f32; 3], transform: Mat4) -> Scene {
    let mut scene = Scene::default();
    let material = material(&mut scene, rgb);
    scene.components.push(Component::new(
        "C",
        "test",
        vec![Part {
            mesh: TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5)),
            material: None,
        }],
    ));
    scene.instances.push(Instance {
        component: 0,
        transform,
        material,
        number: 0,
    });
    scene
}

/// An open tube from `a` to `b` with smooth normals, `sides` facets.
fn tube(a: Vec3, b: Vec3, radius: f32, sides: u32) -> TriMesh {
    let axis = (b - a).normalize();
    let u = axis.any_orthonormal_vector();
    let v = axis.cross(u);
    let mut m = TriMesh::default();
    for k in 0..sides {
        let t = k as f32 / sides as f32 * std::f32::consts::TAU;
        let n = u * t.cos() + v * t.sin();
        m.vertex(a + n * radius, n);
        m.vertex(b + n * radius, n);
    }
    for k in 0..sides {
        let (i, j) = (2 * k, 2 * ((k + 1) % sides));
        m.triangle(i, j, j + 1);
        m.triangle(i, j + 1, i + 1);
    }
    m
}

fn opts(view: View, width: u32, height: u32) -> RenderOptions {
    RenderOptions {
        view,
        width,
        height,
        ..Default::default()
    }
}

/// Pixels that are not background: (count, bounding box x0, y0, x1, y1).
fn drawn(img: &Image) -> (usize, [u32; 4]) {
    let mut n = 0;
    let mut bb = [u32::MAX, u32::MAX, 0, 0];
    for y in 0..img.height {
        for x in 0..img.width {
            if img.pixel(x, y) != BACKGROUND {
                n += 1;
                bb = [bb[0].min(x), bb[1].min(y), bb[2].max(x), bb[3].max(y)];
            }
        }
    }
    (n, bb)
}

/// Centroid of the pixels where `pick` holds.
fn centroid(img: &Image, pick: impl Fn([u8; 3]) -> bool) -> Vec2 {
    let (mut sum, mut n) = (Vec2::ZERO, 0.0);
    for y in 0..img.height {
        for x in 0..img.width {
            if pick(img.pixel(x, y)) {
                sum += Vec2::new(x as f32, y as f32);
                n += 1.0;
            }
        }
    }
    assert!(n > 0.0, "no pixel matched");
    sum / n
}

#[test]
fn red_cube_front_view_is_shaded_red_on_background() {
    let scene = cube_scene(RED, Mat4::IDENTITY);
    let img = render(&scene, &opts(View::Front, 64, 48));
    assert_eq!(
        (img.width, img.height, img.rgb.len()),
        (64, 48, 64 * 48 * 3)
    );
    let [r, g, b] = img.pixel(32, 24);
    assert!(r > 150 && g < 100 && b < 100, "centre {:?}", [r, g, b]);
    // shaded: darker than the full material colour, brighter than ambient
    assert!(r < 230 && r > 160, "centre red {r}");
    for (x, y) in [(0, 0), (63, 0), (0, 47), (63, 47)] {
        assert_eq!(img.pixel(x, y), BACKGROUND, "corner {x},{y}");
    }
    // The cube fills 90% of the height, centred: a 43-pixel square.
    let (_, bb) = drawn(&img);
    assert!(bb[1] <= 3 && bb[3] >= 44, "{bb:?}");
    assert!((bb[0] + bb[2]) as i32 - 63 <= 1, "not centred: {bb:?}");
}

#[test]
fn tall_box_is_tall_from_the_front_and_square_from_the_top() {
    let scene = cube_scene(GREEN, Mat4::from_scale(Vec3::new(0.2, 2.0, 0.2)));
    let aspect = |view| {
        let (n, bb) = drawn(&render(&scene, &opts(view, 100, 100)));
        let (w, h) = ((bb[2] - bb[0] + 1) as f32, (bb[3] - bb[1] + 1) as f32);
        (n, h / w)
    };
    let (front_n, front) = aspect(View::Front);
    let (top_n, top) = aspect(View::Top);
    assert!(front > 7.0, "front aspect {front}");
    assert!((top - 1.0).abs() < 0.1, "top aspect {top}");
    // framed to fit: the top view's square fills the picture
    assert!(front_n < 1500 && top_n > 7000, "{front_n} {top_n}");
}

#[test]
fn empty_scene_is_all_background() {
    for scene in [Scene::default(), {
        // materials and a component but nothing placed
        let mut s = cube_scene(RED, Mat4::IDENTITY);
        s.instances.clear();
        s
    }] {
        let img = render(&scene, &opts(View::Iso, 33, 17));
        assert!(img.rgb.chunks(3).all(|p| p == BACKGROUND));
    }
    let img = render(&Scene::default(), &opts(View::Front, 0, 10));
    assert!(img.rgb.is_empty());
}

#[test]
fn degenerate_scenes_do_not_panic() {
    // a single point (three coincident vertices)
    let mut point = Scene::default();
    let mut m = TriMesh::default();
    for _ in 0..3 {
        m.vertex(Vec3::ONE, Vec3::Y);
    }
    m.triangle(0, 1, 2);
    stroke(&mut point, m, RED);
    let img = render(&point, &opts(View::Iso, 20, 20));
    assert!(img.rgb.chunks(3).all(|p| p == BACKGROUND));

    // a flat square in the XZ plane: a line from the front, a square from the top
    let flat = cube_scene(RED, Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0)));
    let img = render(&flat, &opts(View::Top, 20, 20));
    assert!(drawn(&img).0 > 250);
    render(&flat, &opts(View::Front, 20, 20));

    // non-finite and absurd coordinates are skipped, the rest drawn
    let mut bad = cube_scene(RED, Mat4::IDENTITY);
    let mut m = TriMesh::default();
    m.vertex(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y);
    m.vertex(Vec3::new(f32::INFINITY, 1.0, 0.0), Vec3::Y);
    m.vertex(Vec3::ZERO, Vec3::ZERO);
    m.triangle(0, 1, 2);
    stroke(&mut bad, m, [f32::NAN, 2.0, -1.0]);
    let img = render(&bad, &opts(View::Front, 20, 20));
    assert!(img.pixel(10, 10)[0] > 150);
    let mut huge = Scene::default();
    stroke(
        &mut huge,
        TriMesh::cuboid(Vec3::splat(-3e38), Vec3::splat(3e38)),
        RED,
    );
    render(&huge, &opts(View::Iso, 20, 20));
}

#[test]
fn nearer_quad_wins_whatever_the_drawing_order() {
    let quad = |z: f32, x0: f32| {
        let mut m = TriMesh::default();
        let c = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
        for (x, y) in c {
            m.vertex(Vec3::new(x0 + x, y, z), Vec3::Z);
        }
        m.triangle(0, 1, 2);
        m.triangle(0, 2, 3);
        m
    };
    for near_first in [true, false] {
        let mut scene = Scene::default();
        // red is nearer (+Z is towards the front camera), blue behind and
        // shifted right so that both show
        let (near, far) = ((quad(1.0, 0.0), RED), (quad(-1.0, 1.0), BLUE));
        let order = if near_first { [near, far] } else { [far, near] };
        for (m, rgb) in order {
            stroke(&mut scene, m, rgb);
        }
        let img = render(&scene, &opts(View::Front, 60, 40));
        // the overlap, x in 1..2 of 0..3 world units
        let [r, _, b] = img.pixel(30, 20);
        assert!(r > 150 && b < 80, "overlap {:?}", img.pixel(30, 20));
        let [r, _, b] = img.pixel(50, 20);
        assert!(b > 150 && r < 80, "blue part {:?}", img.pixel(50, 20));
    }
}

#[test]
fn views_put_the_axes_where_documented() {
    // red cube on +X, green on +Y, blue on +Z
    let mut scene = Scene::default();
    for (centre, rgb) in [(Vec3::X, RED), (Vec3::Y, GREEN), (Vec3::Z, BLUE)] {
        stroke(&mut scene, TriMesh::cuboid(centre - 0.3, centre + 0.3), rgb);
    }
    // Centroids of the red, green and blue pixels; screen y grows down.
    let at = |view| {
        let img = render(&scene, &opts(view, 120, 120));
        [0, 1, 2].map(|c| {
            centroid(&img, |p: [u8; 3]| {
                let p = p.map(i32::from);
                p[c] > p[(c + 1) % 3] + 40 && p[c] > p[(c + 2) % 3] + 40
            })
        })
    };
    let near = |a: f32, b: f32| (a - b).abs() < 2.0;
    let [x, y, z] = at(View::Front);
    assert!(
        x.x > z.x + 20.0 && near(x.y, z.y),
        "front: +X right {x} {z}"
    );
    assert!(y.y < z.y - 20.0 && near(y.x, z.x), "front: +Y up {y} {z}");
    let [x, y, z] = at(View::Side);
    assert!(z.x < x.x - 20.0 && near(z.y, x.y), "side: +Z left {z} {x}");
    assert!(y.y < x.y - 20.0 && near(y.x, x.x), "side: +Y up {y} {x}");
    let [x, y, z] = at(View::Top);
    assert!(x.x > y.x + 20.0 && near(x.y, y.y), "top: +X right {x} {y}");
    assert!(z.y > y.y + 20.0 && near(z.x, y.x), "top: +Z down {z} {y}");
    let [x, y, z] = at(View::Iso);
    assert!(
        x.x > z.x + 20.0 && near(x.y, z.y),
        "iso: +X right of +Z {x} {z}"
    );
    assert!(
        y.y < x.y - 20.0 && near(y.x, (x.x + z.x) / 2.0),
        "iso: +Y up {y}"
    );
}

#[test]
fn thin_tubes_show_as_continuous_faint_lines() {
    // a 1-unit cube for scale and a tube 0.002 units thick, ~0.1 pixel
    let mut scene = cube_scene(GREEN, Mat4::IDENTITY);
    for (i, y) in [-0.3f32, 0.1].into_iter().enumerate() {
        // one horizontal, one slanted; both beside the cube
        let end = Vec3::new(2.5, y + 0.2 * i as f32, 0.0);
        stroke(
            &mut scene,
            tube(Vec3::new(0.7, y, 0.0), end, 0.001, 6),
            [0.2, 0.1, 0.0],
        );
    }
    let img = render(&scene, &opts(View::Front, 200, 100));
    let (_, bb) = drawn(&img);
    // every column between the cube and the tube ends shows both tubes
    let mut shown = 0;
    for x in 90..bb[2] - 1 {
        let marks = (0..img.height)
            .filter(|&y| img.pixel(x, y) != BACKGROUND)
            .count();
        assert!(marks >= 2, "column {x} shows {marks} tube pixels");
        let darkest = (0..img.height).map(|y| img.pixel(x, y)[1]).min().unwrap();
        assert!(darkest < 215, "column {x} too faint: {darkest}");
        shown += 1;
    }
    assert!(shown > 40, "{shown}");
}

#[test]
fn back_faces_and_open_meshes_are_shaded_towards_the_viewer() {
    // One quad facing away from the camera, one facing it: same shade.
    let quad = |flip: bool| {
        let mut m = TriMesh::default();
        let n = if flip { Vec3::NEG_Z } else { Vec3::Z };
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            m.vertex(Vec3::new(x, y, 0.0), n);
        }
        if flip {
            m.triangle(0, 2, 1);
            m.triangle(0, 3, 2);
        } else {
            m.triangle(0, 1, 2);
            m.triangle(0, 2, 3);
        }
        m
    };
    let px = |flip| {
        let mut s = Scene::default();
        stroke(&mut s, quad(flip), RED);
        render(&s, &opts(View::Front, 20, 20)).pixel(10, 10)
    };
    assert_eq!(px(false), px(true));
    assert!(px(true)[0] > 150);
}

#[test]
fn banded_rendering_matches_one_pass() {
    let mut scene = cube_scene(RED, Mat4::from_rotation_y(0.5));
    stroke(
        &mut scene,
        tube(
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.2, 0.3),
            0.004,
            5,
        ),
        BLUE,
    );
    let o = opts(View::Iso, 50, 37);
    let whole = render(&scene, &o);
    for band_samples in [1, 100 * 2 * 3, 100 * 2 * 2 * 10] {
        assert_eq!(
            render_in_bands(&scene, &o, band_samples),
            whole,
            "{band_samples}"
        );
    }
    // supersampling is optional
    render(
        &scene,
        &RenderOptions {
            supersample: 1,
            ..o
        },
    );
}

#[test]
fn png_round_trips() {
    let img = render(&cube_scene(RED, Mat4::IDENTITY), &opts(View::Iso, 31, 17));
    let mut bytes = Vec::new();
    write_png(&img, &mut bytes).unwrap();
    let mut reader = png::Decoder::new(io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (31, 17));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(&buf[..info.buffer_size()], &img.rgb[..]);
}

#[test]
fn save_png_writes_atomically_and_names_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let img = render(&Scene::default(), &opts(View::Top, 4, 3));
    let path = dir.path().join("out.png");
    save_png(&img, &path).unwrap();
    assert_eq!(&std::fs::read(&path).unwrap()[1..4], b"PNG");
    let missing = dir.path().join("no/such/dir/out.png");
    let e = save_png(&img, &missing).unwrap_err();
    assert!(matches!(&e, RenderError::Save { path, .. } if path.contains("no/such")));
    // clap's value parsers need errors that cross threads
    fn send_sync<T: std::error::Error + Send + Sync + 'static>() {}
    send_sync::<RenderError>();
}

#[test]
fn options_parse_and_validate() {
    assert_eq!("front".parse::<View>().unwrap(), View::Front);
    assert_eq!(" ISO ".parse::<View>().unwrap(), View::Iso);
    let e = "perspective".parse::<View>().unwrap_err();
    let text = crate::diag::render_plain(&e);
    assert!(text.contains("lsys::render::unknown_view"), "{text}");
    assert!(text.contains("front, side, top, iso"), "{text}");
    for v in View::ALL {
        assert_eq!(v.to_string().parse::<View>().unwrap(), v);
    }

    assert_eq!(parse_size("1024x768").unwrap(), (1024, 768));
    assert_eq!(parse_size("8X16384").unwrap(), (8, 16384));
    for (s, code) in [
        ("1024", "bad_size"),
        ("ax3", "bad_size"),
        ("-4x3", "bad_size"),
        ("0x768", "zero_size"),
        ("16385x10", "too_large"),
    ] {
        let e = parse_size(s).unwrap_err();
        let code = format!("lsys::render::{code}");
        assert_eq!(e.code().unwrap().to_string(), code, "{s}");
    }
    assert!(RenderOptions::default().validate().is_ok());
    let o = RenderOptions {
        supersample: 5,
        ..Default::default()
    };
    assert!(matches!(
        o.validate(),
        Err(RenderError::BadSupersample { given: 5 })
    ));
}

/// A cube with an axis marker and a few tubes, for looking at:
/// `cargo test --lib render::tests::write_sample_pictures -- --ignored`
/// writes /tmp/render_test_<view>.png.
#[test]
#[ignore]
fn write_sample_pictures() {
    let mut scene = cube_scene(RED, Mat4::IDENTITY);
    // green post on +X, blue towards +Z (the front), yellow up +Y
    stroke(
        &mut scene,
        tube(
            Vec3::new(0.6, -0.5, 0.0),
            Vec3::new(1.6, -0.5, 0.0),
            0.08,
            16,
        ),
        GREEN,
    );
    stroke(
        &mut scene,
        tube(
            Vec3::new(0.0, -0.5, 0.6),
            Vec3::new(0.0, -0.5, 1.6),
            0.08,
            16,
        ),
        BLUE,
    );
    stroke(
        &mut scene,
        tube(Vec3::new(0.0, 0.6, 0.0), Vec3::new(0.0, 1.6, 0.0), 0.08, 16),
        [0.9, 0.8, 0.1],
    );
    // a fan of thin brown twigs, down to sub-pixel thickness
    for k in 0..8 {
        let a = k as f32 * 0.2;
        let r = 0.02 / (1 << k) as f32;
        stroke(
            &mut scene,
            tube(
                Vec3::new(-0.6, 0.3, 0.0),
                Vec3::new(-0.6 - a.cos() * 1.2, 0.3 + a.sin() * 1.2, 0.0),
                r,
                8,
            ),
            [0.45, 0.3, 0.15],
        );
    }
    for v in View::ALL {
        let img = render(&scene, &opts(v, 480, 360));
        let path = format!("/tmp/render_test_{v}.png");
        let mut f = std::fs::File::create(&path).unwrap();
        write_png(&img, &mut f).unwrap();
        eprintln!("wrote {path}");
        // a 4x enlargement of the upper left quarter, to check edges
        let zoom = Image {
            width: 960,
            height: 720,
            rgb: (0..720 * 960)
                .flat_map(|i| img.pixel(80 + (i % 960) / 4, (i / 960) / 4))
                .collect(),
        };
        let path = format!("/tmp/render_test_{v}_zoom.png");
        write_png(&zoom, &mut std::fs::File::create(&path).unwrap()).unwrap();
    }
}

/// Timing, 1M triangles by default:
/// `cargo test --release --lib render::tests::bench -- --ignored --nocapture`
/// (environment: `PLACEMENTS`, 1000 triangles each, default 1000; `RUNS`,
/// default 5). Writes the iso picture to /tmp/render_bench_iso.png.
#[test]
#[ignore]
fn bench_render_1m_triangles() {
    let env =
        |name: &str, default: u32| std::env::var(name).map_or(default, |s| s.parse().expect(name));
    // placements of a 1000-triangle tube in a random-ish bush
    let mut scene = Scene::default();
    let material = material(&mut scene, GREEN);
    scene.components.push(Component::new(
        "T",
        "test",
        vec![Part {
            mesh: {
                let mut m = TriMesh::default();
                for k in 0..50 {
                    let y = k as f32 * 0.02;
                    m.append(&tube(
                        Vec3::new(0.0, y, 0.0),
                        Vec3::new(0.0, y + 0.02, 0.0),
                        0.01,
                        10,
                    ));
                }
                m
            },
            material: None,
        }],
    ));
    let mut seed = 12345u32;
    let mut rnd = || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1 << 24) as f32
    };
    for n in 0..env("PLACEMENTS", 1000) {
        let rot = Quat::from_euler(glam::EulerRot::YXZ, rnd() * 6.3, rnd() * 1.2, rnd() * 1.2);
        let pos = Vec3::new(rnd() - 0.5, rnd() * 1.5, rnd() - 0.5) * 3.0;
        scene.instances.push(Instance {
            component: 0,
            transform: Mat4::from_scale_rotation_translation(Vec3::splat(1.0 + rnd()), rot, pos),
            material,
            number: n,
        });
    }
    eprintln!("{} triangles", scene.triangle_count());
    for view in [View::Iso, View::Front] {
        let mut times: Vec<f64> = (0..env("RUNS", 5))
            .map(|_| {
                let t = std::time::Instant::now();
                let img = std::hint::black_box(render(&scene, &opts(view, 1024, 768)));
                let took = t.elapsed().as_secs_f64();
                if view == View::Iso {
                    let mut f = std::fs::File::create("/tmp/render_bench_iso.png").unwrap();
                    write_png(&img, &mut f).unwrap();
                }
                took
            })
            .collect();
        times.sort_by(f64::total_cmp);
        eprintln!(
            "{view}: median {:.3} s, runs {times:.3?}",
            times[times.len() / 2]
        );
    }
}
