//! Load: cpfg surface files (`.s`). A view file's `surface: f leaf.s 1.5 3
//! 3` line names surface `f` (drawn by `~f`); the file's text in, its
//! bicubic Bézier patches out, already moved, turned and scaled as cpfg
//! places them (the mesh stage tessellates them).
//!
//! The format, as cpfg reads it: six numbers (the control points' extent,
//! unused), an optional `PRECISION S: n T: n`, then `CONTACT POINT X: x Y:
//! y Z: z`, `END POINT ...`, `HEADING ...`, `UP ...`, `SIZE: d`; then
//! patches, each a name, `TOP COLOR: c DIFFUSE: d BOTTOM COLOR: c DIFFUSE:
//! d`, the names of its eight neighbours (`AL: A: AR: L: R: BL: B: BR:`,
//! `~` for none) and 16 control points `x y z`, four rows of four.
//!
//! Placement, as cpfg computes it: the contact point goes to the origin,
//! the whole is scaled so that `SIZE` becomes the view line's size, and
//! each point `(x, y, z)` becomes `x·L + y·H + z·U` with `H` the file's
//! heading, `L = H × U` and `U` its up made square to `H` (for the usual
//! heading +y and up +z, the identity). The turtle then draws x along
//! its left, y along its heading and z along its up, times `~f`'s
//! parameter.

/// One surface a view file names.
#[derive(Clone, Debug, PartialEq)]
pub struct CpfgSurface {
    /// The name `~NAME` draws (one letter in cpfg).
    pub name: String,
    /// The file, as the view file names it (relative to its folder).
    pub file: String,
    /// Subdivisions of each patch along s and t: the view line's, else
    /// the file's `PRECISION`, else 5; at most 10 as in cpfg.
    pub s: u32,
    pub t: u32,
    /// The file's patches in the surface's own frame, or why the file
    /// could not be used.
    pub patches: Result<Vec<Patch>, String>,
}

/// A bicubic Bézier patch, placed (see the module's documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub name: String,
    /// `TOP COLOR` and `BOTTOM COLOR`: cpfg colour indices, 0 for the
    /// turtle's colour.
    pub colours: [u32; 2],
    /// The control points, `points[i][j]`: `i` along s, `j` along t.
    pub points: [[[f64; 3]; 4]; 4],
}

/// The most subdivisions cpfg makes along s or t.
const MAX_PRECISION: u32 = 10;

/// The name, file, size and s, t precision (0: the file's) of one
/// `surface:` line's words after the colon (`f leaf.s 1.5 3 3`). `None`
/// when the line names no surface and file.
pub fn surface_line(words: &[&str]) -> Option<(String, String, f64, u32, u32)> {
    let name = words.first()?.to_string();
    let file = words.get(1)?.to_string();
    let num = |i: usize| words.get(i).and_then(|w| w.parse::<f64>().ok());
    let size = num(2).unwrap_or(1.0);
    let s = num(3).map_or(0, |v| v.max(0.0) as u32);
    let t = num(4).map_or(0, |v| v.max(0.0) as u32);
    Some((name, file, size, s, t))
}

/// A surface file's patches and the precision it gives, if any.
pub type Parsed = (Vec<Patch>, Option<(u32, u32)>);

/// A `.s` file's patches placed for a surface of size `size`, and the
/// file's precision (s, t) when it gives one. `Err` says what is wrong and
/// on which line.
pub fn parse_surface(text: &str, size: f64) -> Result<Parsed, String> {
    let mut c = Cursor::new(text);
    for _ in 0..6 {
        c.number("the control points' extent (six numbers)")?;
    }
    let mut precision = None;
    if c.peek_is("PRECISION") {
        c.word("PRECISION")?;
        c.word("S:")?;
        let s = c.number("the s precision")?;
        c.word("T:")?;
        let t = c.number("the t precision")?;
        precision = Some((s.max(0.0) as u32, t.max(0.0) as u32));
    }
    c.word("CONTACT")?;
    c.word("POINT")?;
    let contact = c.xyz()?;
    c.word("END")?;
    c.word("POINT")?;
    let _end = c.xyz()?;
    c.word("HEADING")?;
    let heading = normalise(c.xyz()?);
    c.word("UP")?;
    let up = normalise(c.xyz()?);
    c.word("SIZE:")?;
    let dimension = c.number("the size")?;
    if dimension == 0.0 || !dimension.is_finite() {
        return Err(format!("line {}: `SIZE:` must not be 0", c.line()));
    }
    let scale = size / dimension;
    let left = cross(heading, up);
    let up = cross(left, heading);
    let mut patches = Vec::new();
    while let Some(name) = c.next_word() {
        c.word("TOP")?;
        c.word("COLOR:")?;
        let top = c.number("the top colour")?;
        c.word("DIFFUSE:")?;
        c.number("the top diffuse")?;
        c.word("BOTTOM")?;
        c.word("COLOR:")?;
        let bottom = c.number("the bottom colour")?;
        c.word("DIFFUSE:")?;
        c.number("the bottom diffuse")?;
        for key in ["AL:", "A:", "AR:", "L:", "R:", "BL:", "B:", "BR:"] {
            c.word(key)?;
            c.next_word()
                .ok_or_else(|| format!("the file ends after `{key}`"))?;
        }
        let mut points = [[[0.0; 3]; 4]; 4];
        for row in &mut points {
            for p in row.iter_mut() {
                let mut v = [0.0; 3];
                for (k, x) in v.iter_mut().enumerate() {
                    *x = (c.number("a control point")? - contact[k]) * scale;
                }
                *p = [0, 1, 2].map(|k| v[0] * left[k] + v[1] * heading[k] + v[2] * up[k]);
            }
        }
        patches.push(Patch {
            name: name.to_string(),
            colours: [top, bottom].map(|c| c.max(0.0) as u32),
            points,
        });
    }
    if patches.is_empty() {
        return Err("the file has no patches".to_string());
    }
    Ok((patches, precision))
}

/// The precision cpfg uses: the view line's when not 0, else the file's
/// (cpfg takes the file's s precision for t as well), else 5; kept in
/// 1..=10.
pub fn precision(view: (u32, u32), file: Option<(u32, u32)>) -> (u32, u32) {
    let fallback = file.map_or(MAX_PRECISION / 2, |(s, _)| s);
    let pick = |v: u32| if v == 0 { fallback } else { v };
    (
        pick(view.0).clamp(1, MAX_PRECISION),
        pick(view.1).clamp(1, MAX_PRECISION),
    )
}

fn normalise(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if l == 0.0 {
        v
    } else {
        v.map(|x| x / l)
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Words of the file with their line numbers; a colon ends a word
/// (`X:0.5` reads as `X:` `0.5`, as C's `scanf("X: %f")` does).
struct Cursor<'a> {
    words: Vec<(usize, &'a str)>,
    at: usize,
}

impl<'a> Cursor<'a> {
    fn new(text: &'a str) -> Self {
        let mut words = Vec::new();
        for (n, line) in text.lines().enumerate() {
            for w in line.split_whitespace() {
                let mut rest = w;
                while let Some(i) = rest.find(':') {
                    words.push((n + 1, &rest[..=i]));
                    rest = &rest[i + 1..];
                }
                if !rest.is_empty() {
                    words.push((n + 1, rest));
                }
            }
        }
        Cursor { words, at: 0 }
    }

    fn line(&self) -> usize {
        self.words
            .get(self.at)
            .or(self.words.last())
            .map_or(1, |w| w.0)
    }

    fn next_word(&mut self) -> Option<&'a str> {
        let w = self.words.get(self.at)?.1;
        self.at += 1;
        Some(w)
    }

    fn peek_is(&self, word: &str) -> bool {
        self.words
            .get(self.at)
            .is_some_and(|w| w.1.eq_ignore_ascii_case(word))
    }

    fn word(&mut self, word: &str) -> Result<(), String> {
        let line = self.line();
        match self.next_word() {
            Some(w) if w.eq_ignore_ascii_case(word) => Ok(()),
            Some(w) => Err(format!("line {line}: expected `{word}`, found `{w}`")),
            None => Err(format!("the file ends where `{word}` should come")),
        }
    }

    fn number(&mut self, what: &str) -> Result<f64, String> {
        let line = self.line();
        match self.next_word() {
            Some(w) => w
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("line {line}: expected {what}, found `{w}`")),
            None => Err(format!("the file ends where {what} should come")),
        }
    }

    fn xyz(&mut self) -> Result<[f64; 3], String> {
        let mut v = [0.0; 3];
        for (k, axis) in ["X:", "Y:", "Z:"].iter().enumerate() {
            self.word(axis)?;
            v[k] = self.number("a coordinate")?;
        }
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square 2 × 2, contact point at the middle of its bottom
    /// edge, heading +y, up +z, size 2.
    pub(crate) const SQUARE: &str = "-1 1 0 2 0 0
CONTACT POINT X: 0 Y: 0 Z: 0
END POINT X: 0 Y: 2 Z: 0
HEADING X: 0 Y: 1 Z: 0
UP X: 0 Y: 0 Z: 1
SIZE: 2
square
TOP COLOR: 3 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0
AL: ~ A: ~ AR: ~
L: ~ R: ~
BL: ~ B: ~ BR: ~
-1 0 0  -1 0.667 0  -1 1.333 0  -1 2 0
-0.333 0 0  -0.333 0.667 0  -0.333 1.333 0  -0.333 2 0
0.333 0 0  0.333 0.667 0  0.333 1.333 0  0.333 2 0
1 0 0  1 0.667 0  1 1.333 0  1 2 0
";

    #[test]
    fn reads_and_places_a_patch() {
        let (patches, precision) = parse_surface(SQUARE, 1.0).unwrap();
        assert_eq!(precision, None);
        assert_eq!(patches.len(), 1);
        assert_eq!(patches[0].colours, [3, 0]);
        // size 1 for SIZE 2: half; heading +y, up +z: x stays x.
        assert_eq!(patches[0].points[0][0], [-0.5, 0.0, 0.0]);
        assert_eq!(patches[0].points[3][3], [0.5, 1.0, 0.0]);
    }

    #[test]
    fn a_turned_frame_turns_the_points() {
        // Heading +x, up +z: L = H × U = -y, and x·L sends the file's
        // (1, 0, 0) to (0, -1, 0), as cpfg computes it.
        let text = SQUARE.replace("HEADING X: 0 Y: 1", "HEADING X: 1 Y: 0");
        let (patches, _) = parse_surface(&text, 2.0).unwrap();
        let p = patches[0].points[3][0];
        assert!((p[1] + 1.0).abs() < 1e-12 && p[0].abs() < 1e-12, "{p:?}");
    }

    #[test]
    fn errors_name_the_line() {
        let text = SQUARE.replace("SIZE: 2", "SIZE: two");
        let e = parse_surface(&text, 1.0).unwrap_err();
        assert!(e.contains("line 6") && e.contains("two"), "{e}");
        let e = parse_surface("0 1 0 1 0 1\nCONTACT POINT X: 0\n", 1.0).unwrap_err();
        assert!(e.contains("ends"), "{e}");
    }

    #[test]
    fn precision_prefers_the_view_line() {
        assert_eq!(precision((3, 4), Some((8, 9))), (3, 4));
        assert_eq!(precision((0, 0), Some((8, 9))), (8, 8));
        assert_eq!(precision((0, 0), None), (5, 5));
        assert_eq!(precision((40, 0), None), (10, 5));
    }
}
