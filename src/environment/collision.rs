//! Collision: cpfg's `honda81` environmental program (vlab
//! `ENVIRO/honda81/honda81.c`). Each `?E(vigor[, group])` with at least one
//! parameter gets `p1 = 0` when another query of the same group (0 when
//! not given) with a vigor at least its own lies within `radius` of it,
//! else `p1 = 1`. Two queries with the same vigor therefore both stop. In
//! 3D (`3d case: on`) distances are between positions; otherwise between
//! the (x, z) coordinates. Arithmetic is in `f32`, as the program's.

use miette::SourceSpan;

use super::communication::{lines, number, switch};
use super::error::EnvironmentError;
use super::{EnvironmentalProgram, Query, Reply};

/// `radius:` (0 when not given: only coincident queries collide) and
/// `3d case:` (off when not given).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    pub radius: f32,
    pub three_d: bool,
}

impl Settings {
    pub(super) fn read(
        text: &str,
        bad: impl Fn(&str, SourceSpan, String) -> Box<EnvironmentError>,
    ) -> Result<Settings, Box<EnvironmentError>> {
        let mut s = Settings::default();
        for line in lines(text) {
            match line.key.as_str() {
                "radius" => {
                    s.radius = number(line.value).ok_or_else(|| {
                        bad("radius", line.span, "the radius is not a number".into())
                    })? as f32
                }
                "3d case" => s.three_d = switch(line.value),
                _ => {}
            }
        }
        Ok(s)
    }
}

/// The program.
pub struct Collision {
    settings: Settings,
}

impl Collision {
    pub fn new(settings: Settings) -> Collision {
        Collision { settings }
    }
}

impl EnvironmentalProgram for Collision {
    fn respond(&mut self, queries: &[Query]) -> Vec<Reply> {
        let r2 = self.settings.radius * self.settings.radius;
        // (vigor, group, point) of the queries the program stores: those
        // with a parameter and a position.
        let stored: Vec<Option<(f32, i64, [f32; 3])>> = queries
            .iter()
            .map(|q| {
                let vigor = *q.params.first()? as f32;
                let group = q.params.get(1).map_or(0, |&g| g as f32 as i64);
                let p = q.position?;
                let point = if self.settings.three_d {
                    p
                } else {
                    [p[0], p[2], 0.0]
                };
                Some((vigor, group, point))
            })
            .collect();
        stored
            .iter()
            .enumerate()
            .map(|(i, me)| {
                let Some((vigor, group, p)) = *me else {
                    return vec![None; queries[i].params.len()];
                };
                let hit = stored.iter().enumerate().any(|(j, other)| {
                    let Some((v, g, q)) = *other else {
                        return false;
                    };
                    if i == j || g != group || vigor > v {
                        return false;
                    }
                    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= r2
                });
                let mut reply = vec![None; queries[i].params.len()];
                reply[0] = Some(if hit { 0.0 } else { 1.0 });
                reply
            })
            .collect()
    }
}
