//! Running compiled code against a derivation's state: a successor into an
//! output string (with the dialect's parameter storage) and the
//! L-system's statement blocks. Input: [`Tables`], [`State`], a chunk;
//! output: modules appended, variables changed, or a fault.

use super::error::Fail;
use super::faults::{fault_error, Site};
use super::state::State;
use super::store::ModuleStore;
use super::tables::Tables;
use crate::bytecode::vm::{self, NoSink};
use crate::bytecode::{Chunk, Fault};

/// Round the parameters written since `from` to `f32`, when the dialect
/// stores them so.
#[inline]
pub(crate) fn store_params(tab: &Tables, out: &mut ModuleStore, from: usize) {
    if tab.f32_params {
        for v in &mut out.params[from..] {
            *v = *v as f32 as f64;
        }
    }
}

/// Run a successor chunk with bindings `binds`, appending to `out`.
#[inline]
pub(crate) fn run_successor(
    tab: &Tables,
    st: &mut State,
    succ: &Chunk,
    binds: &[f64],
    out: &mut ModuleStore,
) -> Result<f64, Fault> {
    let from = out.params.len();
    let r = vm::run(succ, binds, st.machine(tab.compiled), out);
    store_params(tab, out, from);
    r
}

/// Run one of the L-system's statement blocks, if it has it.
pub(crate) fn run_hook(
    tab: &Tables,
    st: &mut State,
    name: &'static str,
    chunk: Option<&Chunk>,
) -> Result<(), Fail> {
    let Some(chunk) = chunk else {
        return Ok(());
    };
    vm::run(chunk, &[], st.machine(tab.compiled), &mut NoSink)
        .map(|_| ())
        .map_err(|f| fault_error(tab, f, Site::Hook(name), st.step))
}
