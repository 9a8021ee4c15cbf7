//! An interactive job (the REPL's), without terminal I/O: one input (a
//! command, a production, a module string), read by the front end as a
//! [`Typed`], in; a [`Reply`] (text, success) out.
//!
//! * `mod.rs`: the state, loading, compiling, deriving to a step;
//! * `edit.rs`: typed productions, `:drop`, `:axiom`, `:set`, `:seed`;
//! * `inspect.rs`: what looks (`:show`, `:diff`, `:rules`, `:export`, ...);
//! * `grammar.rs`: edits of the grammar's text; `show.rs`: printing strings;
//! * `shadow.rs`: rules an earlier one always shadows (never applied);
//! * `same.rs`: whether two productions are the same rule;
//! * `undo.rs`: `:undo`, the stack of the grammar before each edit.
//!
//! The grammar is kept as source text ([`Grammar::text`]: the loaded
//! file's text with the productions typed or dropped in the session) and
//! recompiled after every edit; an edit whose text does not compile is
//! refused with its diagnostics, and the last good grammar stays. The
//! derivation is kept as one [`Checkpoint`] per step, so `:back` costs
//! nothing and stepping forward again continues with the same random
//! numbers; a change to the grammar or a define re-derives to the same step.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::build::Stage;
use crate::derive::{Checkpoint, DeriveOptions, ModuleStore, NumberStyle};
use crate::load::{Input, Options};
use crate::pipeline::{self, Compilation};
use crate::simulation::Simulation;

mod edit;
mod grammar;
mod inspect;
mod precision;
mod same;
mod save;
mod shadow;
mod show;
mod undo;

/// Progress of one long operation (deriving, building, writing): told
/// each stage as it starts, and done when dropped. The REPL's is a
/// progress bar on a terminal.
pub trait Meter {
    /// A stage has started (each derivation step once).
    fn stage(&self, stage: Stage);
    /// Work after the derivation (`rendering`, `writing`).
    fn message(&self, what: &'static str);
}

/// Makes a [`Meter`] for each long operation.
pub type Meters = Box<dyn Fn() -> Box<dyn Meter>>;

struct NoMeter;

impl Meter for NoMeter {
    fn stage(&self, _: Stage) {}
    fn message(&self, _: &'static str) {}
}

/// The meter of one operation: the session's, or one that shows nothing.
fn meter(meters: &Option<Meters>) -> Box<dyn Meter> {
    match meters {
        Some(m) => m(),
        None => Box::new(NoMeter),
    }
}

/// One input as the front end read it (the REPL: `src/repl/input.rs`).
pub enum Typed<'a> {
    /// A blank line.
    Empty,
    /// A command, found in the front end's table: its name (what `:undo`
    /// reports), what it does, and its argument text.
    Command {
        name: &'static str,
        run: fn(&mut Session, &str) -> Out,
        args: &'a str,
    },
    /// A command the front end does not know: why.
    Unknown(String),
    /// A production or `Axiom:` statement: the grammar is edited.
    Statement,
    /// A module string: rewritten once with the grammar.
    Modules,
}

/// A command's result: its text, or the text of what went wrong.
pub type Out = Result<String, String>;

/// Stored strings of past steps beyond this many bytes are dropped (and
/// derived again from an earlier step when needed).
const HISTORY_BYTES: usize = 1 << 30;

/// Where a grammar's text comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Source {
    File(PathBuf),
    /// `std:NAME`.
    Std(String),
    /// Typed in the session, from nothing.
    Scratch,
}

impl Source {
    /// A command-line argument: `std:NAME` or a path.
    pub fn from_arg(arg: &str) -> Source {
        match arg.strip_prefix("std:") {
            Some(n) => Source::Std(n.to_string()),
            None => Source::File(PathBuf::from(arg)),
        }
    }

    pub fn name(&self) -> String {
        match self {
            Source::File(p) => p.display().to_string(),
            Source::Std(n) => format!("std:{n}"),
            Source::Scratch => "<repl>".into(),
        }
    }

    fn read(&self) -> Result<String, String> {
        match self {
            Source::File(p) => std::fs::read(p)
                .map(|b| String::from_utf8_lossy(&b).into_owned())
                .map_err(|e| format!("cannot read {}: {e}", p.display())),
            Source::Std(n) => crate::stdlib::get(n).map(String::from).ok_or_else(|| {
                format!(
                    "no standard library grammar `std:{n}`; {}",
                    crate::stdlib::unknown_help(n, |m| format!("std:{m}"))
                )
            }),
            Source::Scratch => Ok(String::new()),
        }
    }

    fn input(&self, text: &str) -> Input {
        match self {
            Source::File(p) => Input::Edited {
                path: p.clone(),
                text: text.to_string(),
            },
            _ => Input::Text {
                name: self.name(),
                text: text.to_string(),
            },
        }
    }

    /// The grammar's directory, where `components/` is looked for.
    pub fn dir(&self) -> Option<PathBuf> {
        match self {
            Source::File(p) => Some(
                p.parent()
                    .filter(|d| !d.as_os_str().is_empty())
                    .map_or(PathBuf::from("."), |d| d.to_path_buf()),
            ),
            _ => None,
        }
    }
}

/// The working grammar: its text and what it compiled to.
pub struct Grammar {
    pub source: Source,
    pub text: String,
    pub comp: Compilation,
    /// Whether the text differs from the file (productions typed or dropped).
    pub edited: bool,
}

/// How a session starts.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    /// ANSI colour in diagnostics.
    pub color: bool,
    /// The seed, the module limits and the `-D` overrides (`:set` changes
    /// the overrides later).
    pub options: crate::GrammarOptions,
}

/// What one input produced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reply {
    pub text: String,
    pub ok: bool,
}

/// Words the line editor completes.
#[derive(Clone, Debug, Default)]
pub struct Names {
    pub modules: Vec<String>,
    pub defines: Vec<String>,
}

pub struct Session {
    pub(super) color: bool,
    /// Makes the meter of one long operation; none by default.
    meters: Option<Meters>,
    interrupt: Arc<AtomicBool>,
    pub(super) opts: DeriveOptions,
    pub(super) overrides: Vec<(String, String)>,
    /// What `:reload` reads: the grammar in use, or, before any loaded,
    /// the last one `:load` tried (to read again once it is fixed).
    target: Option<Source>,
    pub(super) grammar: Option<Grammar>,
    /// `history[i]`: the derivation after step i, if kept.
    history: Vec<Option<Checkpoint>>,
    pub(super) pos: u32,
    /// The last production typed, which an indented line continues.
    pub(super) last_production: Option<String>,
    /// Productions typed in the session (one line each), for `:rules`.
    pub(super) typed: Vec<String>,
    /// The edits `:undo` can take back, the last on top.
    undo: Vec<undo::Edit>,
    /// Time of the last derivation.
    pub(super) derive_time: Duration,
    /// How parameters print (`:precision`).
    number_style: NumberStyle,
    pub(super) quit: bool,
}

impl Session {
    pub fn new(settings: Settings) -> Session {
        Session {
            color: settings.color,
            meters: None,
            interrupt: Arc::new(AtomicBool::new(false)),
            opts: settings.options.build.derive,
            overrides: settings.options.build.source.defines,
            target: None,
            grammar: None,
            history: Vec::new(),
            pos: 0,
            last_production: None,
            typed: Vec::new(),
            undo: Vec::new(),
            derive_time: Duration::ZERO,
            number_style: NumberStyle::Shortest,
            quit: false,
        }
    }

    /// Shows the progress of long operations through meters `make` makes.
    pub fn set_meters(&mut self, make: Meters) {
        self.meters = Some(make);
    }

    /// Set this (from a Ctrl-C handler) to stop a derivation between steps.
    pub fn interrupt_flag(&self) -> Arc<AtomicBool> {
        self.interrupt.clone()
    }

    /// The current step.
    pub fn step(&self) -> u32 {
        self.pos
    }

    /// Runs one input `text` read as `typed`; an edit that succeeds is
    /// recorded for `:undo`.
    pub fn run_input(&mut self, text: &str, typed: Typed<'_>) -> Reply {
        self.interrupt.store(false, Ordering::SeqCst);
        let before = self.edit_state();
        let mut command = None;
        // A blank line keeps the production an indented line continues.
        if !matches!(typed, Typed::Statement | Typed::Empty) {
            self.last_production = None;
        }
        let out = match typed {
            Typed::Empty => Ok(String::new()),
            Typed::Unknown(why) => Err(why),
            Typed::Command { name, run, args } => {
                command = Some(name);
                run(self, args)
            }
            Typed::Statement => self.statement(text),
            Typed::Modules => self.rewrite_once(text),
        };
        if out.is_ok() {
            self.record_edit(text, before, command);
        }
        match out {
            Ok(text) => Reply { text, ok: true },
            Err(text) => Reply { text, ok: false },
        }
    }

    /// The last production typed, which an indented line continues.
    pub fn last_production(&self) -> Option<&str> {
        self.last_production.as_deref()
    }

    /// Whether `:quit` was given.
    pub fn quit_requested(&self) -> bool {
        self.quit
    }

    /// `:quit`: the front end leaves after this input.
    pub fn request_quit(&mut self) {
        self.quit = true;
    }

    /// The prompt of an interactive session: `lsys[3]> `.
    pub fn prompt(&self) -> String {
        format!("lsys[{}]> ", self.pos)
    }

    /// The current string, if the axiom could be evaluated.
    pub fn current(&self) -> Option<&ModuleStore> {
        self.history
            .get(self.pos as usize)
            .and_then(|c| c.as_ref())
            .map(|c| &c.string)
    }

    /// Module and define names of the grammar, for completion.
    pub fn names(&self) -> Names {
        match &self.grammar {
            None => Names::default(),
            Some(g) => {
                let p = &g.comp.program;
                Names {
                    modules: p.symbols.list.iter().map(|s| s.name.clone()).collect(),
                    defines: p.defines.iter().map(|d| d.name.clone()).collect(),
                }
            }
        }
    }

    // ------------------------------------------------------------ grammar

    /// Compiles `text` as the grammar from `source` with `overrides`;
    /// the diagnostics, rendered, when it has errors.
    pub(super) fn compile(
        &self,
        source: &Source,
        text: &str,
        overrides: &[(String, String)],
    ) -> Result<Compilation, String> {
        let opts = Options {
            defines: overrides.to_vec(),
            ..Options::default()
        };
        match pipeline::compile(&source.input(text), &opts) {
            Ok(c) => Ok(c),
            Err(d) if d.is_input_error() => Err(d.render(self.color)),
            Err(diagnostics) => {
                let errors = diagnostics.error_count();
                let mut out = diagnostics.render(self.color);
                out.push_str(&format!(
                    "{}: {errors} error{}",
                    source.name(),
                    if errors == 1 { "" } else { "s" }
                ));
                Err(out)
            }
        }
    }

    /// The working grammar's source and text (nothing yet: an empty scratch).
    pub(super) fn base(&self) -> (Source, String) {
        match &self.grammar {
            Some(g) => (g.source.clone(), g.text.clone()),
            None => (Source::Scratch, String::new()),
        }
    }

    /// The working grammar, or the error that there is none.
    pub(super) fn grammar(&self) -> Result<&Grammar, String> {
        self.grammar.as_ref().ok_or_else(|| {
            "no grammar yet: `:load FILE`, or start one with `:axiom MODULES` and type productions"
                .to_string()
        })
    }

    /// Makes `comp` the working grammar and derives to the same step.
    /// Returns the warnings that are new, then the status.
    pub(super) fn install(
        &mut self,
        source: Source,
        text: String,
        comp: Compilation,
        edited: bool,
    ) -> Out {
        let old: Vec<String> = match &self.grammar {
            Some(g) if g.source == source => {
                g.comp.warnings.iter().map(|w| w.to_string()).collect()
            }
            _ => Vec::new(),
        };
        let mut warnings = String::new();
        for w in &comp.warnings {
            if !old.contains(&w.to_string()) {
                warnings.push_str(&crate::driver::render_diagnostic(w.as_ref(), self.color));
            }
        }
        self.grammar = Some(Grammar {
            source,
            text,
            comp,
            edited,
        });
        let keep = self.pos;
        self.rederive(keep).map(|s| warnings.clone() + &s)
    }

    /// `:load FILE`: on errors the previous grammar stays, and so does
    /// what `:reload` reads.
    pub fn load(&mut self, arg: &str) -> Out {
        if arg.is_empty() {
            return Err("`:load` needs a file (or std:NAME)".into());
        }
        let source = Source::from_arg(arg);
        if self.grammar.is_none() {
            self.target = Some(source.clone());
        }
        let text = source.read().map_err(|e| self.kept(e))?;
        let comp = self
            .compile(&source, &text, &[])
            .map_err(|e| self.kept(e))?;
        self.overrides.clear();
        self.typed.clear();
        self.pos = 0;
        self.target = Some(source.clone());
        let summary = self.summary(&comp, &source);
        let rest = self.install(source, text, comp, false)?;
        Ok(format!("{summary}\n{rest}"))
    }

    /// Loads the first file with the `-D` overrides of the command line
    /// and derives to `step`.
    pub fn start(&mut self, arg: &str, step: u32) -> Out {
        let source = Source::from_arg(arg);
        self.target = Some(source.clone());
        let text = source.read()?;
        let overrides = self.overrides.clone();
        let comp = self.compile(&source, &text, &overrides)?;
        let summary = self.summary(&comp, &source);
        self.pos = step;
        let rest = self.install(source, text, comp, false)?;
        Ok(format!("{summary}\n{rest}"))
    }

    /// `:reload`: reads the file again (edits typed in the session are
    /// dropped), keeps the defines set and the step.
    pub fn reload(&mut self) -> Out {
        let Some(source) = self.target.clone() else {
            return Err("nothing to reload: `:load FILE` first".into());
        };
        let text = source.read().map_err(|e| self.kept(e))?;
        let same = self.grammar.as_ref().is_some_and(|g| g.source == source);
        let overrides = if same {
            self.overrides.clone()
        } else {
            Vec::new()
        };
        let comp = self
            .compile(&source, &text, &overrides)
            .map_err(|e| self.kept(e))?;
        let dropped = same && self.grammar.as_ref().is_some_and(|g| g.edited);
        if !same {
            self.overrides.clear();
            self.pos = 0;
        }
        self.typed.clear();
        let mut summary = self.summary(&comp, &source);
        if dropped {
            summary.push_str(" (the edits typed in the session were dropped)");
        }
        let rest = self.install(source, text, comp, false)?;
        Ok(format!("{summary}\n{rest}"))
    }

    pub(super) fn kept(&self, errors: String) -> String {
        match &self.grammar {
            Some(g) => format!(
                "{errors}\nkeeping the previous grammar ({})",
                g.source.name()
            ),
            None => errors,
        }
    }

    fn summary(&self, comp: &Compilation, source: &Source) -> String {
        let p = &comp.program;
        let n = p.productions.len() + p.decomposition.len() + p.homomorphism.len();
        let mut s = format!(
            "loaded {}: {n} rule{}, {} symbols, derivation length {}",
            source.name(),
            if n == 1 { "" } else { "s" },
            p.symbols.len(),
            p.derivation_length
        );
        if !comp.warnings.is_empty() {
            let w = comp.warnings.len();
            s.push_str(&format!(", {w} warning{}", if w == 1 { "" } else { "s" }));
        }
        s
    }

    // --------------------------------------------------------- derivation

    /// Derives again from the axiom to step `target`.
    pub(super) fn rederive(&mut self, target: u32) -> Out {
        self.history.clear();
        self.pos = 0;
        self.goto(target)
    }

    /// Moves to step `target`, deriving what is not kept; the status, or
    /// why it stopped earlier (an error, Ctrl-C) with the status there.
    pub fn goto(&mut self, target: u32) -> Out {
        match self.derive_to(target) {
            Ok(()) => Ok(self.status()),
            Err(e) => Err(match self.history.is_empty() {
                true => e,
                false => format!("{e}\n{}", self.status()),
            }),
        }
    }

    fn derive_to(&mut self, target: u32) -> Result<(), String> {
        let t0 = Instant::now();
        let color = self.color;
        let render = |e: &dyn miette::Diagnostic| crate::driver::render_diagnostic(e, color);
        let Session {
            grammar,
            history,
            pos,
            opts,
            interrupt,
            meters,
            ..
        } = self;
        let g = grammar.as_ref().ok_or_else(|| {
            "no grammar yet: `:load FILE`, or start one with `:axiom MODULES`".to_string()
        })?;
        let (program, compiled) = (&g.comp.program, &g.comp.compiled);
        if history.is_empty() {
            let end = program.derivation_length;
            let d =
                Simulation::new(program, compiled, opts.clone(), end).map_err(|e| render(&e))?;
            history.push(Some(d.derivation().checkpoint()));
            *pos = 0;
        }
        let t = target as usize;
        if history.get(t).is_some_and(Option::is_some) {
            *pos = target;
            return Ok(());
        }
        let start = (0..=t.min(history.len() - 1))
            .rev()
            .find(|&i| history[i].is_some())
            .expect("step 0 is always kept");
        let cp = history[start].as_ref().expect("found above");
        let end = program.derivation_length;
        let mut d =
            Simulation::resume(program, compiled, opts.clone(), end, cp).map_err(|e| render(&e))?;
        *pos = start as u32;
        let bar = meter(meters);
        let total = target - start as u32;
        for s in start + 1..=t {
            if interrupt.swap(false, Ordering::SeqCst) {
                return Err(format!(
                    "interrupted: stopped at step {pos} (`:step` goes on from there)"
                ));
            }
            bar.stage(Stage::Derive {
                done: (s - start - 1) as u32,
                of: total,
            });
            if let Err(e) = d.step() {
                return Err(format!("{}derivation stopped at step {pos}", render(&e)));
            }
            if history.len() <= s {
                history.resize(s + 1, None);
            }
            history[s] = Some(d.derivation().checkpoint());
            *pos = s as u32;
            trim(history, *pos as usize);
        }
        drop(bar);
        self.derive_time = t0.elapsed();
        Ok(())
    }

    /// The string at step `step` (derived if not kept), staying where we are.
    pub(super) fn string_at(&mut self, step: u32) -> Result<ModuleStore, String> {
        let here = self.pos;
        let got = self.derive_to(step).map(|_| {
            self.current()
                .cloned()
                .expect("derive_to succeeded, so the step is kept")
        });
        self.derive_to(here)?;
        got
    }

    /// `step N: M modules` and the string (abbreviated).
    pub(super) fn status(&self) -> String {
        match (self.current(), &self.grammar) {
            (Some(s), Some(g)) => format!(
                "step {}: {} module{}\n{}",
                self.pos,
                s.len(),
                if s.len() == 1 { "" } else { "s" },
                show::abbreviate(
                    s,
                    &g.comp.program.symbols,
                    self.numbers(&g.comp.program),
                    show::BUDGET,
                )
            ),
            _ => format!("step {}: no string", self.pos),
        }
    }

    /// Steps kept in memory and their size in bytes.
    pub(super) fn history_size(&self) -> (usize, usize) {
        let kept = self.history.iter().flatten();
        let n = kept.clone().count();
        (n, kept.map(|c| bytes(&c.string)).sum())
    }
}

fn bytes(s: &ModuleStore) -> usize {
    s.len() * 4 + s.param_count() * 8
}

/// Drops the oldest kept strings (never step 0, nor `keep`) while the
/// history holds more than [`HISTORY_BYTES`].
fn trim(history: &mut [Option<Checkpoint>], keep: usize) {
    let mut total: usize = history.iter().flatten().map(|c| bytes(&c.string)).sum();
    for (i, slot) in history.iter_mut().enumerate().skip(1) {
        if total <= HISTORY_BYTES {
            break;
        }
        if i != keep {
            if let Some(c) = slot.take() {
                total -= bytes(&c.string);
            }
        }
    }
}
