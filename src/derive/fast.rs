//! The fast main-table step: a [`Plan`] (built once per derivation from the
//! program's main productions and their code) and an input string in, the
//! rewritten string out — or "not done", and the general engine
//! (`rewrite.rs`) does the step instead.
//!
//! Why: the general dispatch loop pays for features most large derivations
//! never use (context, multi-module predecessors, stochastic choice,
//! binding buffers, recursion levels). This loop keeps only
//! "first candidate whose condition holds, run its successor".
//!
//! Eligibility is a conservative whitelist ([`Plan::new`]): the paper's
//! dialect, and every main production has a one-module strict predecessor, no context, no
//! probability, and its condition and successor use only the instructions
//! listed in [`op_allowed`] (no `ran`, so the generator is untouched and
//! the step's result cannot depend on evaluation order). Anything else —
//! including any instruction or production feature added later — leaves
//! the derivation on the general engine.
//!
//! The fast step never reports errors itself: on a VM fault or a limit
//! overrun it gives up, the string is left untouched, and the general
//! engine redoes the step from the same input (with the generator in the
//! same state), producing exactly the diagnostic it always did.

use super::store::{head_arity, head_sym, ModuleStore};
use super::tables::Tables;
use super::template::{Cond, Succ};
use crate::bytecode::vm::{self, Machine, NoSink, Sink};
use crate::bytecode::{Chunk, CondCode, Op, ProdCode};
use crate::lang::rng::Rand48;

/// Instructions the fast path may run. Everything here is a pure function
/// of the bindings and the constant pool (no generator, no state), so the
/// fast and parallel steps compute exactly what the general engine does.
/// New instructions are not listed and so disable the fast path.
fn op_allowed(op: &Op) -> bool {
    matches!(
        op,
        Op::Const(_)
            | Op::Param(_)
            | Op::Neg
            | Op::Not
            | Op::Add
            | Op::Sub
            | Op::Mul
            | Op::Div
            | Op::Rem
            | Op::Pow
            | Op::Lt
            | Op::Le
            | Op::Gt
            | Op::Ge
            | Op::Eq
            | Op::Ne
            | Op::Jump(_)
            | Op::JumpIfFalse(_)
            | Op::JumpIfTrue(_)
            | Op::Call(_)
            | Op::Index { .. }
            | Op::Emit { .. }
            | Op::EmitConst { .. }
            | Op::Ret
    )
}

fn chunk_allowed(c: &Chunk) -> bool {
    c.code.iter().all(op_allowed)
}

/// Modules and parameter values a successor always writes, when that is
/// known without running it (no jumps, so every `Emit` runs once).
fn static_output(c: &Chunk) -> Option<(usize, usize)> {
    let mut mods = 0;
    let mut params = 0;
    for op in &c.code {
        match *op {
            Op::Jump(_) | Op::JumpIfFalse(_) | Op::JumpIfTrue(_) => return None,
            Op::Emit { arity, .. } | Op::EmitConst { arity, .. } => {
                mods += 1;
                params += arity as usize;
            }
            _ => {}
        }
    }
    Some((mods, params))
}

/// Inputs smaller than this are rewritten on one core (the default
/// [`Plan::par_min`]): below it the threads' start-up and the extra passes
/// of `parallel.rs` cost more than they save. (Measured: W2 at 2^18
/// modules per step is no faster on two busy cores.)
const PAR_MIN_MODULES: usize = 1 << 20;

/// What the fast step needs besides the tables: whether it applies, and
/// the fixed output size of every production (for the parallel step).
pub(crate) struct Plan {
    /// `out[p]`: modules and parameters production `p` writes, when fixed.
    pub(crate) out: Vec<Option<(usize, usize)>>,
    /// Strings this long or longer are rewritten in parallel.
    pub(crate) par_min: usize,
    /// `succ[p]`: production `p`'s successor as a template, when simple.
    succ: Vec<Option<Succ>>,
    /// `cond[p]`: its condition as a comparison, when simple.
    cond: Vec<Option<Cond>>,
}

impl Plan {
    /// The plan for `tab`'s main table, or `None` when some production
    /// needs the general engine.
    pub(crate) fn new(tab: &Tables) -> Option<Plan> {
        let rules = &tab.rules[0];
        if rules.has_context {
            return None;
        }
        // Only the dialect whose rewriting is exactly "first matching
        // production, run its code": other dialects may add rules of their
        // own to the general engine (cpfg's `%` cuts, parameters stored
        // as f32) that no instruction shows.
        if !tab.program.profile.fast_path || !tab.program.sub_lsystems.is_empty() {
            return None;
        }
        let consts = &tab.compiled.consts;
        let mut out = Vec::with_capacity(rules.shapes.len());
        let mut succs = Vec::with_capacity(rules.shapes.len());
        let mut conds = Vec::with_capacity(rules.shapes.len());
        for (shape, code) in rules.shapes.iter().zip(&tab.compiled.main) {
            // Every field is named, so a field added to `ProdCode` (a new
            // kind of code a production runs) stops the build here until
            // the fast path has been taught about it.
            let ProdCode { cond, prob, succ } = code;
            let cond_ok = match cond {
                CondCode::Always | CondCode::Never(_) => true,
                CondCode::Code(c) => chunk_allowed(c),
            };
            let simple = shape.pred.len() == 1
                && shape.lctx.is_empty()
                && shape.rctx.is_empty()
                && shape.direct
                && !shape.has_prob
                && prob.is_none();
            if !(simple && cond_ok && chunk_allowed(succ)) {
                return None;
            }
            out.push(static_output(succ));
            succs.push(Succ::new(succ, consts));
            conds.push(match cond {
                CondCode::Code(c) => Cond::new(c, consts),
                _ => None,
            });
        }
        Some(Plan {
            out,
            par_min: PAR_MIN_MODULES,
            succ: succs,
            cond: conds,
        })
    }

    /// Production `p`'s successor as a template, when it is simple enough.
    #[inline(always)]
    pub(crate) fn template(&self, p: usize) -> Option<&Succ> {
        self.succ[p].as_ref()
    }

    /// Rewrite `input` with the main table into `out` (cleared first), on
    /// this thread (`parallel.rs`'s `fast_step` decides when to use all
    /// cores instead). `false`: not done (fault or limit), `out` holds
    /// garbage and the general engine must do the step.
    pub(crate) fn step(
        &self,
        tab: &Tables,
        stack: &mut [f64],
        input: &ModuleStore,
        out: &mut ModuleStore,
    ) -> bool {
        out.clear();
        // Growth is usually steady: reserve for the same ratio as the last
        // step so the vectors are not regrown (and their pages faulted in)
        // while writing.
        out.heads.reserve(input.len());
        out.params.reserve(input.param_count());
        let mut sink = LimitSink::new(out, tab);
        run_range(self, tab, stack, &input.heads, &input.params, &mut sink).is_ok()
    }
}

/// Where the fast loop writes: the general store (checking the limits as
/// the general engine does) or a slice of a preallocated one.
pub(crate) trait Out: Sink {
    /// Copy modules unchanged.
    fn copy(&mut self, heads: &[u32], params: &[f64]);
    /// Called after every production or copied run; `Err`: give up.
    fn check(&self) -> Result<(), ()>;
    /// Write successor template `t` with bindings `b`; `Err`: a value is
    /// not finite.
    fn template(&mut self, t: &Succ, b: &[f64]) -> Result<(), ()>;
}

pub(crate) struct LimitSink<'a> {
    out: &'a mut ModuleStore,
    max_modules: usize,
    max_params: usize,
}

impl<'a> LimitSink<'a> {
    /// Writing to `out` within `tab`'s limits.
    pub(crate) fn new(out: &'a mut ModuleStore, tab: &Tables) -> LimitSink<'a> {
        LimitSink {
            out,
            max_modules: tab.max_modules,
            max_params: tab.max_params,
        }
    }
}

impl Sink for LimitSink<'_> {
    #[inline(always)]
    fn emit(&mut self, sym: u32, params: &[f64]) {
        self.out.push(sym, params);
    }
}

impl Out for LimitSink<'_> {
    #[inline(always)]
    fn copy(&mut self, heads: &[u32], params: &[f64]) {
        self.out.extend_raw(heads, params);
    }

    #[inline(always)]
    fn check(&self) -> Result<(), ()> {
        if self.out.len() > self.max_modules || self.out.param_count() > self.max_params {
            return Err(());
        }
        Ok(())
    }

    #[inline(always)]
    fn template(&mut self, t: &Succ, b: &[f64]) -> Result<(), ()> {
        t.write(b, &mut self.out.heads, &mut self.out.params)
    }
}

/// The production that applies to the module `head` with parameters `b`,
/// if any: the first candidate (file order) whose condition holds.
/// `Err`: the condition faulted.
#[inline(always)]
pub(crate) fn first_match(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    head: u32,
    b: &[f64],
) -> Result<Option<usize>, ()> {
    let rules = &tab.rules[0];
    let codes = &tab.compiled.main;
    for &p in rules.candidates(head_sym(head)) {
        let p = p as usize;
        if rules.shapes[p].pred[0].head != head {
            continue;
        }
        match &codes[p].cond {
            CondCode::Always => return Ok(Some(p)),
            CondCode::Never(_) => {}
            CondCode::Code(_) if plan.cond[p].is_some() => {
                if plan.cond[p].is_some_and(|c| c.holds(b)) {
                    return Ok(Some(p));
                }
            }
            CondCode::Code(ch) => {
                // No `ran` in eligible code: the generator is never drawn.
                let mut rng = Rand48::new(0);
                let machine = Machine::pure(&tab.compiled.consts, stack, &mut rng);
                let v = vm::run(ch, b, machine, &mut NoSink).map_err(|_| ())?;
                // Zero is false; anything else, NaN included, is true.
                if v != 0.0 {
                    return Ok(Some(p));
                }
            }
        }
    }
    Ok(None)
}

/// Rewrite the modules `heads` (parameters `params`, starting with the
/// first module's) into `sink`.
#[inline(always)]
pub(crate) fn run_range<S: Out>(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    heads: &[u32],
    params: &[f64],
    sink: &mut S,
) -> Result<(), ()> {
    let rules = &tab.rules[0];
    let codes = &tab.compiled.main;
    let consts = &tab.compiled.consts[..];
    let mut rng = Rand48::new(0);
    let n = heads.len();
    let (mut i, mut off) = (0usize, 0usize);
    while i < n {
        let h = heads[i];
        if !rules.has_rules[head_sym(h) as usize] {
            let (i0, off0) = (i, off);
            while i < n && !rules.has_rules[head_sym(heads[i]) as usize] {
                off += head_arity(heads[i]);
                i += 1;
            }
            sink.copy(&heads[i0..i], &params[off0..off]);
            sink.check()?;
            continue;
        }
        let a = head_arity(h);
        let b = &params[off..off + a];
        match first_match(plan, tab, stack, h, b)? {
            None => sink.copy(&heads[i..i + 1], b),
            Some(p) if plan.succ[p].is_some() => {
                if let Some(t) = &plan.succ[p] {
                    sink.template(t, b)?;
                }
            }
            Some(p) => {
                vm::run(
                    &codes[p].succ,
                    b,
                    Machine::pure(consts, stack, &mut rng),
                    sink,
                )
                .map_err(|_| ())?;
            }
        }
        sink.check()?;
        i += 1;
        off += a;
    }
    Ok(())
}
