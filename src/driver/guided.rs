//! A guided scene's job (docs/guided.md): a scene file (`FILE.toml`) and
//! options -> every seed run along its guides, meshed (with the guides and
//! links drawn, if asked) and written -> [`GuidedDone`] with its figures,
//! or a [`Failure`].

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::job::Output;
use super::run::{refuse_inputs, write_output, Failure, Reason};
use super::stats::{ms, shown};
use crate::api::GrammarOptions;
use crate::guided;

/// One guided scene to run and write.
#[derive(Clone, Debug)]
pub struct GuidedJob {
    pub path: PathBuf,
    /// Defines, include folders, seed, steps, component folders, facets;
    /// the steps and seed given here override the scene's.
    pub options: GrammarOptions,
    /// Draw the guides and links as thin lines too.
    pub guides: bool,
    pub output: Output,
}

/// A guided scene run, meshed and written.
pub struct GuidedDone {
    pub seeds: usize,
    pub messages: usize,
    pub triangles: usize,
    /// The box around everything drawn, `(min, max)`; `None` when nothing
    /// is.
    pub bounds: Option<([f32; 3], [f32; 3])>,
    pub output: Option<PathBuf>,
    pub written: u64,
    pub bytes: Option<Vec<u8>>,
    pub steps: u32,
    /// Reading the scene and compiling its grammars.
    pub load: Duration,
    /// Running every seed.
    pub run: Duration,
}

/// Runs, meshes and writes the guided scene of `job`.
pub fn run_guided(job: &GuidedJob) -> Result<GuidedDone, Failure> {
    let fail = |e: Box<dyn miette::Diagnostic + Send + Sync>| Failure {
        reason: Reason::Guided(e),
        sources: Vec::new(),
    };
    let opts = &job.options.build;
    let t0 = Instant::now();
    let mut loaded =
        guided::load_file(&job.path, &opts.source, &opts.components.dirs).map_err(|e| fail(e))?;
    // The scene and every grammar it read are inputs: never the output.
    let mut sources = vec![job.path.clone()];
    for g in &loaded.grammars {
        sources.extend(g.program.sources.disk_paths());
    }
    refuse_inputs(&job.output, &sources)?;
    if let Some(n) = opts.steps {
        loaded.spec.steps = n;
    }
    if let Some(s) = opts.derive.seed {
        loaded.spec.seed = Some(s);
    }
    let t1 = Instant::now();
    let outcome = guided::run(&loaded).map_err(|e| fail(Box::new(e)))?;
    let t2 = Instant::now();
    let scene = mesh_guided(
        &loaded,
        &outcome,
        job.guides,
        &job.options,
        job.path.parent(),
    )?;
    let (written, bytes) = write_output(&scene, &job.output, &sources)?;
    Ok(GuidedDone {
        seeds: outcome.seeds.len(),
        messages: outcome.messages.len(),
        triangles: scene.triangle_count(),
        bounds: scene
            .bounds()
            .map(|(lo, hi)| (lo.to_array(), hi.to_array())),
        output: job.output.path().map(PathBuf::from),
        written,
        bytes,
        steps: loaded.spec.steps,
        load: t1 - t0,
        run: t2 - t1,
    })
}

/// Meshes a run (with the guides and links drawn when `overlay`); the
/// components its grammars place are looked for beside `folder` (the
/// scene's) and in the options' component folders.
pub fn mesh_guided(
    loaded: &guided::Loaded,
    outcome: &guided::Outcome,
    overlay: bool,
    options: &GrammarOptions,
    folder: Option<&Path>,
) -> Result<crate::mesh::Scene, Failure> {
    let opts = &options.build;
    let mut search = opts.components.clone();
    search.grammar_dir = folder.map(PathBuf::from);
    let mut grammars = crate::build::grammar_components(opts);
    guided::build::scene(loaded, outcome, overlay, &search, &opts.mesh, &mut grammars)
        .map_err(|e| guided_failure(Box::new(e)))
}

fn guided_failure(e: Box<dyn miette::Diagnostic + Send + Sync>) -> Failure {
    Failure {
        reason: Reason::Guided(e),
        sources: Vec::new(),
    }
}

/// A scene's text (the studio's guides page) named `name`, its grammars
/// relative to `base` and required inside one of `allowed`, read and its
/// grammars compiled with `options`' defines and include folders.
pub fn load_scene_text(
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
pub fn grow_scene(
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

impl GuidedDone {
    /// The `--stats` figures of a guided scene.
    pub fn stats(&self) -> serde_json::Value {
        let path = shown(&self.output);
        serde_json::json!({
            "seeds": self.seeds,
            "messages": self.messages,
            "triangles": self.triangles,
            "output": {"path": path, "bytes": self.written},
            "timings_ms": {
                "load": ms(self.load),
                "run": ms(self.run),
                "per_step": ms(self.run / self.steps.max(1)),
            },
        })
    }
}
