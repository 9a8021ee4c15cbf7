//! Plane geometry for guides: points and segments of the turtle's drawing
//! plane (x, y) in, distances, ray and segment hits, inside tests and
//! signed angles out. Every test is closed (touching counts) with one
//! tolerance, [`EPS`], so results do not hang on rounding.

use glam::DVec2;

/// Lengths below this are zero: a point this close to an edge is on it.
pub const EPS: f64 = 1e-9;

/// A closed polygon's edges: vertex `k` to vertex `k + 1` (the last one
/// back to the first).
pub fn edges(vertices: &[DVec2]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    (0..vertices.len()).map(move |k| (vertices[k], vertices[(k + 1) % vertices.len()]))
}

/// The point of segment `a`–`b` closest to `p`, and its parameter in [0, 1].
pub fn closest_on_segment(p: DVec2, a: DVec2, b: DVec2) -> (DVec2, f64) {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 <= EPS * EPS {
        return (a, 0.0);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    (a + ab * t, t)
}

/// Distance from `p` to segment `a`–`b`.
pub fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    p.distance(closest_on_segment(p, a, b).0)
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Where segment `p`–`q` meets segment `a`–`b`: the parameters along
/// `p`–`q` and along `a`–`b` of the first common point (collinear overlaps
/// give the one nearest `p`), or `None`.
pub fn segment_hit(p: DVec2, q: DVec2, a: DVec2, b: DVec2) -> Option<(f64, f64)> {
    let r = q - p;
    let s = b - a;
    let denom = cross(r, s);
    let ap = a - p;
    let tol = EPS / r.length().max(EPS);
    if denom.abs() <= EPS * r.length() * s.length() {
        // Parallel: a hit only when collinear and overlapping.
        if cross(ap, r).abs() > EPS * r.length().max(1.0) {
            return None;
        }
        let rr = r.length_squared().max(EPS * EPS);
        let (t0, t1) = (ap.dot(r) / rr, (b - p).dot(r) / rr);
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        if hi < -tol || lo > 1.0 + tol {
            return None;
        }
        let t = lo.max(0.0);
        let pt = p + r * t;
        let u = closest_on_segment(pt, a, b).1;
        return Some((t, u));
    }
    let t = cross(ap, s) / denom;
    let u = cross(ap, r) / denom;
    let ut = EPS / s.length().max(EPS);
    if t < -tol || t > 1.0 + tol || u < -ut || u > 1.0 + ut {
        return None;
    }
    Some((t.clamp(0.0, 1.0), u.clamp(0.0, 1.0)))
}

/// Distance along the ray from `p` in unit direction `dir` to segment
/// `a`–`b`, ignoring hits closer than [`EPS`] (the ray's own start).
pub fn ray_hit(p: DVec2, dir: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let s = b - a;
    let denom = cross(dir, s);
    let ap = a - p;
    if denom.abs() <= EPS {
        // Parallel: the nearest end of a collinear segment ahead.
        if cross(ap, dir).abs() > EPS {
            return None;
        }
        let d = [ap.dot(dir), (b - p).dot(dir)]
            .into_iter()
            .filter(|d| *d > EPS)
            .fold(f64::INFINITY, f64::min);
        return d.is_finite().then_some(d);
    }
    let t = cross(ap, s) / denom;
    let u = cross(ap, dir) / denom;
    let ut = EPS / s.length().max(EPS);
    (t > EPS && u >= -ut && u <= 1.0 + ut).then_some(t)
}

/// Whether `p` is inside the closed polygon or on its boundary.
pub fn inside(p: DVec2, vertices: &[DVec2]) -> bool {
    if edges(vertices).any(|(a, b)| distance_to_segment(p, a, b) <= EPS) {
        return true;
    }
    let mut inside = false;
    for (a, b) in edges(vertices) {
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Twice the signed area: positive for counter-clockwise vertices.
pub fn signed_area2(vertices: &[DVec2]) -> f64 {
    edges(vertices).map(|(a, b)| cross(a, b)).sum()
}

/// The signed angle in degrees from `heading` to `dir`, in (−180, 180],
/// positive to the left (counter-clockwise).
pub fn signed_angle(heading: DVec2, dir: DVec2) -> f64 {
    let a = cross(heading, dir).atan2(heading.dot(dir)).to_degrees();
    if a <= -180.0 {
        a + 360.0
    } else {
        a
    }
}

/// A unit vector at `degrees` counter-clockwise from +x.
pub fn direction(degrees: f64) -> DVec2 {
    let (s, c) = degrees.to_radians().sin_cos();
    DVec2::new(c, s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<DVec2> {
        vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ]
    }

    #[test]
    fn the_boundary_counts_as_inside() {
        let sq = square();
        assert!(inside(DVec2::new(0.5, 0.5), &sq));
        assert!(inside(DVec2::new(1.0, 0.5), &sq));
        assert!(inside(DVec2::new(0.0, 0.0), &sq));
        assert!(!inside(DVec2::new(1.0 + 1e-6, 0.5), &sq));
        assert!(!inside(DVec2::new(-0.5, 0.5), &sq));
    }

    #[test]
    fn angles_are_positive_to_the_left() {
        let h = DVec2::new(0.0, 1.0);
        assert!((signed_angle(h, DVec2::new(-1.0, 0.0)) - 90.0).abs() < 1e-12);
        assert!((signed_angle(h, DVec2::new(1.0, 0.0)) + 90.0).abs() < 1e-12);
        assert_eq!(signed_angle(h, DVec2::new(0.0, -1.0)), 180.0);
    }

    #[test]
    fn segments_touching_at_an_end_hit() {
        let hit = segment_hit(
            DVec2::new(0.5, 0.0),
            DVec2::new(0.5, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(1.0, 1.0),
        );
        let (t, u) = hit.unwrap();
        assert!((t - 1.0).abs() < 1e-12 && (u - 0.5).abs() < 1e-12);
        assert!(segment_hit(
            DVec2::new(0.5, 0.0),
            DVec2::new(0.5, 0.99),
            DVec2::new(0.0, 1.0),
            DVec2::new(1.0, 1.0)
        )
        .is_none());
    }

    #[test]
    fn a_ray_ignores_its_own_start() {
        let d = ray_hit(
            DVec2::new(0.5, 0.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
        );
        assert_eq!(d, None);
        let d = ray_hit(
            DVec2::new(0.5, 0.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(1.0, 2.0),
        );
        assert!((d.unwrap() - 2.0).abs() < 1e-12);
    }
}
