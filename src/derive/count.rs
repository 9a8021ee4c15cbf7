//! Counting without deriving (`lsys derive --count`): a program, its code
//! and a number of steps in; the number of modules of every symbol in the
//! string those steps would derive out, without building that string.
//!
//! When every main production takes the fast path (one-module
//! predecessor, no context, no probability, no `ran`; see `fast.rs`) and
//! there is no decomposition, every module rewrites independently of the
//! others and of the order of evaluation, so the string after `n` steps is
//! the concatenation of each axiom module expanded `n` times. That
//! expansion is done depth first, memoising the counts of each
//! (module, remaining steps) pair, so memory stays proportional to the
//! number of distinct modules, and systems of 10^9 modules or more are
//! counted in milliseconds. Otherwise the string is derived (within the
//! usual limits) and counted.

use std::collections::HashMap;

use super::engine::Derivation;
use super::error::DeriveError;
use super::fast::{first_match, Plan};
use super::options::DeriveOptions;
use super::store::{head_arity, head_sym, ModuleStore};
use super::tables::Tables;
use crate::bytecode::vm::{self, Machine};
use crate::bytecode::Compiled;
use crate::lang::rng::Rand48;
use crate::resolve::Program;

/// Distinct (module, remaining steps) pairs remembered; beyond this the
/// expansion goes on without remembering (slower, same result).
const MEMO_LIMIT: usize = 1 << 20;

/// Module counts of a derived string.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Counts {
    /// `per_symbol[s]`: modules with symbol id `s` (saturating at
    /// `u64::MAX`).
    pub per_symbol: Vec<u64>,
    /// Whether the string was counted without being built.
    pub expanded: bool,
}

impl Counts {
    /// All modules together (saturating).
    pub fn total(&self) -> u64 {
        self.per_symbol
            .iter()
            .fold(0u64, |a, &b| a.saturating_add(b))
    }
}

/// The module counts of the string `steps` steps derive.
pub fn count(
    program: &Program,
    compiled: &Compiled,
    opts: DeriveOptions,
    steps: u32,
) -> Result<Counts, DeriveError> {
    let nsyms = program.symbols.len();
    let tab = Tables::new(program, compiled, &opts)?;
    let plan = Plan::new(&tab).filter(|_| program.decomposition.is_empty());
    if let Some(plan) = plan {
        // The axiom (which may call `ran`) is evaluated as usual.
        let axiom = Derivation::new(program, compiled, opts.clone())?.into_current();
        let mut c = Counter {
            plan: &plan,
            tab: &tab,
            stack: vec![0.0; compiled.max_stack.max(1)],
            memo: HashMap::new(),
            levels: Vec::new(),
            nsyms,
        };
        let mut per_symbol = vec![0u64; nsyms];
        let ok = axiom
            .iter()
            .zip(axiom.heads())
            .try_for_each(|(m, &h)| c.expand(h, m.params, steps, &mut per_symbol));
        if ok.is_ok() {
            return Ok(Counts {
                per_symbol,
                expanded: true,
            });
        }
        // A fault: the derivation below reports it as it always does.
    }
    let mut d = Derivation::new(program, compiled, opts)?;
    for _ in 0..steps {
        d.step()?;
    }
    Ok(Counts {
        per_symbol: d
            .current()
            .counts(nsyms)
            .into_iter()
            .map(|c| c as u64)
            .collect(),
        expanded: false,
    })
}

struct Counter<'t, 'p> {
    plan: &'t Plan,
    tab: &'t Tables<'p>,
    stack: Vec<f64>,
    /// (head, parameter bits, remaining steps) -> counts per symbol.
    memo: HashMap<(u32, Vec<u64>, u32), Box<[u64]>>,
    /// Successor scratch per remaining-steps level.
    levels: Vec<ModuleStore>,
    nsyms: usize,
}

fn add(acc: &mut [u64], c: &[u64]) {
    for (a, &b) in acc.iter_mut().zip(c) {
        *a = a.saturating_add(b);
    }
}

impl Counter<'_, '_> {
    /// Add the counts of module `head(params)` rewritten `depth` times.
    /// `Err`: the code faulted.
    fn expand(&mut self, head: u32, params: &[f64], depth: u32, acc: &mut [u64]) -> Result<(), ()> {
        let sym = head_sym(head) as usize;
        if depth == 0 || !self.tab.rules[0].has_rules[sym] {
            acc[sym] = acc[sym].saturating_add(1);
            return Ok(());
        }
        let key = (head, params.iter().map(|v| v.to_bits()).collect(), depth);
        if let Some(c) = self.memo.get(&key) {
            add(acc, c);
            return Ok(());
        }
        let Some(p) = first_match(self.plan, self.tab, &mut self.stack, head, params)? else {
            // No production applies now, so none ever will: the module's
            // symbol and parameters never change.
            acc[sym] = acc[sym].saturating_add(1);
            return Ok(());
        };
        let d = depth as usize;
        if self.levels.len() <= d {
            self.levels.resize_with(d + 1, ModuleStore::new);
        }
        let mut succ = std::mem::take(&mut self.levels[d]);
        succ.clear();
        let mut rng = Rand48::new(0); // eligible code never draws
        let code = &self.tab.compiled.main[p].succ;
        let machine = Machine::pure(&self.tab.compiled.consts, &mut self.stack, &mut rng);
        let r = vm::run(code, params, machine, &mut succ);
        let mut local = vec![0u64; self.nsyms];
        let mut res = r.map(|_| ()).map_err(|_| ());
        if res.is_ok() {
            let mut off = 0;
            for &h in succ.heads() {
                let a = head_arity(h);
                res = self.expand(h, &succ.params()[off..off + a], depth - 1, &mut local);
                if res.is_err() {
                    break;
                }
                off += a;
            }
        }
        self.levels[d] = succ;
        res?;
        add(acc, &local);
        if self.memo.len() < MEMO_LIMIT {
            self.memo.insert(key, local.into_boxed_slice());
        }
        Ok(())
    }
}
