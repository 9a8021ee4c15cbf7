//! Procedural roofs, built on the fly as the paper does: a roof kind and a
//! level of detail -> a closed mesh in the unit box (x along the ridge, y
//! up, z depth). The eaves roof RE is hipped, with the curved (sagging)
//! profile of Chinese roofs and upturned eaves corners; the clipped roof RC
//! has straight ends and no corners. Both have a ridge whose top is the
//! box's top. Detail 0 (previews) is the bare shell; detail 1 (the
//! default) adds rows of round tiles (tongwa) down the front and back
//! slopes with a disc (wadang) at each eave end; detail 2 doubles them.

use std::sync::Arc;

use glam::{Mat4, Vec3};

use super::components::{normalise_meshes, UnitBox};
use super::scene::{bounds_from, bounds_of, Component, Instance, Later, Nested, Part, TriMesh};

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

/// Grid cells along the ridge and across the slopes, at detail 1 and 2
/// (detail 0 halves them).
const NX: usize = 48;
const NZ: usize = 16;
/// The finest detail.
pub const MAX_DETAIL: u8 = 2;
/// Shell thickness and the ridge's size, before normalisation.
const THICK: f32 = 0.05;
const RIDGE: f32 = 0.07;

/// Height of the roof surface at (x, z), both in [-0.5, 0.5].
fn height(kind: RoofKind, x: f32, z: f32) -> f32 {
    surface(kind, x, z) + 0.008 * (x * 28.0 * std::f32::consts::PI).sin().abs()
}

/// The smooth surface under the tiles.
fn surface(kind: RoofKind, x: f32, z: f32) -> f32 {
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
    if kind == RoofKind::Eaves {
        // The corners sweep up.
        let c = (x.abs() / 0.5).powi(6) * tz.powi(4);
        y += 0.22 * c;
    }
    y
}

/// The roof's mesh at a level of detail (0 to [`MAX_DETAIL`]), normalised
/// to the unit box.
pub fn roof(kind: RoofKind, detail: u8) -> TriMesh {
    let mut m = unnormalised(kind, detail);
    normalise_meshes(vec![&mut m]);
    m
}

/// The shell and every row of tiles, before normalisation.
fn unnormalised(kind: RoofKind, detail: u8) -> TriMesh {
    let mut m = shell(kind, detail);
    for (x, side) in row_places(detail) {
        if let Some(row) = tile_row(kind, detail, x, side) {
            m.append(&row);
        }
    }
    m
}

/// Where rows of tiles may go: (x along the ridge, the slope's side).
fn row_places(detail: u8) -> impl Iterator<Item = (f32, f32)> {
    let n = 28 * usize::from(detail);
    [-1.0f32, 1.0]
        .into_iter()
        .flat_map(move |side| (0..n).map(move |t| (-0.5 + (t as f32 + 0.5) / n as f32, side)))
}

/// The roof as a component named `name`. A clipped roof with tiles is
/// kept as a shell and placements of one row of tiles: its profile does
/// not change along the ridge, so every row is the same mesh moved (and
/// mirrored for the back slope), and a file that keeps placements (glTF)
/// stores it once. Its flattened mesh ([`roof`]) is built only when read.
pub fn roof_component(name: &str, kind: RoofKind, detail: u8) -> Component {
    const ORIGIN: &str = "built-in (procedural)";
    let whole = |mesh: TriMesh| {
        vec![Part {
            mesh,
            material: None,
        }]
    };
    if kind != RoofKind::Clipped || detail == 0 {
        return Component::new(name, ORIGIN, whole(roof(kind, detail)));
    }
    // The normalisation needs the bounds of the flattened mesh, in its
    // vertex order (so that the frame is the one `roof` applies); the rows
    // are measured one at a time and dropped.
    let shell = shell(kind, detail);
    let mut bounds = bounds_of(shell.positions.iter().copied());
    let (mut vertices, mut triangles) = (shell.vertex_count(), shell.triangle_count());
    let mut rows = Vec::new();
    for (x, side) in row_places(detail) {
        if let Some(row) = tile_row(kind, detail, x, side) {
            bounds = bounds_from(bounds, row.positions.iter().copied());
            vertices += row.vertex_count();
            triangles += row.triangle_count();
            rows.push((x, side));
        }
    }
    let Some((lo, hi)) = bounds.filter(|_| !rows.is_empty()) else {
        return Component::new(name, ORIGIN, whole(roof(kind, detail)));
    };
    let row = tile_row(kind, detail, 0.0, 1.0).unwrap_or_default();
    let nested = Nested {
        frame: UnitBox::of(lo, hi).matrix(),
        parts: vec![Part {
            mesh: shell,
            material: None,
        }],
        components: vec![Component::new(
            "tiles",
            ORIGIN,
            vec![Part {
                mesh: row,
                material: None,
            }],
        )],
        instances: rows
            .iter()
            .enumerate()
            .map(|(number, &(x, side))| Instance {
                component: 0,
                transform: Mat4::from_translation(Vec3::X * x)
                    * Mat4::from_scale(Vec3::new(1.0, 1.0, side)),
                material: 0,
                number: number as u32,
            })
            .collect(),
        placement_colour: true,
    };
    let later = Later {
        vertices,
        triangles,
        placement_colour: true,
        build: Arc::new(move |_| whole(roof(kind, detail))),
    };
    Component::built_later(name, ORIGIN, nested, later)
}

/// The shell (a smooth top and underside, walls all around) and the ridge.
fn shell(kind: RoofKind, detail: u8) -> TriMesh {
    let mut m = TriMesh::default();
    let (nx, nz) = if detail == 0 {
        (NX / 2, NZ / 2)
    } else {
        (NX, NZ)
    };
    let y = |x: f32, z: f32| {
        if detail == 0 {
            surface(kind, x, z)
        } else {
            height(kind, x, z)
        }
    };
    let at = |i: usize, k: usize| {
        let x = -0.5 + i as f32 / nx as f32;
        let z = -0.5 + k as f32 / nz as f32;
        Vec3::new(x, y(x, z), z)
    };
    // Top and underside of the shell. A clipped roof's surface is smooth:
    // grids of shared vertices, each with the area-weighted normal of the
    // faces around it, so the curve is shaded smooth and each vertex is
    // stored once. An eaves roof's has creases (the hips, the upswept
    // corners) where one normal per vertex would face away from some of
    // its faces: flat faces there, three vertices each.
    let down = Vec3::Y * -THICK;
    let index = |i: usize, k: usize| i * (nz + 1) + k;
    let points: Vec<Vec3> = (0..=nx)
        .flat_map(|i| (0..=nz).map(move |k| (i, k)))
        .map(|(i, k)| at(i, k))
        .collect();
    let mut normals = vec![Vec3::ZERO; points.len()];
    let mut cells = Vec::with_capacity(nx * nz * 2);
    for i in 0..nx {
        for k in 0..nz {
            let [a, b, c, d] = [
                index(i, k),
                index(i + 1, k),
                index(i + 1, k + 1),
                index(i, k + 1),
            ];
            for t in [[a, d, c], [a, c, b]] {
                let [p, q, r] = t.map(|v| points[v]);
                let face = (q - p).cross(r - p);
                for v in t {
                    normals[v] += face;
                }
                cells.push(t);
            }
        }
    }
    // Room for everything below at once (grown a vertex at a time, the
    // lists were copied a dozen times).
    let (surfaces, surface_indices) = match kind {
        RoofKind::Eaves => (2 * cells.len() * 3, 2 * cells.len() * 3),
        RoofKind::Clipped => (2 * points.len(), 2 * cells.len() * 3),
    };
    let (rim, ridge) = (2 * (nx + nz) * 6, 3 * 24);
    m.positions.reserve_exact(surfaces + rim + ridge);
    m.normals.reserve_exact(surfaces + rim + ridge);
    m.indices.reserve_exact(surface_indices + rim + 3 * 36);
    for (offset, sign) in [(Vec3::ZERO, 1.0f32), (down, -1.0)] {
        if kind == RoofKind::Eaves {
            for t in &cells {
                let [a, b, c] = t.map(|v| points[v] + offset);
                if sign > 0.0 {
                    flat(&mut m, a, b, c);
                } else {
                    flat(&mut m, a, c, b);
                }
            }
            continue;
        }
        let base = m.vertex_count() as u32;
        for (p, n) in points.iter().zip(&normals) {
            m.vertex(*p + offset, n.normalize_or(Vec3::Y) * sign);
        }
        for t in &cells {
            let [a, b, c] = t.map(|v| base + v as u32);
            if sign > 0.0 {
                m.triangle(a, b, c);
            } else {
                m.triangle(a, c, b);
            }
        }
    }
    // The rim: walls between the two surfaces all around.
    for i in 0..nx {
        let (a, b) = (at(i, 0), at(i + 1, 0));
        quad(&mut m, a, b, b + down, a + down);
        let (a, b) = (at(i, nz), at(i + 1, nz));
        quad(&mut m, b, a, a + down, b + down);
    }
    for k in 0..nz {
        let (a, b) = (at(0, k), at(0, k + 1));
        quad(&mut m, b, a, a + down, b + down);
        let (a, b) = (at(nx, k), at(nx, k + 1));
        quad(&mut m, a, b, b + down, a + down);
    }
    if kind == RoofKind::Clipped {
        gables(&mut m, nz, &y);
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
    m
}

/// Where a clipped roof's gable walls stand, inside its ends (the roof
/// overhangs them), and how thick they are.
const GABLE_X: f32 = 0.46;
const GABLE_THICK: f32 = 0.02;

/// A clipped roof's two gable ends (issue 37: seen end-on the roof was a
/// thin arc): under the shell near each end, a wall filling the profile
/// down to the eaves, closed so it reads as solid from any side. Inside
/// the unit box, so the roof's normalisation and placement are unchanged.
fn gables(m: &mut TriMesh, nz: usize, y: &dyn Fn(f32, f32) -> f32) {
    for s in [-1.0f32, 1.0] {
        let (outer, inner) = (s * GABLE_X, s * (GABLE_X - GABLE_THICK));
        let profile: Vec<(f32, f32)> = (0..=nz)
            .map(|k| {
                let z = -0.5 + k as f32 / nz as f32;
                (z, y(outer, z) - THICK)
            })
            .collect();
        let eave = profile.iter().map(|p| p.1).fold(f32::INFINITY, f32::min);
        let at = |x: f32, (z, h): (f32, f32)| Vec3::new(x, h, z);
        let foot = |x: f32, z: f32| Vec3::new(x, eave, z);
        // Each face as the +x end has it; the -x end is its mirror, wound
        // the other way (all the faces are flat, so either diagonal).
        let mut face = |a, b, c, d| {
            if s > 0.0 {
                quad(m, a, b, c, d)
            } else {
                quad(m, a, d, c, b)
            }
        };
        for pair in profile.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            // Outer and inner faces: a strip from the eave line up to
            // the profile; then the wall's top, under the shell.
            let (op, oq) = (at(outer, p), at(outer, q));
            let (ip, iq) = (at(inner, p), at(inner, q));
            face(foot(outer, p.0), op, oq, foot(outer, q.0));
            face(foot(inner, q.0), iq, ip, foot(inner, p.0));
            face(oq, op, ip, iq);
        }
        // The bottom, along the eave line.
        let (z0, z1) = (profile[0].0, profile[nz].0);
        face(
            foot(outer, z0),
            foot(outer, z1),
            foot(inner, z1),
            foot(inner, z0),
        );
    }
}

/// One row of round tiles on the `side` slope (+1 front, -1 back) at `x`:
/// a half tube lying on the surface from just below the ridge to the eave,
/// closed at the eave by a disc. 28 rows a side at detail 1, 56 at detail
/// 2; on an eaves roof only where the slope, not the hip, is under them
/// (`None` elsewhere).
fn tile_row(kind: RoofKind, detail: u8, x: f32, side: f32) -> Option<TriMesh> {
    let rows = 28 * usize::from(detail);
    let (segments, facets) = (12 * usize::from(detail), 6);
    let r = 0.35 / rows as f32;
    let mut m = TriMesh::default();
    // the slope's extent at this x: past the hip line on RE
    let hip = match kind {
        RoofKind::Clipped => 0.0,
        RoofKind::Eaves => ((x.abs() - 0.25) / 0.25).max(0.0),
    };
    let z0 = 0.5 * hip.max(0.06);
    if z0 >= 0.46 {
        return None;
    }
    // Every ring has the same directions around the tile (computed once:
    // a row is built 113 times a Pailou).
    let around: Vec<Vec3> = (0..=facets)
        .map(|f| {
            let a = std::f32::consts::PI * f as f32 / facets as f32;
            Vec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let ring_vertices = (segments + 2) * (facets + 1) + 1;
    m.positions.reserve_exact(ring_vertices);
    m.normals.reserve_exact(ring_vertices);
    m.indices.reserve_exact(segments * facets * 6 + facets * 3);
    let ring = |k: usize| {
        let z = side * (z0 + (0.5 - z0) * k as f32 / segments as f32);
        let c = Vec3::new(x, surface(kind, x, z), z);
        move |n: Vec3| (c + n * r, n)
    };
    // Rings of shared vertices (smooth round tiles), quads between.
    let mut prev = ring(0);
    let mut prev_at = 0;
    for &n in &around {
        let (p, n) = prev(n);
        m.vertex(p, n);
    }
    for k in 1..=segments {
        let next = ring(k);
        let next_at = m.vertex_count() as u32;
        for &n in &around {
            let (p, n) = next(n);
            m.vertex(p, n);
        }
        for f in 0..facets as u32 {
            let (a, b) = (prev_at + f, prev_at + f + 1);
            let (c, d) = (next_at + f, next_at + f + 1);
            // outward for either slope
            if side > 0.0 {
                m.triangle(a, b, d);
                m.triangle(a, d, c);
            } else {
                m.triangle(b, a, c);
                m.triangle(b, c, d);
            }
        }
        prev = next;
        prev_at = next_at;
    }
    // the disc at the eave end, facing out
    let n = Vec3::Z * side;
    let centre = Vec3::new(x, surface(kind, x, side * 0.5), side * 0.5);
    let c = m.vertex(centre, n);
    let first = m.vertex_count() as u32;
    for &d in &around {
        m.vertex(prev(d).0, n);
    }
    for f in 0..facets as u32 {
        if side > 0.0 {
            m.triangle(c, first + f, first + f + 1);
        } else {
            m.triangle(c, first + f + 1, first + f);
        }
    }
    Some(m)
}

/// A flat-shaded quad a-b-c-d, counter-clockwise seen from outside.
fn quad(m: &mut TriMesh, a: Vec3, b: Vec3, c: Vec3, d: Vec3) {
    flat(m, a, b, c);
    flat(m, a, c, d);
}

/// A flat-shaded triangle a-b-c, counter-clockwise seen from outside.
fn flat(m: &mut TriMesh, a: Vec3, b: Vec3, c: Vec3) {
    let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
    let i = m.vertex(a, n);
    m.vertex(b, n);
    m.vertex(c, n);
    m.triangle(i, i + 1, i + 2);
}

fn cuboid(m: &mut TriMesh, lo: Vec3, hi: Vec3) {
    m.append(&TriMesh::cuboid(lo, hi));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roofs_fill_the_unit_box_and_face_outward() {
        for (kind, detail) in [RoofKind::Clipped, RoofKind::Eaves]
            .into_iter()
            .flat_map(|k| (0..=MAX_DETAIL).map(move |d| (k, d)))
        {
            let m = roof(kind, detail);
            let (lo, hi) = m.bounds().unwrap();
            assert!(
                (lo - Vec3::splat(-0.5)).abs().max_element() < 1e-5,
                "{kind:?} {lo}"
            );
            assert!(
                (hi - Vec3::splat(0.5)).abs().max_element() < 1e-5,
                "{kind:?} {hi}"
            );
            // Every face winds as its normal says.
            for t in m.indices.chunks_exact(3) {
                let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
                let n = (b - a).cross(c - a);
                if n.length() > 1e-9 {
                    assert!(
                        n.dot(m.normals[t[0] as usize]) > 0.0,
                        "{kind:?} {detail} {a} {b} {c} {n} {}",
                        m.normals[t[0] as usize]
                    );
                }
            }
            // Signed volume of the closed pieces: positive when outward.
            let vol = signed_volume(&m);
            assert!(vol > 0.0, "{kind:?} volume {vol}");
        }
    }

    /// The volume a mesh's triangles enclose, positive when they face out.
    fn signed_volume(m: &TriMesh) -> f32 {
        m.indices
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// A clipped roof's gables are closed solids facing outward, their
    /// outer faces at the ends looking away from the middle; an eaves
    /// roof (hipped) has none.
    #[test]
    fn clipped_roofs_have_closed_gable_ends() {
        let mut m = TriMesh::default();
        gables(&mut m, NZ, &|x, z| surface(RoofKind::Clipped, x, z));
        let vol = signed_volume(&m);
        // Two walls, each the profile's area times the thickness.
        let area = 2.0 * GABLE_THICK * (0.6 / 2.7);
        assert!(
            (vol - area).abs() < 0.3 * area,
            "volume {vol}, about {area}"
        );
        let outer: Vec<f32> = m
            .positions
            .iter()
            .zip(&m.normals)
            .filter(|(p, _)| (p.x.abs() - GABLE_X).abs() < 1e-6)
            .map(|(p, n)| p.x * n.x)
            .filter(|d| d.abs() > 1e-3)
            .collect();
        assert!(!outer.is_empty() && outer.iter().all(|&d| d > 0.0));
        // The two bottoms (two triangles, six vertices each) face down;
        // every other level face is a wall's top, under the roof, up.
        let down = m.normals.iter().filter(|n| n.y < -0.999).count();
        assert_eq!(down, 12);
        let eaves = roof(RoofKind::Eaves, 1);
        let flat_ends = eaves.normals.iter().filter(|n| n.x.abs() > 0.999).count();
        let clipped = roof(RoofKind::Clipped, 1);
        let clipped_ends = clipped.normals.iter().filter(|n| n.x.abs() > 0.999).count();
        assert!(
            clipped_ends > flat_ends + 4 * NZ,
            "{clipped_ends} vs {flat_ends}"
        );
    }

    /// Each level has more triangles than the one below; the preview is
    /// light, the default carries tiles.
    #[test]
    fn detail_levels_add_tiles() {
        for kind in [RoofKind::Clipped, RoofKind::Eaves] {
            let n: Vec<usize> = (0..=MAX_DETAIL)
                .map(|d| roof(kind, d).triangle_count())
                .collect();
            assert!(n[0] < 2_000 && n[0] < n[1] && n[1] < n[2], "{kind:?} {n:?}");
            assert!(n[1] > 10_000, "{kind:?} {n:?}");
        }
    }

    #[test]
    fn eaves_corners_turn_up() {
        let corner = |k| height(k, 0.5, 0.5);
        assert!(corner(RoofKind::Eaves) > corner(RoofKind::Clipped) + 0.1);
    }
}
