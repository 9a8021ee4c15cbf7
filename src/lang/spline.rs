//! cpfg's function files (`.func`, and galleries `.fset`): text in,
//! [`SplineFn`]s out, and their values as cpfg's `func(id, x)` computes
//! them.
//!
//! A function is a uniform cubic B-spline through its control points,
//! `y` as a function of `x` on [0, 1]. cpfg samples it `samples:` times
//! (finding each `x` by bisection to 0.001) and then interpolates linearly
//! between the samples; both steps are reproduced exactly here so that
//! models derive the numbers cpfg derives.

/// One function of a view file's `function:` lines or function set.
#[derive(Clone, Debug, PartialEq)]
pub struct SplineFn {
    pub name: String,
    /// Control points (each repeated by its multiplicity), as `f32` read
    /// them in cpfg.
    pub points: Vec<(f64, f64)>,
    /// The precomputed samples (empty when `samples:` is 2 or less: the
    /// value is then searched on the curve at every call).
    pub table: Vec<f64>,
    /// Instead of the above: one coordinate (0 x, 1 y, 2 z) of a contour
    /// curve at arc length `x` (cpfg's `curveX/Y/Z(id, x)`), so that the
    /// VM calls both kinds the same way.
    pub contour: Option<(Box<super::curve::Curve>, usize)>,
}

/// Why a function file could not be read: the message and the 1-based line.
#[derive(Clone, Debug, PartialEq)]
pub struct FuncError {
    pub line: usize,
    pub message: String,
}

struct Lines<'a> {
    it: std::iter::Peekable<std::iter::Enumerate<std::str::Lines<'a>>>,
    last: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Lines<'a> {
        Lines {
            it: text.lines().enumerate().peekable(),
            last: 0,
        }
    }

    fn next(&mut self, what: &str) -> Result<&'a str, FuncError> {
        match self.it.next() {
            Some((i, l)) => {
                self.last = i + 1;
                Ok(l.trim())
            }
            None => Err(FuncError {
                line: self.last + 1,
                message: format!("the file ends where {what} was expected"),
            }),
        }
    }

    fn peek_starts(&mut self, prefix: &str) -> bool {
        self.it
            .peek()
            .is_some_and(|(_, l)| l.trim_start().starts_with(prefix))
    }

    fn err(&self, message: String) -> FuncError {
        FuncError {
            line: self.last,
            message,
        }
    }

    fn field(&mut self, key: &str) -> Result<&'a str, FuncError> {
        let l = self.next(&format!("`{key}:`"))?;
        l.strip_prefix(key)
            .and_then(|r| r.trim_start().strip_prefix(':'))
            .map(str::trim)
            .ok_or_else(|| self.err(format!("expected `{key}: ...`, found `{l}`")))
    }
}

/// Reads one `.func` file: format `fver 1 1`, which says its own number
/// of samples, or the older `range: 0 1` format, which takes `samples`
/// from the view file's `function:` line.
pub fn parse_func(text: &str, samples: usize) -> Result<SplineFn, FuncError> {
    let mut lines = Lines::new(text);
    if lines.peek_starts("range:") {
        lines.next("`range:`")?;
        let mut f = SplineFn {
            contour: None,
            name: String::new(),
            points: read_points(&mut lines)?,
            table: Vec::new(),
        };
        f.precompute(samples.min(1_000_000));
        return Ok(f);
    }
    read_one(&mut lines)
}

/// Reads a function gallery (`.fset`, `funcgalleryver 1 1`).
pub fn parse_gallery(text: &str) -> Result<Vec<SplineFn>, FuncError> {
    let mut lines = Lines::new(text);
    let head = lines.next("`funcgalleryver 1 1`")?;
    if !head.starts_with("funcgalleryver") {
        return Err(lines.err(format!("expected `funcgalleryver 1 1`, found `{head}`")));
    }
    let items = lines.field("items")?;
    let n: usize = items
        .parse()
        .map_err(|_| lines.err(format!("`items:` must be a count, found `{items}`")))?;
    (0..n).map(|_| read_one(&mut lines)).collect()
}

fn read_one(lines: &mut Lines) -> Result<SplineFn, FuncError> {
    let head = lines.next("`fver 1 1`")?;
    let ver: Vec<&str> = head.split_whitespace().collect();
    if ver.first() != Some(&"fver") {
        return Err(lines.err(format!(
            "expected `fver 1 1`, found `{head}` (the old `range:` format is not supported; save the function again with funcedit)"
        )));
    }
    if ver.get(1..3) != Some(&["1", "1"][..]) {
        return Err(lines.err(format!(
            "function format `{head}` is not supported (only `fver 1 1`)"
        )));
    }
    let name = lines.field("name")?.to_string();
    let samples_text = lines.field("samples")?;
    let samples: usize = samples_text.parse().map_err(|_| {
        lines.err(format!(
            "`samples:` must be a count, found `{samples_text}`"
        ))
    })?;
    if samples > 1_000_000 {
        return Err(lines.err(format!(
            "{samples} samples is more than the 1000000 allowed"
        )));
    }
    if lines.peek_starts("b") {
        lines.next("a background line")?;
        lines.next("a background line")?;
    }
    if lines.peek_starts("m") {
        let m = lines.field("markers")?;
        let n: usize = m
            .parse()
            .map_err(|_| lines.err(format!("`markers:` must be a count, found `{m}`")))?;
        for _ in 0..n {
            lines.next("a marker")?;
        }
    }
    lines.next("`flip:`")?;
    let mut f = SplineFn {
        contour: None,
        name,
        points: read_points(lines)?,
        table: Vec::new(),
    };
    f.precompute(samples);
    Ok(f)
}

/// `points: n` and the n points `x y [multiplicity]`.
fn read_points(lines: &mut Lines) -> Result<Vec<(f64, f64)>, FuncError> {
    let pts_text = lines.field("points")?;
    let npts: usize = pts_text
        .parse()
        .map_err(|_| lines.err(format!("`points:` must be a count, found `{pts_text}`")))?;
    if npts < 4 {
        return Err(lines.err(format!(
            "a function needs at least 4 points, this one has {npts}"
        )));
    }
    let mut points = Vec::new();
    for _ in 0..npts {
        let l = lines.next("a point `x y`")?;
        let v: Vec<&str> = l.split_whitespace().collect();
        let num = |s: &str| -> Result<f64, FuncError> {
            s.parse::<f32>()
                .map(f64::from)
                .map_err(|_| lines.err(format!("`{s}` is not a number")))
        };
        if !(2..=3).contains(&v.len()) {
            return Err(lines.err(format!(
                "a point is `x y` or `x y multiplicity`, found `{l}`"
            )));
        }
        let (x, y) = (num(v[0])?, num(v[1])?);
        let mult = match v.get(2) {
            Some(m) => (num(m)? as i64).clamp(1, 16) as usize,
            None => 1,
        };
        points.extend(std::iter::repeat((x, y)).take(mult));
    }
    Ok(points)
}

impl SplineFn {
    /// Sample the curve `samples` times, as cpfg does when there are more
    /// than 2 (with 2 or fewer every call searches the curve).
    fn precompute(&mut self, samples: usize) {
        if samples > 2 {
            self.table = (0..samples)
                .map(|i| self.value(i as f64 / (samples - 1) as f64))
                .collect();
        }
    }

    /// cpfg's `func(id, x)`: `x` is clamped to [0, 1].
    pub fn value(&self, x: f64) -> f64 {
        if let Some((curve, axis)) = &self.contour {
            return curve.at(*axis, x);
        }
        let v = if x < 0.0 {
            0.0
        } else if x > 1.0 {
            1.0
        } else if x.is_nan() {
            return x;
        } else {
            x
        };
        if self.table.len() > 2 {
            let s = self.table.len();
            let index = v * (s - 1) as f64;
            let i = index.floor() as usize;
            if i >= s - 1 {
                return self.table[s - 1];
            }
            let (w1, w2) = (1.0 - index + i as f64, index - i as f64);
            return w1 * self.table[i] + w2 * self.table[i + 1];
        }
        self.search(v)
    }

    /// The curve's `y` where its `x` is within 0.001 of `v`, by bisection
    /// on the curve parameter (cpfg's method, with a cap on the rounds for
    /// curves that never get that close).
    fn search(&self, v: f64) -> f64 {
        let (mut low, mut high) = (0.0f64, 1.0f64);
        let mut tst = (0.0, 0.0);
        for _ in 0..200 {
            let check = (low + high) / 2.0;
            tst = self.point(check);
            if tst.0 > v {
                high = check;
            } else {
                low = check;
            }
            if (tst.0 - v).abs() <= 0.001 {
                break;
            }
        }
        tst.1
    }

    /// The point at parameter `d` in [0, 1]: order-4 B-spline with
    /// integer knots, clamped at both ends.
    fn point(&self, d: f64) -> (f64, f64) {
        let n = self.points.len() as i64 - 1;
        let u = d * (n - 2) as f64;
        let mut sum = (0.0, 0.0);
        for (k, p) in self.points.iter().enumerate() {
            let w = super::curve::basis(k as i64, 4, u, n);
            sum.0 += p.0 * w;
            sum.1 += p.1 * w;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINE: &str = "fver 1 1\nname: ramp\nsamples: 5\nflip: off\npoints: 4\n0 0\n0.333333 0.333333\n0.666667 0.666667\n1 1\n";

    #[test]
    fn a_straight_line_is_itself() {
        let f = parse_func(LINE, 0).unwrap();
        assert_eq!(f.name, "ramp");
        assert_eq!(f.table.len(), 5);
        for x in [0.0, 0.1, 0.5, 0.77, 1.0] {
            assert!((f.value(x) - x).abs() < 0.002, "f({x}) = {}", f.value(x));
        }
        // Clamped outside [0, 1].
        assert!((f.value(2.0) - f.value(1.0)).abs() < 1e-12);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse_func(
            "fver 1 1\nname: x\nsamples: 3\nflip: off\npoints: 2\n0 0\n1 1\n",
            0,
        )
        .unwrap_err();
        assert_eq!(e.line, 5);
        assert!(e.message.contains("at least 4 points"));
        let e = parse_func("fver 1 1\nname: x\nsamples: z\n", 0).unwrap_err();
        assert_eq!(e.line, 3);
    }

    #[test]
    fn a_gallery_holds_several() {
        let g = format!(
            "funcgalleryver 1 1\nitems: 2\n{LINE}{}",
            LINE.replace("ramp", "two")
        );
        let fs = parse_gallery(&g).unwrap();
        assert_eq!(
            fs.iter().map(|f| f.name.as_str()).collect::<Vec<_>>(),
            ["ramp", "two"]
        );
    }
}
