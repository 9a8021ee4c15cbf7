//! One rewriting pass: a table of productions (with their code, in
//! [`Tables`]) and an input string in, the rewritten string appended to an
//! output store out. Holds the dispatch loop, the paper's choice of a
//! production (the first match; a stochastic choice among those with a
//! probability; cpfg's choice is `stochastic.rs`'s) and the recursion of
//! decomposition and homomorphism. Whether a production applies and what
//! it weighs is asked of `condition.rs`; faults and limit overruns become
//! [`DeriveError`](super::DeriveError)s in `faults.rs`.

use std::mem;

use super::condition::{applies, bindings, weight};
use super::error::{DepthWarning, Fail};
use super::faults::{check_limits, fault_error, src, Site};
use super::matching::{match_at, Bound, Input};
use super::run::run_successor;
use super::state::{Level, State};
use super::store::{head_arity, head_sym, rest_of_branch, ContextIndex, ModuleStore};
use super::sublsystem::switch_lsystem;
use super::tables::{table_index, table_name, Tables};
use crate::resolve::Table;

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
