//! Drawings of guided seeds: a seed's string in, its turtle drawing moved
//! to the seed's place and clipped to its guide out (an element whose
//! centre is outside the guide is dropped; on the boundary counts inside);
//! and the overlay of guides and links as thin chains.

use glam::{DVec2, Mat4, Vec3};

use super::geometry;
use super::queries::{Element, Placement};
use super::scene::SceneSpec;
use crate::bytecode::Compiled;
use crate::derive::{self, DeriveOptions, ModuleStore};
use crate::resolve::Program;
use crate::turtle::drawing::{Chain, ChainPoints, TubePoint};
use crate::turtle::{self, Drawing, TurtleError, TurtleOptions};

fn plane(v: Vec3) -> DVec2 {
    DVec2::new(v.x as f64, v.y as f64)
}

fn moved(at: &Placement, v: Vec3) -> Vec3 {
    let p = at.point(plane(v));
    Vec3::new(p.x as f32, p.y as f32, v.z)
}

fn turned(at: &Placement, v: Vec3) -> Vec3 {
    let p = at.vector(plane(v));
    Vec3::new(p.x as f32, p.y as f32, v.z)
}

/// The seed's string as the turtle draws it (through the homomorphism),
/// in the seed's own frame.
pub fn local_drawing(
    program: &Program,
    compiled: &Compiled,
    string: &ModuleStore,
    opts: &DeriveOptions,
    step: u32,
) -> Result<Drawing, TurtleError> {
    let topts = TurtleOptions::new(program, None, None, None);
    if program.homomorphism.is_empty() {
        return turtle::interpret(program, string, &topts);
    }
    match derive::homomorphism(program, compiled, string, opts, step) {
        Ok(h) => turtle::interpret(program, &h.modules, &topts),
        Err(_) => turtle::interpret(program, string, &topts),
    }
}

/// `d` moved to `at` and clipped to `guide`: chains split where a segment
/// is dropped, polygons, shapes and placements dropped by their centre.
pub fn place_and_clip(d: &Drawing, at: &Placement, guide: &[DVec2]) -> Drawing {
    let keep = |c: Vec3| geometry::inside(plane(c), guide);
    let mut out = Drawing::default();
    for ch in &d.chains {
        let pts: Vec<TubePoint> = ch
            .points
            .iter()
            .map(|p| TubePoint {
                pos: moved(at, p.pos),
                radius: p.radius,
                up: turned(at, p.up),
            })
            .collect();
        let mut run = ChainPoints::new();
        for w in pts.windows(2) {
            if keep((w[0].pos + w[1].pos) * 0.5) {
                if run.is_empty() {
                    run.push(w[0]);
                }
                run.push(w[1]);
            } else if run.len() > 1 {
                out.chains.push(Chain {
                    colour: ch.colour,
                    points: std::mem::take(&mut run),
                });
            } else {
                run.clear();
            }
        }
        if run.len() > 1 {
            out.chains.push(Chain {
                colour: ch.colour,
                points: run,
            });
        }
    }
    for p in &d.polygons {
        let pts: Vec<Vec3> = p.points.iter().map(|v| moved(at, *v)).collect();
        let c = pts.iter().copied().sum::<Vec3>() / pts.len().max(1) as f32;
        if keep(c) {
            out.polygons.push(crate::turtle::drawing::Polygon {
                colour: p.colour,
                points: pts,
                uv: p.uv.clone(),
            });
        }
    }
    for s in &d.shapes {
        let centre = moved(at, s.centre);
        if keep(centre) {
            out.shapes.push(crate::turtle::drawing::Shape {
                centre,
                normal: turned(at, s.normal),
                ..*s
            });
        }
    }
    let angle = (at.heading - 90.0).to_radians() as f32;
    let m = Mat4::from_translation(Vec3::new(at.origin.x as f32, at.origin.y as f32, 0.0))
        * Mat4::from_rotation_z(angle);
    for p in &d.placements {
        let transform = m * p.transform;
        if keep(transform.w_axis.truncate()) {
            out.placements
                .push(crate::turtle::drawing::Placement { transform, ..*p });
        }
    }
    out
}

/// The drawn segments of a placed, clipped drawing, as elements of `seed`.
pub fn elements(d: &Drawing, seed: usize) -> Vec<Element> {
    d.chains
        .iter()
        .flat_map(|c| {
            c.points.windows(2).map(move |w| Element {
                a: plane(w[0].pos),
                b: plane(w[1].pos),
                seed,
            })
        })
        .filter(|e| e.a.distance(e.b) > geometry::EPS)
        .collect()
}

/// Guides (colour `guide_colour`) and links (`link_colour`: an arrow out
/// of the source edge's middle, one into the target edge's) as chains
/// of width `width`; a guide with a height is drawn as a prism.
pub fn overlay(spec: &SceneSpec, width: f32, guide_colour: u32, link_colour: u32) -> Drawing {
    let mut d = Drawing::default();
    let pt = |p: DVec2, z: f64| TubePoint {
        pos: Vec3::new(p.x as f32, p.y as f32, z as f32),
        radius: width * 0.5,
        up: Vec3::Z,
    };
    let chain = |pts: Vec<TubePoint>, colour| Chain {
        colour,
        points: pts.into(),
    };
    for g in &spec.guides {
        for z in [0.0, g.height]
            .iter()
            .take(if g.height > 0.0 { 2 } else { 1 })
        {
            let mut pts: Vec<TubePoint> = g.points.iter().map(|p| pt(*p, *z)).collect();
            pts.push(pts[0]);
            d.chains.push(chain(pts, guide_colour));
        }
        if g.height > 0.0 {
            for p in &g.points {
                d.chains
                    .push(chain(vec![pt(*p, 0.0), pt(*p, g.height)], guide_colour));
            }
        }
    }
    for l in &spec.links {
        // An arrow across the source edge's middle, pointing out; and one
        // across the target edge's middle, pointing in (snapped guides:
        // one arrow).
        for (g, e, sign) in [(l.from, l.from_edge, -1.0), (l.to, l.to_edge, 1.0)] {
            let (a, b) = spec.guides[g].edge(e);
            let m = (a + b) * 0.5;
            let n = spec.guides[g].inward_normal(e) * sign;
            let s = (b - a).length().min(2.0) * 0.2;
            let (from, tip) = (m - n * s, m + n * s);
            let back = (n.perp() - n) * s * 0.35;
            d.chains.push(chain(
                vec![pt(from, 0.0), pt(tip, 0.0), pt(tip + back, 0.0)],
                link_colour,
            ));
        }
    }
    d
}
