//! Component placements: `~X`, `~X(s)`, `~X(sx,sy,sz)` at the turtle,
//! and `~X` fitted to the scope (docs/shapes.md). Input: the turtle's
//! frame (and scope); output: a [`Placement`] in the drawing.

use glam::{Mat4, Vec3, Vec4};

use super::drawing::Placement;
use super::interp::Turtle;
use super::scope::axes;
use crate::resolve::ir::SymId;
use glam::DVec3;

impl Turtle<'_> {
    /// `~X`, `~X(s)`, `~X(sx,sy,sz)`: the unit box's width (x) along the
    /// turtle's L, its height (y) along H and its front (−z) facing U, with
    /// the middle of its bottom face at the turtle.
    pub(super) fn place(&mut self, sym: SymId, args: &[f64], index: usize) {
        if let (Some(size), []) = (self.state.scope, args) {
            // In a scope, `~X` fills it (docs/shapes.md).
            return self.fit(sym, size, index);
        }
        let s = match *args {
            [] => Vec3::ONE,
            [k] => Vec3::splat(k as f32),
            [x, y, z, ..] => Vec3::new(x as f32, y as f32, z as f32),
            [x, y] => Vec3::new(x as f32, y as f32, 1.0),
        };
        if s.x == 0.0 || s.y == 0.0 || s.z == 0.0 {
            // The paper switches decorations off by scaling them to 0.
            return;
        }
        let f = &self.state.frame;
        let (fl, fh, fu, fp) = (f.l.as_vec3(), f.h.as_vec3(), f.u.as_vec3(), f.pos.as_vec3());
        let transform = Mat4::from_cols(
            (fl * s.x).extend(0.0),
            (fh * s.y).extend(0.0),
            (-fu * s.z).extend(0.0),
            Vec4::from((fp + fh * (s.y * 0.5), 1.0)),
        );
        self.push_placement(sym, transform, index, args.len() <= 1);
    }

    pub(super) fn push_placement(
        &mut self,
        sym: SymId,
        transform: Mat4,
        index: usize,
        uniform: bool,
    ) {
        self.drawing.placements.push(Placement {
            symbol: sym,
            transform,
            colour: self.state.colour,
            module: index,
            uniform,
        });
    }

    /// `~X` in a scope: the unit box stretched to fill it, with the same
    /// orientation as a sized `~X` (width along L, front facing U).
    pub(super) fn fit(&mut self, sym: SymId, size: DVec3, index: usize) {
        let f = &self.state.frame;
        let [x, y, z] = axes(f);
        // A face scope has no depth: give the component a thin one so
        // that it shows (a tenth of its smaller side).
        let depth = if size.z > 0.0 {
            size.z
        } else {
            size.x.min(size.y) * 0.1
        };
        if size.x == 0.0 || size.y == 0.0 || depth == 0.0 {
            return;
        }
        let centre = f.pos + x * (size.x / 2.0) + y * (size.y / 2.0) + z * (size.z / 2.0);
        let transform = Mat4::from_cols(
            (f.l * size.x).as_vec3().extend(0.0),
            (f.h * size.y).as_vec3().extend(0.0),
            (-f.u * depth).as_vec3().extend(0.0),
            Vec4::from((centre.as_vec3(), 1.0)),
        );
        self.push_placement(sym, transform, index, false);
    }
}
