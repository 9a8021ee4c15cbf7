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

pub(super) fn guided_failure(e: Box<dyn miette::Diagnostic + Send + Sync>) -> Failure {
    Failure {
        reason: Reason::Guided(e),
        sources: Vec::new(),
    }
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
