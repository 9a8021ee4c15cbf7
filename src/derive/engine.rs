//! The derivation driver: [`Program`] + [`Compiled`] in, module strings
//! out, one parallel step at a time ([`Derivation`]), plus the homomorphism
//! that produces the interpreted string ([`homomorphism`]). The rewriting
//! pass itself is in `rewrite.rs`.

use std::mem;

use super::error::{DepthWarning, DeriveError};
use super::fast::Plan;
use super::faults::{check_limits, fault_error, Site};
use super::options::DeriveOptions;
use super::parallel::fast_step;
use super::rewrite::{rewrite, rewrite_recursive, At};
use super::run::{run_hook, store_params};
use super::state::State;
use super::store::{ContextIndex, ModuleStore};
use super::tables::Tables;
use crate::bytecode::{vm, Compiled};
use crate::lang::rng::Rand48;
use crate::resolve::{Program, Table};

/// A derivation in progress: the current string and the generator.
///
/// After an error the derivation must not be stepped further.
pub struct Derivation<'p> {
    tab: Tables<'p>,
    st: State,
    seed: u64,
    cur: ModuleStore,
    next: ModuleStore,
    spare: ModuleStore,
    index: ContextIndex,
    steps: u32,
    /// The fast main-table step, when every production is simple enough.
    fast: Option<Plan>,
    /// Length of the string before the current one (growth projection).
    prev_len: usize,
}

impl<'p> Derivation<'p> {
    /// Evaluate the axiom (step 0), then decompose it.
    pub fn new(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
    ) -> Result<Derivation<'p>, DeriveError> {
        let tab = Tables::new(program, compiled, &opts)?;
        let seed = opts.effective_seed(program);
        let mut st = State::new(&tab, seed);
        st.choice = opts.choice_generator(program);
        let mut next = ModuleStore::new();
        run_hook(&tab, &mut st, "Start", compiled.hooks.start.as_ref())?;
        vm::run(&compiled.axiom, &[], st.machine(compiled), &mut next)
            .map_err(|f| fault_error(&tab, f, Site::Axiom, 0))?;
        store_params(&tab, &mut next, 0);
        check_limits(&tab, &next, None, 0)?;
        let mut d = Derivation {
            tab,
            st,
            seed,
            cur: ModuleStore::new(),
            next,
            spare: ModuleStore::new(),
            index: ContextIndex::default(),
            steps: 0,
            fast: None,
            prev_len: 0,
        };
        d.fast = Plan::new(&d.tab);
        if program.profile.decompose_axiom {
            d.decompose()?;
        }
        mem::swap(&mut d.cur, &mut d.next);
        Ok(d)
    }

    /// Apply the decomposition to `next` in place (via `spare`).
    fn decompose(&mut self) -> Result<(), DeriveError> {
        if self.tab.program.decomposition.is_empty() {
            return Ok(());
        }
        rewrite_recursive(
            &self.tab,
            &mut self.st,
            Table::Decomposition,
            &self.next,
            &mut self.index,
            &mut self.spare,
        )?;
        mem::swap(&mut self.next, &mut self.spare);
        Ok(())
    }

    /// One whole step as far as derivation goes: [`rewrite_step`]
    /// (`StartEach:`, the main productions, the decomposition), then
    /// [`end_each`]. Nothing answers query modules and `End:` never runs
    /// here: that is the simulation loop's (`src/simulation/`), which
    /// knows the target step count and the environments.
    ///
    /// [`rewrite_step`]: Derivation::rewrite_step
    /// [`end_each`]: Derivation::end_each
    pub fn step(&mut self) -> Result<(), DeriveError> {
        self.rewrite_step()?;
        self.end_each()
    }

    /// `StartEach:`, one parallel rewriting step with the main
    /// productions, then the decomposition; the result becomes the current
    /// string.
    pub fn rewrite_step(&mut self) -> Result<(), DeriveError> {
        self.st.step = self.steps + 1;
        self.st.loop_rounds = 0;
        let hooks = &self.tab.compiled.hooks;
        run_hook(
            &self.tab,
            &mut self.st,
            "StartEach",
            hooks.start_each.as_ref(),
        )?;
        self.check_memory(self.st.step)?;
        self.prev_len = self.cur.len();
        let fast_done = self.fast.as_ref().is_some_and(|f| {
            fast_step(f, &self.tab, &mut self.st.stack, &self.cur, &mut self.next)
        });
        if !fast_done {
            self.general_step()?;
        }
        self.decompose()?;
        mem::swap(&mut self.cur, &mut self.next);
        self.steps += 1;
        Ok(())
    }

    /// `steps` more whole steps ([`step`](Derivation::step) each), the
    /// last of them (up to 64) expanded depth first straight into the
    /// final string when the grammar allows it: the fast path applies, no
    /// decomposition, no `StartEach:` / `EndEach:` blocks and no query
    /// modules (nothing may look at the strings in between). The result,
    /// and every error, is that of stepping; intermediate strings are
    /// never built. Callers that need each step's string (`--every`, the
    /// REPL, environments) step instead.
    pub fn run_steps(&mut self, steps: u32) -> Result<(), DeriveError> {
        let hooks = &self.tab.compiled.hooks;
        let eligible = self.fast.is_some()
            && self.tab.program.decomposition.is_empty()
            && hooks.start_each.is_none()
            && hooks.end_each.is_none()
            && !self.tab.has_queries;
        let mut deep = if eligible {
            steps.min(super::depth_first::MAX_DEPTH)
        } else {
            0
        };
        for _ in deep..steps {
            self.step()?;
        }
        // With two threads, a string long enough to be split in two first
        // (W2 starts from one module).
        if super::parallel::threads() > 1 {
            while deep > 1 && self.cur.len() < super::depth_first::PAR_SPLIT {
                self.step()?;
                deep -= 1;
            }
        }
        if deep == 0 || !self.depth_first(deep)? {
            for _ in 0..deep {
                self.step()?;
            }
        }
        Ok(())
    }

    /// Refuses step `step` when the string could outgrow the memory left.
    /// Only strings over ~1M modules can exhaust memory in one step; below
    /// that, reading /proc/meminfo would cost more than the step.
    fn check_memory(&self, step: u32) -> Result<(), DeriveError> {
        if self.cur.len() > 1 << 20 {
            super::budget::check(
                self.prev_len,
                &self.cur,
                step,
                (self.tab.max_modules, self.tab.max_params),
                super::budget::available_memory(),
            )?;
        }
        Ok(())
    }

    /// The next `steps` steps depth first; `false`: not done (the string
    /// is as it was, and stepping reports what went wrong).
    fn depth_first(&mut self, steps: u32) -> Result<bool, DeriveError> {
        let Some(plan) = &self.fast else {
            return Ok(false);
        };
        // The first of the steps checks memory as stepping would.
        self.check_memory(self.steps + 1)?;
        let mut out = mem::take(&mut self.next);
        let done = super::depth_first::expand(
            plan,
            &self.tab,
            &mut self.st.stack,
            &self.cur,
            steps,
            &mut out,
        );
        let Some(before_last) = done else {
            self.next = out;
            return Ok(false);
        };
        // The string before is not kept: only the final one is in memory.
        self.cur = out;
        self.prev_len = before_last;
        self.steps += steps;
        self.st.step = self.steps;
        Ok(true)
    }

    /// The `EndEach:` block of the step just rewritten.
    pub fn end_each(&mut self) -> Result<(), DeriveError> {
        let hooks = &self.tab.compiled.hooks;
        run_hook(&self.tab, &mut self.st, "EndEach", hooks.end_each.as_ref())?;
        Ok(())
    }

    /// The `End:` block: once, after the last step the caller runs.
    pub fn end(&mut self) -> Result<(), DeriveError> {
        let hooks = &self.tab.compiled.hooks;
        run_hook(&self.tab, &mut self.st, "End", hooks.end.as_ref())?;
        Ok(())
    }

    /// Whether the alphabet has query modules (`?P`, `?H`, ...) that
    /// something must answer after each step.
    pub fn has_queries(&self) -> bool {
        self.tab.has_queries
    }

    /// After parameters of the current string were overwritten (query
    /// answers): store them as the profile stores parameters (f32 in
    /// cpfg's).
    pub fn parameters_changed(&mut self) {
        store_params(&self.tab, &mut self.cur, 0);
    }

    /// The main-table rewrite of [`step`](Derivation::step) by the general
    /// engine (everything the fast path does not take).
    fn general_step(&mut self) -> Result<(), DeriveError> {
        let idx = if self.tab.rules[0].has_context {
            self.index.build(&self.cur);
            Some(&self.index)
        } else {
            None
        };
        self.next.clear();
        rewrite(
            &self.tab,
            &mut self.st,
            Table::Main,
            &self.cur,
            idx,
            At::top(&self.tab),
            &mut self.next,
        )?;
        Ok(())
    }

    fn with_fast_plan(mut self) -> Derivation<'p> {
        self.fast = Plan::new(&self.tab);
        self
    }

    /// Whether steps take the fast (and, for large strings, parallel)
    /// path of `fast.rs`.
    pub fn uses_fast_path(&self) -> bool {
        self.fast.is_some()
    }

    /// Counts how many times each main production applies from now on
    /// (an editor's code lens). Counting takes the general engine, never
    /// the fast or parallel path, which do not look at productions one by
    /// one.
    pub fn counting_firings(mut self) -> Derivation<'p> {
        self.fast = None;
        self.st.fired = vec![0; self.tab.program.productions.len()];
        self
    }

    /// With [`Derivation::counting_firings`]: the number of times each
    /// main production (`Program::productions`, in order) applied so far.
    pub fn firings(&self) -> &[u64] {
        &self.st.fired
    }

    /// Tests: always use the general engine.
    #[doc(hidden)]
    pub fn without_fast_path(mut self) -> Derivation<'p> {
        self.fast = None;
        self
    }

    /// Tests: rewrite strings of at least `n` modules in parallel (when
    /// there is more than one thread).
    #[doc(hidden)]
    pub fn with_parallel_threshold(mut self, n: usize) -> Derivation<'p> {
        if let Some(f) = &mut self.fast {
            f.par_min = n;
        }
        self
    }

    /// The current string.
    pub fn current(&self) -> &ModuleStore {
        &self.cur
    }

    /// The current string, for filling query modules in place.
    pub fn current_mut(&mut self) -> &mut ModuleStore {
        &mut self.cur
    }

    /// Take the current string, ending the derivation.
    pub fn into_current(self) -> ModuleStore {
        self.cur
    }

    /// Steps done so far (0: the axiom).
    pub fn step_number(&self) -> u32 {
        self.steps
    }

    /// The seed in effect.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Depth-limit warnings of the decomposition so far.
    pub fn warnings(&self) -> &[DepthWarning] {
        &self.st.warnings
    }

    /// The derivation as it stands, to [`resume`](Derivation::resume) later
    /// (the REPL keeps one per step, so going back costs nothing and going
    /// forward again continues with the same random numbers).
    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            string: self.cur.clone(),
            step: self.steps,
            rng: self.st.rng.clone(),
            choice: self.st.choice.clone(),
            vars: self.st.vars.clone(),
            warnings: self.st.warnings.clone(),
        }
    }

    /// Continue a derivation from `cp`, which must come from a derivation
    /// of the same program with the same options: stepping on gives exactly
    /// the strings the original derivation would have given.
    pub fn resume(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: DeriveOptions,
        cp: &Checkpoint,
    ) -> Result<Derivation<'p>, DeriveError> {
        let tab = Tables::new(program, compiled, &opts)?;
        let seed = opts.effective_seed(program);
        let mut st = State::new(&tab, seed);
        st.rng = cp.rng.clone();
        st.choice = cp.choice.clone();
        st.vars = cp.vars.clone();
        st.warnings = cp.warnings.clone();
        st.step = cp.step;
        Ok(Derivation {
            tab,
            st,
            seed,
            cur: cp.string.clone(),
            next: ModuleStore::new(),
            spare: ModuleStore::new(),
            index: ContextIndex::default(),
            steps: cp.step,
            fast: None,
            prev_len: 0,
        }
        .with_fast_plan())
    }

    /// The homomorphism of the current string drawing its random numbers
    /// from this derivation's generator and reading and writing its
    /// variables, as cpfg's turtle does each time it interprets the string
    /// ([`Profile::shared_random_stream`]): the derivation's next draws
    /// come after the interpretation's. Its depth-limit warnings are the
    /// result's, not the derivation's.
    ///
    /// [`Profile::shared_random_stream`]: crate::lang::Profile::shared_random_stream
    pub fn interpret(&mut self) -> Result<Interpreted, DeriveError> {
        if self.tab.program.homomorphism.is_empty() {
            return Ok(Interpreted {
                modules: self.cur.clone(),
                warnings: Vec::new(),
            });
        }
        self.st.step = self.steps;
        self.st.loop_rounds = 0;
        let before = self.st.warnings.len();
        let mut out = ModuleStore::new();
        rewrite_recursive(
            &self.tab,
            &mut self.st,
            Table::Homomorphism,
            &self.cur,
            &mut self.index,
            &mut out,
        )?;
        Ok(Interpreted {
            modules: out,
            warnings: self.st.warnings.split_off(before),
        })
    }

    /// The homomorphism of the current string (see [`homomorphism`]).
    pub fn homomorphism(&self) -> Result<Interpreted, DeriveError> {
        let opts = DeriveOptions {
            seed: Some(self.seed),
            max_modules: self.tab.max_modules,
            max_params: self.tab.max_params,
        };
        homomorphism_in(
            self.tab.program,
            self.tab.compiled,
            &self.cur,
            &opts,
            self.steps,
            Some(&self.st.vars),
        )
    }
}

/// A derivation frozen after a step ([`Derivation::checkpoint`]): the
/// string, the step number and the generator's state.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub string: ModuleStore,
    pub step: u32,
    rng: Rand48,
    choice: Option<Rand48>,
    vars: Vec<f64>,
    warnings: Vec<DepthWarning>,
}

impl Checkpoint {
    /// Depth-limit warnings of the decomposition up to this step.
    pub fn warnings(&self) -> &[DepthWarning] {
        &self.warnings
    }
}

/// The interpreted string and the homomorphism's depth-limit warnings.
#[derive(Debug)]
pub struct Interpreted {
    pub modules: ModuleStore,
    pub warnings: Vec<DepthWarning>,
}

/// Apply the homomorphism recursively (depth `homomorphism_depth`) to
/// `store`, the string of step `step`, producing the string the turtle
/// interprets. It uses its own generator, seeded afresh with
/// `opts.effective_seed(program)` on every call, so interpreting never
/// changes the derivation and the result depends only on the string.
/// Without homomorphism productions the result is a copy of `store`.
/// The statement blocks' variables are those the `Start:` block sets (cpfg
/// models set the homomorphism's constants there, as Ring's angle); a
/// [`Derivation::homomorphism`] sees the derivation's own.
pub fn homomorphism(
    program: &Program,
    compiled: &Compiled,
    store: &ModuleStore,
    opts: &DeriveOptions,
    step: u32,
) -> Result<Interpreted, DeriveError> {
    homomorphism_in(program, compiled, store, opts, step, None)
}

fn homomorphism_in(
    program: &Program,
    compiled: &Compiled,
    store: &ModuleStore,
    opts: &DeriveOptions,
    step: u32,
    vars: Option<&[f64]>,
) -> Result<Interpreted, DeriveError> {
    if program.homomorphism.is_empty() {
        return Ok(Interpreted {
            modules: store.clone(),
            warnings: Vec::new(),
        });
    }
    let tab = Tables::new(program, compiled, opts)?;
    let mut st = State::new(&tab, opts.effective_seed(program));
    match vars {
        Some(v) => st.vars.copy_from_slice(v),
        None => {
            // On a copy of the generator: the homomorphism's own sequence
            // stays what it was without the block.
            let rng = st.rng.clone();
            run_hook(&tab, &mut st, "Start", compiled.hooks.start.as_ref())?;
            st.rng = rng;
        }
    }
    st.step = step;
    let mut out = ModuleStore::new();
    let mut index = ContextIndex::default();
    rewrite_recursive(
        &tab,
        &mut st,
        Table::Homomorphism,
        store,
        &mut index,
        &mut out,
    )?;
    Ok(Interpreted {
        modules: out,
        warnings: st.warnings,
    })
}
