//! Components drawn out of proportion. `~X` and `~X(s)` draw the
//! component's unit box scaled alike on every axis, and every model is
//! normalised to that box one axis at a time, so a model much longer on
//! one axis than on another is drawn as a cube: the Pailou paper's uniform
//! `~TM(1.4)` squashes a 0.37 × 0.58 × 1.8 Toukung into a 1.4 cube. Input:
//! the drawing's placements and the scene's components; output: one
//! warning for each component placed that way.

use glam::Vec3;

use super::error::MeshError;
use super::scene::Scene;
use crate::resolve::Program;
use crate::turtle::Drawing;

/// A uniform placement warns when the model's longest side is more than
/// this many times its shortest (flat axes left out). 2 lets through the
/// caps, blocks and bases that are roughly cubes, and catches arms, Angs,
/// lintels, pillars and whole bracket sets.
pub const DISTORTION_LIMIT: f32 = 2.0;

/// A side shorter than this part of the longest is flat (a leaf's depth).
const FLAT: f32 = 1e-3;

/// The warnings for `drawing`'s uniform placements of elongated models.
pub fn distortions(program: &Program, drawing: &Drawing, scene: &Scene) -> Vec<MeshError> {
    let mut seen: Vec<u32> = Vec::new();
    let mut out = Vec::new();
    for p in drawing.placements.iter().filter(|p| p.uniform) {
        if seen.contains(&p.symbol) {
            continue;
        }
        seen.push(p.symbol);
        let symbol = &program.symbols.list[p.symbol as usize];
        let name = symbol.name.trim_start_matches(['~', '∼']);
        let Some(size) = scene
            .components
            .iter()
            .find(|c| c.name == name)
            .and_then(|c| c.modelled)
        else {
            continue;
        };
        let Some(factor) = elongation(size) else {
            continue;
        };
        if factor <= DISTORTION_LIMIT {
            continue;
        }
        let count = drawing
            .placements
            .iter()
            .filter(|q| q.uniform && q.symbol == p.symbol)
            .count();
        let side = p.transform.y_axis.truncate().length();
        let shape = size / size.max_element();
        let (src, span) = super::assemble::symbol_source(program, Some(p.symbol));
        out.push(MeshError::Distorted(Box::new(super::error::Distorted {
            name: name.to_string(),
            modelled: sizes(size),
            side: short(side),
            factor: format!("{factor:.1}"),
            count,
            placements: if count == 1 {
                "placement"
            } else {
                "placements"
            },
            example: format!(
                "~{name}({}, {}, {})",
                times_s(shape.x),
                times_s(shape.y),
                times_s(shape.z)
            ),
            src,
            span,
        })));
    }
    out
}

/// The longest side over the shortest, flat sides left out; `None` for a
/// model with fewer than two sides that are not flat.
fn elongation(size: Vec3) -> Option<f32> {
    let longest = size.max_element();
    let sides: Vec<f32> = size
        .to_array()
        .into_iter()
        .filter(|&s| s > longest * FLAT)
        .collect();
    if sides.len() < 2 {
        return None;
    }
    let shortest = sides.iter().copied().fold(f32::INFINITY, f32::min);
    Some(longest / shortest)
}

fn short(x: f32) -> String {
    crate::turtle::scope::num_places(f64::from(x), 2)
}

/// `s*0.21`, or `s` for the longest side.
fn times_s(x: f32) -> String {
    match short(x).as_str() {
        "1" => "s".to_string(),
        k => format!("s*{k}"),
    }
}

fn sizes(size: Vec3) -> String {
    format!("{} × {} × {}", short(size.x), short(size.y), short(size.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elongation_leaves_flat_sides_out() {
        assert_eq!(elongation(Vec3::new(1.0, 4.0, 2.0)), Some(4.0));
        assert_eq!(elongation(Vec3::new(1.0, 3.0, 0.0)), Some(3.0));
        assert_eq!(elongation(Vec3::new(0.0, 3.0, 0.0)), None);
    }
}
