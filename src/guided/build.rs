//! A run's outcome in, one mesh [`Scene`] out: every seed's clipped
//! drawing, and with `overlay` the guides and links as thin lines, meshed
//! with the first guide's grammar (its palette and components).

use super::draw;
use super::load::Loaded;
use super::run::Outcome;
use crate::mesh::{self, ComponentSearch, MeshError, MeshOptions, Palette, Scene};

/// Palette colours of the overlay: guides and links.
pub const GUIDE_COLOUR: u32 = 1;
pub const LINK_COLOUR: u32 = 4;

struct NoGrammars;

impl mesh::GrammarComponents for NoGrammars {
    fn scene(
        &mut self,
        name: &str,
        _input: &crate::load::Input,
        _search: &ComponentSearch,
    ) -> Result<Scene, String> {
        Err(format!(
            "grammar component `{name}` is not available in a guided scene"
        ))
    }
}

/// Meshes `o` (and the overlay).
pub fn scene(
    l: &Loaded,
    o: &Outcome,
    overlay: bool,
    search: &ComponentSearch,
    opts: &MeshOptions,
) -> Result<Scene, MeshError> {
    let first = l.guide_grammar.first().copied().unwrap_or(0);
    let program = &l.grammars[first].program;
    let mut d = o.drawing();
    // Placements name symbols of their own grammar: only the first
    // grammar's can be meshed with its symbol table.
    let keep: Vec<bool> = o.seeds.iter().map(|s| s.grammar == first).collect();
    d.placements = o
        .seeds
        .iter()
        .zip(&keep)
        .filter(|(_, k)| **k)
        .flat_map(|(s, _)| s.drawing.placements.iter().copied())
        .collect();
    if overlay {
        let (lo, hi) = l.spec.guides.iter().flat_map(|g| g.points.iter()).fold(
            (glam::DVec2::INFINITY, glam::DVec2::NEG_INFINITY),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let width = (hi - lo).length().max(1.0) as f32 * 0.003;
        let o = draw::overlay(&l.spec, width, GUIDE_COLOUR, LINK_COLOUR);
        d.chains.extend(o.chains);
    }
    let palette = Palette::new(&program.turtle.palette);
    mesh::assemble_scene(program, &d, &palette, search, opts, &mut NoGrammars)
}
