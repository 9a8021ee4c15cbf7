//! Density: vlab's `density` environmental program (`ENVIRO/density/`), a
//! 2D field in the x-y plane. In a pass, every `?E(v)` with one parameter
//! is a source of strength v (`v / (1 + distance)` at a point, v may be
//! negative); every other `?E` is a part of the pattern, adding
//! `1 / (1 + distance²)`. Each `?E(a, b, c)` with three parameters is
//! answered, leaving itself out of the field: `(density, gradient angle in
//! degrees, gradient magnitude)`, or with `return vector: yes` `(density,
//! gradient x, gradient y)`. The density is the minimum over a 6 × 6 grid of
//! samples spanning ±0.5 around the query, the gradient from the samples
//! at its middle, or with `one point value: on` the value at the point and
//! central differences over ±0.5. The program's image output (`output
//! image:`) is not written. Arithmetic is in `f32` as the program's.

use miette::SourceSpan;

use super::communication::lines;
use super::error::EnvironmentError;
use super::{EnvironmentalProgram, Query, Reply};

/// The specification file's settings (both off by default).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    pub one_point: bool,
    pub return_vector: bool,
}

impl Settings {
    pub(super) fn read(
        text: &str,
        _bad: impl Fn(&str, SourceSpan, String) -> Box<EnvironmentError>,
    ) -> Result<Settings, Box<EnvironmentError>> {
        let mut s = Settings::default();
        for line in lines(text) {
            let word = line
                .value
                .split([' ', '\t', ',', ';', 'x'])
                .find(|w| !w.is_empty());
            match line.key.as_str() {
                "one point value" => s.one_point = word == Some("on"),
                "return vector" => s.return_vector = word == Some("yes"),
                _ => {}
            }
        }
        Ok(s)
    }
}

/// The program.
pub struct Density {
    settings: Settings,
}

impl Density {
    pub fn new(settings: Settings) -> Density {
        Density { settings }
    }
}

/// The field of one pass.
struct Field {
    /// Pattern parts (every stored query).
    parts: Vec<[f32; 2]>,
    sources: Vec<([f32; 2], f32)>,
}

impl Field {
    /// The density at (x, y), part `skip` left out.
    fn at(&self, skip: usize, x: f32, y: f32) -> f32 {
        let mut d = 0f32;
        for (k, p) in self.parts.iter().enumerate() {
            if k == skip {
                continue;
            }
            let (ax, ay) = (x - p[0], y - p[1]);
            d = (d as f64 + 1.0 / (1.0 + (ax * ax + ay * ay) as f64)) as f32;
        }
        for (p, v) in &self.sources {
            let (ax, ay) = (x - p[0], y - p[1]);
            let w = (1.0 / (1.0 + ((ax * ax + ay * ay) as f64).sqrt())) as f32;
            d += v * w;
        }
        d
    }
}

impl EnvironmentalProgram for Density {
    fn respond(&mut self, queries: &[Query]) -> Vec<Reply> {
        let mut field = Field {
            parts: Vec::new(),
            sources: Vec::new(),
        };
        // (query, part index) of the queries to answer.
        let mut answer = Vec::new();
        for (i, q) in queries.iter().enumerate() {
            let Some(p) = q.position else { continue };
            let xy = [p[0], p[1]];
            if q.params.len() == 1 {
                field.sources.push((xy, q.params[0] as f32));
                continue;
            }
            if q.params.len() == 3 {
                answer.push((i, field.parts.len()));
            }
            field.parts.push(xy);
        }
        let mut replies: Vec<Reply> = queries.iter().map(|q| vec![None; q.params.len()]).collect();
        for (i, k) in answer {
            let [x, y] = field.parts[k];
            let (dmin, g) = if self.settings.one_point {
                let d = field.at(k, x, y);
                let gx = -(field.at(k, x + 0.5, y) - field.at(k, x - 0.5, y));
                let gy = -(field.at(k, x, y + 0.5) - field.at(k, x, y - 0.5));
                (d, [gx, gy])
            } else {
                const N: usize = 6;
                let mut grid = [[0f32; N]; N];
                let step = 1.0 / (N - 1) as f32;
                let mut sx = x - 0.5;
                for row in grid.iter_mut() {
                    let mut sy = y - 0.5;
                    for v in row.iter_mut() {
                        *v = field.at(k, sx, sy);
                        sy += step;
                    }
                    sx += step;
                }
                let dmin = grid.iter().flatten().copied().fold(grid[0][0], f32::min);
                let m = N / 2;
                let gx = -(grid[m][m] - grid[m - 1][m]) / N as f32;
                let gy = -(grid[m][m] - grid[m][m - 1]) / N as f32;
                (dmin, [gx, gy])
            };
            let (a, b) = if self.settings.return_vector {
                (g[0], g[1])
            } else {
                let len = ((g[0] * g[0] + g[1] * g[1]) as f64).sqrt() as f32;
                let mut angle = 90f32;
                if len > 0.0 {
                    let nx = g[0] / len;
                    angle = ((nx as f64).acos() / std::f64::consts::PI * 180.0) as f32;
                    if g[1] / len < 0.0 {
                        angle = 360.0 - angle;
                    }
                }
                (angle, len)
            };
            replies[i] = vec![Some(dmin as f64), Some(a as f64), Some(b as f64)];
        }
        replies
    }
}
