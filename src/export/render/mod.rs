//! Rendering: a [`Scene`] and [`RenderOptions`] -> an [`Image`] (8-bit sRGB)
//! and PNG bytes, for `lsys render`. A small software rasteriser: an
//! orthographic camera along one of four fixed [`View`]s with the model
//! framed automatically, a depth buffer, Lambert shading (a key light from
//! the upper front-left plus ambient) in linear light, and supersampling so
//! that thin tubes still show as faint lines.
//!
//! World convention: +Y is up; the front view looks from +Z towards -Z.

mod camera;
mod lines;
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

/// How the model is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Style {
    /// Shaded surfaces in their colours, lit from the upper front-left.
    #[default]
    Shaded,
    /// An architect's line drawing: visible edges in black on white, hidden
    /// ones removed (outlines, creases, changes of material and depth
    /// steps). With `--view front` an elevation, as `lsys infer` reads.
    Lines,
}

/// How to render. The default is the iso view at 1024 x 768 with 2 x 2
/// supersampling; a struct literal should end in `..Default::default()`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    pub view: View,
    pub style: Style,
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
            style: Style::Shaded,
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

/// Where [`render`] puts model points in its picture: the same camera,
/// in output pixels (the supersampling divided out), y down. For tools
/// that compare a picture with the model drawn in it (the drawing round
/// trip).
#[derive(Clone, Copy, Debug)]
pub struct PixelFrame {
    camera: Camera,
    supersample: f32,
}

impl PixelFrame {
    /// The framing of `scene` under `opts`; `None` when nothing is drawn.
    pub fn of(scene: &Scene, opts: &RenderOptions) -> Option<PixelFrame> {
        let ss = opts.supersample.clamp(1, MAX_SUPERSAMPLE);
        let size = Vec2::new((opts.width * ss) as f32, (opts.height * ss) as f32);
        let camera = Camera::frame(scene, opts.view, size)?;
        Some(PixelFrame {
            camera,
            supersample: ss as f32,
        })
    }

    /// A world point -> (pixel x, pixel y downwards).
    pub fn project(&self, p: Vec3) -> Vec2 {
        let q = self.camera.project(p);
        Vec2::new(q.x, q.y) / self.supersample
    }

    /// Each placed component of `scene` as (its symbol, the box `[x0, y0,
    /// x1, y1]` in pixels around its geometry's box projected), in the
    /// scene's order; placements smaller than a pixel either way left out.
    pub fn instance_boxes<'s>(&self, scene: &'s Scene) -> Vec<(&'s str, [f64; 4])> {
        let mut out = Vec::new();
        for inst in &scene.instances {
            let c = &scene.components[inst.component];
            let Some((lo, hi)) = c
                .parts()
                .iter()
                .filter_map(|p| p.mesh.bounds())
                .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
            else {
                continue;
            };
            let mut b = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
            for k in 0..8 {
                let corner = Vec3::new(
                    if k & 1 == 0 { lo.x } else { hi.x },
                    if k & 2 == 0 { lo.y } else { hi.y },
                    if k & 4 == 0 { lo.z } else { hi.z },
                );
                let p = self.project(inst.transform.transform_point3(corner));
                let (x, y) = (f64::from(p.x), f64::from(p.y));
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
            if b[2] - b[0] >= 1.0 && b[3] - b[1] >= 1.0 {
                out.push((c.name.as_str(), b));
            }
        }
        out
    }
}

/// Renders `scene` as seen from `opts.view`, framed to fill the image less
/// a 5% margin on each side, centred, aspect ratio kept. An empty scene
/// gives a picture of the background only; a zero size an empty image;
/// triangles with non-finite or absurdly large coordinates are skipped.
/// Sizes are not checked here ([`RenderOptions::validate`] does that): the
/// output alone takes `width * height * 3` bytes, while the working buffer
/// stays bounded (about 128 MiB) by drawing large images in bands.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Image {
    if opts.style == Style::Lines {
        return lines::render(scene, opts);
    }
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
        let Some(s) = project_triangle(camera, &p, band_lo, band_hi) else {
            return;
        };
        let normals = facing_normals(&p, &n, toward_viewer);
        let base = materials.get(material).copied().unwrap_or(fallback);
        let attrs: [Attrs; 3] = std::array::from_fn(|k| {
            let c = base * (AMBIENT + KEY * normals[k].dot(light).max(0.0));
            [s[k].z, c.x, c.y, c.z]
        });
        let v = [s[0].truncate(), s[1].truncate(), s[2].truncate()];
        if raster::triangle(v, attrs, &clip, &mut write) == Coverage::Missed {
            raster::sliver(v, attrs, &clip, &mut write);
        }
    });
}

/// Triangle `p` in sample coordinates, when it reaches the sample rows
/// `band_lo..band_hi` and its coordinates are finite and within
/// [`COORD_LIMIT`].
fn project_triangle(
    camera: &Camera,
    p: &[Vec3; 3],
    band_lo: f32,
    band_hi: f32,
) -> Option<[Vec3; 3]> {
    let s = p.map(|q| camera.project(q));
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
    inside.then_some(s)
}

/// The vertex normals of the side of triangle `p` that faces the viewer.
/// Meshes may be open (leaves, petals) or wound inconsistently, so the
/// geometric normal decides which side is seen, and the vertex normals are
/// flipped if they belong to the other side; a zero normal becomes the
/// geometric one.
fn facing_normals(p: &[Vec3; 3], n: &[Vec3; 3], toward_viewer: Vec3) -> [Vec3; 3] {
    let g = (p[1] - p[0]).cross(p[2] - p[0]);
    let seen = if g.dot(toward_viewer) >= 0.0 { g } else { -g };
    let flip = (n[0] + n[1] + n[2]).dot(seen) < 0.0;
    let seen = seen.normalize_or_zero();
    n.map(|nk| {
        if nk == Vec3::ZERO {
            seen
        } else if flip {
            -nk
        } else {
            nk
        }
    })
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
mod tests;
