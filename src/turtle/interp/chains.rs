//! Drawn moves -> tube chains: a move of the turtle extends the chain it
//! is on, or starts a chain with its origin (the drawn point it left from,
//! a hint for meshing); inside a polygon it traces the outline instead.
//! For a big string, room for its chains is reserved up front and their
//! pages backed on the second core ([`crate::support::prefault`]).

use super::{push_vertex, Act, Turtle, Walk};
use crate::derive::store::head_sym;
use crate::lang::commands::Action;
use crate::support::prefault::{region, Prefault};
use crate::turtle::drawing::{Chain, Origin, TubePoint};

/// Strings shorter than this draw too little for a prefault helper.
const PREFAULT_FROM: usize = 1 << 16;

/// Chains drawn between two looks at their buffers by the helper.
const CHAINS_LOOK_EVERY: usize = 1024;

impl Turtle<'_> {
    /// For a big string: room for as many chains (and origins) as it has
    /// drawing moves (each starts at most one; generalized cylinders may
    /// add more, and then the chains outgrow the room and the helper
    /// stops), with a helper backing their pages ahead of the walk (W2:
    /// 19 MB of chains, 4,600 fresh pages).
    pub(super) fn reserve_chains(&mut self, w: &Walk) {
        if w.heads.len() < PREFAULT_FROM {
            return;
        }
        let draws = w
            .heads
            .iter()
            .filter(|&&h| {
                matches!(
                    w.acts[head_sym(h) as usize],
                    Act::Command(Action::Move { draw: true, .. })
                )
            })
            .count();
        let d = &mut self.drawing;
        d.chains.reserve(draws);
        d.origins.reserve(draws);
        let regions = [region(&d.chains), region(&d.origins)];
        self.prefault = Prefault::start(regions, crate::derive::threads(), CHAINS_LOOK_EVERY);
    }

    pub(super) fn forward(&mut self, d: f32, draw: bool, vertex: bool) {
        let s = &mut self.state;
        let from = s.frame.pos.as_vec3();
        s.frame.pos += s.frame.h * f64::from(d);
        let to = s.frame.pos.as_vec3();
        if !self.polygons.is_empty() {
            // Inside a polygon moves trace its outline instead of drawing.
            if vertex {
                if let Some((_, poly)) = self.polygons.last_mut() {
                    push_vertex(poly, to);
                }
            }
        } else if draw
            // cpfg's `F` draws inside a generalized cylinder too.
            && (s.cylinder.is_none() || self.opts.profile.cpfg_turtle)
            && s.width > 0.0
            && d != 0.0
        {
            let radius = s.width * 0.5;
            let point = TubePoint {
                pos: to,
                radius,
                up: s.frame.u.as_vec3(),
            };
            let chains = &mut self.drawing.chains;
            match s.chain {
                Some(c)
                    if chains[c].colour == s.colour
                        && chains[c].points.last().map(|p| p.pos) == Some(from) =>
                {
                    chains[c].points.push(point);
                    s.at = Some((c as u32, (chains[c].points.len() - 1) as u32));
                }
                _ => {
                    let origin = s.at.filter(|&(c, k)| {
                        chains[c as usize].points.get(k as usize).map(|p| p.pos) == Some(from)
                    });
                    let origins = &mut self.drawing.origins;
                    if let Some((chain, point)) = origin {
                        origins.resize(chains.len(), None);
                        origins.push(Some(Origin { chain, point }));
                    }
                    s.at = Some((chains.len() as u32, 1));
                    chains.push(Chain {
                        colour: s.colour,
                        points: smallvec::smallvec![
                            TubePoint {
                                pos: from,
                                radius,
                                up: s.frame.u.as_vec3(),
                            },
                            point,
                        ],
                    });
                    s.chain = Some(chains.len() - 1);
                    if let Some(p) = &mut self.prefault {
                        p.progress(chains.len(), || [region(chains), region(origins)]);
                    }
                }
            }
        } else {
            s.chain = None;
            if d != 0.0 {
                s.at = None;
            }
        }
        if s.elasticity != 0.0 {
            s.frame.bend(s.tropism.as_dvec3(), f64::from(s.elasticity));
        }
    }
}
