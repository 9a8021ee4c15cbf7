//! cpfg's sub-L-systems while rewriting: a module of the string in, the
//! L-system whose productions rewrite the modules after it out. `?(n, s)`
//! enters L-system n and `$` returns to the one before (generate.c,
//! `CheckPred`), so a module is rewritten by the L-system that the
//! enclosing `?( )`...`$` name; those two by the one they leave.

use super::store::{head_arity, head_sym};
use super::tables::Tables;

/// What a module does to the L-system that rewrites the modules after it.
#[derive(Clone, Copy)]
pub(crate) enum Switch {
    None,
    /// `?(n, scale)`: L-system n.
    Enter(u32),
    /// `$`: back to the one before.
    Leave,
}

impl Switch {
    /// The L-system after the module; `entered` is the stack of the ones
    /// left behind, `outer` the one the string started in.
    pub(crate) fn apply(self, entered: &mut Vec<u32>, current: u32, outer: u32) -> u32 {
        match self {
            Switch::None => current,
            Switch::Enter(n) => {
                entered.push(current);
                n
            }
            // An unmatched `$` goes back to where the string started, as
            // cpfg's stack stops at its bottom.
            Switch::Leave => entered.pop().unwrap_or(outer),
        }
    }
}

pub(crate) fn switch_lsystem(tab: &Tables, head: u32, params: &[f64]) -> Switch {
    if tab.sub_open.is_none() && tab.sub_close.is_none() {
        return Switch::None;
    }
    let sym = Some(head_sym(head));
    if sym == tab.sub_open && head_arity(head) >= 1 {
        // `?(n, ...)`: n as cpfg reads it, truncated.
        return Switch::Enter(params[0].max(0.0) as u32);
    }
    if sym == tab.sub_close {
        return Switch::Leave;
    }
    Switch::None
}
