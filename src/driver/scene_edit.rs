//! A guided scene edited in memory (the studio's guides page): the scene's
//! tables ([`SceneDoc`]) and the run before in; the scene checked,
//! compiled and run (only the guides downstream of a moved one derive
//! again) as a [`SceneRun`], its drawing by guide and its model out; and
//! a mass–spring drag of the guides ([`drag_guides`], seed 002 §4.2).

use std::path::{Path, PathBuf};

use glam::DVec2;

use super::guided::{guided_failure, mesh_guided};
use super::run::{model_bytes, Failure};
use crate::api::GrammarOptions;
use crate::export::output::Format;
use crate::guided::springs::Springs;
use crate::guided::{self, scene};

pub use crate::guided::document::SceneDoc;

/// A scene's tables run: the compiled scene and what its seeds did.
pub struct SceneRun {
    loaded: guided::Loaded,
    outcome: guided::Outcome,
    /// The guides this run derived (all of them, or the moved one and
    /// those downstream of it).
    pub regrown: Vec<usize>,
}

impl SceneRun {
    /// Checks `doc` (named `name` in diagnostics; its grammars relative to
    /// `folder` and inside one of `allowed`), compiles and runs it; with
    /// `before`, a run of the same scene but for one guide's points
    /// derives only that guide and those downstream of it again.
    pub fn new(
        name: &str,
        doc: &SceneDoc,
        folder: &Path,
        allowed: &[PathBuf],
        options: &GrammarOptions,
        before: Option<&SceneRun>,
    ) -> Result<SceneRun, Failure> {
        let loaded = load_scene_text(name, &doc.to_toml(), folder, allowed, options)?;
        let (outcome, regrown) = grow_scene(&loaded, before.map(|b| (&b.loaded, &b.outcome)))?;
        Ok(SceneRun {
            loaded,
            outcome,
            regrown,
        })
    }

    pub fn guides(&self) -> usize {
        self.loaded.spec.guides.len()
    }

    /// Seeds run (explicit and from messages).
    pub fn seeds(&self) -> usize {
        self.outcome.seeds.len()
    }

    pub fn messages(&self) -> usize {
        self.outcome.messages.len()
    }

    /// What guide `g`'s seeds drew, placed and clipped, as segments
    /// `[x0, y0, x1, y1]` in the plane.
    pub fn segments(&self, g: usize) -> Vec<[f64; 4]> {
        guided::run::guide_elements(&self.outcome, g)
            .iter()
            .map(|e| [e.a.x, e.a.y, e.b.x, e.b.y])
            .collect()
    }

    /// The model (with the guides and links as lines) as GLB bytes, and
    /// its triangles; components are looked for beside `folder`.
    pub fn model(
        &self,
        options: &GrammarOptions,
        folder: &Path,
    ) -> Result<(usize, Vec<u8>), Failure> {
        let scene = mesh_guided(&self.loaded, &self.outcome, true, options, Some(folder))?;
        Ok((scene.triangle_count(), model_bytes(&scene, Format::Glb)?))
    }
}

/// Whether `text` reads as a guided scene (its tables check: guides,
/// links and seeds that name each other); the located diagnostic if not.
pub fn check_scene(
    name: &str,
    text: &str,
) -> Result<(), Box<dyn miette::Diagnostic + Send + Sync>> {
    scene::read(name, text).map(|_| ()).map_err(|e| e as _)
}

/// A mass–spring drag: every guide's points at rest and every seed's
/// position and heading carried with its guide.
pub struct Drag {
    pub points: Vec<Vec<[f64; 2]>>,
    /// Per seed: position and heading (degrees).
    pub seeds: Vec<([f64; 2], f64)>,
    pub sweeps: usize,
    /// The largest stretch or squeeze left, as a fraction of rest.
    pub strain: f64,
    pub particles: usize,
    pub springs: usize,
}

/// Why a drag was refused.
pub enum DragError {
    /// The tables do not check (the located diagnostic).
    Scene(Box<dyn miette::Diagnostic + Send + Sync>),
    /// A vertex named that the scene does not have.
    NoVertex(usize, usize),
}

/// Guide `vertex.0`'s vertex `vertex.1` of `doc`, as it was when the drag
/// began, moved to `to` with the vertices `held` fixed: the springs'
/// rest state (`guided::springs`), without running the scene.
pub fn drag_guides(
    doc: &SceneDoc,
    vertex: (usize, usize),
    to: [f64; 2],
    held: &[(usize, usize)],
) -> Result<Drag, DragError> {
    let spec = scene::read("scene", &doc.to_toml()).map_err(|e| DragError::Scene(e as _))?;
    let s = Springs::new(&spec);
    let particle = |(g, k): (usize, usize)| s.particle(g, k).ok_or(DragError::NoVertex(g, k));
    let dragged = particle(vertex)?;
    let held = held
        .iter()
        .map(|&v| particle(v))
        .collect::<Result<Vec<_>, _>>()?;
    let (x, sweeps) = s.relax(dragged, DVec2::from(to), &held);
    Ok(Drag {
        points: s
            .guide_points(&x)
            .iter()
            .map(|g| g.iter().map(|p| p.to_array()).collect())
            .collect(),
        seeds: spec
            .seeds
            .iter()
            .map(|sd| {
                let (p, heading) = s.carry(sd.guide, &x, sd.position, sd.heading);
                (p.to_array(), heading)
            })
            .collect(),
        sweeps,
        strain: s.strain(&x),
        particles: s.particles.len(),
        springs: s.springs.len(),
    })
}

/// A scene's text (the studio's guides page) named `name`, its grammars
/// relative to `base` and required inside one of `allowed`, read and its
/// grammars compiled with `options`' defines and include folders.
fn load_scene_text(
    name: &str,
    text: &str,
    base: &Path,
    allowed: &[PathBuf],
    options: &GrammarOptions,
) -> Result<guided::Loaded, Failure> {
    guided::load_text_within(name, text, base, &options.build.source, allowed)
        .map_err(|e| guided_failure(e))
}

/// Runs `now`. When `before` is a run of the same scene but for the
/// points of one guide (and its grammars read the same text), only
/// that guide and those downstream of it derive again, the others
/// replaying what they did (`guided::update`, equal to a full run). The
/// outcome, and the guides derived again.
fn grow_scene(
    now: &guided::Loaded,
    before: Option<(&guided::Loaded, &guided::Outcome)>,
) -> Result<(guided::Outcome, Vec<usize>), Failure> {
    let fail = |e: crate::derive::DeriveError| guided_failure(Box::new(e));
    let moved = before
        .filter(|(l, _)| same_grammars(l, now))
        .and_then(|(l, _)| one_guide_moved(&l.spec, &now.spec));
    if let Some(g) = moved {
        let (_, outcome) = before.unwrap_or_else(|| unreachable!());
        let out = guided::update(now, outcome, g).map_err(fail)?;
        return Ok((out, guided::run::downstream(now, g).into_iter().collect()));
    }
    let out = guided::run(now).map_err(fail)?;
    Ok((out, (0..now.spec.guides.len()).collect()))
}

/// Whether `a` and `b` compiled the same grammars from the same text
/// (a grammar edited on disk between two runs derives anew).
fn same_grammars(a: &guided::Loaded, b: &guided::Loaded) -> bool {
    let texts = |l: &guided::Loaded| -> Vec<std::sync::Arc<String>> {
        l.grammars
            .iter()
            .flat_map(|c| c.program.sources.files().iter().map(|f| f.text.clone()))
            .collect()
    };
    a.grammar_names == b.grammar_names && texts(a) == texts(b)
}

/// The guide whose points alone differ between `a` and `b`, if exactly
/// one does and nothing else does.
fn one_guide_moved(a: &guided::SceneSpec, b: &guided::SceneSpec) -> Option<usize> {
    if (a.steps, a.seed, &a.links, a.guides.len()) != (b.steps, b.seed, &b.links, b.guides.len())
        || a.seeds.len() != b.seeds.len()
        || a.seeds.iter().zip(&b.seeds).any(|(x, y)| {
            (x.guide, x.position, x.heading, &x.parameters)
                != (y.guide, y.position, y.heading, &y.parameters)
                || x.grammar.as_ref().map(|g| &g.0) != y.grammar.as_ref().map(|g| &g.0)
        })
    {
        return None;
    }
    let mut moved = None;
    for (i, (x, y)) in a.guides.iter().zip(&b.guides).enumerate() {
        if (&x.name, &x.grammar, x.height, x.id) != (&y.name, &y.grammar, y.height, y.id) {
            return None;
        }
        if x.points != y.points {
            if moved.is_some() {
                return None;
            }
            moved = Some(i);
        }
    }
    moved
}
