//! The drawing page (seed 003's interaction): an elevation line drawing
//! (a file of the opened folder, or an upload) with the user's separator
//! strokes and label corrections -> the inferred shape tree and grammar
//! (through the driver, as `lsys infer`) and the 3D hall that grammar
//! builds, as the page shows them.
//!
//! The page sends its whole list of strokes and corrections with every
//! change, so the server keeps no history: undo is the page's.

use serde_json::{json, Value};

use super::model::{self, Model};
use crate::driver::{self, Correction, InferFailure, InferOptions, Inference, Ink, INFER_LABELS};

/// Strokes and their points a page may send (a hand draws a few).
const MAX_STROKES: usize = 500;
const MAX_POINTS: usize = 20_000;
/// Corrections a page may send.
const MAX_CORRECTIONS: usize = 2_000;

pub struct DrawingSession {
    /// As the page and messages name it: the file's path in the folder, or
    /// the upload's name.
    pub name: String,
    ink: Ink,
    /// The drawing as read (ink black on white), for the page: its pixels
    /// are the tree's.
    pub png: Vec<u8>,
    lines: Vec<Vec<[f32; 2]>>,
    corrections: Vec<Correction>,
    gap: usize,
    inference: Option<Inference>,
    pub model: Option<Model>,
    /// Why the last reading or build failed (`None`: it did not).
    problem: Option<Value>,
    max_triangles: usize,
}

impl DrawingSession {
    /// Reads `bytes` (PNG or SVG) named `name` and infers its hall.
    pub fn open(name: &str, bytes: &[u8], max_triangles: usize) -> Result<DrawingSession, Value> {
        let ink = driver::read_drawing(bytes, name).map_err(|f| failure_json(&f))?;
        let png = ink_png(&ink);
        let mut s = DrawingSession {
            name: name.to_string(),
            ink,
            png,
            lines: Vec::new(),
            corrections: Vec::new(),
            gap: InferOptions::default().gap,
            inference: None,
            model: None,
            problem: None,
            max_triangles,
        };
        s.infer();
        Ok(s)
    }

    /// Takes the page's strokes, corrections and gap (each optional) and
    /// infers again. A malformed edit is refused whole.
    pub fn edit(&mut self, v: &Value) -> Result<(), Value> {
        let refuse = |m: String| json!({"message": m});
        let lines = match v.get("strokes") {
            None => self.lines.clone(),
            Some(s) => strokes(s).map_err(refuse)?,
        };
        let corrections = match v.get("corrections") {
            None => self.corrections.clone(),
            Some(c) => corrections(c).map_err(refuse)?,
        };
        let gap = match v.get("gap") {
            None => self.gap,
            Some(g) => match g.as_u64() {
                Some(g) if g <= 8 => g as usize,
                _ => return Err(refuse("gap: a whole number of pixels from 0 to 8".into())),
            },
        };
        (self.lines, self.corrections, self.gap) = (lines, corrections, gap);
        self.infer();
        Ok(())
    }

    fn infer(&mut self) {
        let opts = InferOptions {
            gap: self.gap,
            ..InferOptions::default()
        };
        // The build below compiles the grammar: a grammar that does not
        // compile is its diagnostic on the page.
        match driver::infer_edited(&self.ink, &self.name, &self.lines, &self.corrections, &opts) {
            Ok(inference) => {
                let input = driver::Input::Text {
                    name: "inferred.lsys".into(),
                    text: inference.grammar.clone(),
                };
                let defines = &inference.build_defines;
                let job = model::job(
                    input,
                    "inferred.lsys",
                    defines,
                    None,
                    false,
                    self.max_triangles,
                );
                match model::build(&job) {
                    Ok((m, _)) => {
                        self.model = Some(m);
                        self.problem = None;
                    }
                    Err(d) => {
                        self.model = None;
                        self.problem = Some(json!({"diagnostics": model::diagnostics_json(&d)}));
                    }
                }
                self.inference = Some(inference);
            }
            Err(f) => {
                // The last good reading stays on the page, marked stale.
                self.problem = Some(failure_json(&f));
            }
        }
    }

    /// The grammar the page shows and downloads.
    pub fn grammar(&self) -> Option<&str> {
        self.inference.as_ref().map(|i| i.grammar.as_str())
    }

    /// What the page draws: the tree over the drawing, the regions' boxes,
    /// the grammar, the counts, what could not be labelled or corrected.
    pub fn state(&self) -> Value {
        let mut v = json!({
            "name": self.name,
            "width": self.ink.width,
            "height": self.ink.height,
            "strokes": self.lines,
            "corrections": self.corrections.iter().map(|c| json!({"box": c.bbox, "label": c.label})).collect::<Vec<_>>(),
            "gap": self.gap,
            "labels": INFER_LABELS,
            "problem": self.problem,
            "current": self.problem.is_none(),
        });
        if let Some(i) = &self.inference {
            let counts: serde_json::Map<String, Value> = i
                .counts()
                .into_iter()
                .map(|(l, _, n)| (l.to_string(), json!(n)))
                .collect();
            v["tree"] = i.tree_json()["root"].clone();
            v["regions"] = json!(i.regions.iter().map(|r| r.bbox).collect::<Vec<_>>());
            v["unlabelled"] = json!(i.unlabelled);
            v["missed"] = json!(i.missed);
            v["grammar"] = json!(i.grammar);
            v["counts"] = Value::Object(counts);
            // A Pailou's front: its style, type and Toukung levels (the
            // counts alone say nothing of them); null for a hall.
            v["summary"] = json!(i.summary);
        }
        if let Some(m) = &self.model {
            v["triangles"] = json!(m.triangles);
        }
        v
    }
}

/// `[[[x, y], ...], ...]`: polylines in the drawing's pixels.
fn strokes(v: &Value) -> Result<Vec<Vec<[f32; 2]>>, String> {
    let bad = || "strokes: a list of polylines, each a list of [x, y] points".to_string();
    let lines = v.as_array().ok_or_else(bad)?;
    if lines.len() > MAX_STROKES {
        return Err(format!("strokes: at most {MAX_STROKES}"));
    }
    let mut points = 0;
    lines
        .iter()
        .map(|l| {
            let l = l.as_array().ok_or_else(bad)?;
            points += l.len();
            if points > MAX_POINTS {
                return Err(format!("strokes: at most {MAX_POINTS} points in all"));
            }
            l.iter()
                .map(|p| match p.as_array().map(Vec::as_slice) {
                    Some([x, y]) => match (x.as_f64(), y.as_f64()) {
                        (Some(x), Some(y)) => Ok([x as f32, y as f32]),
                        _ => Err(bad()),
                    },
                    _ => Err(bad()),
                })
                .collect()
        })
        .collect()
}

/// `[{"box": [x0, y0, x1, y1], "label": "door"}, ...]`.
fn corrections(v: &Value) -> Result<Vec<Correction>, String> {
    let bad = || {
        "corrections: a list of {\"box\": [x0, y0, x1, y1], \"label\": ...} (a node's box as the tree gives it)"
            .to_string()
    };
    let list = v.as_array().ok_or_else(bad)?;
    if list.len() > MAX_CORRECTIONS {
        return Err(format!("corrections: at most {MAX_CORRECTIONS}"));
    }
    list.iter()
        .map(|c| {
            let label = c["label"].as_str().ok_or_else(bad)?;
            let label = driver::infer_label(label)
                .map_err(|e| format!("corrections: {e}; one of {}", INFER_LABELS.join(", ")))?;
            let b = c["box"]
                .as_array()
                .filter(|b| b.len() == 4)
                .ok_or_else(bad)?;
            let mut bbox = [0i32; 4];
            for (o, n) in bbox.iter_mut().zip(b) {
                *o = n
                    .as_i64()
                    .and_then(|n| i32::try_from(n).ok())
                    .ok_or_else(bad)?;
            }
            Ok(Correction {
                bbox,
                label: label.to_string(),
            })
        })
        .collect()
}

/// A failure as the page shows it: the CLI's rendering and the code.
pub fn failure_json(f: &InferFailure) -> Value {
    match f {
        InferFailure::Drawing(e) => json!({"diagnostics": [model::one_json(e)]}),
        InferFailure::Grammar(d) => json!({"diagnostics": model::diagnostics_json(d)}),
        InferFailure::Write(e) => {
            json!({"diagnostics": [{"message": e.to_string(), "rendered": e.to_string()}]})
        }
    }
}

/// The ink as an 8-bit grey PNG, black on white.
fn ink_png(ink: &Ink) -> Vec<u8> {
    let grey: Vec<u8> = ink.ink.iter().map(|&i| if i { 0 } else { 255 }).collect();
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, ink.width as u32, ink.height as u32);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    let written = enc
        .write_header()
        .and_then(|mut w| w.write_image_data(&grey));
    // Writing to memory fails only on a size the reader already refused.
    debug_assert!(written.is_ok());
    out
}
