//! The seam between the simulation loop and whatever answers query
//! modules: a string after a step in, some of its parameters overwritten.

use crate::bytecode::Compiled;
use crate::derive::{DeriveError, DeriveOptions, ModuleStore};
use crate::resolve::Program;

/// What an environment is told about the step it answers.
pub struct StepContext<'a> {
    pub program: &'a Program,
    pub compiled: &'a Compiled,
    /// The derivation's options (its seed: an environment that interprets
    /// the string through the homomorphism seeds it the same way).
    pub opts: &'a DeriveOptions,
    /// The step whose string is answered (0: the axiom).
    pub step: u32,
}

/// Something that answers query modules after each step: it reads the
/// string and overwrites the parameters it answers, and only those. The
/// loop then stores parameters as the language profile says (f32 in
/// cpfg's) and runs `EndEach:`.
pub trait Environment {
    fn answer(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError>;
}
