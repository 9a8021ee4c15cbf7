//! Load: the cross-sections of a cpfg view file's `contour: ID FILE`
//! lines. The view file's text in; each contour file read (confined as
//! includes are, added to the source map so `lsys watch` sees it), its
//! B-spline sampled into the points a generalized cylinder sweeps, out.
//!
//! As cpfg reads them (general.c, `process_contour_file`, `MakeContour`):
//! `cver 1 1` to `cver 1 3` files (`points: N TOTAL`, `type: o|c` open or
//! closed, then `x y z multiplicity` per control point) and the older
//! `N DIM open|closed` files. The control points, each repeated by its
//! multiplicity, make a uniform cubic B-spline (closed ones wrap around),
//! cut into `contour sides:` (8 unless the view file says) pieces of equal
//! length. The points are in the contour's own units: cpfg scales them by
//! the cylinder's radius, x along the turtle's up, y along its right.

use std::path::Path;

use super::include::IncludeFinder;
use crate::source::{FileId, Origin, SourceFile, SourceMap};

/// cpfg's sides of a cylinder without `contour sides:`.
const DEFAULT_SIDES: usize = 8;

/// Curve samples per B-spline segment for the arc-length table.
const SAMPLES_PER_SEGMENT: usize = 32;

/// A cross-section ready to sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// The number `@#(id)` selects it by.
    pub id: u32,
    /// `sides` points (closed) or `sides + 1` (open), equally spaced along
    /// the curve.
    pub points: Vec<[f32; 2]>,
    pub closed: bool,
}

/// Every `contour:` line of the view file `view_id` (at `view`) that
/// names a readable contour; the others are left out (the cylinder is
/// then drawn round, as without the line), each with why in `skipped`.
pub(super) fn contours(
    view_id: FileId,
    view: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> (Vec<Contour>, Vec<String>) {
    let dir = view.parent().unwrap_or(Path::new("."));
    let text = sources.get(view_id).text.clone();
    let sides = super::view::keyed_lines(&text, "contour sides")
        .filter_map(|r| r.split_whitespace().next()?.parse::<usize>().ok())
        .last()
        .unwrap_or(DEFAULT_SIDES)
        .clamp(3, 256);
    let (mut out, mut skipped) = (Vec::new(), Vec::new());
    for rest in super::view::keyed_lines(&text, "contour") {
        let mut words = rest.split_whitespace();
        let (Some(id), Some(file)) = (words.next().and_then(|w| w.parse().ok()), words.next())
        else {
            skipped.push(format!("`contour:{rest}` needs a number and a file"));
            continue;
        };
        let path = dir.join(file);
        let body = match finder.read(&path) {
            Ok(b) => b,
            Err(r) => {
                skipped.push(format!("cannot read {}: {}", path.display(), r.message()));
                continue;
            }
        };
        sources.add(SourceFile::new(
            path.display().to_string(),
            Origin::Disk(path.clone()),
            body.clone(),
        ));
        match parse(&body) {
            Ok((points, closed)) => out.push(Contour {
                id,
                points: sample(&points, closed, sides),
                closed,
            }),
            Err(e) => skipped.push(format!("{}: {e}", path.display())),
        }
    }
    (out, skipped)
}

/// A contour file's control points (multiplicities expanded) and whether
/// it is closed.
fn parse(text: &str) -> Result<(Vec<[f64; 2]>, bool), String> {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines.next().ok_or("the file is empty")?;
    let mut closed = false;
    let mut points = Vec::new();
    if first.starts_with("cver") {
        let mut count = None;
        for line in lines {
            if let Some(v) = line.strip_prefix("points:") {
                count = v
                    .split_whitespace()
                    .next()
                    .and_then(|n| n.parse::<usize>().ok());
            } else if let Some(v) = line.strip_prefix("type:") {
                closed = v.trim().starts_with('c');
            } else if line.contains(':') {
                // name:, samples:, background and markers lines.
            } else {
                let v: Vec<f64> = line
                    .split_whitespace()
                    .map(|w| w.parse().map_err(|_| format!("not a number in `{line}`")))
                    .collect::<Result<_, _>>()?;
                if v.len() < 2 {
                    return Err(format!("a point needs x and y: `{line}`"));
                }
                let m = v.get(3).map_or(1, |&m| m.max(1.0) as usize).min(16);
                points.extend(std::iter::repeat([v[0], v[1]]).take(m));
            }
        }
        if count.is_none() {
            return Err("no `points:` line".into());
        }
    } else {
        // The older form: `N DIM open|closed`, then N points.
        closed = first.split_whitespace().nth(2) == Some("closed");
        for line in lines {
            let v: Vec<f64> = line
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if v.len() >= 2 {
                points.push([v[0], v[1]]);
            }
        }
    }
    if points.len() < 4 {
        return Err("a contour needs at least 4 control points (with multiplicities)".into());
    }
    Ok((points, closed))
}

/// Point `t` (0..=1) of the uniform cubic B-spline segment on `p`.
fn segment(p: [[f64; 2]; 4], t: f64) -> [f64; 2] {
    let (t2, t3) = (t * t, t * t * t);
    let b = [
        (1.0 - t).powi(3) / 6.0,
        (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
        (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
        t3 / 6.0,
    ];
    let mut out = [0.0; 2];
    for (w, q) in b.iter().zip(p) {
        out[0] += w * q[0];
        out[1] += w * q[1];
    }
    out
}

/// `sides` (+1 when open) points equally spaced along the B-spline.
fn sample(points: &[[f64; 2]], closed: bool, sides: usize) -> Vec<[f32; 2]> {
    let n = points.len();
    let segments = if closed { n } else { n - 3 };
    let at = |k: usize| points[k % n];
    let mut dense = Vec::with_capacity(segments * SAMPLES_PER_SEGMENT + 1);
    for s in 0..segments {
        let p = [at(s), at(s + 1), at(s + 2), at(s + 3)];
        for j in 0..SAMPLES_PER_SEGMENT {
            dense.push(segment(p, j as f64 / SAMPLES_PER_SEGMENT as f64));
        }
    }
    let last = [
        at(segments - 1),
        at(segments),
        at(segments + 1),
        at(segments + 2),
    ];
    dense.push(segment(last, 1.0));
    let mut lengths = vec![0.0];
    for w in dense.windows(2) {
        let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        lengths.push(lengths.last().unwrap_or(&0.0) + d);
    }
    let total = *lengths.last().unwrap_or(&0.0);
    let count = if closed { sides } else { sides + 1 };
    let mut j = 0;
    (0..count)
        .map(|k| {
            let target = total * k as f64 / sides as f64;
            while j + 1 < lengths.len() - 1 && lengths[j + 1] < target {
                j += 1;
            }
            let span = lengths[j + 1] - lengths[j];
            let f = if span > 0.0 {
                (target - lengths[j]) / span
            } else {
                0.0
            };
            let f = f.clamp(0.0, 1.0);
            let (a, b) = (dense[j], dense[j + 1]);
            [
                (a[0] + (b[0] - a[0]) * f) as f32,
                (a[1] + (b[1] - a[1]) * f) as f32,
            ]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed square of control points gives a closed round-ish curve:
    /// `sides` points, all at about the same distance from the centre.
    #[test]
    fn a_closed_contour_is_sampled_evenly() {
        let text = "cver 1 2\nname: sq\npoints: 4 4\ntype: cr\n\
                    1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n1 -1 0 1\n";
        let (p, closed) = parse(text).unwrap();
        assert!(closed);
        let s = sample(&p, closed, 8);
        assert_eq!(s.len(), 8);
        let r: Vec<f32> = s
            .iter()
            .map(|q| (q[0] * q[0] + q[1] * q[1]).sqrt())
            .collect();
        let (lo, hi) = r
            .iter()
            .fold((f32::MAX, 0f32), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi - lo < 0.15 * hi, "{r:?}");
    }

    /// An open contour with tripled ends runs from its first control
    /// point to its last.
    #[test]
    fn an_open_contour_reaches_its_ends() {
        let text = "cver 1 3\nname: l\npoints: 3 7\ntype: or\nsamples: 8\n\
                    -2 0 0 3\n0 1 0 1\n2 0 0 3\n";
        let (p, closed) = parse(text).unwrap();
        assert!(!closed);
        let s = sample(&p, closed, 8);
        assert_eq!(s.len(), 9);
        assert!(
            (s[0][0] + 2.0).abs() < 1e-3 && (s[8][0] - 2.0).abs() < 1e-3,
            "{s:?}"
        );
    }
}
