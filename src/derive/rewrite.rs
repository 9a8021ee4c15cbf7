//! One rewriting pass: a table of productions (with their code) and an
//! input string in, the rewritten string appended to an output store out.
//! Holds the dispatch loop, condition / probability evaluation, the
//! stochastic choice and the recursion of decomposition and homomorphism.
//! Faults and limit overruns become [`DeriveError`]s in `faults.rs`.

use std::mem;

use super::engine::DeriveOptions;
use super::error::{DepthWarning, DeriveError};
pub(crate) use super::faults::{check_limits, fault_error, Fail, Site};
use super::faults::{site_context, src};
use super::matching::{match_at, Bound, Input, Rules};
use super::run::run_successor;
use super::store::{head_arity, head_sym, rest_of_branch, ContextIndex, ModuleStore, MAX_SYMBOLS};
use super::sublsystem::switch_lsystem;
use crate::bytecode::vm::{self, Machine, NoSink};
use crate::bytecode::{Chunk, Compiled, CondCode};
use crate::lang::rng::Rand48;
use crate::resolve::{Program, Table, CLOSE_BRACKET, OPEN_BRACKET};

const TABLES: [Table; 3] = [Table::Main, Table::Decomposition, Table::Homomorphism];

pub(crate) fn table_index(t: Table) -> usize {
    match t {
        Table::Main => 0,
        Table::Decomposition => 1,
        Table::Homomorphism => 2,
    }
}

pub(crate) fn table_name(t: Table) -> &'static str {
    match t {
        Table::Main => "production",
        Table::Decomposition => "decomposition",
        Table::Homomorphism => "homomorphism",
    }
}

/// Everything that does not change during a derivation.
pub(crate) struct Tables<'p> {
    pub(crate) program: &'p Program,
    pub(crate) compiled: &'p Compiled,
    pub(crate) rules: [Rules; 3],
    /// `skip[s]`: context matching passes over symbol `s`.
    pub(crate) skip: Vec<bool>,
    pub(crate) max_modules: usize,
    pub(crate) max_params: usize,
    /// cpfg dialect: parameters are stored as 32-bit floats, as cpfg
    /// stores them in its string (expressions still compute in f64).
    pub(crate) f32_params: bool,
    /// cpfg dialect: the symbol `%`, which cuts the rest of its branch
    /// from the string when the next step reads it.
    pub(crate) cut: Option<u32>,
    /// The alphabet has cpfg query modules to fill after each step.
    pub(crate) has_queries: bool,
    /// A file with sub-L-systems: the symbols `?` (with the L-system's
    /// number) and `$` that start and end one in the string.
    pub(crate) sub_open: Option<u32>,
    pub(crate) sub_close: Option<u32>,
    /// A cpfg model file: probabilities are cpfg's (`stochastic.rs`).
    pub(crate) cpfg_choice: bool,
}

impl<'p> Tables<'p> {
    /// Whether a string of `modules` modules and `params` parameter values
    /// is over `--max-modules` or `--max-params`.
    pub(crate) fn over(&self, modules: usize, params: usize) -> bool {
        modules > self.max_modules || params > self.max_params
    }

    pub(crate) fn new(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: &DeriveOptions,
    ) -> Result<Tables<'p>, Fail> {
        let nsyms = program.symbols.len();
        if nsyms > MAX_SYMBOLS {
            return Err(Box::new(DeriveError::TooManySymbols {
                count: nsyms,
                limit: MAX_SYMBOLS,
            }));
        }
        let profile = program.profile;
        let cut = program
            .symbols
            .get("%")
            .filter(|_| profile.cut_in_rewriting);
        let mut rules = TABLES.map(|t| {
            let never: Vec<bool> = compiled
                .table(t)
                .iter()
                .map(|c| matches!(c.cond, CondCode::Never(_)))
                .collect();
            Rules::new(program.table(t), &never, nsyms)
        });
        if let Some(c) = cut {
            // Route `%` to the dispatch loop, where it is cut.
            rules[0].has_rules[c as usize] = true;
        }
        let subs = !program.sub_lsystems.is_empty();
        let sub_open = program.symbols.get("?").filter(|_| subs);
        let sub_close = program.symbols.get("$").filter(|_| subs);
        for s in [sub_open, sub_close].into_iter().flatten() {
            // The dispatch loop switches L-systems at these.
            for r in &mut rules {
                r.has_rules[s as usize] = true;
            }
        }
        Ok(Tables {
            program,
            compiled,
            rules,
            // Outside the cpfg dialect brackets always structure context.
            skip: (0..nsyms as u32)
                .map(|s| {
                    program.skips_in_context(s)
                        && (profile.context_through_brackets
                            || (s != OPEN_BRACKET && s != CLOSE_BRACKET))
                })
                .collect(),
            max_modules: opts.max_modules,
            max_params: opts.max_params.min(u32::MAX as usize),
            f32_params: profile.f32_params,
            cut,
            has_queries: program.symbols.list.iter().any(|s| {
                s.kind == crate::resolve::SymbolKind::Query
                    && matches!(s.name.as_str(), "?P" | "?H" | "?L" | "?U" | "?S")
            }),
            sub_open,
            sub_close,
            cpfg_choice: profile.cpfg_stochastic,
        })
    }

    fn nbinds(&self) -> usize {
        TABLES
            .iter()
            .flat_map(|&t| self.program.table(t))
            .map(|p| p.nparams as usize)
            .max()
            .unwrap_or(0)
    }
}

/// Scratch for one recursion level of decomposition / homomorphism.
#[derive(Default)]
struct Level {
    store: ModuleStore,
    index: ContextIndex,
}

/// Everything that changes.
pub(crate) struct State {
    pub(crate) rng: Rand48,
    /// cpfg's generator of stochastic choices, in a stochastic cpfg model
    /// file (`stochastic.rs`).
    pub(crate) choice: Option<Rand48>,
    pub(crate) stack: Vec<f64>,
    pub(crate) binds: Vec<f64>,
    /// Variables of cpfg's statement blocks.
    pub(crate) vars: Vec<f64>,
    pub(crate) weights: Vec<(u32, f64)>,
    levels: Vec<Level>,
    pub(crate) warnings: Vec<DepthWarning>,
    pub(crate) step: u32,
    /// When counting (see `Derivation::counting_firings`): how many times
    /// each main production applied; empty otherwise.
    pub(crate) fired: Vec<u64>,
}

impl State {
    /// The VM's context for `compiled`'s code run in this state.
    pub(crate) fn machine<'s>(&'s mut self, compiled: &'s Compiled) -> Machine<'s> {
        Machine {
            consts: &compiled.consts,
            functions: &compiled.functions,
            vars: &mut self.vars,
            stack: &mut self.stack,
            rng: &mut self.rng,
        }
    }

    pub(crate) fn new(tab: &Tables, seed: u64) -> State {
        State {
            rng: Rand48::new(seed),
            choice: None,
            stack: vec![0.0; tab.compiled.max_stack.max(1)],
            binds: vec![0.0; tab.nbinds().max(1)],
            vars: tab.program.var_init.clone(),
            weights: Vec::new(),
            levels: Vec::new(),
            warnings: Vec::new(),
            step: 0,
            fired: Vec::new(),
        }
    }
}

/// Run an expression chunk (condition or probability).
#[inline(always)]
fn eval(
    tab: &Tables,
    st: &mut State,
    chunk: &Chunk,
    binds: &[f64],
    site: Site,
) -> Result<f64, Fail> {
    vm::run(chunk, binds, st.machine(tab.compiled), &mut NoSink)
        .map_err(|f| fault_error(tab, f, site, st.step))
}

/// The slice a match's bindings are in.
#[inline(always)]
fn bindings<'a>(
    bound: Bound,
    params: &'a [f64],
    off: usize,
    n: usize,
    buf: &'a [f64],
) -> &'a [f64] {
    match bound {
        Bound::Direct => &params[off..off + n],
        Bound::Buffer => buf,
    }
}

/// Whether production `p` of table `t` applies at `i` (pattern and
/// condition); leaves its bindings in place.
#[inline(always)]
pub(crate) fn applies(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    i: usize,
    off: usize,
) -> Result<Option<Bound>, Fail> {
    let shape = &tab.rules[table_index(t)].shapes[p];
    let Some(bound) = match_at(shape, inp, &tab.skip, i, off, &mut st.binds) else {
        return Ok(None);
    };
    if let CondCode::Code(ch) = &tab.compiled.table(t)[p].cond {
        let binds = mem::take(&mut st.binds);
        let b = bindings(bound, inp.params, off, shape.pred_params, &binds);
        let v = eval(tab, st, ch, b, Site::Prod(t, p));
        st.binds = binds;
        if v? == 0.0 {
            return Ok(None);
        }
    }
    Ok(Some(bound))
}

/// The production to apply at `i`, if any (first match in file order,
/// stochastic choice among the matching productions with a probability).
fn choose(
    tab: &Tables,
    st: &mut State,
    t: Table,
    inp: &Input,
    i: usize,
    off: usize,
) -> Result<Option<(usize, Bound)>, Fail> {
    if tab.cpfg_choice {
        return super::stochastic::choose(tab, st, t, (inp, i, off));
    }
    let rules = &tab.rules[table_index(t)];
    let cands = rules.candidates(head_sym(inp.heads[i]));
    for (ci, &p) in cands.iter().enumerate() {
        let p = p as usize;
        if rules.shapes[p].lsystem != inp.lsystem {
            continue;
        }
        let Some(bound) = applies(tab, st, t, p, inp, i, off)? else {
            continue;
        };
        if !rules.shapes[p].has_prob {
            return Ok(Some((p, bound)));
        }
        st.weights.clear();
        let w = weight(tab, st, t, p, inp, off, bound)?;
        st.weights.push((p as u32, w));
        for &q in &cands[ci + 1..] {
            let q = q as usize;
            if !rules.shapes[q].has_prob || rules.shapes[q].lsystem != inp.lsystem {
                continue;
            }
            if let Some(b) = applies(tab, st, t, q, inp, i, off)? {
                let w = weight(tab, st, t, q, inp, off, b)?;
                st.weights.push((q as u32, w));
            }
        }
        // Exactly one draw per decision.
        let u = st.rng.next_f64();
        let mut total: f64 = st.weights.iter().map(|&(_, w)| w).sum();
        if total.is_infinite() {
            // Finite weights whose sum overflows (`: 1e308` twice): scale
            // them down so that they still share the draw in proportion.
            let max = st.weights.iter().map(|&(_, w)| w).fold(0.0, f64::max);
            st.weights.iter_mut().for_each(|(_, w)| *w /= max);
            total = st.weights.iter().map(|&(_, w)| w).sum();
        }
        if total <= 0.0 {
            return Ok(None);
        }
        let r = u * total;
        let mut acc = 0.0;
        let mut chosen = None;
        for &(q, w) in &st.weights {
            if w > 0.0 {
                chosen = Some(q as usize);
                acc += w;
                if acc > r {
                    break;
                }
            }
        }
        let q = chosen.expect("a positive weight exists");
        let bound = match_at(&rules.shapes[q], inp, &tab.skip, i, off, &mut st.binds)
            .expect("the chosen production matched");
        return Ok(Some((q, bound)));
    }
    Ok(None)
}

pub(crate) fn weight(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    off: usize,
    bound: Bound,
) -> Result<f64, Fail> {
    let ch = tab.compiled.table(t)[p]
        .prob
        .as_ref()
        .expect("stochastic productions have a probability chunk");
    let binds = mem::take(&mut st.binds);
    let pred_params = tab.rules[table_index(t)].shapes[p].pred_params;
    let b = bindings(bound, inp.params, off, pred_params, &binds);
    let w = eval(tab, st, ch, b, Site::Prod(t, p));
    st.binds = binds;
    let w = w?;
    if !(w >= 0.0 && w.is_finite()) {
        let (context, prod) = site_context(tab, Site::Prod(t, p));
        let span = ch.spans.last().copied().unwrap_or_default();
        return Err(Box::new(DeriveError::BadProbability {
            value: w,
            context,
            step: st.step,
            src: src(tab, span),
            span: span.into(),
            production: prod.filter(|s| s.file == span.file).map(Into::into),
        }));
    }
    Ok(w)
}

/// Record that production `p` of `t` still applied at the depth limit.
fn warn_depth(tab: &Tables, st: &mut State, t: Table, p: usize, depth: u32) {
    let name = table_name(t);
    if let Some(w) = st
        .warnings
        .iter_mut()
        .find(|w| w.table == name && w.production == p)
    {
        w.count += 1;
        return;
    }
    let span = tab.program.table(t)[p].head_span;
    st.warnings.push(DepthWarning {
        table: name,
        depth,
        step: st.step,
        count: 1,
        production: p,
        src: src(tab, span),
        span: span.into(),
    });
}

/// Rewrite `input` with table `t` into `out` (appending). The main table
/// rewrites once; decomposition and homomorphism rewrite the successors
/// again, recursively, until nothing applies or `depth` reaches the limit.
/// `at`: the recursion depth, and the L-system whose productions apply
/// from the start of `input` (the file's first, or the sub-L-system of
/// the module whose successor this is).
pub(crate) fn rewrite(
    tab: &Tables,
    st: &mut State,
    t: Table,
    input: &ModuleStore,
    index: Option<&ContextIndex>,
    at: At,
    out: &mut ModuleStore,
) -> Result<(), Fail> {
    let At { depth, lsystem } = at;
    let rules = &tab.rules[table_index(t)];
    let codes = tab.compiled.table(t);
    let max_depth = match t {
        Table::Main => None,
        Table::Decomposition => Some(tab.program.decomposition_depth),
        Table::Homomorphism => Some(tab.program.homomorphism_depth),
    };
    let mut inp = Input {
        heads: &input.heads,
        params: &input.params,
        index,
        ring: tab.program.ring,
        lsystem,
    };
    // The L-systems that `?(n, s)` entered and `$` has not yet left.
    let mut entered: Vec<u32> = Vec::new();
    let heads = inp.heads;
    let params = inp.params;
    let n = heads.len();
    let (mut i, mut off) = (0usize, 0usize);
    while i < n {
        let h = heads[i];
        if !rules.has_rules[head_sym(h) as usize] {
            // A run of modules no production looks at: copy in bulk.
            let (i0, off0) = (i, off);
            while i < n && !rules.has_rules[head_sym(heads[i]) as usize] {
                off += head_arity(heads[i]);
                i += 1;
            }
            out.extend_raw(&heads[i0..i], &params[off0..off]);
            check_limits(tab, out, None, st.step)?;
            super::stochastic::pass_over(st, t, i - i0);
            continue;
        }
        if t == Table::Main && tab.cut == Some(head_sym(h)) && head_arity(h) == 0 {
            // cpfg's cut: drop `%` and the rest of its branch, up to (not
            // including) the `]` that closes it.
            super::stochastic::pass_over(st, t, 1);
            let (end, skipped) = rest_of_branch(heads, i);
            i = end;
            off += skipped;
            continue;
        }
        // A module is rewritten by its own L-system; `?(n, s)` and `$`
        // themselves by the one they leave.
        let switch = switch_lsystem(tab, h, &params[off..]);
        let Some((p, bound)) = choose(tab, st, t, &inp, i, off)? else {
            let a = head_arity(h);
            out.extend_raw(&heads[i..i + 1], &params[off..off + a]);
            i += 1;
            off += a;
            inp.lsystem = switch.apply(&mut entered, inp.lsystem, lsystem);
            continue;
        };
        if t == Table::Main && !st.fired.is_empty() {
            st.fired[p] += 1;
        }
        let shape = &rules.shapes[p];
        let site = Site::Prod(t, p);
        let binds = mem::take(&mut st.binds);
        let b = bindings(bound, params, off, shape.pred_params, &binds);
        let succ = &codes[p].succ;
        match max_depth {
            None => {
                let r = run_successor(tab, st, succ, b, out);
                st.binds = binds;
                r.map_err(|f| fault_error(tab, f, site, st.step))?;
            }
            Some(max) if depth >= max => {
                st.binds = binds;
                warn_depth(tab, st, t, p, max);
                let plen = shape.pred.len();
                out.extend_raw(&heads[i..i + plen], &params[off..off + shape.pred_params]);
            }
            Some(_) => {
                let d = depth as usize;
                if st.levels.len() <= d {
                    st.levels.resize_with(d + 1, Level::default);
                }
                let mut level = mem::take(&mut st.levels[d]);
                level.store.clear();
                let r = run_successor(tab, st, succ, b, &mut level.store)
                    .map_err(|f| fault_error(tab, f, site, st.step));
                st.binds = binds;
                let r = r.and_then(|_| {
                    let idx = if rules.has_context {
                        level.index.build(&level.store);
                        Some(&level.index)
                    } else {
                        None
                    };
                    // Up to 100 000 levels deep: never overflow the stack.
                    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
                        let at = At {
                            depth: depth + 1,
                            lsystem: inp.lsystem,
                        };
                        rewrite(tab, st, t, &level.store, idx, at, out)
                    })
                });
                st.levels[d] = level;
                r?;
            }
        }
        i += shape.pred.len();
        off += shape.pred_params;
        inp.lsystem = switch.apply(&mut entered, inp.lsystem, lsystem);
        check_limits(tab, out, Some(site), st.step)?;
    }
    Ok(())
}

/// Apply table `t` (decomposition or homomorphism) to `input` into `out`,
/// building the context index when the table needs it.
pub(crate) fn rewrite_recursive(
    tab: &Tables,
    st: &mut State,
    t: Table,
    input: &ModuleStore,
    index: &mut ContextIndex,
    out: &mut ModuleStore,
) -> Result<(), Fail> {
    out.clear();
    let idx = if tab.rules[table_index(t)].has_context {
        index.build(input);
        Some(&*index)
    } else {
        None
    };
    rewrite(tab, st, t, input, idx, At::top(tab), out)
}

/// Where a rewrite starts: see [`rewrite`].
#[derive(Clone, Copy)]
pub(crate) struct At {
    depth: u32,
    lsystem: u32,
}

impl At {
    /// A whole string, in the file's first L-system.
    pub(crate) fn top(tab: &Tables) -> At {
        At {
            depth: 0,
            lsystem: tab.program.main_lsystem,
        }
    }
}
