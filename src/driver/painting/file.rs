//! A painting session's file: a [`PaintDoc`] (the rules it includes, the
//! threshold, reference photos and painted parts) <-> the `.lsys` text
//! that `lsys build` rebuilds to the page's model. Each part is one line
//! of the axiom, `[@M(x, y, z) @Scope(sx, sy, sz) Name]  // paint VIEW`:
//! its box's corner and size and the component whose construction rule
//! fills it. What only the page needs (threshold, photos) is in comments
//! starting `// paint`, which the compiler skips.

use serde::{Deserialize, Serialize};

use super::{number, PaintView, Part};

/// A painting session.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PaintDoc {
    /// The rules file, relative to the session's file (`#include`).
    pub rules: String,
    /// The automatic correction's threshold.
    pub threshold: f64,
    /// Whether each part's faces toward the view it was painted in show
    /// the photo under that view (seed 004, §5.1): a `texture i:` header
    /// per photo and `@Tex` with the part's crop.
    #[serde(default)]
    pub textures: bool,
    #[serde(default)]
    pub photos: Vec<Photo>,
    #[serde(default)]
    pub parts: Vec<Part>,
}

/// A reference photo under a view: an image of the session's folder
/// stretched over `rect` (`[u0, v0, u1, v1]` in the view).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Photo {
    pub view: PaintView,
    pub file: String,
    pub rect: [f64; 4],
}

/// Steps the session derives: the rules' shapes are rewritten once each,
/// so their nesting depth; a rules file that nests deeper says so with
/// its own `derivation length:` after the include.
const STEPS: u32 = 16;

impl PaintDoc {
    /// The session as the `.lsys` file the page saves.
    pub fn to_lsys(&self) -> String {
        let mut s = String::from(
            "/* A painting session of the lsys studio (the /paint page, seed 004's\n   \
             interface). Each part of the axiom is a rectangle painted in one\n   \
             view, its third dimension from the rules' configure rules (DEPTH_,\n   \
             THROUGH_) and its edges corrected within the threshold; the\n   \
             construction rules fill it in. Rebuild with `lsys build`. The\n   \
             `// paint` lines are the page's. */\n",
        );
        s += &format!("// paint threshold {}\n", number(self.threshold));
        if self.textures {
            s += "// paint textures\n";
        }
        for p in &self.photos {
            s += &format!(
                "// paint photo {} {} {} {} {} {}\n",
                p.view.name(),
                p.file,
                number(p.rect[0]),
                number(p.rect[1]),
                number(p.rect[2]),
                number(p.rect[3])
            );
        }
        s += &format!(
            "\nderivation length: {STEPS}\n#include \"{}\"\n",
            self.rules
        );
        // The photos as textures, numbered in order.
        let textured: Vec<&Photo> = if self.textures {
            self.photos.iter().collect()
        } else {
            Vec::new()
        };
        for (k, p) in textured.iter().enumerate() {
            s += &format!("texture {}: \"{}\"\n", k + 1, p.file);
        }
        s += "\nAxiom:";
        for p in &self.parts {
            let (corner, turn, size) = p.scope();
            let three = |v: [f64; 3]| v.map(number).join(", ");
            let tex = textured
                .iter()
                .position(|ph| ph.view == p.view)
                .map(|k| {
                    let crop = crop(&p.rect(p.view), &textured[k].rect);
                    format!(" @Tex({}, {})", k + 1, crop.map(number).join(", "))
                })
                .unwrap_or_default();
            s += &format!(
                "\n  [@M({}) {turn}@Scope({}){tex} {}]  // paint {}",
                three(corner),
                three(size),
                p.component,
                p.view.name()
            );
        }
        s.push('\n');
        s
    }

    /// Reads a session back from the text [`PaintDoc::to_lsys`] writes
    /// (edited by hand or not): the error names the line and column of
    /// what does not read.
    pub fn from_lsys(text: &str) -> Result<PaintDoc, PaintFileError> {
        let mut doc = PaintDoc {
            rules: String::new(),
            threshold: 0.0,
            textures: false,
            photos: Vec::new(),
            parts: Vec::new(),
        };
        let mut in_axiom = false;
        let mut in_comment = false;
        for (n, line) in text.lines().enumerate() {
            let at = |col: usize, what: &str| PaintFileError {
                line: n + 1,
                col: col + 1,
                what: what.to_string(),
            };
            let t = line.trim_start();
            let indent = line.len() - t.len();
            if in_comment {
                in_comment = !line.contains("*/");
                continue;
            }
            if t.starts_with("/*") {
                in_comment = !t.contains("*/");
                continue;
            }
            if t.trim_end() == "// paint textures" {
                doc.textures = true;
            } else if t.starts_with("texture ") {
                // Written from the photos.
            } else if let Some(rest) = t.strip_prefix("// paint threshold ") {
                doc.threshold = rest
                    .trim()
                    .parse()
                    .ok()
                    .filter(|x: &f64| x.is_finite() && *x >= 0.0)
                    .ok_or_else(|| at(indent, "a threshold is a number ≥ 0"))?;
            } else if let Some(rest) = t.strip_prefix("// paint photo ") {
                let w: Vec<&str> = rest.split_whitespace().collect();
                let view = w.first().and_then(|v| PaintView::from_name(v));
                let rect: Vec<f64> = w.iter().skip(2).filter_map(|x| x.parse().ok()).collect();
                match (view, w.get(1), rect.len(), w.len()) {
                    (Some(view), Some(file), 4, 6) => doc.photos.push(Photo {
                        view,
                        file: file.to_string(),
                        rect: [rect[0], rect[1], rect[2], rect[3]],
                    }),
                    _ => {
                        return Err(at(
                            indent,
                            "a photo is `// paint photo VIEW FILE u0 v0 u1 v1`",
                        ))
                    }
                }
            } else if let Some(rest) = t.strip_prefix("#include") {
                let name = rest.trim().trim_matches('"');
                if doc.rules.is_empty() {
                    doc.rules = name.to_string();
                }
            } else if let Some(rest) = t.strip_prefix("Axiom:") {
                in_axiom = true;
                if !rest.trim().is_empty() {
                    return Err(at(indent + 6, "the parts start on the line after `Axiom:`"));
                }
            } else if in_axiom && !t.is_empty() && !t.starts_with("//") {
                doc.parts.push(part(t).ok_or_else(|| {
                    at(
                        indent,
                        "a painted part is `[@M(x, y, z) @Scope(sx, sy, sz) Name]  // paint VIEW`, with the view's turn before `@Scope` (`/(90)` for the right view)",
                    )
                })?);
            }
        }
        if doc.rules.is_empty() {
            return Err(PaintFileError {
                line: 1,
                col: 1,
                what: "a painting session includes its rules: `#include \"house.rules\"`".into(),
            });
        }
        Ok(doc)
    }
}

/// Where rectangle `r` lies in the photo stretched over `photo` (both
/// `[u0, v0, u1, v1]` in one view): `@Tex`'s crop, 0..1 from the photo's
/// bottom left (outside it where the part reaches past the photo).
fn crop(r: &[f64; 4], photo: &[f64; 4]) -> [f64; 4] {
    let w = (photo[2] - photo[0]).max(1e-9);
    let h = (photo[3] - photo[1]).max(1e-9);
    [
        (r[0] - photo[0]) / w,
        (r[1] - photo[1]) / h,
        (r[2] - photo[0]) / w,
        (r[3] - photo[1]) / h,
    ]
}

/// One axiom line: `[@M(x, y, z) TURN @Scope(sx, sy, sz) Name]  // paint
/// VIEW`, where TURN is the view's ([`PaintView::turn`]).
fn part(t: &str) -> Option<Part> {
    let (body, comment) = t.split_once("//")?;
    let view = PaintView::from_name(comment.trim().strip_prefix("paint")?.trim())?;
    let body = body.trim().strip_prefix("[@M(")?.strip_suffix(']')?;
    let (at, rest) = body.split_once(')')?;
    let rest = rest.trim_start().strip_prefix(view.turn().trim())?;
    let rest = rest.trim_start().strip_prefix("@Scope(")?;
    let (size, name) = rest.split_once(')')?;
    // `@Tex(...)` is written from the photos.
    let name = match name.trim_start().strip_prefix("@Tex(") {
        Some(tex) => tex.split_once(')')?.1,
        None => name,
    };
    let three = |s: &str| -> Option<[f64; 3]> {
        let v: Vec<f64> = s
            .split(',')
            .map(|x| x.trim().parse().ok())
            .collect::<Option<_>>()?;
        (v.len() == 3 && v.iter().all(|x| x.is_finite())).then(|| [v[0], v[1], v[2]])
    };
    let (corner, size) = (three(at)?, three(size)?);
    let name = name.trim();
    let ident = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !ident || size.iter().any(|&s| s <= 0.0) {
        return None;
    }
    Some(Part::from_scope(name.to_string(), view, corner, size))
}

/// A line of a session file that does not read as one.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("line {line}, column {col}: {what}")]
#[diagnostic(
    code(lsys::driver::paint_file),
    help("the painting page writes these files; fix the line or paint the session again")
)]
pub struct PaintFileError {
    pub line: usize,
    pub col: usize,
    pub what: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc() -> PaintDoc {
        PaintDoc {
            rules: "house.rules".into(),
            threshold: 0.25,
            textures: true,
            photos: vec![Photo {
                view: PaintView::Front,
                file: "villa.png".into(),
                rect: [-1.0, 0.0, 13.0, 9.5],
            }],
            parts: vec![
                Part {
                    component: "Wall".into(),
                    view: PaintView::Front,
                    min: [0.0, 0.0, 0.0],
                    max: [10.0, 3.2, 6.0],
                },
                Part {
                    component: "Window".into(),
                    view: PaintView::Left,
                    min: [-0.25, 1.0, 2.0],
                    max: [0.25, 2.3333, 3.0],
                },
            ],
        }
    }

    #[test]
    fn a_session_reads_back_as_written() {
        let text = doc().to_lsys();
        insta::assert_snapshot!(text);
        let mut back = PaintDoc::from_lsys(&text).unwrap();
        // Written to 3 decimals.
        back.parts[1].max[1] = 2.3333;
        assert_eq!(back, doc());
    }

    #[test]
    fn a_line_that_is_no_part_is_named() {
        let text = doc()
            .to_lsys()
            .replace("@Scope(10, 3.2, 6) @Tex", "@Scope(10, 3.2) @Tex");
        let e = PaintDoc::from_lsys(&text).unwrap_err();
        assert_eq!((e.line, e.col), (16, 3));
        let text = doc().to_lsys().replace("#include", "// #include");
        assert_eq!(PaintDoc::from_lsys(&text).unwrap_err().line, 1);
    }
}
