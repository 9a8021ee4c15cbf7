//! Rendering: a [`Scene`] and [`RenderOptions`] -> an [`Image`] (8-bit sRGB)
//! and PNG bytes, for `lsys render`. A small software rasteriser: an
//! orthographic camera along one of four fixed [`View`]s with the model
//! framed automatically, a depth buffer, Lambert shading (a key light from
//! the upper front-left plus ambient) in linear light, and supersampling so
//! that thin tubes still show as faint lines.
//!
//! World convention: +Y is up; the front view looks from +Z towards -Z.

mod camera;
mod raster;

use std::fmt;
use std::io::{self, Write};
use std::path::Path;
use std::str::FromStr;

use glam::{Vec2, Vec3};
use miette::Diagnostic;
use thiserror::Error;

use super::atomic;
use crate::mesh::Scene;
use camera::Camera;
use raster::{Attrs, Band, Coverage, COORD_LIMIT};

/// Largest accepted width or height, in pixels.
pub const MAX_SIZE: u32 = 16384;
/// Largest accepted supersampling factor (per axis).
pub const MAX_SUPERSAMPLE: u32 = 4;
/// The background colour (sRGB), where nothing is drawn.
pub const BACKGROUND: [u8; 3] = [0xf0, 0xf0, 0xf0];

/// Light that reaches every surface, whatever its orientation.
const AMBIENT: f32 = 0.35;
/// Strength of the key light; with [`AMBIENT`] it sums to 1, so a surface
/// facing the light shows its material colour exactly.
const KEY: f32 = 0.65;
/// Colour of triangles whose material index is out of range (sRGB grey).
const FALLBACK_RGB: [f32; 3] = [0.6, 0.6, 0.6];
/// Supersamples held in memory at once (16 bytes each): larger images are
/// drawn in horizontal bands, each a pass over the scene.
const MAX_BAND_SAMPLES: usize = 1 << 23;

/// Where the camera looks from. Every view keeps world +Y up on the screen
/// except [`View::Top`], which looks down it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum View {
    /// From +Z towards -Z: +X right, +Y up.
    Front,
    /// From +X towards -X: -Z right, +Y up.
    Side,
    /// From +Y down: +X right, -Z up, so +Z (the side the front view
    /// sees) is at the bottom, as in a plan drawing.
    Top,
    /// From the front-right and above, direction (1, 0.8, 1): shows the
    /// front, right and top of a box at once. The default.
    #[default]
    Iso,
}

impl View {
    pub const ALL: [View; 4] = [View::Front, View::Side, View::Top, View::Iso];

    /// The name accepted by `--view`.
    pub fn name(self) -> &'static str {
        match self {
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
            View::Iso => "iso",
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for View {
    type Err = RenderError;

    /// Parses `front`, `side`, `top` or `iso`, ignoring case.
    fn from_str(s: &str) -> Result<View, RenderError> {
        View::ALL
            .into_iter()
            .find(|v| v.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| RenderError::UnknownView {
                given: s.to_string(),
            })
    }
}

/// How to render. The default is the iso view at 1024 x 768 with 2 x 2
/// supersampling; a struct literal should end in `..Default::default()`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    pub view: View,
    /// Output width in pixels, 1 to [`MAX_SIZE`].
    pub width: u32,
    /// Output height in pixels, 1 to [`MAX_SIZE`].
    pub height: u32,
    /// Samples per pixel along each axis, 1 to [`MAX_SUPERSAMPLE`]: 2 means
    /// 4 samples per pixel.
    pub supersample: u32,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            view: View::Iso,
            width: 1024,
            height: 768,
            supersample: 2,
        }
    }
}

impl RenderOptions {
    /// Checks the size and supersampling factor. [`render`] itself accepts
    /// anything (a zero size gives an empty image, the factor is clamped),
    /// so call this where the options come from the user.
    pub fn validate(&self) -> Result<(), RenderError> {
        check_size(self.width, self.height)?;
        if !(1..=MAX_SUPERSAMPLE).contains(&self.supersample) {
            return Err(RenderError::BadSupersample {
                given: self.supersample,
            });
        }
        Ok(())
    }
}

fn check_size(width: u32, height: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::ZeroSize { width, height });
    }
    if width > MAX_SIZE || height > MAX_SIZE {
        return Err(RenderError::TooLarge { width, height });
    }
    Ok(())
}

/// Parses `--size WxH`, e.g. `1024x768` (`X` also accepted), and checks it
/// against [`MAX_SIZE`].
pub fn parse_size(s: &str) -> Result<(u32, u32), RenderError> {
    let bad = || RenderError::BadSize {
        given: s.to_string(),
    };
    let (w, h) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    let (width, height) = (
        w.trim().parse::<u32>().map_err(|_| bad())?,
        h.trim().parse::<u32>().map_err(|_| bad())?,
    );
    check_size(width, height)?;
    Ok((width, height))
}

/// A rendered picture: `width * height` pixels, row by row from the top,
/// 3 bytes (sRGB) each.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

impl Image {
    /// The pixel at column `x`, row `y` (0 is the top). Panics outside.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        assert!(x < self.width && y < self.height, "pixel out of range");
        let i = (y as usize * self.width as usize + x as usize) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

#[derive(Debug, Error, Diagnostic)]
pub enum RenderError {
    #[error("unknown view `{given}`")]
    #[diagnostic(
        code(lsys::render::unknown_view),
        help("choose one of: front, side, top, iso")
    )]
    UnknownView { given: String },

    #[error("`{given}` is not an image size")]
    #[diagnostic(
        code(lsys::render::bad_size),
        help("give the size as WIDTHxHEIGHT in pixels, e.g. --size 1024x768")
    )]
    BadSize { given: String },

    #[error("image size {width}x{height} has no pixels")]
    #[diagnostic(
        code(lsys::render::zero_size),
        help("width and height must both be at least 1")
    )]
    ZeroSize { width: u32, height: u32 },

    #[error("image size {width}x{height} is too large")]
    #[diagnostic(
        code(lsys::render::too_large),
        help("width and height may be at most 16384 pixels each")
    )]
    TooLarge { width: u32, height: u32 },

    #[error("supersampling factor {given} is out of range")]
    #[diagnostic(
        code(lsys::render::bad_supersample),
        help("use 1 (none) to 4 (4x4 samples per pixel)")
    )]
    BadSupersample { given: u32 },

    #[error("cannot encode the PNG image")]
    #[diagnostic(code(lsys::render::png))]
    Png(#[from] png::EncodingError),

    #[error("cannot write the image")]
    #[diagnostic(code(lsys::render::io))]
    Io(#[from] io::Error),

    #[error("cannot write {path}")]
    #[diagnostic(code(lsys::render::save))]
    Save {
        path: String,
        #[source]
        source: io::Error,
    },
}

/// Renders `scene` as seen from `opts.view`, framed to fill the image less
/// a 5% margin on each side, centred, aspect ratio kept. An empty scene
/// gives a picture of the background only; a zero size an empty image;
/// triangles with non-finite or absurdly large coordinates are skipped.
/// Sizes are not checked here ([`RenderOptions::validate`] does that): the
/// output alone takes `width * height * 3` bytes, while the working buffer
/// stays bounded (about 128 MiB) by drawing large images in bands.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Image {
    render_in_bands(scene, opts, MAX_BAND_SAMPLES)
}

fn render_in_bands(scene: &Scene, opts: &RenderOptions, max_band_samples: usize) -> Image {
    let (width, height) = (opts.width as usize, opts.height as usize);
    let mut image = Image {
        width: opts.width,
        height: opts.height,
        rgb: vec![0; width * height * 3],
    };
    if width == 0 || height == 0 {
        return image;
    }
    let ss = opts.supersample.clamp(1, MAX_SUPERSAMPLE) as usize;
    let (sw, sh) = (width * ss, height * ss);
    let camera = Camera::frame(scene, opts.view, Vec2::new(sw as f32, sh as f32));
    let materials: Vec<Vec3> = scene.materials.iter().map(|m| linear(m.rgb)).collect();
    let background = linear(BACKGROUND.map(|c| c as f32 / 255.0)).to_array();

    let band_rows = (max_band_samples / (sw * ss)).clamp(1, height);
    let mut band = Band::new(sw);
    for y in (0..height).step_by(band_rows) {
        let rows = band_rows.min(height - y);
        band.reset(y * ss, rows * ss, background);
        if let Some(camera) = &camera {
            draw(scene, camera, &materials, &mut band);
        }
        raster::resolve(
            &band,
            ss,
            &mut image.rgb[y * width * 3..(y + rows) * width * 3],
        );
    }
    image
}

/// sRGB material colour -> linear, with out-of-range values clamped.
fn linear(rgb: [f32; 3]) -> Vec3 {
    Vec3::from_array(
        rgb.map(|c| raster::srgb_to_linear(if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) })),
    )
}

/// Draws every triangle of `scene` that reaches `band`.
fn draw(scene: &Scene, camera: &Camera, materials: &[Vec3], band: &mut Band) {
    let light = camera.light();
    let toward_viewer = camera.toward_viewer();
    let fallback = linear(FALLBACK_RGB);
    let clip = band.clip();
    // Float rows the band may take samples from, with a little slack.
    let (band_lo, band_hi) = (clip.y0 as f32 - 1.0, clip.y1 as f32 + 1.0);
    let (depth, rgb) = (&mut band.depth, &mut band.rgb);
    let mut write = |i: usize, a: Attrs| {
        // A select rather than a branch: the depth test is a coin toss
        // between the front and back of a tube, and mispredicting it cost
        // about a third of the rendering time.
        let nearer = a[0] > depth[i];
        depth[i] = if nearer { a[0] } else { depth[i] };
        rgb[i] = if nearer { [a[1], a[2], a[3]] } else { rgb[i] };
    };
    scene.for_each_triangle(|p, n, material| {
        let s = [
            camera.project(p[0]),
            camera.project(p[1]),
            camera.project(p[2]),
        ];
        let (lo, hi) = (s[0].min(s[1]).min(s[2]), s[0].max(s[1]).max(s[2]));
        // Written so that NaN fails every test.
        let inside = hi.y >= band_lo
            && lo.y <= band_hi
            && lo.x > -COORD_LIMIT
            && lo.y > -COORD_LIMIT
            && hi.x < COORD_LIMIT
            && hi.y < COORD_LIMIT
            && lo.z.is_finite()
            && hi.z.is_finite();
        if !inside {
            return;
        }
        // Shade the side that faces the viewer: meshes may be open (leaves,
        // petals) or wound inconsistently, so decide with the geometric
        // normal which side is seen, then flip the vertex normals if they
        // belong to the other side.
        let g = (p[1] - p[0]).cross(p[2] - p[0]);
        let seen = if g.dot(toward_viewer) >= 0.0 { g } else { -g };
        let flip = (n[0] + n[1] + n[2]).dot(seen) < 0.0;
        let seen = seen.normalize_or_zero();
        let base = materials.get(material).copied().unwrap_or(fallback);
        let attrs: [Attrs; 3] = std::array::from_fn(|k| {
            let nk = if n[k] == Vec3::ZERO {
                seen
            } else if flip {
                -n[k]
            } else {
                n[k]
            };
            let c = base * (AMBIENT + KEY * nk.dot(light).max(0.0));
            [s[k].z, c.x, c.y, c.z]
        });
        let v = [s[0].truncate(), s[1].truncate(), s[2].truncate()];
        if raster::triangle(v, attrs, &clip, &mut write) == Coverage::Missed {
            raster::sliver(v, attrs, &clip, &mut write);
        }
    });
}

/// Writes `img` to `path` as PNG, atomically: the file appears complete or
/// not at all, and a failure keeps any existing file.
pub fn save_png(img: &Image, path: &Path) -> Result<(), RenderError> {
    atomic::write_file(path, |w| write_png(img, w)).map_err(|e| match e {
        RenderError::Io(source) | RenderError::Png(png::EncodingError::IoError(source)) => {
            RenderError::Save {
                path: path.display().to_string(),
                source,
            }
        }
        e => e,
    })
}

/// Writes `img` as an 8-bit RGB PNG tagged sRGB.
pub fn write_png(img: &Image, out: &mut dyn Write) -> Result<(), RenderError> {
    let mut encoder = png::Encoder::new(out, img.width, img.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&img.rgb)?;
    writer.finish()?;
    Ok(())
}

#[cfg(test)]
mod tests {
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
        scene.components.push(Component {
            name: "C".into(),
            parts: vec![Part {
                mesh: TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5)),
                material: None,
            }],
            origin: "test".into(),
        });
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
        let env = |name: &str, default: u32| {
            std::env::var(name).map_or(default, |s| s.parse().expect(name))
        };
        // placements of a 1000-triangle tube in a random-ish bush
        let mut scene = Scene::default();
        let material = material(&mut scene, GREEN);
        scene.components.push(Component {
            name: "T".into(),
            parts: vec![Part {
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
            origin: "test".into(),
        });
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
                transform: Mat4::from_scale_rotation_translation(
                    Vec3::splat(1.0 + rnd()),
                    rot,
                    pos,
                ),
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
}
