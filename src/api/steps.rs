//! A derivation as an iterator: a compiled [`Grammar`] and a last step
//! in; the axiom and the string after each step out, as [`Derived`]
//! values (`lsys derive --every`).

use super::derived::Derived;
use super::grammar::Grammar;
use crate::diag::Diagnostics;
use crate::simulation::Simulation;

impl Grammar {
    /// The axiom and the string after each step, up to the file's
    /// `derivation length:`.
    pub fn steps(&self) -> Steps<'_> {
        self.steps_to(self.derivation_length())
    }

    /// The axiom and the string after each step, up to `steps`.
    pub fn steps_to(&self, steps: u32) -> Steps<'_> {
        Steps::new(self, steps)
    }
}

/// The axiom and the string after each step ([`Grammar::steps`]); `End:`
/// runs with the last. After an error the iterator ends.
pub struct Steps<'g> {
    grammar: &'g Grammar,
    sim: Option<Simulation<'g>>,
    /// An error to hand out before ending.
    pending: Option<Diagnostics>,
    target: u32,
    started: bool,
}

/// A short form: the grammar's name, the last step and whether it ended.
impl std::fmt::Debug for Steps<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Steps")
            .field("grammar", &self.grammar.name())
            .field("to", &self.target)
            .field("ended", &self.sim.is_none())
            .finish()
    }
}

impl<'g> Steps<'g> {
    pub(crate) fn new(grammar: &'g Grammar, target: u32) -> Steps<'g> {
        let (sim, pending) = match grammar.simulation(target) {
            Ok(s) => (Some(s), None),
            Err(e) => (None, Some(e)),
        };
        Steps {
            grammar,
            sim,
            pending,
            target,
            started: false,
        }
    }
}

impl Iterator for Steps<'_> {
    type Item = Result<Derived, Diagnostics>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some(e) = self.pending.take() {
            self.sim = None;
            return Some(Err(e));
        }
        let sim = self.sim.as_mut()?;
        if !self.started {
            self.started = true;
            if self.target == 0 {
                // No step follows: End: runs after the axiom.
                self.pending = sim.finish().err().map(Diagnostics::one);
            }
            return Some(Ok(self.grammar.derived(sim.current().clone(), 0)));
        }
        if sim.step_number() >= self.target {
            self.sim = None;
            return None;
        }
        Some(match sim.step() {
            Ok(()) => Ok(self
                .grammar
                .derived(sim.current().clone(), sim.step_number())),
            Err(e) => {
                self.sim = None;
                Err(Diagnostics::one(e))
            }
        })
    }
}
