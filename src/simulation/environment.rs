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
    /// The string as the turtle draws it, when the loop has interpreted it
    /// already (a cpfg model file, whose interpretation draws from the
    /// derivation's generator and so must happen once per string, see
    /// [`Profile::shared_random_stream`]); `None`: apply the homomorphism
    /// afresh.
    ///
    /// [`Profile::shared_random_stream`]: crate::lang::Profile::shared_random_stream
    pub drawn: Option<&'a ModuleStore>,
}

/// Something that answers query modules: it reads the string and
/// overwrites the parameters it answers, and only those; the loop then
/// stores parameters as the language profile says (f32 in cpfg's).
///
/// cpfg's order: an environment pass over string k−1 ([`before_step`],
/// before `StartEach:` of step k; none over the final string), while the
/// turtle's own queries (`?P`, ...) are filled by every interpretation
/// ([`after_step`]: after the axiom and after each step, after
/// `EndEach:`, where cpfg's next derivation step interprets the string).
///
/// [`before_step`]: Environment::before_step
/// [`after_step`]: Environment::after_step
pub trait Environment {
    /// Before step `ctx.step + 1` rewrites `string` (step `ctx.step`'s).
    fn before_step(
        &mut self,
        _ctx: &StepContext<'_>,
        _string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        Ok(())
    }

    /// After the axiom (`ctx.step` 0) and after each step.
    fn after_step(
        &mut self,
        _ctx: &StepContext<'_>,
        _string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        Ok(())
    }
}
