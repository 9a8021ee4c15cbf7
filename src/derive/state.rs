//! What changes during a derivation: the generators, the VM's stack,
//! the bindings of the production being applied, the statement blocks'
//! variables, the warnings so far ([`State`]), made from the
//! [`Tables`] and a seed. Every pass of `derive/` writes it; `Tables` is
//! what does not change.

use super::error::DepthWarning;
use super::store::{ContextIndex, ModuleStore};
use super::tables::Tables;
use crate::bytecode::vm::Machine;
use crate::bytecode::Compiled;
use crate::lang::rng::Rand48;

/// Scratch for one recursion level of decomposition / homomorphism.
#[derive(Default)]
pub(crate) struct Level {
    pub(crate) store: ModuleStore,
    pub(crate) index: ContextIndex,
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
    /// Scratch of `rewrite.rs`, one per recursion level.
    pub(crate) levels: Vec<Level>,
    pub(crate) warnings: Vec<DepthWarning>,
    pub(crate) step: u32,
    /// When counting (see `Derivation::counting_firings`): how many times
    /// each main production applied; empty otherwise.
    pub(crate) fired: Vec<u64>,
    /// Loop rounds of the statement blocks in this step (see
    /// [`crate::bytecode::vm::MAX_LOOP_ITERATIONS`]).
    pub(crate) loop_rounds: u64,
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
            rounds: Some(&mut self.loop_rounds),
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
            loop_rounds: 0,
        }
    }
}
