//! The turtle as an environment: a string after a step in, the parameters
//! of cpfg's query modules (`?P(x,y,z)`, `?H`, `?L`, `?U`) set to the
//! turtle's position and orientation where they stand.

use super::environment::{Environment, StepContext};
use crate::derive::{self, DeriveError, ModuleStore};
use crate::turtle::{self, TurtleOptions};

/// Answers `?P`, `?H`, `?L`, `?U` by interpreting the string (through the
/// homomorphism, as the turtle draws it) with the file's own turtle
/// settings.
pub struct TurtleQueries;

impl Environment for TurtleQueries {
    fn after_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        let program = ctx.program;
        let opts = TurtleOptions::new(program, None, None, None);
        let own = turtle::query_values(program, string, &opts);
        // The turtle draws the homomorphism's output; the queries in it are
        // those of the string, in the same order, unless the homomorphism
        // rewrites query modules too (then the string is interpreted as it
        // stands).
        let drawn = if program.homomorphism.is_empty() {
            None
        } else {
            let dopts = derive::DeriveOptions {
                seed: Some(ctx.opts.effective_seed(program)),
                ..ctx.opts.clone()
            };
            derive::homomorphism(program, ctx.compiled, string, &dopts, ctx.step)
                .ok()
                .and_then(|h| turtle::query_values(program, &h.modules, &opts).ok())
        };
        // A string the turtle refuses (a NaN parameter) keeps its values.
        let Ok(own) = own else { return Ok(()) };
        let vals: Vec<(usize, usize, [f64; 3])> = match drawn {
            Some(d) if d.len() == own.len() => own
                .iter()
                .zip(d)
                .map(|(o, d)| (o.0, o.1.min(d.1), d.2))
                .collect(),
            _ => own,
        };
        let params = string.params_mut();
        for (at, n, v) in vals {
            params[at..at + n].copy_from_slice(&v[..n]);
        }
        Ok(())
    }
}
