//! The painting page (seed 004's interface): a painting session of the
//! opened folder as the page edits it (a rectangle painted in a view as a
//! component of the palette, a part reshaped from another view, parts
//! deleted, the threshold and reference photos changed) -> the session's
//! `.lsys` text built through the driver, the palette its rules give, the
//! correction's and the constraint rules' reports, and the 3D model.
//!
//! The page sends the whole session with every change besides a paint or
//! a reshape (which the server places, by the configure rules and the
//! correction), so the server keeps no history: undo is the page's.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use super::model;
use crate::driver::{self, Component, Input, PaintDoc, PaintView, Painted};

pub struct PaintSession {
    /// The session's path in the folder (`/`-separated): where it saves.
    pub name: String,
    /// The session file, absolute (its rules are included beside it).
    path: PathBuf,
    doc: PaintDoc,
    palette: Vec<Component>,
    /// What the last paint or reshape did.
    painted: Option<Painted>,
    /// The constraint rules' report of the last good build.
    constraints: Vec<String>,
    diagnostics: Vec<Value>,
    /// Whether the model is the current session's (false: the last good).
    current: bool,
    pub glb: Option<Vec<u8>>,
    triangles: usize,
    max_triangles: usize,
}

/// The threshold a new session starts with (metres).
const THRESHOLD: f64 = 0.25;

impl PaintSession {
    /// The session `rel` (absolute `full`), or a new one there with the
    /// folder's rules file `rules` (relative to the session's folder).
    pub fn open(
        rel: &str,
        full: &Path,
        new: Option<&str>,
        max_triangles: usize,
    ) -> Result<PaintSession, Value> {
        let doc = match new {
            Some(rules) => {
                if full.exists() {
                    return Err(
                        json!({"message": format!("{rel} exists: open it, or name a new session")}),
                    );
                }
                PaintDoc {
                    rules: rules.to_string(),
                    threshold: THRESHOLD,
                    textures: false,
                    photos: Vec::new(),
                    parts: Vec::new(),
                }
            }
            None => {
                let text = std::fs::read_to_string(full)
                    .map_err(|e| json!({"message": format!("cannot read {rel}: {e}")}))?;
                PaintDoc::from_lsys(&text).map_err(|e| json!({"message": format!("{rel}: {e}")}))?
            }
        };
        let mut s = PaintSession {
            name: rel.to_string(),
            path: full.to_path_buf(),
            doc,
            palette: Vec::new(),
            painted: None,
            constraints: Vec::new(),
            diagnostics: Vec::new(),
            current: false,
            glb: None,
            triangles: 0,
            max_triangles,
        };
        s.build();
        Ok(s)
    }

    /// Takes the page's session (an undo, a deletion, the threshold or a
    /// photo changed) and builds it.
    pub fn edit(&mut self, v: &Value) -> Result<(), Value> {
        let doc: PaintDoc =
            serde_json::from_value(v.clone()).map_err(|e| json!({"message": e.to_string()}))?;
        if !doc.threshold.is_finite() || !(0.0..=10.0).contains(&doc.threshold) {
            return Err(json!({"message": "the threshold is a length from 0 to 10"}));
        }
        self.doc = doc;
        self.painted = None;
        self.build();
        Ok(())
    }

    /// Paints `{"view", "rect", "component", "on"?}` (`on`: the part it is
    /// painted on, when the user chose one), or reshapes part `"part"`
    /// from `{"view", "rect"}`: the part placed by the configure rules and
    /// the correction, then the session built.
    pub fn paint(&mut self, v: &Value) -> Result<(), Value> {
        let view = v["view"]
            .as_str()
            .and_then(PaintView::from_name)
            .ok_or_else(|| json!({"message": "a view is front, back, top, left or right"}))?;
        let rect: Vec<f64> = v["rect"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default();
        let [u0, v0, u1, v1] = rect[..] else {
            return Err(json!({"message": "a rectangle is [u0, v0, u1, v1]"}));
        };
        let rect = [u0, v0, u1, v1];
        let parts = &self.doc.parts;
        let t = self.doc.threshold;
        let placed = match v["part"].as_u64() {
            Some(i) if (i as usize) < parts.len() => {
                driver::reshape(parts, i as usize, view, rect, t).map(|p| (Some(i as usize), p))
            }
            Some(i) => return Err(json!({"message": format!("no part {}", i + 1)})),
            None => {
                let c = v["component"].as_str().unwrap_or_default();
                let on = v["on"].as_u64().map(|i| i as usize);
                driver::paint(parts, &self.palette, view, rect, c, t, on).map(|p| (None, p))
            }
        };
        let (at, (part, painted)) =
            placed.map_err(|e| json!({"diagnostics": [model::one_json(&e)]}))?;
        match at {
            Some(i) => self.doc.parts[i] = part,
            None => self.doc.parts.push(part),
        }
        self.painted = Some(painted);
        self.build();
        Ok(())
    }

    /// The session's folder, resolved (its rules are beside it).
    pub fn folder(&self) -> Option<PathBuf> {
        self.path.parent().and_then(|p| p.canonicalize().ok())
    }

    /// The session as its file's text.
    pub fn text(&self) -> String {
        self.doc.to_lsys()
    }

    /// The session built from the text it saves as (so the page's model
    /// is `lsys build`'s), its palette read from the compiled rules.
    fn build(&mut self) {
        let input = Input::Edited {
            path: self.path.clone(),
            text: self.text(),
        };
        let job = model::job(input, &self.name, &[], None, false, self.max_triangles);
        match model::build(&job) {
            Ok((m, g)) => {
                self.palette = driver::painting_palette(&g);
                self.constraints = m.scene.constraints().to_vec();
                self.triangles = m.triangles;
                self.glb = Some(m.glb);
                self.diagnostics = model::diagnostics_json(g.warnings());
                self.current = true;
            }
            Err(d) => {
                self.diagnostics = model::diagnostics_json(&d);
                self.current = false;
            }
        }
    }

    pub fn state(&self) -> Value {
        json!({
            "name": self.name,
            "session": self.doc,
            "palette": self.palette,
            "painted": self.painted,
            "holes": driver::holes(&self.doc.parts, &self.palette),
            "constraints": self.constraints,
            "diagnostics": self.diagnostics,
            "current": self.current,
            "triangles": self.triangles,
            "text": self.text(),
            "rects": self.rects(),
        })
    }

    /// Every part's rectangle in each view and how near the viewer its
    /// front is: `{"front": [[u0, v0, u1, v1, near], ...], ...}`, in the
    /// parts' order (the page draws them far to near).
    fn rects(&self) -> Value {
        let mut out = serde_json::Map::new();
        for view in PaintView::ALL {
            let r: Vec<Value> = self
                .doc
                .parts
                .iter()
                .map(|p| {
                    let [a, b, c, d] = p.rect(view);
                    json!([a, b, c, d, p.front(view)])
                })
                .collect();
            out.insert(view.name().to_string(), Value::Array(r));
        }
        Value::Object(out)
    }
}

/// Whether `text` is a painting session this page wrote (its own lines),
/// which is all a save may replace.
pub fn is_session(text: &str) -> bool {
    text.contains("\n// paint threshold ") && PaintDoc::from_lsys(text).is_ok()
}
