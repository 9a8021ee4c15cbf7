//! Camera: a [`View`] and the scene's vertices -> an orthographic projection
//! from world space to sample coordinates (x right, y down, depth growing
//! towards the viewer) that frames the whole model, and the key light's
//! direction in world space.

use glam::{Vec2, Vec3};

use super::View;
use crate::mesh::Scene;

/// Empty border on each side, as a fraction of the image's width and height.
const MARGIN: f32 = 0.05;

/// Direction towards the key light in camera space (x right, y up, z towards
/// the viewer): from the upper front-left, so that in the iso view a box shows
/// a bright top, a mid-tone front and a dark right side.
const KEY_LIGHT: Vec3 = Vec3::new(-0.4, 0.7, 0.6);

impl View {
    /// Camera axes in world space: screen right, screen up, and `back`, the
    /// direction from the model towards the viewer. Right-handed:
    /// `right = up x back`.
    pub(super) fn basis(self) -> (Vec3, Vec3, Vec3) {
        let (up, back) = match self {
            View::Front => (Vec3::Y, Vec3::Z),
            View::Side => (Vec3::Y, Vec3::X),
            // Looking down with -Z up on screen puts the model's front
            // (+Z) at the bottom of the picture, as in a plan drawing.
            View::Top => (Vec3::NEG_Z, Vec3::Y),
            View::Iso => (Vec3::Y, Vec3::new(1.0, 0.8, 1.0).normalize()),
        };
        let right = up.cross(back).normalize();
        // Re-derive `up` so the basis is orthonormal for the tilted iso view
        // (it keeps world +Y pointing up the screen).
        let up = back.cross(right);
        (right, up, back)
    }
}

/// An orthographic camera fitted to one scene and one image size.
#[derive(Clone, Copy, Debug)]
pub(super) struct Camera {
    right: Vec3,
    up: Vec3,
    back: Vec3,
    /// Centre of the model's projected bounds, in camera units.
    centre: Vec2,
    /// Samples per world unit.
    scale: f32,
    /// Half the image size in samples.
    half: Vec2,
}

impl Camera {
    /// Fits the camera so every vertex of `scene` projects inside an image of
    /// `size` samples, less the margin, centred and with equal scale on both
    /// axes. `None` when the scene has no finite vertex.
    ///
    /// Projecting every vertex (rather than the 8 corners of the world
    /// bounds) keeps the iso view tight: box corners project well outside a
    /// plant's silhouette.
    pub(super) fn frame(scene: &Scene, view: View, size: Vec2) -> Option<Camera> {
        let (right, up, back) = view.basis();
        let mut lo = Vec2::splat(f32::INFINITY);
        let mut hi = Vec2::splat(f32::NEG_INFINITY);
        let mut grow = |p: Vec3| {
            let q = Vec2::new(p.dot(right), p.dot(up));
            if q.is_finite() {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        };
        for s in &scene.strokes {
            s.mesh.positions.iter().for_each(|&p| grow(p));
        }
        for i in &scene.instances {
            let Some(c) = scene.components.get(i.component) else {
                continue;
            };
            for part in c.parts() {
                for &p in &part.mesh.positions {
                    grow(i.transform.transform_point3(p));
                }
            }
        }
        if lo.x > hi.x {
            return None;
        }
        let extent = hi - lo;
        let avail = size * (1.0 - 2.0 * MARGIN);
        // A zero extent (a point, or a flat model seen edge-on) leaves that
        // axis unconstrained; when both are zero any finite scale will do.
        let fit = |avail: f32, extent: f32| {
            if extent > 0.0 {
                avail / extent
            } else {
                f32::INFINITY
            }
        };
        let mut scale = fit(avail.x, extent.x).min(fit(avail.y, extent.y));
        if !(scale.is_finite() && scale > 0.0) {
            scale = 1.0;
        }
        Some(Camera {
            right,
            up,
            back,
            // Halves first: lo + hi can overflow for huge coordinates.
            centre: lo * 0.5 + hi * 0.5,
            scale,
            half: size * 0.5,
        })
    }

    /// World point -> (sample x, sample y downwards, depth). Larger depth is
    /// nearer the viewer.
    #[inline]
    pub(super) fn project(&self, p: Vec3) -> Vec3 {
        let x = p.dot(self.right) - self.centre.x;
        let y = p.dot(self.up) - self.centre.y;
        Vec3::new(
            x * self.scale + self.half.x,
            self.half.y - y * self.scale,
            p.dot(self.back),
        )
    }

    /// Screen right, screen up and towards the viewer, in world space.
    pub(super) fn axes(&self) -> (Vec3, Vec3, Vec3) {
        (self.right, self.up, self.back)
    }

    /// Samples per world unit.
    pub(super) fn scale(&self) -> f32 {
        self.scale
    }

    /// Unit vector from the model towards the viewer.
    pub(super) fn toward_viewer(&self) -> Vec3 {
        self.back
    }

    /// Unit vector towards the key light, in world space.
    pub(super) fn light(&self) -> Vec3 {
        let l = KEY_LIGHT.normalize();
        (self.right * l.x + self.up * l.y + self.back * l.z).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bases_are_right_handed_and_orthonormal() {
        for v in View::ALL {
            let (r, u, b) = v.basis();
            for a in [r, u, b] {
                assert!((a.length() - 1.0).abs() < 1e-6, "{v:?}");
            }
            assert!(r.cross(u).distance(b) < 1e-6, "{v:?}");
            // world +Y never points down the screen
            assert!(u.y >= 0.0, "{v:?}");
        }
        assert_eq!(View::Front.basis(), (Vec3::X, Vec3::Y, Vec3::Z));
        assert_eq!(View::Side.basis(), (Vec3::NEG_Z, Vec3::Y, Vec3::X));
        assert_eq!(View::Top.basis(), (Vec3::X, Vec3::NEG_Z, Vec3::Y));
    }
}
