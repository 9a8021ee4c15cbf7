//! The simulation loop: a compiled grammar and a target step count in, the
//! derived string of every step out. One place owns the loop:
//!
//! ```text
//! Start:, axiom, decomposition -> environments answer queries
//! for each step up to the target:
//!     environments' pass before the step
//!     StartEach:, productions, decomposition -> EndEach: -> environments answer
//! End: once, after the last step run
//! ```
//!
//! In a cpfg model file ([`Profile::shared_random_stream`]) the turtle's
//! interpretation draws from the derivation's generator, as cpfg's does:
//! when the file has query modules the loop interprets each string once
//! (after the axiom and after each step's `EndEach:`, where cpfg's next
//! step interprets it) and every environment reads that one
//! interpretation; [`Simulation::drawn`] continues the same generator.
//!
//! [`Profile::shared_random_stream`]: crate::lang::Profile::shared_random_stream
//!
//! Derive knows nothing of the turtle and the turtle nothing of derive:
//! what answers query modules between steps is an [`Environment`] plugged
//! in here. The turtle's own answers to cpfg's `?P`, `?H`, `?L`, `?U`
//! ([`TurtleQueries`]) are the first one, and the one every simulation of
//! a grammar with query modules gets.

mod environment;
mod pass;
mod queries;

pub use environment::{Environment, StepContext};
pub use pass::EnvironmentPass;
pub use queries::{drawn_sites, TurtleQueries};

use crate::bytecode::Compiled;
use crate::derive::{
    self, Checkpoint, Derivation, DeriveError, DeriveOptions, Interpreted, ModuleStore,
};
use crate::resolve::{Program, SymbolKind};

/// A derivation driven to a target step count, with the environments that
/// answer its query modules.
pub struct Simulation<'p> {
    derivation: Derivation<'p>,
    program: &'p Program,
    compiled: &'p Compiled,
    opts: DeriveOptions,
    target: u32,
    environments: Vec<Box<dyn Environment + 'p>>,
    ended: bool,
    /// cpfg interprets every string (its query modules make it check the
    /// environment), drawing from the derivation's generator.
    interprets_each: bool,
    /// That interpretation of the current string.
    drawn: Option<ModuleStore>,
    /// cpfg interprets the final string for its view volume (the pass
    /// that sets its query modules and draws the homomorphism's random
    /// numbers) only when the view file gives no `box:`; `cpfg -g` then
    /// prints the string as the last step left it.
    view_pass: bool,
    /// The interpretation after the target step, left out because cpfg
    /// makes none there (`view_pass` off); made before a further step.
    deferred: bool,
}

impl<'p> Simulation<'p> {
    /// `Start:`, the axiom and its decomposition, then the environments'
    /// answers for the axiom (cpfg interprets the axiom too before the
    /// first step reads it). `target` is the step after which `End:` runs
    /// (normally `-n`, else the file's `derivation length:`). A grammar
    /// with query modules gets [`TurtleQueries`].
    pub fn new(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        target: u32,
    ) -> Result<Simulation<'p>, DeriveError> {
        let derivation = Derivation::new(program, compiled, opts.clone())?;
        Simulation::around(derivation, program, compiled, opts, target)
    }

    /// Continues from `cp` (see [`Derivation::resume`]); the environments
    /// are not asked again about the checkpoint's string.
    pub fn resume(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        target: u32,
        cp: &Checkpoint,
    ) -> Result<Simulation<'p>, DeriveError> {
        let derivation = Derivation::resume(program, compiled, opts.clone(), cp)?;
        let mut s = Simulation::bare(derivation, program, compiled, opts, target);
        s.ended = cp.step >= target && target > 0;
        Ok(s)
    }

    fn bare(
        derivation: Derivation<'p>,
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        target: u32,
    ) -> Simulation<'p> {
        let mut environments: Vec<Box<dyn Environment + 'p>> = Vec::new();
        if derivation.has_queries() {
            environments.push(Box::new(TurtleQueries));
        }
        if let Some(env) = &program.environment {
            environments.push(Box::new(EnvironmentPass::new(env)));
        }
        // cpfg's `checkEnvironment`: a query module anywhere in the file
        // (`?(n,s)`, which opens a sub-L-system, is not one).
        let interprets_each = program.profile.shared_random_stream
            && program
                .symbols
                .list
                .iter()
                .any(|s| s.kind == SymbolKind::Query && s.name != "?");
        let view_pass = !(program.profile.shared_random_stream && program.turtle.view_box);
        Simulation {
            derivation,
            program,
            compiled,
            opts,
            target,
            environments,
            ended: false,
            interprets_each,
            drawn: None,
            view_pass,
            deferred: false,
        }
    }

    fn around(
        derivation: Derivation<'p>,
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        target: u32,
    ) -> Result<Simulation<'p>, DeriveError> {
        let mut s = Simulation::bare(derivation, program, compiled, opts, target);
        s.answer_after()?;
        Ok(s)
    }

    /// [`Simulation::new`] with `extra` environments answering from the
    /// axiom on (after the built-in ones).
    pub fn with_environments(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        target: u32,
        extra: Vec<Box<dyn Environment + 'p>>,
    ) -> Result<Simulation<'p>, DeriveError> {
        let derivation = Derivation::new(program, compiled, opts.clone())?;
        let mut s = Simulation::bare(derivation, program, compiled, opts, target);
        s.environments.extend(extra);
        s.answer_after()?;
        Ok(s)
    }

    /// Adds an environment; it answers after the ones already there,
    /// starting with the next step.
    pub fn with_environment(mut self, env: Box<dyn Environment + 'p>) -> Simulation<'p> {
        self.environments.push(env);
        self
    }

    /// The environments' answers after the axiom or a step, except after
    /// the target step of a cpfg model whose view file has `box:`: cpfg's
    /// batch run interprets the final string only for its view volume,
    /// which a `box:` makes it skip, so the string keeps the query
    /// parameters the last step wrote (topiary's new `?P(0,0,0)`) and no
    /// random number is drawn. Made before a further step, if any.
    fn answer_after(&mut self) -> Result<(), DeriveError> {
        if !self.view_pass && self.derivation.step_number() == self.target {
            self.deferred = true;
            return Ok(());
        }
        self.answer(true)
    }

    /// Every environment answers the queries of the current string, after
    /// a step (`after`) or before the next one.
    fn answer(&mut self, after: bool) -> Result<(), DeriveError> {
        if after && self.interprets_each {
            // Even without an environment to answer: the interpretation
            // draws from the generator the next step goes on with.
            self.drawn = Some(self.derivation.interpret()?.modules);
        }
        if self.environments.is_empty() {
            return Ok(());
        }
        let drawn = self.drawn.take();
        let ctx = StepContext {
            program: self.program,
            compiled: self.compiled,
            opts: &self.opts,
            step: self.derivation.step_number(),
            drawn: drawn.as_ref(),
        };
        for env in &mut self.environments {
            let string = self.derivation.current_mut();
            if after {
                env.after_step(&ctx, string)?;
            } else {
                env.before_step(&ctx, string)?;
            }
        }
        self.derivation.parameters_changed();
        self.drawn = drawn;
        Ok(())
    }

    /// One step: the environments' pass over the current string,
    /// `StartEach:`, productions, decomposition, `EndEach:`, the turtle's
    /// answers to query modules, and `End:` when this was the target step.
    pub fn step(&mut self) -> Result<(), DeriveError> {
        if std::mem::take(&mut self.deferred) {
            self.answer(true)?;
        }
        self.answer(false)?;
        self.drawn = None;
        self.derivation.rewrite_step()?;
        self.derivation.end_each()?;
        self.answer_after()?;
        if self.derivation.step_number() == self.target {
            self.finish()?;
        }
        Ok(())
    }

    /// Steps until the target, telling `observe(done, target)` before each.
    /// `End:` has run once when this returns (also for a target of 0).
    /// Without environments (nor cpfg's interpretation after each step)
    /// the steps are the derivation's
    /// [`run_steps`](Derivation::run_steps) (the last ones depth first
    /// when the grammar allows it), told once.
    pub fn run(&mut self, observe: &mut dyn FnMut(u32, u32)) -> Result<(), DeriveError> {
        let done = self.derivation.step_number();
        // A cpfg file with query modules is interpreted after every step
        // (see `answer`), environments or not: it steps.
        if self.environments.is_empty() && !self.interprets_each && done < self.target {
            observe(done, self.target);
            self.derivation.run_steps(self.target - done)?;
        }
        while self.derivation.step_number() < self.target {
            observe(self.derivation.step_number(), self.target);
            self.step()?;
        }
        self.finish()
    }

    /// The current string as the turtle draws it (the homomorphism's
    /// output), for drawing or printing. In a cpfg model file this is
    /// cpfg's: its interpretation draws from the derivation's generator,
    /// after one interpretation of the string for the view (the one each
    /// string gets anyway when the file has query modules), so each call
    /// goes on drawing and the derivation after it too. Otherwise the
    /// homomorphism starts a generator of its own (see
    /// [`derive::homomorphism`]).
    pub fn drawn(&mut self) -> Result<Interpreted, DeriveError> {
        if !self.program.profile.shared_random_stream {
            return derive::homomorphism(
                self.program,
                self.compiled,
                self.derivation.current(),
                &self.opts,
                self.derivation.step_number(),
            );
        }
        if !self.interprets_each && self.view_pass {
            self.derivation.interpret()?;
        }
        self.derivation.interpret()
    }

    /// `End:`, unless it already ran.
    pub fn finish(&mut self) -> Result<(), DeriveError> {
        if !self.ended {
            self.ended = true;
            self.derivation.end()?;
        }
        Ok(())
    }

    /// The step after which `End:` runs.
    pub fn target(&self) -> u32 {
        self.target
    }

    /// The derivation underneath (the current string, warnings, ...).
    pub fn derivation(&self) -> &Derivation<'p> {
        &self.derivation
    }

    /// The current string.
    pub fn current(&self) -> &ModuleStore {
        self.derivation.current()
    }

    /// Steps done so far (0: the axiom).
    pub fn step_number(&self) -> u32 {
        self.derivation.step_number()
    }

    /// Ends the simulation, keeping the derivation (its string, warnings).
    pub fn into_derivation(self) -> Derivation<'p> {
        self.derivation
    }
}

/// Derives `steps` steps (`End:` after the last) and returns the final
/// string.
pub fn derive(
    program: &Program,
    compiled: &Compiled,
    opts: DeriveOptions,
    steps: u32,
) -> Result<ModuleStore, DeriveError> {
    let mut s = Simulation::new(program, compiled, opts, steps)?;
    s.run(&mut |_, _| {})?;
    Ok(s.into_derivation().into_current())
}

/// Derives `steps` steps, calling `each(step, string)` for the axiom
/// (step 0) and after every step (`--every`); returns the final string.
pub fn derive_each<F: FnMut(u32, &ModuleStore)>(
    program: &Program,
    compiled: &Compiled,
    opts: DeriveOptions,
    steps: u32,
    mut each: F,
) -> Result<ModuleStore, DeriveError> {
    let mut s = Simulation::new(program, compiled, opts, steps)?;
    each(0, s.current());
    while s.step_number() < steps {
        s.step()?;
        each(s.step_number(), s.current());
    }
    s.finish()?;
    Ok(s.into_derivation().into_current())
}
