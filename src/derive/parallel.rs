//! The fast main-table step on all cores: a [`Plan`] whose productions all
//! write a fixed number of modules, and a large input string in; the
//! rewritten string out, identical to the serial step's.
//!
//! Chunked rewriting with prefix sums, in three parallel passes over equal
//! slices of the input:
//! 1. parameter values per slice (heads only), prefix-summed into each
//!    slice's parameter offset;
//! 2. output modules and parameter values per slice (conditions are run,
//!    successors are not: their output size is fixed), prefix-summed into
//!    each slice's place in the output;
//! 3. every slice rewrites straight into its place in the output vectors,
//!    so nothing is copied twice and the output's pages are first touched
//!    by the core that writes them.
//!
//! Eligible code draws no random numbers and has no side effects (see
//! `fast.rs`), so the slices are independent.

use std::mem::MaybeUninit;

use rayon::prelude::*;

use super::fast::{first_match, run_range, Out, Plan};
use super::store::{head_arity, pack, ModuleStore};
use super::tables::Tables;
use super::template::Succ;
use crate::bytecode::vm::Sink;

/// How many threads rayon runs on, without starting its global pool:
/// asking rayon starts it, spawning its threads (0.3–1.5 ms of a small
/// build's process, a Toukung's, that never splits its work). Inside a
/// pool, that pool's size; outside, `RAYON_NUM_THREADS` or the cores, as
/// the global pool will be built.
pub fn threads() -> usize {
    if rayon::current_thread_index().is_some() {
        return rayon::current_num_threads();
    }
    static GLOBAL: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *GLOBAL.get_or_init(|| {
        std::env::var("RAYON_NUM_THREADS")
            .ok()
            .and_then(|n| n.parse().ok())
            .filter(|&n: &usize| n > 0)
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
    })
}

/// Slices per thread, so that a slow slice does not leave a core idle.
const SLICES_PER_THREAD: usize = 8;

/// The fast step of `input` into `out`: on all cores when the string has
/// at least [`Plan::par_min`] modules, there is more than one thread and
/// every production writes a fixed number of modules; else on this one
/// ([`Plan::step`]). `false`: not done (fault or limit), `out` holds
/// garbage and the general engine must do the step.
pub(crate) fn fast_step(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    input: &ModuleStore,
    out: &mut ModuleStore,
) -> bool {
    if input.len() >= plan.par_min && threads() > 1 {
        if let Some(done) = step(plan, tab, input, out) {
            return done;
        }
    }
    plan.step(tab, stack, input, out)
}

/// Rewrite `input` into `out` in parallel. `None`: not applicable (a
/// production's output size is not fixed), do it serially; `Some(false)`:
/// a fault or a limit, the general engine must redo the step.
fn step(plan: &Plan, tab: &Tables, input: &ModuleStore, out: &mut ModuleStore) -> Option<bool> {
    let sizes: Vec<(usize, usize)> = plan.out.iter().copied().collect::<Option<_>>()?;
    let n = input.len();
    let k = (rayon::current_num_threads() * SLICES_PER_THREAD)
        .min(n / 4096)
        .max(1);
    let cut: Vec<usize> = (0..=k).map(|c| c * n / k).collect();
    let heads = &input.heads[..];
    let params = &input.params[..];

    // Pass 1: where each slice's parameters start.
    let in_params: Vec<usize> = (0..k)
        .into_par_iter()
        .map(|c| {
            heads[cut[c]..cut[c + 1]]
                .iter()
                .map(|&h| head_arity(h))
                .sum()
        })
        .collect();
    let in_off = prefix(&in_params);

    // Pass 2: how much each slice writes.
    let measured: Vec<Option<(usize, usize)>> = (0..k)
        .into_par_iter()
        .map(|c| {
            let mut stack = vec![0.0; tab.compiled.max_stack.max(1)];
            let hs = &heads[cut[c]..cut[c + 1]];
            let ps = &params[in_off[c]..in_off[c + 1]];
            measure(plan, tab, &sizes, &mut stack, hs, ps).ok()
        })
        .collect();
    let measured: Vec<(usize, usize)> = match measured.into_iter().collect::<Option<_>>() {
        Some(m) => m,
        None => return Some(false),
    };
    let out_mods = prefix(&measured.iter().map(|m| m.0).collect::<Vec<_>>());
    let out_params = prefix(&measured.iter().map(|m| m.1).collect::<Vec<_>>());
    let (total_mods, total_params) = (out_mods[k], out_params[k]);
    if tab.over(total_mods, total_params) {
        return Some(false);
    }

    // Pass 3: write every slice into its place.
    out.clear();
    out.heads.reserve(total_mods);
    out.params.reserve(total_params);
    let mut head_slots = split(&mut out.heads.spare_capacity_mut()[..total_mods], &out_mods);
    let mut param_slots = split(
        &mut out.params.spare_capacity_mut()[..total_params],
        &out_params,
    );
    let ok = head_slots
        .par_iter_mut()
        .zip(param_slots.par_iter_mut())
        .enumerate()
        .all(|(c, (hs, ps))| {
            let mut stack = vec![0.0; tab.compiled.max_stack.max(1)];
            let mut sink = SliceSink {
                heads: hs,
                params: ps,
                h: 0,
                p: 0,
            };
            let inh = &heads[cut[c]..cut[c + 1]];
            let inp = &params[in_off[c]..in_off[c + 1]];
            run_range(plan, tab, &mut stack, inh, inp, &mut sink).is_ok()
                && sink.h == sink.heads.len()
                && sink.p == sink.params.len()
        });
    if !ok {
        return Some(false);
    }
    // SAFETY: every slice wrote each of its slots exactly once (checked
    // just above: the write cursors reached the slices' ends, and the
    // slices tile `0..total`), so the first `total` elements of both
    // vectors are initialised.
    unsafe {
        out.heads.set_len(total_mods);
        out.params.set_len(total_params);
    }
    Some(true)
}

/// `[0, a, a+b, ...]`: the running sums, one longer than `v`.
fn prefix(v: &[usize]) -> Vec<usize> {
    let mut acc = 0;
    let mut p = Vec::with_capacity(v.len() + 1);
    p.push(0);
    for &x in v {
        acc += x;
        p.push(acc);
    }
    p
}

/// Cut `s` at the running sums `at` (as [`prefix`] makes them).
fn split<'a, T>(mut s: &'a mut [T], at: &[usize]) -> Vec<&'a mut [T]> {
    let mut parts = Vec::with_capacity(at.len().saturating_sub(1));
    for w in at.windows(2) {
        let (a, b) = s.split_at_mut(w[1] - w[0]);
        parts.push(a);
        s = b;
    }
    parts
}

/// Modules and parameter values the slice `heads` / `params` rewrites to.
fn measure(
    plan: &Plan,
    tab: &Tables,
    sizes: &[(usize, usize)],
    stack: &mut [f64],
    heads: &[u32],
    params: &[f64],
) -> Result<(usize, usize), ()> {
    let has_rules = &tab.rules[0].has_rules;
    let (mut mods, mut nparams) = (0usize, 0usize);
    let mut off = 0usize;
    for &h in heads {
        let a = head_arity(h);
        let chosen = if has_rules[(h & super::store::SYM_MASK) as usize] {
            first_match(plan, tab, stack, h, &params[off..off + a])?
        } else {
            None
        };
        match chosen {
            Some(p) => {
                mods += sizes[p].0;
                nparams += sizes[p].1;
            }
            None => {
                mods += 1;
                nparams += a;
            }
        }
        off += a;
    }
    Ok((mods, nparams))
}

/// Writes into a slice of the output's spare capacity.
struct SliceSink<'a, 'b> {
    heads: &'b mut &'a mut [MaybeUninit<u32>],
    params: &'b mut &'a mut [MaybeUninit<f64>],
    h: usize,
    p: usize,
}

impl Sink for SliceSink<'_, '_> {
    #[inline(always)]
    fn emit(&mut self, sym: u32, params: &[f64]) {
        self.heads[self.h].write(pack(sym, params.len() as u8));
        self.h += 1;
        for (slot, &v) in self.params[self.p..self.p + params.len()]
            .iter_mut()
            .zip(params)
        {
            slot.write(v);
        }
        self.p += params.len();
    }
}

impl Out for SliceSink<'_, '_> {
    #[inline(always)]
    fn copy(&mut self, heads: &[u32], params: &[f64]) {
        for (slot, &v) in self.heads[self.h..self.h + heads.len()]
            .iter_mut()
            .zip(heads)
        {
            slot.write(v);
        }
        self.h += heads.len();
        for (slot, &v) in self.params[self.p..self.p + params.len()]
            .iter_mut()
            .zip(params)
        {
            slot.write(v);
        }
        self.p += params.len();
    }

    #[inline(always)]
    fn check(&self) -> Result<(), ()> {
        Ok(())
    }

    #[inline(always)]
    fn template(&mut self, t: &Succ, b: &[f64]) -> Result<(), ()> {
        let (m, n) = t.size();
        t.write_into(
            b,
            &mut self.heads[self.h..self.h + m],
            &mut self.params[self.p..self.p + n],
        )?;
        self.h += m;
        self.p += n;
        Ok(())
    }
}
