//! Procedural roofs, built on the fly as the paper does: a roof kind -> a
//! closed mesh in the unit box (x along the ridge, y up, z depth). The
//! eaves roof RE is hipped, with the curved (sagging) profile of Chinese
//! roofs and upturned eaves corners; the clipped roof RC has straight ends
//! and no corners. Both carry tile ribs down the slopes and a ridge with
//! raised ends.

use glam::Vec3;

use super::scene::TriMesh;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RoofKind {
    /// `RC`: no eaves corners, straight gable ends.
    Clipped,
    /// `RE`: hipped, with upturned eaves corners.
    Eaves,
}

impl RoofKind {
    pub fn from_name(name: &str) -> Option<RoofKind> {
        match name {
            "RC" => Some(RoofKind::Clipped),
            "RE" => Some(RoofKind::Eaves),
            _ => None,
        }
    }
}

/// Grid cells along the ridge and across the slopes.
const NX: usize = 48;
const NZ: usize = 16;
/// Shell thickness and the ridge's size, before normalisation.
const THICK: f32 = 0.05;
const RIDGE: f32 = 0.07;

/// Height of the roof surface at (x, z), both in [-0.5, 0.5].
fn height(kind: RoofKind, x: f32, z: f32) -> f32 {
    let tz = (z.abs() / 0.5).min(1.0);
    let t = match kind {
        RoofKind::Clipped => tz,
        RoofKind::Eaves => {
            // Hip ends: the ridge stops short of the ends by the slope's run.
            let run = 0.5 * 0.5;
            let tx = ((x.abs() - (0.5 - run)) / run).max(0.0);
            tz.max(tx)
        }
    };
    // Steep at the ridge, flattening toward the eaves.
    let mut y = 0.6 * (1.0 - t).powf(1.7);
    // Tile ribs down the slopes.
    y += 0.008 * (x * 28.0 * std::f32::consts::PI).sin().abs();
    if kind == RoofKind::Eaves {
        // The corners sweep up.
        let c = (x.abs() / 0.5).powi(6) * tz.powi(4);
        y += 0.22 * c;
    }
    y
}

/// The roof's mesh, normalised to the unit box.
pub fn roof(kind: RoofKind) -> TriMesh {
    let mut m = TriMesh::default();
    let at = |i: usize, k: usize| {
        let x = -0.5 + i as f32 / NX as f32;
        let z = -0.5 + k as f32 / NZ as f32;
        Vec3::new(x, height(kind, x, z), z)
    };
    // Top and underside of the shell.
    for i in 0..NX {
        for k in 0..NZ {
            let [a, b, c, d] = [at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1)];
            quad(&mut m, a, d, c, b);
            let down = Vec3::Y * -THICK;
            quad(&mut m, a + down, b + down, c + down, d + down);
        }
    }
    // The rim: walls between the two surfaces all around.
    let down = Vec3::Y * -THICK;
    for i in 0..NX {
        let (a, b) = (at(i, 0), at(i + 1, 0));
        quad(&mut m, a, b, b + down, a + down);
        let (a, b) = (at(i, NZ), at(i + 1, NZ));
        quad(&mut m, b, a, a + down, b + down);
    }
    for k in 0..NZ {
        let (a, b) = (at(0, k), at(0, k + 1));
        quad(&mut m, b, a, a + down, b + down);
        let (a, b) = (at(NX, k), at(NX, k + 1));
        quad(&mut m, a, b, b + down, a + down);
    }
    // The ridge along the top, with end blocks no higher than it (what
    // stands on a roof stands on its ridge, the top of its box).
    let top = height(kind, 0.0, 0.0);
    let half = match kind {
        RoofKind::Clipped => 0.5,
        RoofKind::Eaves => 0.27,
    };
    cuboid(
        &mut m,
        Vec3::new(-half, top - RIDGE * 0.5, -RIDGE * 0.5),
        Vec3::new(half, top + RIDGE, RIDGE * 0.5),
    );
    for s in [-1.0f32, 1.0] {
        let x = s * (half - RIDGE * 0.6);
        cuboid(
            &mut m,
            Vec3::new(x - RIDGE * 0.6, top - RIDGE * 0.6, -RIDGE * 0.6),
            Vec3::new(x + RIDGE * 0.6, top + RIDGE, RIDGE * 0.6),
        );
    }
    normalise(&mut m);
    m
}

/// A flat-shaded quad a-b-c-d, counter-clockwise seen from outside.
fn quad(m: &mut TriMesh, a: Vec3, b: Vec3, c: Vec3, d: Vec3) {
    for t in [[a, b, c], [a, c, d]] {
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or(Vec3::Y);
        let i = m.vertex(t[0], n);
        m.vertex(t[1], n);
        m.vertex(t[2], n);
        m.triangle(i, i + 1, i + 2);
    }
}

fn cuboid(m: &mut TriMesh, lo: Vec3, hi: Vec3) {
    m.append(&TriMesh::cuboid(lo, hi));
}

fn normalise(m: &mut TriMesh) {
    let Some((lo, hi)) = m.bounds() else { return };
    let ext = hi - lo;
    let centre = (lo + hi) * 0.5;
    for p in &mut m.positions {
        *p = (*p - centre) / ext;
    }
    for n in &mut m.normals {
        *n = (*n * ext).normalize_or(*n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roofs_fill_the_unit_box_and_face_outward() {
        for kind in [RoofKind::Clipped, RoofKind::Eaves] {
            let m = roof(kind);
            let (lo, hi) = m.bounds().unwrap();
            assert!(
                (lo - Vec3::splat(-0.5)).abs().max_element() < 1e-5,
                "{kind:?} {lo}"
            );
            assert!(
                (hi - Vec3::splat(0.5)).abs().max_element() < 1e-5,
                "{kind:?} {hi}"
            );
            assert!(m.triangle_count() < 6000, "{}", m.triangle_count());
            // Signed volume of the closed pieces: positive when outward.
            let vol: f32 = m
                .indices
                .chunks_exact(3)
                .map(|t| {
                    let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
                    a.dot(b.cross(c)) / 6.0
                })
                .sum();
            assert!(vol > 0.0, "{kind:?} volume {vol}");
        }
    }

    #[test]
    fn eaves_corners_turn_up() {
        let corner = |k| height(k, 0.5, 0.5);
        assert!(corner(RoofKind::Eaves) > corner(RoofKind::Clipped) + 0.1);
    }
}
