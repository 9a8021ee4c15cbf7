//! The turtle as an environment: a string after a step in, the parameters
//! of cpfg's query modules (`?P(x,y,z)`, `?H`, `?L`, `?U`) set to the
//! turtle's position and orientation where they stand, and `?S` to the
//! scope's size (docs/shapes.md). Also where every
//! environment finds its query modules ([`drawn_sites`]).

use super::environment::{Environment, StepContext};
use crate::derive::{self, DeriveError, ModuleStore};
use crate::turtle::{self, QuerySite, TurtleOptions};

/// Every query module of `string` with parameters, in string order, with
/// the turtle's state where the turtle draws it: in the homomorphism's
/// output when that keeps the string's query modules (as many, in order),
/// else in the string itself. `None` when the turtle refuses the string
/// (a NaN parameter): its queries then keep their values.
pub fn drawn_sites(ctx: &StepContext<'_>, string: &ModuleStore) -> Option<Vec<QuerySite>> {
    let program = ctx.program;
    let opts = TurtleOptions::new(program, None, None, None);
    let own = turtle::query_sites(program, string, &opts).ok()?;
    if program.homomorphism.is_empty() {
        return Some(own);
    }
    let drawn = match ctx.drawn {
        Some(d) => turtle::query_sites(program, d, &opts).ok(),
        None => {
            let dopts = derive::DeriveOptions {
                seed: Some(ctx.opts.effective_seed(program)),
                ..ctx.opts.clone()
            };
            derive::homomorphism(program, ctx.compiled, string, &dopts, ctx.step)
                .ok()
                .and_then(|h| turtle::query_sites(program, &h.modules, &opts).ok())
        }
    };
    Some(match drawn {
        Some(d) if d.len() == own.len() => own
            .iter()
            .zip(d)
            .map(|(o, d)| QuerySite {
                // The string's module, at the place the turtle draws it.
                index: o.index,
                offset: o.offset,
                arity: o.arity.min(d.arity),
                sym: o.sym,
                ..d
            })
            .collect(),
        _ => own,
    })
}

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
        let Some(sites) = drawn_sites(ctx, string) else {
            return Ok(());
        };
        let symbols = &ctx.program.symbols;
        let params = string.params_mut();
        for s in sites {
            let f = &s.frame;
            let v = match symbols.name(s.sym) {
                "?P" => f.pos,
                "?H" => f.h,
                "?L" => f.l,
                "?U" => f.u,
                // The scope's size (docs/shapes.md).
                "?S" => s.scope,
                _ => continue,
            };
            let n = s.arity.min(3);
            params[s.offset..s.offset + n].copy_from_slice(&[v.x, v.y, v.z][..n]);
        }
        Ok(())
    }
}
