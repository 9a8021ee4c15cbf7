//! The rewriting engine: [`Program`] + [`Compiled`] in, module strings out,
//! one parallel step at a time ([`Derivation`]), plus the homomorphism
//! that produces the interpreted string ([`homomorphism`]).

use std::mem;
use std::sync::Arc;

use super::error::{DepthWarning, DeriveError, Src};
use super::matching::{match_at, Bound, Input, Rules};
use super::rng::{Rand48, DEFAULT_SEED};
use super::store::{head_arity, head_sym, ContextIndex, ModuleStore, MAX_SYMBOLS};
use crate::bytecode::vm::{self, NoSink};
use crate::bytecode::{Chunk, Compiled, CondCode, Fault, FaultKind};
use crate::resolve::{Program, Table};
use crate::source::Span;

/// Limits and seed of a derivation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeriveOptions {
    /// Overrides the program's `seed:`; with neither, [`DEFAULT_SEED`] (0).
    pub seed: Option<u64>,
    /// Largest string (in modules) a step may produce (`--max-modules`).
    pub max_modules: usize,
    /// Largest number of parameter values a string may hold
    /// (`--max-params`); at most `u32::MAX`.
    pub max_params: usize,
}

impl Default for DeriveOptions {
    fn default() -> DeriveOptions {
        DeriveOptions {
            seed: None,
            max_modules: 50_000_000,
            max_params: 200_000_000,
        }
    }
}

impl DeriveOptions {
    /// The seed in effect for `program`: `--seed`, else `seed:`, else 0.
    pub fn effective_seed(&self, program: &Program) -> u64 {
        self.seed.or(program.seed).unwrap_or(DEFAULT_SEED)
    }
}

const TABLES: [Table; 3] = [Table::Main, Table::Decomposition, Table::Homomorphism];

fn table_index(t: Table) -> usize {
    match t {
        Table::Main => 0,
        Table::Decomposition => 1,
        Table::Homomorphism => 2,
    }
}

fn table_name(t: Table) -> &'static str {
    match t {
        Table::Main => "production",
        Table::Decomposition => "decomposition",
        Table::Homomorphism => "homomorphism",
    }
}

/// Everything that does not change during a derivation.
struct Tables<'p> {
    program: &'p Program,
    compiled: &'p Compiled,
    rules: [Rules; 3],
    /// `skip[s]`: context matching passes over symbol `s`.
    skip: Vec<bool>,
    max_modules: usize,
    max_params: usize,
}

impl<'p> Tables<'p> {
    fn new(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: &DeriveOptions,
    ) -> Result<Tables<'p>, DeriveError> {
        let nsyms = program.symbols.len();
        if nsyms > MAX_SYMBOLS {
            return Err(DeriveError::TooManySymbols {
                count: nsyms,
                limit: MAX_SYMBOLS,
            });
        }
        let rules = TABLES.map(|t| {
            let never: Vec<bool> = compiled
                .table(t)
                .iter()
                .map(|c| matches!(c.cond, CondCode::Never(_)))
                .collect();
            Rules::new(program.table(t), &never, nsyms)
        });
        Ok(Tables {
            program,
            compiled,
            rules,
            skip: (0..nsyms as u32)
                .map(|s| program.skips_in_context(s))
                .collect(),
            max_modules: opts.max_modules,
            max_params: opts.max_params.min(u32::MAX as usize),
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
struct State {
    rng: Rand48,
    stack: Vec<f64>,
    binds: Vec<f64>,
    weights: Vec<(u32, f64)>,
    levels: Vec<Level>,
    warnings: Vec<DepthWarning>,
    step: u32,
}

impl State {
    fn new(tab: &Tables, seed: u64) -> State {
        State {
            rng: Rand48::new(seed),
            stack: vec![0.0; tab.compiled.max_stack.max(1)],
            binds: vec![0.0; tab.nbinds().max(1)],
            weights: Vec::new(),
            levels: Vec::new(),
            warnings: Vec::new(),
            step: 0,
        }
    }
}

fn src(tab: &Tables, span: Span) -> Src {
    Arc::new(tab.program.sources.named_source(span))
}

/// Where code ran, for error messages.
#[derive(Clone, Copy)]
enum Site {
    Axiom,
    Prod(Table, usize),
}

fn site_context(tab: &Tables, site: Site) -> (String, Option<Span>) {
    match site {
        Site::Axiom => ("in the axiom".to_string(), None),
        Site::Prod(t, i) => {
            let p = &tab.program.table(t)[i];
            let mut text = crate::bytecode::one_line(tab.program.sources.slice(p.span));
            if text.chars().count() > 80 {
                text = text.chars().take(77).collect::<String>() + "...";
            }
            (format!("in {} `{text}`", table_name(t)), Some(p.head_span))
        }
    }
}

fn fault_error(tab: &Tables, fault: Fault, site: Site, step: u32) -> DeriveError {
    let (context, prod) = site_context(tab, site);
    let production = prod.filter(|p| p.file == fault.span.file).map(Into::into);
    let src = src(tab, fault.span);
    let span = fault.span.into();
    match fault.kind {
        FaultKind::DivisionByZero | FaultKind::RemainderByZero => DeriveError::DivisionByZero {
            what: if fault.kind == FaultKind::DivisionByZero {
                "division"
            } else {
                "remainder"
            },
            context,
            step,
            src,
            span,
            production,
        },
        FaultKind::NotFinite(value) => DeriveError::NotFinite {
            value,
            context,
            step,
            src,
            span,
            production,
        },
    }
}

fn check_limits(
    tab: &Tables,
    out: &ModuleStore,
    site: Option<Site>,
    step: u32,
) -> Result<(), DeriveError> {
    let over_modules = out.len() > tab.max_modules;
    let over_params = out.param_count() > tab.max_params;
    if !over_modules && !over_params {
        return Ok(());
    }
    let (src, production) = match site {
        Some(Site::Prod(t, i)) => {
            let p = &tab.program.table(t)[i];
            (Some(src(tab, p.head_span)), Some(p.head_span.into()))
        }
        _ => (None, None),
    };
    Err(if over_modules {
        DeriveError::ModuleLimit {
            step,
            limit: tab.max_modules,
            reached: out.len(),
            src,
            production,
        }
    } else {
        DeriveError::ParamLimit {
            step,
            limit: tab.max_params,
            reached: out.param_count(),
            src,
            production,
        }
    })
}

/// Run an expression chunk (condition or probability).
#[inline]
fn eval(
    tab: &Tables,
    st: &mut State,
    chunk: &Chunk,
    binds: &[f64],
    site: Site,
) -> Result<f64, DeriveError> {
    vm::run(
        chunk,
        &tab.compiled.consts,
        binds,
        &mut st.stack,
        &mut st.rng,
        &mut NoSink,
    )
    .map_err(|f| fault_error(tab, f, site, st.step))
}

/// The slice a match's bindings are in.
#[inline]
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
#[inline]
fn applies(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    i: usize,
    off: usize,
) -> Result<Option<Bound>, DeriveError> {
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
) -> Result<Option<(usize, Bound)>, DeriveError> {
    let rules = &tab.rules[table_index(t)];
    let cands = rules.candidates(head_sym(inp.heads[i]));
    for (ci, &p) in cands.iter().enumerate() {
        let p = p as usize;
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
            if !rules.shapes[q].has_prob {
                continue;
            }
            if let Some(b) = applies(tab, st, t, q, inp, i, off)? {
                let w = weight(tab, st, t, q, inp, off, b)?;
                st.weights.push((q as u32, w));
            }
        }
        // Exactly one draw per decision.
        let u = st.rng.next_f64();
        let total: f64 = st.weights.iter().map(|&(_, w)| w).sum();
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

fn weight(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    off: usize,
    bound: Bound,
) -> Result<f64, DeriveError> {
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
        return Err(DeriveError::BadProbability {
            value: w,
            context,
            step: st.step,
            src: src(tab, span),
            span: span.into(),
            production: prod.filter(|s| s.file == span.file).map(Into::into),
        });
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
fn rewrite(
    tab: &Tables,
    st: &mut State,
    t: Table,
    input: &ModuleStore,
    index: Option<&ContextIndex>,
    depth: u32,
    out: &mut ModuleStore,
) -> Result<(), DeriveError> {
    let rules = &tab.rules[table_index(t)];
    let codes = tab.compiled.table(t);
    let consts = &tab.compiled.consts[..];
    let max_depth = match t {
        Table::Main => None,
        Table::Decomposition => Some(tab.program.decomposition_depth),
        Table::Homomorphism => Some(tab.program.homomorphism_depth),
    };
    let inp = Input {
        heads: &input.heads,
        params: &input.params,
        index,
    };
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
            continue;
        }
        let Some((p, bound)) = choose(tab, st, t, &inp, i, off)? else {
            let a = head_arity(h);
            out.extend_raw(&heads[i..i + 1], &params[off..off + a]);
            i += 1;
            off += a;
            continue;
        };
        let shape = &rules.shapes[p];
        let site = Site::Prod(t, p);
        let binds = mem::take(&mut st.binds);
        let b = bindings(bound, params, off, shape.pred_params, &binds);
        let succ = &codes[p].succ;
        match max_depth {
            None => {
                let r = vm::run(succ, consts, b, &mut st.stack, &mut st.rng, out);
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
                let r = vm::run(
                    succ,
                    consts,
                    b,
                    &mut st.stack,
                    &mut st.rng,
                    &mut level.store,
                )
                .map_err(|f| fault_error(tab, f, site, st.step));
                st.binds = binds;
                let r = r.and_then(|_| {
                    let idx = if rules.has_context {
                        level.index.build(&level.store);
                        Some(&level.index)
                    } else {
                        None
                    };
                    rewrite(tab, st, t, &level.store, idx, depth + 1, out)
                });
                st.levels[d] = level;
                r?;
            }
        }
        i += shape.pred.len();
        off += shape.pred_params;
        check_limits(tab, out, Some(site), st.step)?;
    }
    Ok(())
}

/// Apply table `t` (decomposition or homomorphism) to `input` into `out`,
/// building the context index when the table needs it.
fn rewrite_recursive(
    tab: &Tables,
    st: &mut State,
    t: Table,
    input: &ModuleStore,
    index: &mut ContextIndex,
    out: &mut ModuleStore,
) -> Result<(), DeriveError> {
    out.clear();
    let idx = if tab.rules[table_index(t)].has_context {
        index.build(input);
        Some(&*index)
    } else {
        None
    };
    rewrite(tab, st, t, input, idx, 0, out)
}

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
        let mut next = ModuleStore::new();
        vm::run(
            &compiled.axiom,
            &compiled.consts,
            &[],
            &mut st.stack,
            &mut st.rng,
            &mut next,
        )
        .map_err(|f| fault_error(&tab, f, Site::Axiom, 0))?;
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
        };
        d.decompose()?;
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

    /// One parallel rewriting step with the main productions, then the
    /// decomposition.
    pub fn step(&mut self) -> Result<(), DeriveError> {
        self.st.step = self.steps + 1;
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
            0,
            &mut self.next,
        )?;
        self.decompose()?;
        mem::swap(&mut self.cur, &mut self.next);
        self.steps += 1;
        Ok(())
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

    /// The homomorphism of the current string (see [`homomorphism`]).
    pub fn homomorphism(&self) -> Result<Interpreted, DeriveError> {
        let opts = DeriveOptions {
            seed: Some(self.seed),
            max_modules: self.tab.max_modules,
            max_params: self.tab.max_params,
        };
        homomorphism(
            self.tab.program,
            self.tab.compiled,
            &self.cur,
            &opts,
            self.steps,
        )
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
pub fn homomorphism(
    program: &Program,
    compiled: &Compiled,
    store: &ModuleStore,
    opts: &DeriveOptions,
    step: u32,
) -> Result<Interpreted, DeriveError> {
    if program.homomorphism.is_empty() {
        return Ok(Interpreted {
            modules: store.clone(),
            warnings: Vec::new(),
        });
    }
    let tab = Tables::new(program, compiled, opts)?;
    let mut st = State::new(&tab, opts.effective_seed(program));
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

/// Derive `steps` steps and return the final string.
pub fn derive(
    program: &Program,
    compiled: &Compiled,
    opts: DeriveOptions,
    steps: u32,
) -> Result<ModuleStore, DeriveError> {
    derive_each(program, compiled, opts, steps, |_, _| {})
}

/// Derive `steps` steps, calling `each(step, string)` for the axiom
/// (step 0) and after every step (`--every`); returns the final string.
pub fn derive_each<F: FnMut(u32, &ModuleStore)>(
    program: &Program,
    compiled: &Compiled,
    opts: DeriveOptions,
    steps: u32,
    mut each: F,
) -> Result<ModuleStore, DeriveError> {
    let mut d = Derivation::new(program, compiled, opts)?;
    each(0, d.current());
    for _ in 0..steps {
        d.step()?;
        each(d.step_number(), d.current());
    }
    Ok(d.into_current())
}
