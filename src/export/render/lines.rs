//! Line drawings: a [`Scene`] and [`RenderOptions`] -> an [`Image`] drawn as
//! an architect draws an elevation: the visible edges in black on white,
//! hidden ones removed (`lsys render --style lines`).
//!
//! Hidden-line removal is done in image space, which is exact for what is
//! seen and needs no edge bookkeeping in the meshes: every sample records
//! the nearest surface's depth, normal and material (a G-buffer), and an
//! edge is drawn on the nearer of two neighbouring samples that differ in
//!
//! - coverage: the model against the empty background (the outline);
//! - material: two parts of different colour meet (a window in a wall);
//! - normal: a crease sharper than [`CREASE_DEGREES`] (a box's corner;
//!   a 16-sided column's facets, 22.5° apart, stay smooth);
//! - depth: a step larger than the surface's own slope allows, by more than
//!   [`STEP_SAMPLES`] (a frame standing out of the wall behind it).

use glam::{Vec2, Vec3};

use super::camera::Camera;
use super::raster::{self, Clip, Coverage};
use super::{Image, RenderOptions, MAX_SUPERSAMPLE};
use crate::mesh::Scene;

/// Normals more than this many degrees apart make a crease line.
const CREASE_DEGREES: f32 = 30.0;
/// A depth step counts as an edge when it exceeds what the surfaces' slope
/// explains by this many sample widths.
const STEP_SAMPLES: f32 = 2.0;
/// Slopes are capped here: a surface seen almost edge-on would otherwise
/// excuse any depth step beside it.
const MAX_SLOPE: f32 = 8.0;
/// "Nothing drawn" in the material buffer.
const EMPTY: u32 = u32::MAX;
/// Samples held at once (21 bytes each); larger pictures go in bands.
const MAX_BAND_SAMPLES: usize = 1 << 22;

/// One band of the G-buffer: `rows` sample rows of the supersampled picture.
struct GBand {
    width: usize,
    rows: usize,
    depth: Vec<f32>,
    /// Unit normal in camera space (x right, y up, z towards the viewer).
    normal: Vec<Vec3>,
    material: Vec<u32>,
}

/// Renders `scene` as a line drawing; framing and banding as [`super::render`].
pub(super) fn render(scene: &Scene, opts: &RenderOptions) -> Image {
    render_in_bands(scene, opts, MAX_BAND_SAMPLES)
}

fn render_in_bands(scene: &Scene, opts: &RenderOptions, max_band_samples: usize) -> Image {
    let (width, height) = (opts.width as usize, opts.height as usize);
    let mut image = Image {
        width: opts.width,
        height: opts.height,
        rgb: vec![255; width * height * 3],
    };
    if width == 0 || height == 0 {
        return image;
    }
    let ss = opts.supersample.clamp(1, MAX_SUPERSAMPLE) as usize;
    let (sw, sh) = (width * ss, height * ss);
    let Some(camera) = Camera::frame(scene, opts.view, Vec2::new(sw as f32, sh as f32)) else {
        return image;
    };
    let band_rows = (max_band_samples / (sw * ss)).clamp(1, height);
    for y in (0..height).step_by(band_rows) {
        let rows = band_rows.min(height - y);
        // One sample row of overlap on each side, so that edges between
        // bands are found as inside them.
        let lo = (y * ss).saturating_sub(1);
        let hi = ((y + rows) * ss + 1).min(sh);
        let band = draw(scene, &camera, sw, lo, hi - lo);
        let edges = edges(&band, &camera);
        for py in y..y + rows {
            for px in 0..width {
                let inked = (0..ss).any(|sy| {
                    let row = py * ss + sy - lo;
                    (0..ss).any(|sx| edges[row * sw + px * ss + sx])
                });
                if inked {
                    let i = (py * width + px) * 3;
                    image.rgb[i..i + 3].fill(0);
                }
            }
        }
    }
    image
}

/// Fills a G-band with the nearest surface at each sample.
fn draw(scene: &Scene, camera: &Camera, width: usize, y0: usize, rows: usize) -> GBand {
    let n = width * rows;
    let mut band = GBand {
        width,
        rows,
        depth: vec![f32::NEG_INFINITY; n],
        normal: vec![Vec3::ZERO; n],
        material: vec![EMPTY; n],
    };
    let clip = Clip {
        width: width as i64,
        y0: y0 as i64,
        y1: (y0 + rows) as i64,
    };
    let (band_lo, band_hi) = (y0 as f32 - 1.0, (y0 + rows) as f32 + 1.0);
    let (right, up, back) = camera.axes();
    scene.for_each_triangle(|p, n, material| {
        let Some(s) = super::project_triangle(camera, &p, band_lo, band_hi) else {
            return;
        };
        let normals = super::facing_normals(&p, &n, back);
        let attrs: [[f32; 4]; 3] = std::array::from_fn(|k| {
            let nk = normals[k];
            [s[k].z, nk.dot(right), nk.dot(up), nk.dot(back)]
        });
        let material = u32::try_from(material).unwrap_or(EMPTY - 1);
        let (depth, normal, mat) = (&mut band.depth, &mut band.normal, &mut band.material);
        let mut write = |i: usize, a: [f32; 4]| {
            if a[0] > depth[i] {
                depth[i] = a[0];
                normal[i] = Vec3::new(a[1], a[2], a[3]).normalize_or_zero();
                mat[i] = material;
            }
        };
        let v = s.map(|q| q.truncate());
        if raster::triangle(v, attrs, &clip, &mut write) == Coverage::Missed {
            raster::sliver(v, attrs, &clip, &mut write);
        }
    });
    band
}

/// Marks the samples of `band` an edge runs through.
fn edges(band: &GBand, camera: &Camera) -> Vec<bool> {
    let cos_crease = CREASE_DEGREES.to_radians().cos();
    // Depth is in world units; a sample is 1/scale of them.
    let sample = 1.0 / camera.scale();
    let mut marks = vec![false; band.width * band.rows];
    let mut compare = |a: usize, b: usize, across_x: bool| {
        let (ma, mb) = (band.material[a], band.material[b]);
        if ma == EMPTY && mb == EMPTY {
            return;
        }
        let nearer = if band.depth[a] >= band.depth[b] { a } else { b };
        let edge = ma == EMPTY
            || mb == EMPTY
            || ma != mb
            || band.normal[a].dot(band.normal[b]) < cos_crease
            || {
                // How far the depth may change over one sample on each
                // surface: |n_x / n_z| along x, |n_y / n_z| along y.
                let slope = |n: Vec3| {
                    let along = if across_x { n.x } else { n.y };
                    (along.abs() / n.z.abs().max(1e-6)).min(MAX_SLOPE)
                };
                let allowed = slope(band.normal[a]).max(slope(band.normal[b])) + STEP_SAMPLES;
                (band.depth[a] - band.depth[b]).abs() > allowed * sample
            };
        if edge {
            marks[nearer] = true;
        }
    };
    for y in 0..band.rows {
        for x in 0..band.width {
            let i = y * band.width + x;
            if x + 1 < band.width {
                compare(i, i + 1, true);
            }
            if y + 1 < band.rows {
                compare(i, i + band.width, false);
            }
        }
    }
    marks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::render::{Style, View};
    use crate::mesh::{Material, Scene, Stroke, TriMesh};

    /// Boxes `(low corner, high corner, material)`, each a stroke.
    fn cube_scene(boxes: &[(Vec3, Vec3, usize)]) -> Scene {
        let mut scene = Scene::default();
        for m in 0..2 {
            scene.materials.push(Material {
                name: format!("m{m}"),
                rgb: [0.5; 3],
                texture: None,
            });
        }
        for &(lo, hi, material) in boxes {
            scene.strokes.push(Stroke {
                material,
                mesh: TriMesh::cuboid(lo, hi),
            });
        }
        scene
    }

    fn opts(width: u32, height: u32) -> RenderOptions {
        RenderOptions {
            view: View::Front,
            width,
            height,
            style: Style::Lines,
            ..Default::default()
        }
    }

    fn ink(img: &Image) -> usize {
        img.rgb.chunks_exact(3).filter(|p| p[0] < 128).count()
    }

    #[test]
    fn a_box_seen_from_the_front_is_its_outline() {
        let scene = cube_scene(&[(Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0), 0)]);
        let img = render(&scene, &opts(220, 120));
        // The outline's four sides and nothing inside.
        assert_eq!(img.pixel(110, 60), [255; 3]);
        assert_eq!(img.pixel(5, 60), [255; 3]);
        let row: Vec<bool> = (0..220).map(|x| img.pixel(x, 60)[0] == 0).collect();
        assert_eq!(row.iter().filter(|&&b| b).count(), 2, "{row:?}");
        // A perimeter of about 2 * (198 + 99) pixels, one pixel wide.
        let n = ink(&img);
        assert!((560..660).contains(&n), "{n}");
    }

    #[test]
    fn a_step_in_depth_is_drawn_and_a_hidden_box_is_not() {
        // A thin panel standing 0.3 out of a wall: its outline is drawn.
        let wall = (Vec3::ZERO, Vec3::new(4.0, 2.0, 0.5), 0);
        let panel = (Vec3::new(1.0, 0.5, 0.5), Vec3::new(3.0, 1.5, 0.8), 0);
        let with = render(&cube_scene(&[wall, panel]), &opts(420, 220));
        let without = render(&cube_scene(&[wall]), &opts(420, 220));
        assert!(
            ink(&with) > ink(&without) + 400,
            "{} {}",
            ink(&with),
            ink(&without)
        );
        // The same panel behind the wall is hidden.
        let behind = (Vec3::new(1.0, 0.5, -0.8), Vec3::new(3.0, 1.5, -0.2), 0);
        let hidden = render(&cube_scene(&[wall, behind]), &opts(420, 220));
        assert_eq!(ink(&hidden), ink(&without));
    }

    #[test]
    fn a_change_of_material_in_one_plane_is_drawn() {
        let left = (Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0), 0);
        let right = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0), 1);
        let same = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0), 0);
        let two = render(&cube_scene(&[left, right]), &opts(220, 120));
        let one = render(&cube_scene(&[left, same]), &opts(220, 120));
        // The boundary at x = 1 falls between pixels 109 and 110.
        let inked = |img: &Image| (108..=111).filter(|&x| img.pixel(x, 60) == [0; 3]).count();
        assert_eq!(inked(&two), 1);
        assert_eq!(inked(&one), 0);
    }

    #[test]
    fn bands_give_the_same_picture() {
        let wall = (Vec3::ZERO, Vec3::new(4.0, 2.0, 0.5), 0);
        let panel = (Vec3::new(1.0, 0.5, 0.5), Vec3::new(3.0, 1.5, 0.8), 1);
        let scene = cube_scene(&[wall, panel]);
        let o = opts(200, 103);
        let whole = render_in_bands(&scene, &o, usize::MAX);
        let banded = render_in_bands(&scene, &o, 400 * 7);
        assert_eq!(whole, banded);
    }
}
