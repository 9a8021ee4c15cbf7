//! Primitives fitted to a scope (`@Block`, `@Cyl`, `@Prism`; `@Roof` in
//! chinese_roof.rs) and the
//! constraint rule "a hole that intersects a block cuts an opening in it"
//! (`@Hole`). Input: the solids and holes the turtle met, each with its
//! scope; output: polygons for the drawing and one line per cut made.
//!
//! The cut is exact at face level for boxes, not a general mesh boolean:
//! a hole cuts a block when their scopes have parallel axes; the opening
//! goes through the block along its z axis (its thickness), over the part
//! of the hole's x–y rectangle that lies on the block. The block's front
//! and back faces are then tiled by the grid of every opening's edges,
//! leaving out the cells inside an opening, and each opening gets its four
//! reveal faces. Holes at an angle to the block are reported, not cut.

use glam::{DVec3, Vec2, Vec3};

use super::chinese_roof::RoofShape;
use super::drawing::{Polygon, Uv};
use super::frame::Frame;
use super::scope::{axes, frame_from, num};
use crate::lang::scope_commands::Primitive;

/// A primitive or a hole with its scope.
#[derive(Clone, Copy, Debug)]
pub struct Solid {
    pub kind: Primitive,
    pub frame: Frame,
    pub size: DVec3,
    pub colour: u32,
    /// Sides of a cylinder.
    pub sides: usize,
    /// Index of the module in the string (1-based in reports).
    pub module: usize,
    /// Order drawn: a hole cuts only the blocks drawn before it (the
    /// existing scene, as seed 004's T(s, o) tests a new object o against
    /// the scene s), never the window frame drawn after it.
    pub seq: usize,
    /// `@Snap(d)` in force when it was drawn.
    pub snap: f64,
    /// What `@Roof`'s parameters ask for.
    pub roof: Option<RoofShape>,
    /// `@Tex` in force when it was drawn (blocks only use it).
    pub texture: Option<Projection>,
}

/// An opening in a block, in the block's x–y coordinates.
#[derive(Clone, Copy, Debug)]
struct Opening {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

const EPS: f64 = 1e-7;

/// Draws `solids` into polygons, cutting each `holes` opening into the
/// blocks it intersects; returns the polygons and the report lines.
pub fn build(solids: &[Solid], holes: &[Solid]) -> (Vec<Polygon>, Vec<String>) {
    let mut polys = Vec::new();
    let mut report = Vec::new();
    let solids = super::snap::snap(solids, &mut report);
    for s in &solids {
        // A flat scope (a face) has no room for a cylinder or a prism.
        let flat = s.size.z <= 0.0 && s.kind != Primitive::Block;
        if s.size.x <= 0.0 || s.size.y <= 0.0 || flat {
            continue;
        }
        match s.kind {
            Primitive::Block => {
                let b = turned_to_cut(s, holes);
                let openings = openings(&b, holes, &mut report);
                block(&b, &openings, &mut polys);
            }
            Primitive::Cylinder => cylinder(s, &mut polys),
            Primitive::Prism => prism(s, &mut polys),
            Primitive::Roof => {
                if let Some(r) = &s.roof {
                    super::chinese_roof::draw(s, r, &mut polys);
                }
            }
        }
    }
    (polys, report)
}

/// The name `--stats` counts a primitive under.
pub fn kind_name(k: Primitive) -> &'static str {
    match k {
        Primitive::Block => "block",
        Primitive::Cylinder => "cylinder",
        Primitive::Prism => "prism",
        Primitive::Roof => "roof",
    }
}

/// `b` turned so that its z axis is the one the first hole that goes
/// through it along its x or y cuts along (the hole's own z: a window
/// painted on a side wall cuts through the wall's x), the same box with
/// its axes cycled; `b` itself when no hole does (holes cut along z, as
/// they always have).
fn turned_to_cut(b: &Solid, holes: &[Solid]) -> Solid {
    let [bx, by, bz] = axes(&b.frame);
    // A face (no depth) is cut through its own z only.
    if b.size.z.abs() < EPS {
        return *b;
    }
    // The first hole that meets the block and goes through it along
    // the block's x or y, its own z being that axis.
    let along = |h: &Solid| {
        let (lo, hi) = meets(b, h)?;
        let hz = axes(&h.frame)[2];
        [bx, by].iter().enumerate().find_map(|(k, a)| {
            let through = lo[k] <= EPS && hi[k] >= b.size[k] - EPS;
            (hz.dot(*a).abs() > 1.0 - 1e-6 && through).then_some(k)
        })
    };
    let Some(k) = holes.iter().filter(|h| h.seq > b.seq).find_map(along) else {
        return *b;
    };
    let mut t = *b;
    let s = b.size;
    // Cycling the axes keeps the frame right-handed.
    if k == 0 {
        t.frame = frame_from(&b.frame, b.frame.pos, by, bz, bx);
        t.size = DVec3::new(s.y, s.z, s.x);
    } else {
        t.frame = frame_from(&b.frame, b.frame.pos, bz, bx, by);
        t.size = DVec3::new(s.z, s.x, s.y);
    }
    t
}

/// The box of hole `h` in block `b`'s coordinates, when they meet.
fn meets(b: &Solid, h: &Solid) -> Option<(DVec3, DVec3)> {
    let [bx, by, bz] = axes(&b.frame);
    let [hx, hy, hz] = axes(&h.frame);
    let local = |p: DVec3| {
        let d = p - b.frame.pos;
        DVec3::new(d.dot(bx), d.dot(by), d.dot(bz))
    };
    let corners: Vec<DVec3> = (0..8)
        .map(|k| {
            let c = DVec3::new(
                if k & 1 == 0 { 0.0 } else { h.size.x },
                if k & 2 == 0 { 0.0 } else { h.size.y },
                if k & 4 == 0 { 0.0 } else { h.size.z },
            );
            local(h.frame.pos + hx * c.x + hy * c.y + hz * c.z)
        })
        .collect();
    let lo = corners.iter().fold(DVec3::INFINITY, |a, c| a.min(*c));
    let hi = corners.iter().fold(DVec3::NEG_INFINITY, |a, c| a.max(*c));
    let overlap = (0..3).all(|k| lo[k] < b.size[k] - EPS && hi[k] > EPS)
        || (h.size.z == 0.0
            && lo.z >= -EPS
            && hi.z <= b.size.z + EPS
            && (0..2).all(|k| lo[k] < b.size[k] - EPS && hi[k] > EPS));
    overlap.then_some((lo, hi))
}

/// The openings that `holes` cut in block `b` (turned by
/// [`turned_to_cut`]), with a report line each. A hole is cut when its
/// axes are parallel to the block's and its z is the block's z; a hole
/// at an angle, or cutting along another axis than the block's first
/// hole, is reported and not cut.
fn openings(b: &Solid, holes: &[Solid], report: &mut Vec<String>) -> Vec<Opening> {
    let [bx, by, bz] = axes(&b.frame);
    let mut out = Vec::new();
    for h in holes.iter().filter(|h| h.seq > b.seq) {
        let [hx, hy, hz] = axes(&h.frame);
        let Some((lo, hi)) = meets(b, h) else {
            continue;
        };
        let parallel = [hx, hy, hz]
            .iter()
            .all(|a| [bx, by, bz].iter().any(|c| a.dot(*c).abs() > 1.0 - 1e-6));
        if !parallel {
            report.push(format!(
                "hole (module {}) meets block (module {}) at an angle: not cut (only holes parallel to the block are)",
                h.module + 1,
                b.module + 1
            ));
            continue;
        }
        if hz.dot(bz).abs() <= 1.0 - 1e-6 {
            report.push(format!(
                "hole (module {}) meets block (module {}) across another of its axes than its first hole: not cut (a block's openings go through one axis)",
                h.module + 1,
                b.module + 1
            ));
            continue;
        }
        let o = Opening {
            x0: lo.x.max(0.0),
            x1: hi.x.min(b.size.x),
            y0: lo.y.max(0.0),
            y1: hi.y.min(b.size.y),
        };
        let at = h.frame.pos;
        report.push(format!(
            "hole (module {}, at {}, {}, {}) intersects block (module {}): cut an opening {} x {} at ({}, {}) of its face, through its depth {}",
            h.module + 1,
            num(at.x),
            num(at.y),
            num(at.z),
            b.module + 1,
            num(o.x1 - o.x0),
            num(o.y1 - o.y0),
            num(o.x0),
            num(o.y0),
            num(b.size.z)
        ));
        out.push(o);
    }
    out
}

fn push(polys: &mut Vec<Polygon>, colour: u32, pts: &[DVec3]) {
    polys.push(Polygon {
        colour,
        points: pts.iter().map(|p| p.as_vec3()).collect::<Vec<Vec3>>(),
        uv: None,
    });
}

/// A face of block or prism `s`: with texture coordinates when its `@Tex`
/// projection looks at it (the face's outward normal within 75° of the
/// projection's z: a block's face toward it, a roof's slope), else plain.
fn face(polys: &mut Vec<Polygon>, s: &Solid, pts: &[DVec3]) {
    push(polys, s.colour, pts);
    let Some(t) = &s.texture else {
        return;
    };
    // Newell's normal of the outline, as drawn (counter-clockwise outside).
    let mut n = DVec3::ZERO;
    for (i, p) in pts.iter().enumerate() {
        let q = pts[(i + 1) % pts.len()];
        n += DVec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    if n.normalize_or_zero().dot(t.z) > FACING {
        let last = polys.len() - 1;
        polys[last].uv = Some(Box::new(Uv {
            texture: t.texture,
            coords: pts.iter().map(|&p| t.uv(p)).collect(),
        }));
    }
}

/// cos 75°: a face turned further from the projection is not textured.
const FACING: f64 = 0.2588;

/// `@Tex(n, u0, v0, u1, v1)`: texture n's crop laid over the scope it was
/// given in, seen along the scope's z (a planar projection, CGA's
/// `setupProjection` + `projectUV`): a point's place in the scope's x–y
/// rectangle is its place in the crop. Past the scope's edges the image's
/// edge pixels repeat (the exporters clamp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    pub texture: u32,
    pub origin: DVec3,
    pub x: DVec3,
    pub y: DVec3,
    pub z: DVec3,
    /// The scope's width and height.
    pub size: [f64; 2],
    /// u0, v0, u1, v1 in the image, 0..1 from its bottom left.
    pub crop: [f64; 4],
}

impl Projection {
    /// `p`'s texture coordinates, glTF's way: (0, 0) the image's top left.
    pub fn uv(&self, p: DVec3) -> Vec2 {
        let d = p - self.origin;
        let s = d.dot(self.x) / self.size[0].max(1e-12);
        let t = d.dot(self.y) / self.size[1].max(1e-12);
        let [u0, v0, u1, v1] = self.crop;
        Vec2::new(
            (u0 + s * (u1 - u0)) as f32,
            (1.0 - (v0 + t * (v1 - v0))) as f32,
        )
    }
}

/// A box, its front (z = sz) and back (z = 0) faces tiled around openings.
fn block(s: &Solid, openings: &[Opening], polys: &mut Vec<Polygon>) {
    let [x, y, z] = axes(&s.frame);
    let (sx, sy, sz) = (s.size.x, s.size.y, s.size.z);
    let p = |a: f64, b: f64, c: f64| s.frame.pos + x * a + y * b + z * c;
    let flat = sz.abs() < EPS;
    // Sides: left, right, bottom, top (whole; openings go through z).
    if !flat {
        face(
            polys,
            s,
            &[p(0., 0., 0.), p(0., 0., sz), p(0., sy, sz), p(0., sy, 0.)],
        );
        face(
            polys,
            s,
            &[p(sx, 0., 0.), p(sx, sy, 0.), p(sx, sy, sz), p(sx, 0., sz)],
        );
        face(
            polys,
            s,
            &[p(0., 0., 0.), p(sx, 0., 0.), p(sx, 0., sz), p(0., 0., sz)],
        );
        face(
            polys,
            s,
            &[p(0., sy, 0.), p(0., sy, sz), p(sx, sy, sz), p(sx, sy, 0.)],
        );
    }
    // The grid of opening edges over the x–y face.
    let mut xs = vec![0.0, sx];
    let mut ys = vec![0.0, sy];
    for o in openings {
        xs.extend([o.x0, o.x1]);
        ys.extend([o.y0, o.y1]);
    }
    for v in [&mut xs, &mut ys] {
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < EPS);
    }
    for i in 0..xs.len() - 1 {
        for j in 0..ys.len() - 1 {
            let (mx, my) = ((xs[i] + xs[i + 1]) / 2.0, (ys[j] + ys[j + 1]) / 2.0);
            if openings
                .iter()
                .any(|o| mx > o.x0 && mx < o.x1 && my > o.y0 && my < o.y1)
            {
                continue;
            }
            let (a, b, d, e) = (xs[i], xs[i + 1], ys[j], ys[j + 1]);
            face(
                polys,
                s,
                &[p(a, d, sz), p(b, d, sz), p(b, e, sz), p(a, e, sz)],
            );
            if !flat {
                face(
                    polys,
                    s,
                    &[p(a, d, 0.), p(a, e, 0.), p(b, e, 0.), p(b, d, 0.)],
                );
            }
        }
    }
    // Reveals: the opening's four inner faces.
    if !flat {
        for o in openings {
            let (a, b, d, e) = (o.x0, o.x1, o.y0, o.y1);
            face(
                polys,
                s,
                &[p(a, d, 0.), p(b, d, 0.), p(b, d, sz), p(a, d, sz)],
            );
            face(
                polys,
                s,
                &[p(a, e, 0.), p(a, e, sz), p(b, e, sz), p(b, e, 0.)],
            );
            face(
                polys,
                s,
                &[p(a, d, 0.), p(a, d, sz), p(a, e, sz), p(a, e, 0.)],
            );
            face(
                polys,
                s,
                &[p(b, d, 0.), p(b, e, 0.), p(b, e, sz), p(b, d, sz)],
            );
        }
    }
}

/// An upright cylinder inscribed in the scope (elliptic if sx ≠ sz).
fn cylinder(s: &Solid, polys: &mut Vec<Polygon>) {
    let [x, y, z] = axes(&s.frame);
    let n = s.sides.max(3);
    let centre = s.frame.pos + x * (s.size.x / 2.0) + z * (s.size.z / 2.0);
    let ring: Vec<DVec3> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            centre + x * (t.cos() * s.size.x / 2.0) - z * (t.sin() * s.size.z / 2.0)
        })
        .collect();
    let top = y * s.size.y;
    for k in 0..n {
        let (a, b) = (ring[k], ring[(k + 1) % n]);
        push(polys, s.colour, &[a, b, b + top, a + top]);
    }
    let mut cap: Vec<DVec3> = ring.iter().map(|p| *p + top).collect();
    push(polys, s.colour, &cap);
    cap = ring.iter().rev().copied().collect();
    push(polys, s.colour, &cap);
}

/// A gable prism: the ridge runs along x at the top middle of z.
fn prism(s: &Solid, polys: &mut Vec<Polygon>) {
    let [x, y, z] = axes(&s.frame);
    let (sx, sy, sz) = (s.size.x, s.size.y, s.size.z);
    let p = |a: f64, b: f64, c: f64| s.frame.pos + x * a + y * b + z * c;
    face(
        polys,
        s,
        &[
            p(0., 0., sz),
            p(sx, 0., sz),
            p(sx, sy, sz / 2.),
            p(0., sy, sz / 2.),
        ],
    );
    face(
        polys,
        s,
        &[
            p(sx, 0., 0.),
            p(0., 0., 0.),
            p(0., sy, sz / 2.),
            p(sx, sy, sz / 2.),
        ],
    );
    face(
        polys,
        s,
        &[p(0., 0., 0.), p(0., 0., sz), p(0., sy, sz / 2.)],
    );
    face(
        polys,
        s,
        &[p(sx, 0., sz), p(sx, 0., 0.), p(sx, sy, sz / 2.)],
    );
    face(
        polys,
        s,
        &[p(0., 0., 0.), p(sx, 0., 0.), p(sx, 0., sz), p(0., 0., sz)],
    );
}
