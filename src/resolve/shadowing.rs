//! Productions that an earlier one always takes the place of, beyond the
//! plain case `statements.rs` reports (an earlier production for the same
//! predecessor with no condition, context or probability): each
//! production's table, predecessor, context, condition and probability
//! in, in file order; a warning out when
//!
//! - an earlier *stochastic* production for the predecessor has no
//!   condition and no context: every such module goes to the stochastic
//!   choice, which only stochastic productions join, so a later production
//!   without a probability is never chosen (the paper's dialect; cpfg
//!   model files give it a weight of 1 instead);
//! - an earlier production with the same predecessor *and the same
//!   context* has no condition or probability: it always applies first.

use std::collections::HashMap;

use super::ir::{PatItem, PatModule, SymId, Table, CLOSE_BRACKET, OPEN_BRACKET};
use crate::source::Span;

/// Names and parameter counts, brackets as themselves.
type Shapes = Vec<(SymId, u8)>;

/// What a production is, for the checks.
pub(super) struct Candidate<'a> {
    pub table: Table,
    pub pred: &'a [PatModule],
    pub lctx: &'a [PatModule],
    pub rctx: &'a [PatItem],
    /// No condition (or `else`), and the condition compiled.
    pub unconditional: bool,
    pub stochastic: bool,
}

/// Why a production is shadowed, and by which.
pub(super) struct Shadowed {
    pub earlier: Span,
    pub help: &'static str,
}

#[derive(Default)]
pub(super) struct Shadows {
    stochastic: HashMap<(Table, Shapes), Span>,
    with_context: HashMap<(Table, Shapes, Shapes, Shapes), Span>,
}

fn shapes(ms: &[PatModule]) -> Shapes {
    ms.iter().map(|m| (m.sym, m.arity)).collect()
}

fn item_shapes(items: &[PatItem]) -> Shapes {
    items
        .iter()
        .map(|i| match i {
            PatItem::Module(m) => (m.sym, m.arity),
            PatItem::Open(_) => (OPEN_BRACKET, 0),
            PatItem::Close(_) => (CLOSE_BRACKET, 0),
        })
        .collect()
}

impl Shadows {
    /// Checks `c` (whose predecessor starts at `head`) against the
    /// productions before it, then records it. `paper_choice`: stochastic
    /// productions choose among themselves only (not a cpfg model file).
    pub(super) fn check(
        &mut self,
        c: &Candidate<'_>,
        head: Span,
        paper_choice: bool,
    ) -> Option<Shadowed> {
        let pred = shapes(c.pred);
        let context = c.lctx.len() + c.rctx.len() > 0;
        let found = if !c.stochastic && !context && paper_choice {
            self.stochastic.get(&(c.table, pred.clone())).map(|&earlier| Shadowed {
                earlier,
                help: "an earlier stochastic production for the same predecessor has no condition or context: every such module goes to the stochastic choice, which only productions with a probability join; give this one a probability (`: p`) to join it, or a condition to the earlier ones",
            })
        } else {
            None
        };
        let key = (c.table, pred, shapes(c.lctx), item_shapes(c.rctx));
        let found = found.or_else(|| {
            (context && !c.stochastic)
                .then(|| self.with_context.get(&key))
                .flatten()
                .map(|&earlier| Shadowed {
                    earlier,
                    help: "an earlier production with the same predecessor and the same context has no condition or probability, so it always applies first; merge the two, or give the earlier one a condition",
                })
        });
        if c.unconditional {
            if c.stochastic && !context {
                self.stochastic
                    .entry((key.0, key.1.clone()))
                    .or_insert(head);
            }
            if context && !c.stochastic {
                self.with_context.entry(key).or_insert(head);
            }
        }
        found
    }
}
