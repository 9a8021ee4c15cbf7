//! The guides page (seed 002's interaction): a guided scene of the opened
//! folder as the page edits it (guides drawn, bent and deleted, links and
//! seeds added and removed, a vertex dragged with the mass–spring system)
//! -> the scene run again through the driver (only the moved guide and
//! those downstream of it when one guide moved), its drawing as the page
//! draws it, the 3D model, and the scene file's text.
//!
//! The page sends the whole scene with every change, so the server keeps
//! no history: undo is the page's.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde_json::{json, Value};

use super::model;
use crate::api::Grammar;
use crate::driver::{self, DragError, Failure, SceneDoc, SceneRun};

/// Segments of the drawing sent to the page, at most (the 3D model has
/// them all).
const MAX_SEGMENTS: usize = 200_000;

pub struct GuideSession {
    /// The scene's path in the folder (`/`-separated): where it saves.
    pub name: String,
    /// The scene's folder, absolute: its grammars are relative to it.
    folder: PathBuf,
    /// The folder the studio opened: every grammar must be inside.
    root: PathBuf,
    doc: SceneDoc,
    run: Option<SceneRun>,
    timings: Value,
    /// The 3D model (the drawing, with the guides and links as lines).
    pub glb: Option<Vec<u8>>,
    triangles: usize,
    problem: Option<Value>,
    max_triangles: usize,
}

impl GuideSession {
    /// The scene `rel` of `root` (absolute `full`), or a new empty one
    /// there when `new`.
    pub fn open(
        root: &Path,
        rel: &str,
        full: &Path,
        new: bool,
        max_triangles: usize,
    ) -> Result<GuideSession, Value> {
        let doc = if new {
            if full.exists() {
                return Err(
                    json!({"message": format!("{rel} exists: open it, or name a new scene")}),
                );
            }
            SceneDoc {
                steps: 30,
                seed: None,
                guide: Vec::new(),
                link: Vec::new(),
                seeds: Vec::new(),
            }
        } else {
            let text = std::fs::read_to_string(full)
                .map_err(|e| json!({"message": format!("cannot read {rel}: {e}")}))?;
            // The located diagnostic of a scene that does not read.
            driver::check_scene(rel, &text)
                .map_err(|e| json!({"diagnostics": [model::one_json(e.as_ref())]}))?;
            SceneDoc::from_toml(&text).map_err(|e| json!({"message": e}))?
        };
        let mut s = GuideSession {
            name: rel.to_string(),
            folder: full.parent().map(Path::to_path_buf).unwrap_or_default(),
            root: root.to_path_buf(),
            doc,
            run: None,
            timings: Value::Null,
            glb: None,
            triangles: 0,
            problem: None,
            max_triangles,
        };
        s.grow();
        Ok(s)
    }

    /// Takes the page's scene and runs it again. A scene that is not one
    /// (or larger than the studio takes) is refused whole; one that reads
    /// but does not check or build is kept, with its diagnostics.
    pub fn edit(&mut self, v: &Value) -> Result<(), Value> {
        self.doc = SceneDoc::from_json(v).map_err(|m| json!({"message": m}))?;
        self.grow();
        Ok(())
    }

    fn grow(&mut self) {
        let t0 = Instant::now();
        let options = Grammar::options().max_triangles(self.max_triangles);
        let run = match SceneRun::new(
            &self.name,
            &self.doc,
            &self.folder,
            std::slice::from_ref(&self.root),
            &options,
            self.run.as_ref(),
        ) {
            Ok(r) => r,
            Err(f) => return self.fail(f),
        };
        let t1 = Instant::now();
        let built = run.model(&options, &self.folder);
        let t2 = Instant::now();
        self.timings = json!({"grow": driver::ms(t1 - t0), "mesh": driver::ms(t2 - t1)});
        self.run = Some(run);
        match built {
            Ok((triangles, glb)) => match model::within_page_limit(glb.len()) {
                Ok(()) => {
                    self.triangles = triangles;
                    self.glb = Some(glb);
                    self.problem = None;
                }
                Err(e) => {
                    self.glb = None;
                    self.problem = Some(json!({"diagnostics": [model::one_json(&e)]}));
                }
            },
            Err(f) => {
                self.glb = None;
                self.problem = Some(failure_json(f));
            }
        }
    }

    /// A scene that did not load or run: the last good run stays on the
    /// page, marked stale.
    fn fail(&mut self, f: Failure) {
        self.problem = Some(failure_json(f));
    }

    /// The scene file's text, as saved.
    pub fn text(&self) -> String {
        self.doc.to_toml()
    }

    /// What the page draws: the scene, every seed's drawing by guide, what
    /// was derived again and how long it took, the problem if any.
    pub fn state(&self) -> Value {
        let mut v = json!({
            "name": self.name,
            "scene": self.doc,
            "text": self.text(),
            "grammars": self.grammars(),
            "problem": self.problem,
            "current": self.problem.is_none(),
            "timings_ms": self.timings,
        });
        if let Some(r) = &self.run {
            let mut left = MAX_SEGMENTS;
            let drawing: Vec<Value> = (0..r.guides())
                .map(|g| {
                    let mut segs = r.segments(g);
                    segs.truncate(left);
                    left -= segs.len();
                    json!(segs)
                })
                .collect();
            v["drawing"] = json!(drawing);
            v["truncated"] = json!(left == 0);
            v["regrown"] = json!(r.regrown);
            v["seeds_run"] = json!(r.seeds());
            v["messages"] = json!(r.messages());
            v["triangles"] = json!(self.triangles);
        }
        v
    }

    /// The grammars a new guide may host: those the scene names, then the
    /// `.lsys` files beside it.
    fn grammars(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mut push = |g: &str| {
            if !out.iter().any(|x| x == g) {
                out.push(g.to_string());
            }
        };
        for g in &self.doc.guide {
            push(&g.grammar);
        }
        let mut beside: Vec<String> = std::fs::read_dir(&self.folder)
            .into_iter()
            .flatten()
            .flatten()
            .filter_map(|e| e.file_name().to_str().map(str::to_string))
            .filter(|n| n.ends_with(".lsys"))
            .collect();
        beside.sort();
        beside.iter().for_each(|g| push(g));
        out
    }

    /// Whether `full` may be replaced by a save: it is new, or it reads
    /// as a guided scene (a file the page did not write is never replaced).
    pub fn may_replace(full: &Path) -> Result<(), String> {
        match std::fs::read_to_string(full) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
            Err(e) => Err(format!("cannot read it: {e}")),
            Ok(t) if driver::check_scene("existing", &t).is_ok() => Ok(()),
            Ok(_) => Err("it is not a guided scene, and is not replaced".into()),
        }
    }

    /// The scene's folder, absolute: a save goes there.
    pub fn folder(&self) -> &Path {
        &self.folder
    }
}

/// The mass–spring drag (seed 002, §4.2): the page's scene as it was when
/// the drag began, guide `g`'s vertex `k` moved to `to`, the vertices
/// `held` fixed -> every guide's points at rest and every seed carried
/// with its guide (mean value coordinates), without running the scene (the page sends the points as an edit when the drag ends).
pub fn springs(v: &Value) -> Result<Value, Value> {
    let refuse = |m: String| json!({"message": m});
    let doc = SceneDoc::from_json(&v["scene"]).map_err(refuse)?;
    let index = |x: &Value| -> Option<(usize, usize)> {
        Some((x[0].as_u64()? as usize, x[1].as_u64()? as usize))
    };
    let bad = || {
        refuse("a drag is {\"scene\", \"vertex\": [guide, point], \"to\": [x, y], \"held\": [[guide, point], ...]}".into())
    };
    let vertex = index(&v["vertex"]).ok_or_else(bad)?;
    let to = match (v["to"][0].as_f64(), v["to"][1].as_f64()) {
        (Some(x), Some(y)) if x.is_finite() && y.is_finite() => [x, y],
        _ => return Err(bad()),
    };
    let held: Vec<(usize, usize)> = match v.get("held") {
        None | Some(Value::Null) => Vec::new(),
        Some(h) => h
            .as_array()
            .ok_or_else(bad)?
            .iter()
            .map(|x| index(x).ok_or_else(bad))
            .collect::<Result<_, _>>()?,
    };
    let d = driver::drag_guides(&doc, vertex, to, &held).map_err(|e| match e {
        DragError::Scene(e) => json!({"diagnostics": [model::one_json(e.as_ref())]}),
        DragError::NoVertex(g, k) => refuse(format!("guide {g} has no vertex {k}")),
    })?;
    // Seeds go with their guides (a seed left outside its guide is an
    // error of the scene).
    let seeds: Vec<Value> = d
        .seeds
        .iter()
        .map(|(p, heading)| json!({"position": p, "heading": heading}))
        .collect();
    Ok(json!({
        "points": d.points,
        "seeds": seeds,
        "sweeps": d.sweeps,
        "strain": d.strain,
        "particles": d.particles,
        "springs": d.springs,
    }))
}

fn failure_json(f: Failure) -> Value {
    json!({"diagnostics": model::diagnostics_json(&f.diagnostics())})
}
