//! An environment pass, as cpfg runs one: the string before a step in
//! (interpreted through the homomorphism, as the turtle draws it), every
//! `?E` sent in string order with its parameters and the turtle fields
//! the communication file asks for, formatted as cpfg formats them; the
//! parameters the environmental program sets written back out.

use super::environment::{Environment, StepContext};
use crate::derive::{DeriveError, ModuleStore};
use crate::environment::communication::FieldKind;
use crate::environment::{self, EnvironmentalProgram, Query};

/// Runs a model's environmental program before every step.
pub struct EnvironmentPass {
    env: environment::EnvironmentSpec,
    program: Box<dyn EnvironmentalProgram>,
}

impl EnvironmentPass {
    pub fn new(env: &environment::EnvironmentSpec) -> EnvironmentPass {
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

impl Environment for EnvironmentPass {
    fn before_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        let Some(e) = ctx.program.symbols.get("?E") else {
            return Ok(());
        };
        let sites: Vec<_> = super::queries::drawn_sites(ctx, string)
            .unwrap_or_default()
            .into_iter()
            .filter(|s| s.sym == e)
            .collect();
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
