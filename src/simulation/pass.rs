//! An environment pass, as cpfg runs one: the string before a step in
//! (interpreted through the homomorphism, as the turtle draws it), every
//! `?E` sent in string order with its parameters and the turtle fields
//! the communication file asks for, formatted as cpfg formats them; the
//! parameters the environmental program sets written back out.

use super::environment::{Environment, StepContext};
use crate::derive::{DeriveError, ModuleStore};
use crate::environment::communication::FieldKind;
use crate::environment::format::Conversion;
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
    /// (components without a conversion are read as plain floats). cpfg
    /// copies the turtle into the communication library's `CTURTLE`, whose
    /// vectors are C `float`s, before printing them: the value is rounded
    /// to `f32` first. Printed from the double, a position a hair past a
    /// tie rounds the other way (two-trees' `?E` at x = -2.3985 went as
    /// -2.399 where cpfg sends -2.398, and its light answer differed).
    fn vector(&self, kind: FieldKind, v: glam::DVec3) -> Option<[f32; 3]> {
        let conv = self.env.field(kind)?;
        let c = [v.x, v.y, v.z].map(|x| x as f32);
        Some([0, 1, 2].map(|k| conv.get(k).map_or(c[k], |cv| cv.round(f64::from(c[k])))))
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
        // The turtle's vectors as cpfg's turtle has them: they are the
        // frame its `?P` modules report. (lsys negated z here while its
        // pitch went the other way from cpfg's; see `Action::Pitch`.)
        let queries: Vec<Query> = sites
            .iter()
            .map(|s| Query {
                index: s.index,
                params: params[s.offset..s.offset + s.arity]
                    .iter()
                    .map(|&p| as_text(p))
                    .collect(),
                position: self.vector(FieldKind::Position, s.frame.pos),
                heading: self.vector(FieldKind::Heading, s.frame.h),
                left: self.vector(FieldKind::Left, s.frame.l),
                up: self.vector(FieldKind::Up, s.frame.u),
                line_width: self.scalar(FieldKind::LineWidth, s.width),
                scale: self.scalar(FieldKind::ScaleFactor, s.scale),
            })
            .collect();
        let replies = self.program.respond(&queries);
        let params = string.params_mut();
        for (site, reply) in sites.iter().zip(replies) {
            for (k, v) in reply.into_iter().enumerate().take(site.arity) {
                if let Some(v) = v {
                    params[site.offset + k] = as_text(v);
                }
            }
        }
        Ok(())
    }
}

/// A parameter as it crosses between cpfg and an environmental program:
/// both sides write each C `float` parameter with `%g` (6 significant
/// digits; cpfg's `CMSendCommSymbol` in libs/comm/comm_master.c, every
/// vlab program's `CSSendData` in comm_slave.c) and read the text back
/// into a `float`. The rounding shows wherever a model computes with an
/// answer or a program with a parameter: two-trees' leaves take `8·r − 1`
/// of chiba's light `r`, and its string left cpfg's at step 9
/// (`L(6.63319)` for cpfg's `L(6.63318)`) while answers were unrounded;
/// chiba's spheres are as wide as `?E`'s parameter (`vig·0.5`, a power
/// of 0.95), rounded the same way.
fn as_text(v: f64) -> f64 {
    f64::from(Conversion::General(6).round(f64::from(v as f32)))
}
