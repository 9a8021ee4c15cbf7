//! An environment pass, as cpfg runs one: the string before a step in
//! (interpreted through the homomorphism, as the turtle draws it), every
//! `?E` sent in string order with its parameters and the turtle fields
//! the communication file asks for, formatted as cpfg formats them; the
//! parameters the environmental program sets written back out.

use super::environment::{Environment, StepContext};
use crate::derive::{self, DeriveError, ModuleStore};
use crate::environment::communication::FieldKind;
use crate::environment::{self, Program, Query};
use crate::resolve::Program as Grammar;
use crate::turtle::{self, QuerySite, TurtleOptions};

/// Runs a model's environmental program before every step.
pub struct EnvironmentPass {
    env: environment::Environment,
    program: Box<dyn Program>,
}

impl EnvironmentPass {
    pub fn new(env: &environment::Environment) -> EnvironmentPass {
        EnvironmentPass {
            program: env.program(),
            env: env.clone(),
        }
    }

    /// A vector field printed and read back as the file's format says
    /// (components without a conversion are read as plain floats).
    fn vector(&self, kind: FieldKind, v: glam::DVec3) -> Option<[f32; 3]> {
        let conv = self.env.field(kind)?;
        let c = [v.x, v.y, v.z];
        Some([0, 1, 2].map(|k| conv.get(k).map_or(c[k] as f32, |cv| cv.round(c[k]))))
    }

    fn scalar(&self, kind: FieldKind, v: f32) -> Option<f32> {
        let conv = self.env.field(kind)?;
        Some(conv.first().map_or(v, |c| c.round(v as f64)))
    }
}

/// The `?E` sites of `string`, as the turtle finds them in the string it
/// draws: the homomorphism's output when it keeps every `?E` in order,
/// else the string itself.
fn sites(ctx: &StepContext<'_>, string: &ModuleStore) -> Vec<QuerySite> {
    let grammar: &Grammar = ctx.program;
    let Some(e) = grammar.symbols.get("?E") else {
        return Vec::new();
    };
    let opts = TurtleOptions::new(grammar, None, None, None);
    let own: Vec<QuerySite> = turtle::query_sites(grammar, string, &opts)
        .unwrap_or_default()
        .into_iter()
        .filter(|s| s.sym == e)
        .collect();
    if grammar.homomorphism.is_empty() {
        return own;
    }
    let dopts = derive::DeriveOptions {
        seed: Some(ctx.opts.effective_seed(grammar)),
        ..ctx.opts.clone()
    };
    let drawn = derive::homomorphism(grammar, ctx.compiled, string, &dopts, ctx.step)
        .ok()
        .and_then(|h| turtle::query_sites(grammar, &h.modules, &opts).ok());
    match drawn {
        Some(d) => {
            let d: Vec<QuerySite> = d.into_iter().filter(|s| s.sym == e).collect();
            if d.len() == own.len() {
                // The string's modules, at the places the turtle draws them.
                own.iter()
                    .zip(d)
                    .map(|(o, d)| QuerySite {
                        index: o.index,
                        offset: o.offset,
                        arity: o.arity,
                        ..d
                    })
                    .collect()
            } else {
                own
            }
        }
        None => own,
    }
}

impl Environment for EnvironmentPass {
    fn before_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        let sites = sites(ctx, string);
        if sites.is_empty() {
            return Ok(());
        }
        let params = string.params();
        // cpfg sends its environment vectors with z negated relative to the
        // frame its `?P` modules report (lsys's cpfg frame): found with the
        // light-sierp-tetra model, whose chiba answers depend on absolute
        // positions and match cpfg's exactly only so.
        let flip = |v: glam::DVec3| {
            if ctx.program.profile.cpfg_turtle {
                glam::DVec3::new(v.x, v.y, -v.z)
            } else {
                v
            }
        };
        let queries: Vec<Query> = sites
            .iter()
            .map(|s| Query {
                index: s.index,
                params: params[s.offset..s.offset + s.arity].to_vec(),
                position: self.vector(FieldKind::Position, flip(s.frame.pos)),
                heading: self.vector(FieldKind::Heading, flip(s.frame.h)),
                left: self.vector(FieldKind::Left, flip(s.frame.l)),
                up: self.vector(FieldKind::Up, flip(s.frame.u)),
                line_width: self.scalar(FieldKind::LineWidth, s.width),
                scale: self.scalar(FieldKind::ScaleFactor, s.scale),
            })
            .collect();
        let replies = self.program.respond(&queries);
        let params = string.params_mut();
        for (site, reply) in sites.iter().zip(replies) {
            for (k, v) in reply.into_iter().enumerate().take(site.arity) {
                if let Some(v) = v {
                    params[site.offset + k] = v;
                }
            }
        }
        Ok(())
    }
}
