//! The turtle's frame: position and the orthonormal heading H, left L and
//! up U vectors (H × L = U), with the rotations of the turtle commands.
//! Input: rotation angles in degrees; output: the moved frame.

use glam::{DQuat, DVec3};

/// World up: the reference for "roll to horizontal" (`@v`, cpfg's `$`).
pub const WORLD_UP: DVec3 = DVec3::Y;

/// The sine and cosine of an angle in degrees, as the rotations take them.
pub fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    degrees.to_radians().sin_cos()
}

/// The sines and cosines of the last two angles turned by: a plant turns
/// by a few angles again and again (W2: +25 and -25 in turn), and libm's
/// sin_cos was a twentieth of the turtle's time. The same angle, bit for
/// bit, gives the same values.
pub struct SinCosCache {
    cache: [(u64, (f64, f64)); 2],
}

impl Default for SinCosCache {
    fn default() -> SinCosCache {
        SinCosCache {
            cache: [(0f64.to_bits(), sin_cos_degrees(0.0)); 2],
        }
    }
}

impl SinCosCache {
    pub fn sin_cos(&mut self, degrees: f64) -> (f64, f64) {
        let bits = degrees.to_bits();
        if self.cache[0].0 == bits {
            return self.cache[0].1;
        }
        if self.cache[1].0 != bits {
            self.cache[1] = (bits, sin_cos_degrees(degrees));
        }
        self.cache.swap(0, 1);
        self.cache[0].1
    }
}

/// Position and orientation. The start frame is cpfg's: heading up the y
/// axis, left along −x, up toward the viewer (+z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub pos: DVec3,
    pub h: DVec3,
    pub l: DVec3,
    pub u: DVec3,
    /// 1 for the paper's right-handed frame (H × L = U), -1 for cpfg's,
    /// which starts with U = −z (H × L = −U).
    pub hand: f64,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            pos: DVec3::ZERO,
            h: DVec3::Y,
            l: DVec3::NEG_X,
            u: DVec3::Z,
            hand: 1.0,
        }
    }
}

impl Frame {
    /// cpfg's start frame: as the default, but with U toward −z, so that
    /// rotations written in H, L and U mirror the model in z as cpfg does.
    /// cpfg's `&` moves H toward this U, not away from it as
    /// [`Frame::pitch`] does: the turtle negates cpfg's pitch angles
    /// (`Action::Pitch` in `interp.rs`).
    pub fn cpfg() -> Frame {
        Frame {
            u: DVec3::NEG_Z,
            hand: -1.0,
            ..Frame::default()
        }
    }

    /// `+(θ)`: turn left about U (H toward L); negative θ turns right.
    pub fn turn(&mut self, degrees: f64) {
        self.turn_by(sin_cos_degrees(degrees));
    }

    /// [`Frame::turn`] by an angle's [`sin_cos_degrees`].
    pub fn turn_by(&mut self, (s, c): (f64, f64)) {
        let (h, l) = (self.h, self.l);
        self.h = h * c + l * s;
        self.l = l * c - h * s;
    }

    /// `&(θ)`: pitch down about L (H away from U); negative θ pitches up.
    pub fn pitch(&mut self, degrees: f64) {
        self.pitch_by(sin_cos_degrees(degrees));
    }

    /// [`Frame::pitch`] by an angle's [`sin_cos_degrees`].
    pub fn pitch_by(&mut self, (s, c): (f64, f64)) {
        let (h, u) = (self.h, self.u);
        self.h = h * c - u * s;
        self.u = u * c + h * s;
    }

    /// `\(θ)`: roll left about H (U toward L); negative θ rolls right.
    pub fn roll(&mut self, degrees: f64) {
        self.roll_by(sin_cos_degrees(degrees));
    }

    /// [`Frame::roll`] by an angle's [`sin_cos_degrees`].
    pub fn roll_by(&mut self, (s, c): (f64, f64)) {
        let (l, u) = (self.l, self.u);
        self.u = u * c + l * s;
        self.l = l * c - u * s;
    }

    /// `@X`: reflects the frame in the plane of H and U (L becomes −L and
    /// the handedness flips), so that turns toward L go the other way and
    /// components placed afterwards are mirror images (negative
    /// determinant).
    pub fn mirror(&mut self) {
        self.l = -self.l;
        self.hand = -self.hand;
    }

    /// Rolls about H until L is horizontal (L = V × H / |V × H|). Leaves the
    /// frame alone when H is vertical, where "horizontal" is undefined.
    pub fn roll_to_horizontal(&mut self) {
        let l = WORLD_UP.cross(self.h);
        if l.length_squared() > 1e-12 {
            self.l = l.normalize();
            self.u = self.h.cross(self.l) * self.hand;
        }
    }

    /// Rotates the whole frame by the smallest rotation taking H to `dir`.
    pub fn rotate_heading_to(&mut self, dir: DVec3) {
        let dir = dir.normalize_or_zero();
        if dir == DVec3::ZERO {
            return;
        }
        let q = DQuat::from_rotation_arc(self.h, dir);
        self.h = dir;
        self.l = (q * self.l).normalize();
        self.u = self.h.cross(self.l) * self.hand;
    }

    /// Sets H (and U when given), keeping the frame orthonormal.
    pub fn set_heading(&mut self, h: DVec3, u: Option<DVec3>) {
        let h = h.normalize_or_zero();
        if h == DVec3::ZERO {
            return;
        }
        match u {
            Some(u) if u.cross(h).length_squared() > 1e-12 => {
                self.h = h;
                self.l = (u.cross(h) * self.hand).normalize();
                self.u = h.cross(self.l) * self.hand;
            }
            _ => self.rotate_heading_to(h),
        }
    }

    /// Tropism (ABOP §2.2): bends H toward `t` by `e·|H × t|` radians.
    pub fn bend(&mut self, t: DVec3, e: f64) {
        let axis = self.h.cross(t);
        let len = axis.length();
        if len < 1e-9 || e == 0.0 {
            return;
        }
        let q = DQuat::from_axis_angle(axis / len, e * len);
        self.h = (q * self.h).normalize();
        self.l = (q * self.l).normalize();
        self.u = self.h.cross(self.l) * self.hand;
    }

    /// Undoes the drift of many small rotations.
    pub fn orthonormalize(&mut self) {
        self.h = self.h.normalize();
        self.u = (self.h.cross(self.l) * self.hand).normalize();
        self.l = self.u.cross(self.h) * self.hand;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn turn_left_moves_heading_toward_left() {
        let mut f = Frame::default();
        f.turn(90.0);
        assert!(close(f.h, DVec3::NEG_X), "{:?}", f.h);
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn pitch_down_moves_heading_away_from_up() {
        let mut f = Frame::default();
        f.pitch(90.0);
        assert!(close(f.h, DVec3::NEG_Z), "{:?}", f.h);
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn roll_left_tilts_up_toward_left() {
        let mut f = Frame::default();
        f.roll(90.0);
        assert!(close(f.u, DVec3::NEG_X), "{:?}", f.u);
        assert!(close(f.h, DVec3::Y));
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn roll_to_horizontal_levels_the_left_axis() {
        let mut f = Frame::default();
        f.turn(30.0);
        f.pitch(40.0);
        f.roll(25.0);
        f.roll_to_horizontal();
        assert!(f.l.y.abs() < 1e-6);
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn cpfg_frame_is_left_handed_and_stays_so() {
        let mut f = Frame::cpfg();
        assert!(close(f.h.cross(f.l), -f.u));
        f.turn(30.0);
        f.pitch(40.0);
        f.roll(25.0);
        f.bend(DVec3::NEG_Y, 0.3);
        f.roll_to_horizontal();
        f.orthonormalize();
        assert!(close(f.h.cross(f.l), -f.u), "{f:?}");
        // Frame::pitch moves H away from U, toward +z here; the turtle
        // negates cpfg's angles, so cpfg's `&` heads toward -z.
        let mut g = Frame::cpfg();
        g.pitch(90.0);
        assert!(close(g.h, DVec3::Z), "{:?}", g.h);
    }

    #[test]
    fn mirror_flips_left_and_handedness_and_keeps_rotations_consistent() {
        let mut f = Frame::default();
        f.mirror();
        assert!(close(f.l, DVec3::X));
        assert!(close(f.h.cross(f.l), -f.u));
        // Turning left now goes toward +x, the mirror of the unmirrored turn.
        f.turn(90.0);
        assert!(close(f.h, DVec3::X), "{:?}", f.h);
        f.pitch(30.0);
        f.roll(20.0);
        f.orthonormalize();
        assert!(close(f.h.cross(f.l), -f.u), "{f:?}");
        f.mirror();
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn tropism_bends_toward_the_vector() {
        let mut f = Frame::default();
        f.turn(90.0);
        let before = f.h.dot(DVec3::NEG_Y);
        f.bend(DVec3::NEG_Y, 0.2);
        assert!(f.h.dot(DVec3::NEG_Y) > before);
    }
}
