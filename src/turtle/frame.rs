//! The turtle's frame: position and the orthonormal heading H, left L and
//! up U vectors (H × L = U), with the rotations of the turtle commands.
//! Input: rotation angles in degrees; output: the moved frame.

use glam::{Quat, Vec3};

/// World up: the reference for "roll to horizontal" (`@v`, cpfg's `$`).
pub const WORLD_UP: Vec3 = Vec3::Y;

/// Position and orientation. The start frame is cpfg's: heading up the y
/// axis, left along −x, up toward the viewer (+z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub pos: Vec3,
    pub h: Vec3,
    pub l: Vec3,
    pub u: Vec3,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            pos: Vec3::ZERO,
            h: Vec3::Y,
            l: Vec3::NEG_X,
            u: Vec3::Z,
        }
    }
}

impl Frame {
    /// `+(θ)`: turn left about U (H toward L); negative θ turns right.
    pub fn turn(&mut self, degrees: f32) {
        let (s, c) = degrees.to_radians().sin_cos();
        let (h, l) = (self.h, self.l);
        self.h = h * c + l * s;
        self.l = l * c - h * s;
    }

    /// `&(θ)`: pitch down about L (H away from U); negative θ pitches up.
    pub fn pitch(&mut self, degrees: f32) {
        let (s, c) = degrees.to_radians().sin_cos();
        let (h, u) = (self.h, self.u);
        self.h = h * c - u * s;
        self.u = u * c + h * s;
    }

    /// `\(θ)`: roll left about H (U toward L); negative θ rolls right.
    pub fn roll(&mut self, degrees: f32) {
        let (s, c) = degrees.to_radians().sin_cos();
        let (l, u) = (self.l, self.u);
        self.u = u * c + l * s;
        self.l = l * c - u * s;
    }

    /// Rolls about H until L is horizontal (L = V × H / |V × H|). Leaves the
    /// frame alone when H is vertical, where "horizontal" is undefined.
    pub fn roll_to_horizontal(&mut self) {
        let l = WORLD_UP.cross(self.h);
        if l.length_squared() > 1e-12 {
            self.l = l.normalize();
            self.u = self.h.cross(self.l);
        }
    }

    /// Rotates the whole frame by the smallest rotation taking H to `dir`.
    pub fn rotate_heading_to(&mut self, dir: Vec3) {
        let dir = dir.normalize_or_zero();
        if dir == Vec3::ZERO {
            return;
        }
        let q = Quat::from_rotation_arc(self.h, dir);
        self.h = dir;
        self.l = (q * self.l).normalize();
        self.u = self.h.cross(self.l);
    }

    /// Sets H (and U when given), keeping the frame orthonormal.
    pub fn set_heading(&mut self, h: Vec3, u: Option<Vec3>) {
        let h = h.normalize_or_zero();
        if h == Vec3::ZERO {
            return;
        }
        match u {
            Some(u) if u.cross(h).length_squared() > 1e-12 => {
                self.h = h;
                self.l = u.cross(h).normalize();
                self.u = h.cross(self.l);
            }
            _ => self.rotate_heading_to(h),
        }
    }

    /// Tropism (ABOP §2.2): bends H toward `t` by `e·|H × t|` radians.
    pub fn bend(&mut self, t: Vec3, e: f32) {
        let axis = self.h.cross(t);
        let len = axis.length();
        if len < 1e-9 || e == 0.0 {
            return;
        }
        let q = Quat::from_axis_angle(axis / len, e * len);
        self.h = (q * self.h).normalize();
        self.l = (q * self.l).normalize();
        self.u = self.h.cross(self.l);
    }

    /// Undoes the drift of many small rotations.
    pub fn orthonormalize(&mut self) {
        self.h = self.h.normalize();
        self.u = self.h.cross(self.l).normalize();
        self.l = self.u.cross(self.h);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn turn_left_moves_heading_toward_left() {
        let mut f = Frame::default();
        f.turn(90.0);
        assert!(close(f.h, Vec3::NEG_X), "{:?}", f.h);
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn pitch_down_moves_heading_away_from_up() {
        let mut f = Frame::default();
        f.pitch(90.0);
        assert!(close(f.h, Vec3::NEG_Z), "{:?}", f.h);
        assert!(close(f.h.cross(f.l), f.u));
    }

    #[test]
    fn roll_left_tilts_up_toward_left() {
        let mut f = Frame::default();
        f.roll(90.0);
        assert!(close(f.u, Vec3::NEG_X), "{:?}", f.u);
        assert!(close(f.h, Vec3::Y));
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
    fn tropism_bends_toward_the_vector() {
        let mut f = Frame::default();
        f.turn(90.0);
        let before = f.h.dot(Vec3::NEG_Y);
        f.bend(Vec3::NEG_Y, 0.2);
        assert!(f.h.dot(Vec3::NEG_Y) > before);
    }
}
