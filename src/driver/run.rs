//! Running a job: a [`Job`] -> compile (with the grammar components it
//! places started ahead), build, check, write -> [`Done`] or [`Failure`],
//! telling the caller each warning and stage as it happens.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use miette::Diagnostic;

use super::job::{grammar_dir, Job, Output};
use crate::api::{Grammar, Scene};
use crate::build::{self, BuildError, Stage};
use crate::diag::Diagnostics;
use crate::export::output::{scene_bytes, write_scene, Format, WriteError};
use crate::load::Input;
use crate::pailou::structure::Problem;

/// What a job reports while it runs, in the order it happens.
pub enum Event<'a> {
    /// A warning of the compiler or of the build (decomposition depth, ...).
    Warning(&'a dyn Diagnostic),
    /// A warning without a place in the grammar: a structural problem, a
    /// model that draws nothing, a relation matrix that does not read.
    Notice(&'a str),
    /// A build stage starts (each derivation step once).
    Stage(Stage),
    /// The model is being written (or rendered, for a picture).
    Writing(Format),
}

/// A finished job.
pub struct Done {
    /// The compiled grammar (its warnings were reported as events).
    pub grammar: Grammar,
    pub scene: Scene,
    /// What the structural check found (empty without a check).
    pub problems: Vec<Problem>,
    /// The file written, if any.
    pub output: Option<PathBuf>,
    /// Bytes written to the file(s), or the length of [`Done::bytes`].
    pub written: u64,
    /// The model's bytes, for [`Output::Bytes`].
    pub bytes: Option<Vec<u8>>,
    /// Every file the grammar was read from (root, includes, view and
    /// function files).
    pub sources: Vec<PathBuf>,
    /// Reading and compiling the grammar.
    pub parse: Duration,
    /// Writing (or rendering) the output.
    pub write: Duration,
    /// The whole job.
    pub took: Duration,
}

/// Why a job stopped, and what it had read by then.
#[derive(Debug)]
pub struct Failure {
    pub reason: Reason,
    /// The files the grammar was read from (none when it could not be
    /// read), so that a watcher waits for a fix in any of them.
    pub sources: Vec<PathBuf>,
}

/// Why a job stopped.
#[derive(Debug)]
pub enum Reason {
    /// The grammar (or a file it names) could not be read.
    Input(Diagnostics),
    /// The grammar does not compile.
    Grammar(Diagnostics),
    /// Deriving, interpreting or meshing failed.
    Build(Box<BuildError>),
    /// A guided scene did not read, or one of its seeds failed.
    Guided(Box<dyn Diagnostic + Send + Sync>),
    /// The exporter refused the model (too large for the format, ...).
    Export(Box<dyn Diagnostic + Send + Sync>),
    /// The output file could not be written; nothing was.
    Write {
        path: PathBuf,
        error: std::io::Error,
    },
}

impl Failure {
    fn new(reason: Reason, sources: &[PathBuf]) -> Failure {
        Failure {
            reason,
            sources: sources.to_vec(),
        }
    }
}

impl Failure {
    /// Why the job stopped, as diagnostics (a write that failed becomes
    /// one that names the path).
    pub fn diagnostics(self) -> Diagnostics {
        match self.reason {
            Reason::Input(d) | Reason::Grammar(d) => d,
            Reason::Build(e) => Diagnostics::one(*e),
            Reason::Export(e) | Reason::Guided(e) => Diagnostics::boxed(e),
            Reason::Write { path, error } => Diagnostics::one(crate::api::WriteFailed {
                path: path.display().to_string(),
                cause: error.to_string(),
            }),
        }
    }
}

/// How many structural problems are told one by one.
const PROBLEMS_TOLD: usize = 40;

/// Runs `job`, telling `observe` what happens as it happens.
pub fn run(job: &Job, observe: &mut dyn FnMut(Event)) -> Result<Done, Failure> {
    let t0 = Instant::now();
    let mut options = job.options.clone();
    let opts = &mut options.build;
    if let Some(dir) = grammar_dir(&job.input) {
        opts.components.grammar_dir = Some(dir);
    }
    // The grammar components its text places are built on the other core
    // while it compiles (a Pailou's Toukungs; see `build::Early`).
    if let Some(text) = root_text(&job.input) {
        opts.early = build::Early::start(&text, opts);
    }
    let comp = match crate::pipeline::compile(&job.input, &opts.source) {
        Ok(c) => c,
        Err(d) if d.is_input_error() => return Err(Failure::new(Reason::Input(d), &[])),
        Err(d) => {
            // A grammar that failed still names what it read.
            let sources = d.files().to_vec();
            return Err(Failure::new(Reason::Grammar(d), &sources));
        }
    };
    for w in &comp.warnings {
        observe(Event::Warning(w.as_ref()));
    }
    let sources = comp.program.sources.disk_paths();
    // Before the build: an output that would overwrite an input is refused
    // before anything is written, and before the work.
    refuse_inputs(&job.output, &sources)?;
    let parse = t0.elapsed();
    let built = build::build_observed(&comp, opts, &mut |s| observe(Event::Stage(s)))
        .map_err(|e| Failure::new(Reason::Build(Box::new(e)), &sources))?;
    for w in &built.warnings {
        observe(Event::Warning(w));
    }
    for w in &built.mesh_warnings {
        observe(Event::Warning(w));
    }
    let problems = match super::structure::check(&built.scene, &job.check) {
        Ok(p) => p,
        Err(e) => {
            let note = format!("no structural check: the relation matrix does not read: {e}");
            observe(Event::Notice(&note));
            Vec::new()
        }
    };
    for p in problems.iter().take(PROBLEMS_TOLD) {
        observe(Event::Notice(&format!("structure: {p}")));
    }
    if problems.len() > PROBLEMS_TOLD {
        let more = problems.len() - PROBLEMS_TOLD;
        observe(Event::Notice(&format!(
            "structure: ... and {more} more problems"
        )));
    }
    if built.scene.triangle_count() == 0 {
        let path = match &job.input {
            Input::Path(p) => Some(p.as_path()),
            _ => None,
        };
        let note = super::empty::warning(&job.name, built.modules, &comp.program, path);
        observe(Event::Notice(&note));
    }
    let t1 = Instant::now();
    if let Some(format) = job.output.format() {
        observe(Event::Writing(format));
    }
    let (written, bytes) = write_output(&built.scene, &job.output, &sources)?;
    let write = t1.elapsed();
    Ok(Done {
        grammar: Grammar::compiled(comp, options),
        scene: Scene { built },
        problems,
        output: job.output.path().map(PathBuf::from),
        written,
        bytes,
        sources,
        parse,
        write,
        took: t0.elapsed(),
    })
}

/// The text of the grammar's own file, if it can be had without a
/// diagnostic (compiling reads it again, and reports what is wrong).
fn root_text(input: &Input) -> Option<std::borrow::Cow<'static, str>> {
    match input {
        Input::Std(name) => crate::stdlib::get(name).map(Into::into),
        // Only a regular file within the size limit: a pipe read here would
        // be empty when compiling reads it, and is read with its limit there.
        Input::Path(path) => std::fs::metadata(path)
            .is_ok_and(|m| m.is_file() && m.len() <= crate::load::MAX_SOURCE_BYTES)
            .then(|| std::fs::read_to_string(path).ok())
            .flatten()
            .map(Into::into),
        Input::Text { text, .. } | Input::Edited { text, .. } => Some(text.clone().into()),
    }
}

/// Refuses `output` (and an OBJ's `.mtl` beside it) when it is one of the
/// run's input files `sources`.
pub(super) fn refuse_inputs(output: &Output, sources: &[PathBuf]) -> Result<(), Failure> {
    let Output::File { path, format, .. } = output else {
        return Ok(());
    };
    let mut paths = vec![path.clone()];
    if *format == Format::Obj {
        paths.push(path.with_extension("mtl"));
    }
    for p in &paths {
        crate::export::atomic::refuse_inputs(p, sources)
            .map_err(|e| Failure::new(Reason::Export(Box::new(e)), sources))?;
    }
    Ok(())
}

/// `scene` as the bytes of a `format` file, in memory (a picture with
/// the default camera).
pub fn model_bytes(scene: &crate::mesh::Scene, format: Format) -> Result<Vec<u8>, Failure> {
    let out = Output::Bytes {
        format,
        picture: Default::default(),
    };
    Ok(write_output(scene, &out, &[])?.1.unwrap_or_default())
}

/// Writes `scene` as `output` says: the bytes written and, for
/// [`Output::Bytes`], the bytes.
pub(super) fn write_output(
    scene: &crate::mesh::Scene,
    output: &Output,
    sources: &[PathBuf],
) -> Result<(u64, Option<Vec<u8>>), Failure> {
    Ok(match output {
        Output::File {
            path,
            format,
            picture,
        } => match write_scene(scene, path, *format, picture) {
            Ok(n) => (n, None),
            Err(WriteError::Export(e)) => return Err(Failure::new(Reason::Export(e), sources)),
            Err(WriteError::Io(error)) => {
                let path = path.clone();
                return Err(Failure::new(Reason::Write { path, error }, sources));
            }
        },
        Output::Bytes { format, picture } => {
            let b = scene_bytes(scene, *format, picture, "model.mtl")
                .map_err(|e| Failure::new(Reason::Export(e), sources))?;
            (b.len() as u64, Some(b))
        }
        Output::Nothing => (0, None),
    })
}
