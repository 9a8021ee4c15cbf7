//! Depth-first expansion of the last steps (issue 19, item 3): a [`Plan`]
//! (the fast path applies), a string and a number of steps in; the string
//! those steps derive out, written once, in order — or "not done", and the
//! caller steps as usual from the same string.
//!
//! Why: stepping writes every intermediate string in full (W2: about
//! twice the final string, every `F` and bracket copied at every step,
//! into freshly faulted pages). Under the fast path every module rewrites
//! independently of its neighbours and of the order of evaluation (no
//! context, no probability, no `ran`), so the string after `n` steps is
//! the concatenation of each module expanded `n` times. Each module is
//! expanded depth first through one small buffer per level, which stays
//! in the cache; only the final string is written to memory, and the
//! modules that no production rewrites any more are copied into it
//! directly at the level where they appear.
//!
//! Identical results: the productions, conditions and successor templates
//! are those of the fast step. Whatever the fast step would give up on (a
//! fault, a value that is not finite) or the engine would report (a string
//! of some step over `--max-modules` / `--max-params`) makes this give up
//! too, and the caller redoes the steps one by one, reporting exactly
//! what it always did. The size of every intermediate string is still
//! known: each module is counted at the level it is written, and a module
//! no production rewrites counts once at every later level.
//!
//! Repeated subtrees: the expansion of a module depends only on the
//! module (its symbol and the bits of its parameters) and the steps to go,
//! so when a module is the same as the last one expanded with as many
//! steps to go (W2's two `A(x+1)` of one successor, W1's `F F`), its
//! expansion is copied from the output already written, counts included
//! ([`Memo`]). W2: only one branch per level is expanded; the output is
//! written by copies.
//!
//! Two cores: with two threads in the rayon pool, an input of
//! [`PAR_SPLIT`] modules or more is cut in two halves expanded at once;
//! their counts add up and the second output is appended to the first
//! (W2: 8.2 -> 4.5 ms, docs/performance/issue-19-rounds-1-4.md, round 2).
//! Only when the output looks large ([`SPLIT_OUTPUT`], judged from a
//! first slice expanded alone): starting the pool costs a small build
//! more than the split saves.

use super::fast::{first_match, run_range, LimitSink, Plan};
use super::store::{head_arity, head_sym, ModuleStore};
use super::tables::Tables;
use crate::bytecode::vm::{self, Machine};
use crate::lang::rng::Rand48;

/// The last steps of a subtree are done breadth first, a whole (small)
/// string at a time, by the fast step's own loop: expanding every module
/// of the last levels one by one cost more per module than that loop
/// (W1's `F --> FF`: 30 % slower than stepping).
const LEAF_DEPTH: usize = 4;

/// Most steps expanded depth first (the recursion is this deep); a longer
/// derivation steps up to the last ones as usual.
pub(crate) const MAX_DEPTH: u32 = 64;

/// Inputs of at least this many modules are split in two halves, each
/// expanded on a thread of its own when the rayon pool has two.
pub(crate) const PAR_SPLIT: usize = 64;

/// A split input's first `1 / PROBE_PARTS` is expanded on one thread;
/// only if it wrote at least `SPLIT_OUTPUT / PROBE_PARTS` modules is the
/// rest split in halves (tests/depth_first.rs reaches both).
const PROBE_PARTS: usize = 8;
pub(crate) const SPLIT_OUTPUT: usize = 1 << 16;

/// Memo slots per level (see [`Expander::memo`]).
const SLOTS: usize = 8;

/// Per level (steps to go), modules and parameters written, and kept.
type Levels = (Vec<(usize, usize)>, Vec<(usize, usize)>);

/// Expand `input` by `steps` steps (1 ..= [`MAX_DEPTH`]) into `out`
/// (cleared first). `Some(len)`: done, `len` the length of the string one
/// step before the last (for the memory projection of a later step);
/// `None`: not done, `out` holds garbage.
pub(crate) fn expand(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    input: &ModuleStore,
    steps: u32,
    out: &mut ModuleStore,
) -> Option<usize> {
    debug_assert!((1..=MAX_DEPTH).contains(&steps));
    out.clear();
    let d = steps as usize;
    let (heads, params) = (&input.heads[..], &input.params[..]);
    let split = heads.len() >= PAR_SPLIT
        && super::parallel::threads() > 1
        && !repetitive(tab, heads, params);
    let (written, kept) = if split {
        // A first slice on this thread tells whether the rest is worth two
        // threads: starting the pool costs more than a small build's whole
        // derivation (a Pailou's 1,600 modules: 0.7 ms against 0.3).
        let probe = (heads.len() / PROBE_PARTS).max(1);
        let off: usize = heads[..probe].iter().map(|&h| head_arity(h)).sum();
        let first = run(plan, tab, stack, &heads[..probe], &params[..off], d, out)?;
        let (heads, params) = (&heads[probe..], &params[off..]);
        let rest = if out.len().saturating_mul(PROBE_PARTS) >= SPLIT_OUTPUT {
            halves(plan, tab, stack, heads, params, d, out)?
        } else {
            run(plan, tab, stack, heads, params, d, out)?
        };
        add(first, rest)
    } else {
        run(plan, tab, stack, heads, params, d, out)?
    };
    // The string of each step between the input and the output: what was
    // written at its level, plus every module kept from an earlier level.
    let (mut mods, mut params) = (0usize, 0usize);
    let mut before_last = input.len();
    for q in (1..d).rev() {
        mods += kept[q + 1].0;
        params += kept[q + 1].1;
        let (m, p) = (written[q].0 + mods, written[q].1 + params);
        if tab.over(m, p) {
            return None;
        }
        before_last = m;
    }
    Some(before_last)
}

/// Expand `heads` `d` steps in two halves at once, the first appended to
/// `out` here, the second on the pool's other thread and then appended
/// (one copy of half the output, against a second core).
fn halves(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    heads: &[u32],
    params: &[f64],
    d: usize,
    out: &mut ModuleStore,
) -> Option<Levels> {
    let half = heads.len() / 2;
    let off: usize = heads[..half].iter().map(|&h| head_arity(h)).sum();
    let mut right = ModuleStore::new();
    let mut stack2 = vec![0.0; stack.len()];
    let (a, b) = rayon::join(
        || run(plan, tab, stack, &heads[..half], &params[..off], d, out),
        || {
            run(
                plan,
                tab,
                &mut stack2,
                &heads[half..],
                &params[off..],
                d,
                &mut right,
            )
        },
    );
    let both = add(a?, b?);
    out.heads.extend_from_slice(&right.heads);
    out.params.extend_from_slice(&right.params);
    (!tab.over(out.len(), out.param_count())).then_some(both)
}

/// The counts of two pieces of one string, level by level.
fn add((mut written, mut kept): Levels, (w2, k2): Levels) -> Levels {
    for (x, y) in written.iter_mut().zip(w2).chain(kept.iter_mut().zip(k2)) {
        x.0 += y.0;
        x.1 += y.1;
    }
    (written, kept)
}

/// Whether most modules to rewrite at the start of `heads` (the first
/// [`SAMPLE`]) repeat an earlier one: then the memo copies most of the
/// output, which is faster on one core than two halves and the copy that
/// joins them (W2: 0.8 ms against 7 ms, docs/performance/issue-19-rounds-1-4.md,
/// round 3).
fn repetitive(tab: &Tables, heads: &[u32], params: &[f64]) -> bool {
    let has_rules = &tab.rules[0].has_rules;
    let mut seen = std::collections::HashSet::new();
    let (mut n, mut repeats, mut off) = (0usize, 0usize, 0usize);
    for &h in heads {
        let a = head_arity(h);
        if has_rules[head_sym(h) as usize] {
            let bits: Vec<u64> = params[off..off + a].iter().map(|x| x.to_bits()).collect();
            repeats += usize::from(!seen.insert((h, bits)));
            n += 1;
            if n == SAMPLE {
                break;
            }
        }
        off += a;
    }
    2 * repeats >= n
}

/// Modules looked at by [`repetitive`].
const SAMPLE: usize = 4096;

/// Expand `heads` (parameters `params`) `d` steps, appending to `out`;
/// the counts per level.
fn run(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    heads: &[u32],
    params: &[f64],
    d: usize,
    out: &mut ModuleStore,
) -> Option<Levels> {
    let mut e = Expander {
        plan,
        tab,
        stack,
        out,
        levels: (0..=d).map(|_| ModuleStore::new()).collect(),
        written: vec![(0, 0); d + 1],
        kept: vec![(0, 0); d + 1],
        scratch: [ModuleStore::new(), ModuleStore::new()],
        memo: (0..=d).map(|_| Default::default()).collect(),
    };
    e.string(heads, params, d).ok()?;
    Some((e.written, e.kept))
}

struct Expander<'a, 't, 'p> {
    plan: &'a Plan,
    tab: &'a Tables<'p>,
    stack: &'a mut [f64],
    out: &'t mut ModuleStore,
    /// `levels[r]`: the successor being expanded with `r` steps to go.
    levels: Vec<ModuleStore>,
    /// `written[q]`: modules and parameters written by productions into
    /// the string `q` steps before the output.
    written: Vec<(usize, usize)>,
    /// `kept[r]`: modules (and parameters) found with `r` steps to go that
    /// no production rewrites: they are in each of the `r` later strings.
    kept: Vec<(usize, usize)>,
    /// The strings of the breadth-first steps.
    scratch: [ModuleStore; 2],
    /// `memo[r][slot(head)]`: the last module of its slot expanded with
    /// `r` steps to go (a slot per symbol modulo [`SLOTS`], so that
    /// alternating symbols, W1's `F X F X`, each find their last).
    memo: Vec<[Memo; SLOTS]>,
}

/// The last module expanded at one level: what it wrote to the output and
/// what it added to the counts of the levels below (and its own kept).
#[derive(Default)]
struct Memo {
    valid: bool,
    head: u32,
    params: Vec<u64>,
    heads: std::ops::Range<usize>,
    values: std::ops::Range<usize>,
    /// Per level `0..r` (written) and `0..=r` (kept): the counts added.
    written: Vec<(usize, usize)>,
    kept: Vec<(usize, usize)>,
}

impl Memo {
    fn is(&self, head: u32, b: &[f64]) -> bool {
        self.valid
            && self.head == head
            && self.params.len() == b.len()
            && self.params.iter().zip(b).all(|(&x, y)| x == y.to_bits())
    }
}

impl Expander<'_, '_, '_> {
    /// Expand every module of `heads` (parameters `params`) `r` steps.
    fn string(&mut self, heads: &[u32], params: &[f64], r: usize) -> Result<(), ()> {
        let has_rules = &self.tab.rules[0].has_rules;
        let n = heads.len();
        let (mut i, mut off) = (0usize, 0usize);
        while i < n {
            if !has_rules[head_sym(heads[i]) as usize] {
                // A run no production rewrites: straight into the output.
                let (i0, off0) = (i, off);
                while i < n && !has_rules[head_sym(heads[i]) as usize] {
                    off += head_arity(heads[i]);
                    i += 1;
                }
                self.keep(&heads[i0..i], &params[off0..off], r)?;
                continue;
            }
            let a = head_arity(heads[i]);
            self.module(heads[i], &params[off..off + a], r)?;
            i += 1;
            off += a;
        }
        Ok(())
    }

    /// Modules that stay as they are for the `r` steps to go.
    #[inline(always)]
    fn keep(&mut self, heads: &[u32], params: &[f64], r: usize) -> Result<(), ()> {
        self.kept[r].0 += heads.len();
        self.kept[r].1 += params.len();
        self.out.extend_raw(heads, params);
        self.check_out()
    }

    fn check_out(&self) -> Result<(), ()> {
        if self.tab.over(self.out.len(), self.out.param_count()) {
            return Err(());
        }
        Ok(())
    }

    /// Expand module `head(b)`, which has productions, `r` steps: a copy
    /// of the last module's expansion at this level when it is the same
    /// module, else [`Self::expand_module`], remembered.
    fn module(&mut self, head: u32, b: &[f64], r: usize) -> Result<(), ()> {
        if r < 2 {
            return self.expand_module(head, b, r);
        }
        let slot = head_sym(head) as usize % SLOTS;
        if self.memo[r][slot].is(head, b) {
            return self.repeat(r, slot);
        }
        let (h0, v0) = (self.out.heads.len(), self.out.params.len());
        let mut m = std::mem::take(&mut self.memo[r][slot]);
        m.valid = false;
        m.written.clear();
        m.written.extend_from_slice(&self.written[..r]);
        m.kept.clear();
        m.kept.extend_from_slice(&self.kept[..=r]);
        let res = self.expand_module(head, b, r);
        if res.is_ok() {
            m.valid = true;
            m.head = head;
            m.params.clear();
            m.params.extend(b.iter().map(|x| x.to_bits()));
            m.heads = h0..self.out.heads.len();
            m.values = v0..self.out.params.len();
            for (d, now) in m.written.iter_mut().zip(&self.written) {
                *d = (now.0 - d.0, now.1 - d.1);
            }
            for (d, now) in m.kept.iter_mut().zip(&self.kept) {
                *d = (now.0 - d.0, now.1 - d.1);
            }
        }
        self.memo[r][slot] = m;
        res
    }

    /// The last expansion at level `r` again: its output copied, its counts
    /// added, the limits checked as the expansion itself would.
    fn repeat(&mut self, r: usize, slot: usize) -> Result<(), ()> {
        let m = &self.memo[r][slot];
        for (w, d) in self.written.iter_mut().zip(&m.written) {
            w.0 += d.0;
            w.1 += d.1;
            if self.tab.over(w.0, w.1) {
                return Err(());
            }
        }
        for (k, d) in self.kept.iter_mut().zip(&m.kept) {
            k.0 += d.0;
            k.1 += d.1;
        }
        self.out.heads.extend_from_within(m.heads.clone());
        self.out.params.extend_from_within(m.values.clone());
        self.check_out()
    }

    fn expand_module(&mut self, head: u32, b: &[f64], r: usize) -> Result<(), ()> {
        let Some(p) = first_match(self.plan, self.tab, self.stack, head, b)? else {
            // No production applies now, so none ever will (conditions
            // are pure): the module stays as it is.
            return self.keep(&[head], b, r);
        };
        if r == 1 {
            // The last step writes straight into the output.
            let out = &mut *self.out;
            successor(self.plan, self.tab, self.stack, p, b, out)?;
            return self.check_out();
        }
        if r <= LEAF_DEPTH {
            return self.breadth_first(p, b, r);
        }
        let mut succ = std::mem::take(&mut self.levels[r - 1]);
        succ.clear();
        let res = successor(self.plan, self.tab, self.stack, p, b, &mut succ).and_then(|()| {
            let w = &mut self.written[r - 1];
            w.0 += succ.len();
            w.1 += succ.param_count();
            // Each level's string alone can pass the limits: give up
            // early rather than expand all of it.
            if self.tab.over(w.0, w.1) {
                return Err(());
            }
            self.string(&succ.heads, &succ.params, r - 1)
        });
        self.levels[r - 1] = succ;
        res
    }
}

impl Expander<'_, '_, '_> {
    /// Production `p`'s successor for `b`, then `r - 1` more steps of it,
    /// one string at a time (each counted at its level), the last into the
    /// output.
    fn breadth_first(&mut self, p: usize, b: &[f64], r: usize) -> Result<(), ()> {
        let [mut cur, mut next] = std::mem::take(&mut self.scratch);
        cur.clear();
        let mut res = successor(self.plan, self.tab, self.stack, p, b, &mut cur);
        for q in (1..r).rev() {
            if res.is_err() {
                break;
            }
            let w = &mut self.written[q];
            w.0 += cur.len();
            w.1 += cur.param_count();
            if self.tab.over(w.0, w.1) {
                res = Err(());
                break;
            }
            let to = if q == 1 {
                &mut *self.out
            } else {
                next.clear();
                &mut next
            };
            let mut sink = LimitSink::new(to, self.tab);
            res = run_range(
                self.plan,
                self.tab,
                self.stack,
                &cur.heads,
                &cur.params,
                &mut sink,
            );
            std::mem::swap(&mut cur, &mut next);
        }
        self.scratch = [cur, next];
        res
    }
}

/// Write production `p`'s successor for bindings `b` to `out`, as the fast
/// step does (its template, else its code). `Err`: not finite, or a fault.
#[inline(always)]
fn successor(
    plan: &Plan,
    tab: &Tables,
    stack: &mut [f64],
    p: usize,
    b: &[f64],
    out: &mut ModuleStore,
) -> Result<(), ()> {
    if let Some(t) = plan.template(p) {
        return t.write(b, &mut out.heads, &mut out.params);
    }
    // Eligible code never draws from the generator.
    let mut rng = Rand48::new(0);
    let machine = Machine::pure(&tab.compiled.consts, stack, &mut rng);
    vm::run(&tab.compiled.main[p].succ, b, machine, out)
        .map(|_| ())
        .map_err(|_| ())
}
