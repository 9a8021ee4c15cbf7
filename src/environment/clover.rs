//! Clover: vlab's `clover` environmental program (`ENVIRO/clover/`), a
//! light field over a 2D grid lying under a clover patch. The grid takes
//! its light (green) and ratio (red) from an input image; leaves add to
//! and remove from a count of objects per cell, which persists from pass
//! to pass. Queries, in string order:
//! - `?E(p0, area)` with `p0 == 1` adds a leaf of that area (a disc of
//!   cells around the position); any other nonzero `p0` removes one;
//! - `?E(x)` or `?E(0, ...)` asks for the light: `p1 = light/255 · t^objects`
//!   of the cell under it (0 outside the grid), and with two or more
//!   parameters `p2 = ratio/128`; answered after every query of the pass
//!   was seen.
//!
//! Positions use x and y (z with `z is up: no`).

use std::f64::consts::PI;
use std::sync::Arc;

use miette::SourceSpan;

use super::communication::{lines, number};
use super::error::EnvironmentError;
use super::{EnvironmentalProgram, Query, Reply};

/// A cell of the grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Cell {
    objects: u8,
    light: u8,
    ratio: u8,
}

/// The specification file's settings, with the program's defaults.
#[derive(Clone, Debug)]
pub struct Settings {
    /// `grid size: XxY` (512x512).
    pub size: [i32; 2],
    /// `grid position: x y` of the grid's corner (-1 -1).
    pub pos: [f32; 2],
    /// `grid range: WxH` (2x2).
    pub range: [f32; 2],
    /// `transmittance:` per object (0.6; 0 is taken as 0.0001).
    pub transmittance: f32,
    /// `remove old leaves: on|yes` clears the objects before each pass.
    pub remove_old_leaves: bool,
    /// `z is up: no|off` reads the z coordinate as y.
    pub z_is_up: bool,
    /// The input image's cells (light, ratio), row 0 at the grid's bottom;
    /// `None`: full light everywhere.
    image: Option<Arc<Vec<(u8, u8)>>>,
}

impl PartialEq for Settings {
    fn eq(&self, o: &Settings) -> bool {
        self.size == o.size
            && self.pos == o.pos
            && self.range == o.range
            && self.transmittance == o.transmittance
            && self.remove_old_leaves == o.remove_old_leaves
            && self.z_is_up == o.z_is_up
            && self.image == o.image
    }
}

fn pair(value: &str) -> Vec<f64> {
    value
        .split(['x', ',', ';', ' ', '\t'])
        .filter(|w| !w.is_empty())
        .filter_map(number)
        .collect()
}

impl Settings {
    pub(super) fn read(
        text: &str,
        data: &[(String, Arc<Vec<u8>>)],
        bad: impl Fn(&str, SourceSpan, String) -> Box<EnvironmentError>,
    ) -> Result<Settings, Box<EnvironmentError>> {
        let mut s = Settings {
            size: [512, 512],
            pos: [-1.0, -1.0],
            range: [2.0, 2.0],
            transmittance: 0.6,
            remove_old_leaves: false,
            z_is_up: true,
            image: None,
        };
        let mut image = None;
        for line in lines(text) {
            let v = pair(line.value);
            match line.key.as_str() {
                "grid size" => {
                    for (k, n) in v.iter().take(2).enumerate() {
                        if !(2.0..=8192.0).contains(n) {
                            return Err(bad(
                                &line.key,
                                line.span,
                                "each side is 2 to 8192 cells".into(),
                            ));
                        }
                        s.size[k] = *n as i32;
                    }
                }
                "grid position" => {
                    for (k, n) in v.iter().take(2).enumerate() {
                        s.pos[k] = *n as f32;
                    }
                }
                "grid range" => {
                    for (k, n) in v.iter().take(2).enumerate() {
                        s.range[k] = *n as f32;
                    }
                }
                "transmittance" => {
                    s.transmittance = v.first().copied().unwrap_or(0.6) as f32;
                    if s.transmittance == 0.0 {
                        s.transmittance = 0.0001;
                    }
                }
                "remove old leaves" => {
                    let w = line.value.split_whitespace().next();
                    s.remove_old_leaves = matches!(w, Some("on" | "yes"));
                }
                "z is up" => {
                    let w = line.value.split_whitespace().next();
                    s.z_is_up = !matches!(w, Some("no" | "off"));
                }
                "input image" => {
                    let name = line
                        .value
                        .split([',', ';', ' ', '\t'])
                        .find(|w| !w.is_empty());
                    let bytes = name.and_then(|n| data.iter().find(|(d, _)| d == n));
                    let Some((name, bytes)) = bytes else {
                        return Err(bad(&line.key, line.span, "the image was not loaded".into()));
                    };
                    if !name.ends_with("rgb") {
                        return Err(bad(
                            &line.key,
                            line.span,
                            format!("`{name}`: lsys reads SGI `.rgb` input images"),
                        ));
                    }
                    let img = super::sgi::decode(bytes)
                        .map_err(|why| bad(&line.key, line.span, format!("`{name}`: {why}")))?;
                    image = Some((line.span, img));
                }
                _ => {}
            }
        }
        if let Some((span, img)) = image {
            if img.channels.len() < 2 {
                return Err(bad(
                    "input image",
                    span,
                    "the image needs red and green channels".into(),
                ));
            }
            // Each cell samples the pixel (x·xr, y·yr), xr = (w-1)/(size-1).
            let xr = (img.width - 1) as f32 / (s.size[0] - 1) as f32;
            let yr = (img.height - 1) as f32 / (s.size[1] - 1) as f32;
            let mut cells = Vec::with_capacity((s.size[0] * s.size[1]) as usize);
            for y in 0..s.size[1] {
                for x in 0..s.size[0] {
                    let px = (x as f32 * xr) as usize;
                    let py = (y as f32 * yr) as usize;
                    let at = py * img.width + px;
                    cells.push((img.channels[1][at], img.channels[0][at]));
                }
            }
            s.image = Some(Arc::new(cells));
        }
        Ok(s)
    }
}

/// The program, with its grid (objects persist between passes).
pub struct Clover {
    settings: Settings,
    cells: Vec<Cell>,
    powers: [f32; 256],
}

impl Clover {
    pub fn new(settings: Settings) -> Clover {
        let n = (settings.size[0] * settings.size[1]) as usize;
        let cells = match &settings.image {
            Some(img) => img
                .iter()
                .map(|&(light, ratio)| Cell {
                    objects: 0,
                    light,
                    ratio,
                })
                .collect(),
            None => vec![
                Cell {
                    objects: 0,
                    light: 255,
                    ratio: 0,
                };
                n
            ],
        };
        let mut powers = [1f32; 256];
        for i in 1..256 {
            powers[i] = settings.transmittance * powers[i - 1];
        }
        Clover {
            settings,
            cells,
            powers,
        }
    }

    fn node(&self, p: [f32; 2]) -> [i32; 2] {
        let s = &self.settings;
        [0, 1].map(|c| ((p[c] - s.pos[c]) / s.range[c] * s.size[c] as f32).floor() as i32)
    }

    fn cell(&mut self, x: i32, y: i32) -> Option<&mut Cell> {
        let [w, h] = self.settings.size;
        if x < 0 || x >= w || y < 0 || y >= h {
            return None;
        }
        self.cells.get_mut((y * w + x) as usize)
    }
}

impl EnvironmentalProgram for Clover {
    fn respond(&mut self, queries: &[Query]) -> Vec<Reply> {
        if self.settings.remove_old_leaves {
            self.cells.iter_mut().for_each(|c| c.objects = 0);
        }
        let mut asked = Vec::new();
        for (i, q) in queries.iter().enumerate() {
            let (Some(&p0), Some(pos)) = (q.params.first(), q.position) else {
                continue;
            };
            let xy = [
                pos[0],
                if self.settings.z_is_up {
                    pos[1]
                } else {
                    pos[2]
                },
            ];
            if q.params.len() == 1 || p0 == 0.0 {
                asked.push((i, xy));
                continue;
            }
            // A leaf added (p0 = 1) or removed: a disc of its area.
            let add = p0 as f32 == 1.0;
            let area = q.params[1] as f32;
            if area < 0.0000001 {
                continue;
            }
            let radius = (area as f64 / PI).sqrt() as f32;
            let node = self.node(xy);
            let s = &self.settings;
            let reach: [i32; 2] =
                [0, 1].map(|c| (radius / s.range[c] * s.size[c] as f32 + 1.0) as i32);
            for y in -reach[1]..reach[1] {
                for x in -reach[0]..reach[0] {
                    let inside = (x * x) as f32 / (reach[0] * reach[0]) as f32
                        + (y * y) as f32 / (reach[1] * reach[1]) as f32
                        <= 1.0;
                    if !inside {
                        continue;
                    }
                    if let Some(c) = self.cell(node[0] + x, node[1] + y) {
                        if add && c.objects < 255 {
                            c.objects += 1;
                        } else if !add && c.objects > 0 {
                            c.objects -= 1;
                        }
                    }
                }
            }
        }
        let mut replies: Vec<Reply> = queries.iter().map(|q| vec![None; q.params.len()]).collect();
        for (i, xy) in asked {
            let node = self.node(xy);
            let powers = self.powers;
            let cell = self.cell(node[0], node[1]).copied();
            let light = cell.map_or(0.0, |c| {
                (c.light as f32 as f64 / 255.0 * powers[c.objects as usize] as f64) as f32
            });
            let reply = &mut replies[i];
            reply[0] = Some(light as f64);
            if reply.len() >= 2 {
                reply[1] =
                    Some(cell.map_or(0.0, |c| (c.ratio as f32 as f64 / 128.0) as f32) as f64);
            }
        }
        replies
    }
}
