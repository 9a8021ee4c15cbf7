//! cpfg's contour curves (`.con` files named on a view file's `curve:`
//! lines): a file's text in, a curve that `curveX/Y/Z(id, s)` evaluates at
//! arc length `s` (0..1) and whose length `curveGAL(id)` gives, out. As
//! cpfg computes them (curveXYZ.cpp, `CCurveXYZ`): the control points,
//! each repeated by its multiplicity, make a uniform cubic B-spline (or a
//! B-spline with end points, or Bézier segments); `samples` points on it
//! (100 unless the view line says) make a table of accumulated chord
//! lengths; `s` is found in that table by bisection and turned back into
//! the curve's parameter by linear interpolation.

/// A contour curve ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub name: String,
    kind: Kind,
    /// Control points, each repeated by its multiplicity.
    points: Vec<[f64; 3]>,
    /// Accumulated chord length at each sample, divided by the total.
    lengths: Vec<f64>,
    /// The total chord length (`curveGAL`).
    pub length: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    BSpline,
    EndPoints,
    Bezier,
}

impl Curve {
    /// Reads a `.con` file's text; `samples` from the view line (cpfg's
    /// default is 100). The error says what is wrong and on which line.
    pub fn parse(name: &str, text: &str, samples: usize) -> Result<Curve, String> {
        let mut declared = None;
        let mut dim = 2;
        let mut kind = Kind::BSpline;
        let mut points = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let line = line.trim();
            let bad = |what: &str| format!("line {}: {what}: `{line}`", n + 1);
            if let Some(v) = line.strip_prefix("points:") {
                if declared.is_some() {
                    return Err(bad("curves inside a curve are not supported"));
                }
                declared = Some(v.trim().parse::<usize>().map_err(|_| bad("not a count"))?);
            } else if let Some(v) = line
                .strip_prefix("dimension:")
                .or_else(|| line.strip_prefix("dim:"))
            {
                dim = v
                    .trim()
                    .parse::<usize>()
                    .map_err(|_| bad("not a dimension"))?;
            } else if let Some(v) = line.strip_prefix("type:") {
                kind = match v.trim() {
                    "bspline" => Kind::BSpline,
                    "bspline-endpoint" => Kind::EndPoints,
                    "bezier" => Kind::Bezier,
                    _ => return Err(bad("this curve type is not supported")),
                };
            } else if line.len() > 2 && !line.contains(':') && !line.starts_with("//") {
                let v: Vec<f64> = line
                    .split_whitespace()
                    .map(|w| w.parse::<f64>().unwrap_or(0.0))
                    .collect();
                if v.len() < dim {
                    return Err(bad(&format!("a point needs {dim} numbers")));
                }
                let z = if dim > 2 { v[2] } else { 0.0 };
                let mult = if dim > 3 { v[3] as usize } else { 1 };
                // Function and contour files cap theirs at 16 too; more
                // is no shape a cubic spline can have, and 1e8 copies of
                // a point aborted for memory (issue 36).
                if mult > 16 {
                    return Err(bad(&format!(
                        "a control point's multiplicity is at most 16, found {}; 3 pins the curve to the point",
                        v[3]
                    )));
                }
                for _ in 0..mult {
                    points.push([v[0], v[1], z]);
                }
            }
        }
        if points.len() < 4 {
            return Err("a curve needs at least 4 control points (with multiplicities)".into());
        }
        let mut c = Curve {
            name: name.to_string(),
            kind,
            points,
            lengths: Vec::new(),
            length: 0.0,
        };
        c.measure(samples.max(2));
        Ok(c)
    }

    /// The table of normalised arc lengths (cpfg's `createAPoints`).
    fn measure(&mut self, samples: usize) {
        let mut total = 0.0;
        let mut prev = self.at_parameter(0.0);
        let mut lengths = vec![0.0];
        for i in 1..samples {
            let p = self.at_parameter(i as f64 / (samples - 1) as f64);
            let d = [p[0] - prev[0], p[1] - prev[1], p[2] - prev[2]];
            total += (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            lengths.push(total);
            prev = p;
        }
        self.length = total;
        self.lengths = lengths.iter().map(|l| l / total).collect();
    }

    /// Coordinate `axis` (0 x, 1 y, 2 z) at arc length `s`, clamped to
    /// 0..1 (cpfg's `CurveCXS`).
    pub fn at(&self, axis: usize, s: f64) -> f64 {
        let s = if s.is_nan() {
            return s;
        } else {
            s.clamp(0.0, 1.0)
        };
        let a = &self.lengths;
        let (mut min, mut max) = (0, a.len() - 1);
        while max - min > 1 {
            let med = (min + max) / 2;
            if a[med] > s {
                max = med;
            } else {
                min = med;
            }
        }
        let t = (min as f64 + (s - a[min]) / (a[max] - a[min])) / (a.len() - 1) as f64;
        self.at_parameter(t)[axis]
    }

    /// The point at curve parameter `t` in 0..1 (cpfg's `calcPValue`).
    fn at_parameter(&self, t: f64) -> [f64; 3] {
        let p = &self.points;
        let n = p.len();
        let mix = |ws: &mut dyn Iterator<Item = (usize, f64)>| {
            let mut out = [0.0; 3];
            for (k, w) in ws {
                for (o, c) in out.iter_mut().zip(p[k]) {
                    *o += c * w;
                }
            }
            out
        };
        match self.kind {
            Kind::BSpline => {
                let i = 3 + (t * (n as f64 - 3.000001)) as usize;
                let u = 3.0 + t * (n as f64 - 3.000001);
                mix(&mut (i - 3..=i).map(|k| (k, uniform(k, u))))
            }
            Kind::EndPoints => {
                let u = t * (n as f64 - 3.000001);
                mix(&mut (0..n).map(|k| (k, clamped(k, u, n))))
            }
            Kind::Bezier => {
                let segs = 1 + (n - 4) / 3;
                let c = ((t / (1.000001 / segs as f64)) as usize).min(segs - 1);
                let u = (t - c as f64 / segs as f64) * segs as f64 / 1.000001;
                mix(&mut (0..4).map(|k| (c * 3 + k, clamped(k, u, 4))))
            }
        }
    }
}

/// The uniform cubic B-spline basis on integer knots (cpfg's `Bi4`).
fn uniform(i: usize, t: f64) -> f64 {
    fn b(i: f64, t: f64, order: u32) -> f64 {
        if order == 1 {
            return if i <= t && t < i + 1.0 { 1.0 } else { 0.0 };
        }
        let o = f64::from(order - 1);
        (t - i) / o * b(i, t, order - 1) + (i + o + 1.0 - t) / o * b(i + 1.0, t, order - 1)
    }
    b(i as f64, t, 4)
}

/// The cubic B-spline basis with end knots repeated (cpfg's `Nk4`) over
/// `n` points: interpolates the first and last points.
fn clamped(k: usize, u: f64, n: usize) -> f64 {
    basis(k as i64, 4, u, n as i64 - 1)
}

fn knot(j: i64, n: i64) -> i64 {
    if j < 4 {
        0
    } else if j > n {
        n - 2
    } else {
        j - 3
    }
}

/// The B-spline basis of order `t` with end knots repeated ([`knot`]),
/// over the points 0..=n.
pub(super) fn basis(k: i64, t: i64, u: f64, n: i64) -> f64 {
    if t == 1 {
        return if knot(k, n) as f64 <= u && u < knot(k + 1, n) as f64 {
            1.0
        } else {
            0.0
        };
    }
    let mut sum = 0.0;
    let div = knot(k + t - 1, n) - knot(k, n);
    if div != 0 {
        sum = (u - knot(k, n) as f64) / div as f64 * basis(k, t - 1, u, n);
    }
    let div = knot(k + t, n) - knot(k + 1, n);
    if div != 0 {
        sum += (knot(k + t, n) as f64 - u) / div as f64 * basis(k + 1, t - 1, u, n);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINE: &str = "version: 1.4\npoints: 4\ntype: bspline\ndimension: 4\n0 0 0 3\n0 1 0 1\n0 2 0 1\n0 3 0 3\n";

    /// A straight curve: its points lie on the y axis, from the first
    /// control point to the last (multiplicity 3 pins the ends), and the
    /// arc length runs evenly along it.
    #[test]
    fn a_straight_curve_is_measured_by_arc_length() {
        let c = Curve::parse("line", LINE, 100).unwrap();
        assert!((c.length - 3.0).abs() < 1e-6, "{}", c.length);
        assert!(c.at(1, 0.0).abs() < 1e-9);
        assert!((c.at(1, 1.0) - 3.0).abs() < 1e-3);
        assert!((c.at(1, 0.5) - 1.5).abs() < 1e-2, "{}", c.at(1, 0.5));
        assert_eq!(c.at(0, 0.3), 0.0);
        // Outside 0..1 the ends.
        assert_eq!(c.at(1, -1.0), c.at(1, 0.0));
    }

    #[test]
    fn too_few_points_and_nested_curves_are_refused() {
        assert!(Curve::parse("x", "points: 2\n0 0\n1 1\n", 100).is_err());
        let nested = "points: 4\npoints: 2\n";
        assert!(Curve::parse("x", nested, 100)
            .unwrap_err()
            .contains("line 2"));
    }
}
