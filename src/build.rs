//! The back half in one call: a compiled grammar -> derive -> homomorphism
//! -> turtle -> meshes, timed per stage. The CLI's `build` and `render`,
//! the tests and the REPL all go through here.

use std::collections::HashMap;
use std::fmt;
use std::sync::mpsc::Receiver;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use miette::Diagnostic;
use thiserror::Error;

use crate::derive::{self, DepthWarning, DeriveError, DeriveOptions, ModuleStore};
use crate::mesh::{self, ComponentSearch, MeshError, MeshOptions, Palette, Scene};
use crate::pipeline::Compilation;
use crate::simulation::Simulation;
use crate::turtle::{self, BracketOrigin, Drawing, TurtleError, TurtleOptions};

/// The stack the compiler runs on. Its recursive parts (the PEG, the Pratt
/// parser, resolve, folding) take input up to the parser's ceilings
/// (`parse::MAX_NESTING_CEILING`) with room to spare on it; the binary, the
/// studio and grammar components built ahead run on threads this deep.
pub const WORKER_STACK: usize = 256 << 20;

/// Everything a build can be told besides the grammar: one value that
/// travels from the front end into the grammar and every grammar
/// component it places.
#[derive(Clone, Debug, Default)]
pub struct BuildOptions {
    /// The compilation options the grammar was compiled with: `-D`
    /// (namespaced ones, `TM.NTL=5`, are for grammar components), include
    /// folders, parser limits, dialect override. Grammar components are
    /// compiled with these, their own namespace's defines applied.
    pub source: crate::load::Options,
    /// Derivation steps; `None` takes the file's `derivation length:`.
    pub steps: Option<u32>,
    pub derive: DeriveOptions,
    /// Command-line overrides of the file's `angle:`, `step:`, `width:`.
    pub angle: Option<f64>,
    pub step: Option<f64>,
    pub width: Option<f64>,
    pub components: ComponentSearch,
    pub mesh: MeshOptions,
    /// Grammar components already being built (see [`Early`]).
    pub early: Early,
}

impl BuildOptions {
    /// The options grammar component `name` is built with: the same seed,
    /// limits, include folders, component folders and mesh options; its
    /// own `-D name.X=V` as `-D X=V` (and `name.A.X` as `A.X`, for the
    /// components it places); its own `derivation length:` and turtle
    /// headers rather than the outer command line's `-n`, `--angle`, ...
    pub fn for_component(&self, name: &str, search: ComponentSearch) -> BuildOptions {
        BuildOptions {
            source: self.source.for_namespace(name),
            steps: None,
            angle: None,
            step: None,
            width: None,
            components: search,
            // What was started is the outer grammar's own components.
            early: Early::default(),
            ..self.clone()
        }
    }
}

/// A grammar component's scene, or its rendered diagnostics.
type SceneOrDiagnostics = Result<Scene, String>;

/// Grammar components started before the grammar that places them is
/// compiled: a Pailou's Toukungs are whole builds of their own that need
/// nothing of the Pailou but the command line's options, so they are built
/// on the other core while the Pailou is parsed, resolved and derived. Each
/// is built exactly as [`mesh::GrammarComponents::scene`] would build it
/// then; one the grammar never places is dropped.
#[derive(Clone, Default)]
pub struct Early {
    started: Arc<Mutex<HashMap<String, Receiver<SceneOrDiagnostics>>>>,
}

impl fmt::Debug for Early {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let started = self.started.lock().map(|s| s.len()).unwrap_or(0);
        f.debug_struct("Early").field("started", &started).finish()
    }
}

impl Early {
    /// Starts the grammar components that `text` (the grammar's own
    /// source, not its includes) places with `~NAME` and `opts` finds as
    /// grammars, one after the other on one thread beside the compiler's
    /// (so that the two cores are busy with no third thread taking turns
    /// with the compiler: three made the Pailou slower). Nothing on one
    /// core. A name in a comment or a placement never reached costs a build
    /// on the other core, and nothing else.
    pub fn start(text: &str, opts: &BuildOptions) -> Early {
        let early = Early::default();
        if crate::derive::threads() < 2 {
            return early;
        }
        let wanted = opts.components.grammars_among(placed_names(text));
        if wanted.is_empty() {
            return early;
        }
        let mut started = early.started.lock().expect("not shared yet");
        let mut sends = Vec::new();
        for w in &wanted {
            let (send, receive) = std::sync::mpsc::sync_channel(1);
            started.insert(w.name.clone(), receive);
            sends.push(send);
        }
        drop(started);
        let opts = opts.clone();
        let task = move || {
            for (w, send) in wanted.iter().zip(sends) {
                // A receiver gone (the build ended early) stops nothing
                // else: the rest still run to their own end.
                let _ = send.send(build_component(&opts, w));
            }
        };
        let thread = std::thread::Builder::new()
            .stack_size(WORKER_STACK)
            .spawn(task);
        if thread.is_err() {
            // Built when asked for instead.
            early.started.lock().expect("not shared yet").clear();
        }
        early
    }

    /// The components started and not yet taken by a build, by name.
    pub fn waiting(&self) -> Vec<String> {
        let mut names: Vec<String> = self
            .started
            .lock()
            .map(|s| s.keys().cloned().collect())
            .unwrap_or_default();
        names.sort_unstable();
        names
    }

    fn has(&self, name: &str) -> bool {
        self.started.lock().is_ok_and(|s| s.contains_key(name))
    }

    /// The scene of `name` if it was started (waiting for it); `None` if
    /// not, or if its thread panicked (it is then built when asked for).
    fn take(&self, name: &str) -> Option<SceneOrDiagnostics> {
        let receive = self.started.lock().ok()?.remove(name)?;
        receive.recv().ok()
    }
}

/// The names `text` places as components (`~NAME`, `∼NAME`), sorted, each
/// once; a name in a comment is found too.
fn placed_names(text: &str) -> Vec<&str> {
    let mut names: Vec<&str> = text
        .split(['~', '∼'])
        .skip(1)
        .map(|rest| {
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .filter(|name| !name.is_empty())
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// Compiles and builds grammar component `w` with the outer build's
/// options (see [`BuildOptions::for_component`]).
fn build_component(opts: &BuildOptions, w: &mesh::Wanted) -> SceneOrDiagnostics {
    let opts = opts.for_component(&w.name, w.search.clone());
    let comp = crate::pipeline::compile(&w.input, &opts.source).map_err(|f| f.render_plain())?;
    build(&comp, &opts)
        .map(|b| b.scene)
        .map_err(|e| crate::diag::render_plain(&e))
}

/// The grammar components of a build with `opts`, compiled and built by
/// this crate's own pipeline (guided scenes mesh their seeds with it).
pub fn grammar_components(opts: &BuildOptions) -> impl mesh::GrammarComponents + '_ {
    SubGrammars {
        opts,
        built: HashMap::new(),
    }
}

/// Grammar components built by this crate's own pipeline, with the outer
/// build's options (see [`BuildOptions::for_component`]).
struct SubGrammars<'a> {
    opts: &'a BuildOptions,
    /// Scenes built ahead (see [`mesh::GrammarComponents::ahead`]), by name.
    built: HashMap<String, SceneOrDiagnostics>,
}

impl mesh::GrammarComponents for SubGrammars<'_> {
    fn scene(
        &mut self,
        name: &str,
        input: &crate::load::Input,
        search: &ComponentSearch,
    ) -> SceneOrDiagnostics {
        if let Some(scene) = self.built.remove(name) {
            return scene;
        }
        if let Some(scene) = self.opts.early.take(name) {
            return scene;
        }
        let wanted = mesh::Wanted {
            name: name.to_string(),
            input: input.clone(),
            search: search.clone(),
        };
        build_component(self.opts, &wanted)
    }

    /// Each grammar component is a whole build of its own (a Pailou's two
    /// Toukungs: parse, derive, turtle, meshes): they are built at once, one
    /// thread per core, each thread with the compiler's deep stack (see
    /// [`WORKER_STACK`]). A failed one is reported when `scene` asks for
    /// it, in placement order, as if built then.
    fn ahead(&mut self, mut wanted: Vec<mesh::Wanted>) {
        wanted.retain(|w| !self.opts.early.has(&w.name));
        if wanted.is_empty() {
            return;
        }
        let workers = crate::derive::threads().clamp(1, wanted.len());
        let opts = self.opts;
        let share = |first: usize| {
            wanted
                .iter()
                .skip(first)
                .step_by(workers)
                .map(|w| (w.name.clone(), build_component(opts, w)))
                .collect::<Vec<_>>()
        };
        let built = std::thread::scope(|scope| {
            let others: Vec<_> = (1..workers)
                .map(|w| {
                    std::thread::Builder::new()
                        .stack_size(WORKER_STACK)
                        .spawn_scoped(scope, move || share(w))
                })
                .collect();
            let mut built = share(0);
            for other in others {
                // A thread that cannot start, or that panicked, leaves its
                // components to be built when asked for.
                if let Ok(Ok(more)) = other.map(|h| h.join()) {
                    built.extend(more);
                }
            }
            built
        });
        self.built.extend(built);
    }
}

/// Wall-clock time per stage.
#[derive(Clone, Copy, Debug, Default)]
pub struct Timings {
    pub derive: Duration,
    pub interpret: Duration,
    pub mesh: Duration,
}

/// A built model.
pub struct Built {
    pub scene: Scene,
    /// The turtle's records, before meshing (tests print them).
    pub drawing: Drawing,
    /// Modules in the string the turtle read.
    pub modules: usize,
    pub timings: Timings,
    /// Decomposition and homomorphism depth warnings.
    pub warnings: Vec<DepthWarning>,
    /// Meshing's warnings (`lsys::mesh::distorted_component`).
    pub mesh_warnings: Vec<MeshError>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum BuildError {
    #[error(transparent)]
    #[diagnostic(transparent)]
    Derive(#[from] DeriveError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Turtle(#[from] TurtleError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Mesh(#[from] MeshError),
}

/// What a build is doing, reported as it goes (the CLI's progress bar).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// About to derive step `done + 1` of `of`.
    Derive { done: u32, of: u32 },
    /// Applying the homomorphism.
    Homomorphism,
    /// Running the turtle.
    Interpret,
    /// Building the meshes.
    Mesh,
}

impl Stage {
    /// The stage's name as a progress bar shows it.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Derive { .. } => "deriving",
            Stage::Homomorphism => "homomorphism",
            Stage::Interpret => "turtle",
            Stage::Mesh => "meshing",
        }
    }
}

/// Derives, interprets and meshes `comp`.
pub fn build(comp: &Compilation, opts: &BuildOptions) -> Result<Built, BuildError> {
    build_observed(comp, opts, &mut |_| {})
}

/// [`build`], telling `observe` every stage and every derivation step as
/// it starts (once per step, never per module).
pub fn build_observed(
    comp: &Compilation,
    opts: &BuildOptions,
    observe: &mut dyn FnMut(Stage),
) -> Result<Built, BuildError> {
    let (program, compiled) = (&comp.program, &comp.compiled);
    let t0 = Instant::now();
    let steps = opts.steps.unwrap_or(program.derivation_length);
    let mut sim = Simulation::new(program, compiled, opts.derive.clone(), steps)?;
    sim.run(&mut |done, of| observe(Stage::Derive { done, of }))?;
    // A cpfg model file's drawn string continues the derivation's
    // generator (`Simulation::drawn`), so it is made here; others in `model`.
    let drawn = if program.profile.shared_random_stream && !program.homomorphism.is_empty() {
        observe(Stage::Homomorphism);
        Some(sim.drawn()?)
    } else {
        None
    };
    let d = sim.into_derivation();
    let warnings = d.warnings().to_vec();
    let step = d.step_number();
    let string = d.into_current();
    let derived = t0.elapsed();
    let mut built = locate_bracket(
        model(comp, &string, step, drawn, opts, observe),
        comp,
        opts,
        steps,
        None,
    )?;
    built.timings.derive += derived;
    built.warnings.splice(0..0, warnings);
    Ok(built)
}

/// Which step first wrote a stray `]`: the turtle only sees the final
/// string, so on that error the derivation is run again (it is seeded and
/// deterministic) and each step's string is checked. Only a failed build
/// pays for this. With `expect`, the answer is given only when the string
/// of step `steps` is that string (a string built elsewhere, e.g. one the
/// caller made up, has no step that wrote it).
fn bracket_origin(
    comp: &Compilation,
    opts: &BuildOptions,
    steps: u32,
    expect: Option<&ModuleStore>,
) -> Option<BracketOrigin> {
    let (program, compiled) = (&comp.program, &comp.compiled);
    let Ok(mut sim) = Simulation::new(program, compiled, opts.derive.clone(), steps) else {
        return expect
            .is_none()
            .then_some(BracketOrigin::Homomorphism(steps));
    };
    let mut first = has_stray_close(sim.current()).then_some(BracketOrigin::Axiom);
    while sim.step_number() < steps && (first.is_none() || expect.is_some()) {
        if sim.step().is_err() {
            break;
        }
        if first.is_none() && has_stray_close(sim.current()) {
            first = Some(BracketOrigin::Step(sim.step_number()));
        }
    }
    if let Some(expect) = expect {
        if sim.step_number() != steps || sim.current() != expect {
            return None;
        }
    }
    Some(first.unwrap_or(BracketOrigin::Homomorphism(sim.step_number())))
}

/// Whether a `]` in `string` closes no `[`.
fn has_stray_close(string: &ModuleStore) -> bool {
    // The branch that is open at the start (none) ends before the end of
    // the string only at a `]` that closes nothing.
    let heads = string.heads();
    derive::store::rest_of_branch(heads, 0).0 < heads.len()
}

/// The back half alone: `string`, step `step` of `comp`'s derivation ->
/// homomorphism -> turtle -> meshes (the REPL's `:export` builds the
/// string it shows), telling `observe` each stage. `opts.steps` is not
/// used; `timings.derive` is the homomorphism's time.
pub fn build_string(
    comp: &Compilation,
    string: &ModuleStore,
    step: u32,
    opts: &BuildOptions,
    observe: &mut dyn FnMut(Stage),
) -> Result<Built, BuildError> {
    // The REPL's string is step `step` of the derivation: find the step
    // that wrote a stray `]`, as `build` does.
    let built = model(comp, string, step, None, opts, observe);
    locate_bracket(built, comp, opts, step, Some(string))
}

/// A stray-`]` error of `built` names the step that first wrote it (see
/// [`bracket_origin`]); every other result is returned as it is.
fn locate_bracket(
    built: Result<Built, BuildError>,
    comp: &Compilation,
    opts: &BuildOptions,
    steps: u32,
    expect: Option<&ModuleStore>,
) -> Result<Built, BuildError> {
    match built {
        Err(BuildError::Turtle(e @ TurtleError::UnbalancedBracket { .. })) => {
            Err(match bracket_origin(comp, opts, steps, expect) {
                Some(origin) => e.with_bracket_origin(origin, &comp.program).into(),
                None => e.into(),
            })
        }
        other => other,
    }
}

/// `drawn`: the homomorphism's output when the caller made it already.
fn model(
    comp: &Compilation,
    string: &ModuleStore,
    step: u32,
    drawn: Option<derive::Interpreted>,
    opts: &BuildOptions,
    observe: &mut dyn FnMut(Stage),
) -> Result<Built, BuildError> {
    let program = &comp.program;
    let t0 = Instant::now();
    let mut warnings = Vec::new();
    let interpreted: Option<ModuleStore> = if let Some(h) = drawn {
        warnings.extend(h.warnings);
        Some(h.modules)
    } else if program.homomorphism.is_empty() {
        None
    } else {
        observe(Stage::Homomorphism);
        let h = derive::homomorphism(program, &comp.compiled, string, &opts.derive, step)?;
        warnings.extend(h.warnings);
        Some(h.modules)
    };
    let string = interpreted.as_ref().unwrap_or(string);
    let t1 = Instant::now();
    observe(Stage::Interpret);
    let topts = TurtleOptions {
        max_triangles: opts.mesh.max_triangles,
        ..TurtleOptions::new(program, opts.angle, opts.step, opts.width)
    };
    let drawing = turtle::interpret(program, string, &topts)?;
    let t2 = Instant::now();
    observe(Stage::Mesh);
    let palette = Palette::new(&program.turtle.palette);
    let mut grammars = SubGrammars {
        opts,
        built: HashMap::new(),
    };
    let scene = mesh::assemble_scene(
        program,
        &drawing,
        &palette,
        &opts.components,
        &opts.mesh,
        &mut grammars,
    )?;
    let t3 = Instant::now();
    let mut mesh_warnings = mesh::distortion::distortions(program, &drawing, &scene);
    mesh_warnings.extend(mesh::widths::wide_lines(program, &drawing));
    Ok(Built {
        mesh_warnings,
        scene,
        drawing,
        modules: string.len(),
        timings: Timings {
            derive: t1 - t0,
            interpret: t2 - t1,
            mesh: t3 - t2,
        },
        warnings,
    })
}
