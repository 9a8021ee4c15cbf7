//! A run's outcome in, one mesh [`Scene`] out: every seed's clipped
//! drawing, and with `overlay` the guides and links as thin lines. Strokes
//! take the first guide's grammar's palette; each seed's component
//! placements are meshed with its own grammar (placements name symbols of
//! their grammar), and the scenes are merged.

use super::draw;
use super::load::Loaded;
use super::run::Outcome;
use crate::mesh::{self, ComponentSearch, MeshError, MeshOptions, Palette, Scene};
use crate::turtle::drawing::Drawing;

/// Palette colours of the overlay: guides and links.
pub const GUIDE_COLOUR: u32 = 1;
pub const LINK_COLOUR: u32 = 4;

/// Meshes `o` (and the overlay); the grammar components its seeds place
/// (`~TM`: a grammar of their own) are asked of `grammars`.
pub fn scene(
    l: &Loaded,
    o: &Outcome,
    overlay: bool,
    search: &ComponentSearch,
    opts: &MeshOptions,
    grammars: &mut dyn mesh::GrammarComponents,
) -> Result<Scene, MeshError> {
    // A scene without guides (the studio's new scene) draws nothing.
    let Some(&first) = l.guide_grammar.first() else {
        return Ok(Scene::default());
    };
    let mut d = o.drawing();
    // Placements by grammar, in the order the grammars are first used.
    let mut by_grammar: Vec<(usize, Drawing)> = Vec::new();
    for s in &o.seeds {
        let at = match by_grammar.iter().position(|(g, _)| *g == s.grammar) {
            Some(at) => at,
            None => {
                by_grammar.push((s.grammar, Drawing::default()));
                by_grammar.len() - 1
            }
        };
        by_grammar[at]
            .1
            .placements
            .extend(s.drawing.placements.iter().copied());
    }
    d.placements = match by_grammar.iter().position(|(g, _)| *g == first) {
        Some(at) => by_grammar.remove(at).1.placements,
        None => Vec::new(),
    };
    if overlay {
        let (lo, hi) = l.spec.guides.iter().flat_map(|g| g.points.iter()).fold(
            (glam::DVec2::INFINITY, glam::DVec2::NEG_INFINITY),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let width = (hi - lo).length().max(1.0) as f32 * 0.003;
        let o = draw::overlay(&l.spec, width, GUIDE_COLOUR, LINK_COLOUR);
        d.chains.extend(o.chains);
    }
    let mut build = |grammar: usize, d: &Drawing| {
        let program = &l.grammars[grammar].program;
        let palette = Palette::new(&program.turtle.palette);
        mesh::assemble_scene(program, d, &palette, search, opts, grammars)
    };
    let mut scene = build(first, &d)?;
    for (grammar, d) in by_grammar.iter().filter(|(_, d)| !d.placements.is_empty()) {
        merge(&mut scene, build(*grammar, d)?);
    }
    Ok(scene)
}

/// Adds `other`'s components, instances and strokes to `into`: materials
/// and components that are already there (same name and colour, same name
/// and origin) are reused, and instances keep counting per component.
fn merge(into: &mut Scene, other: Scene) {
    let materials: Vec<usize> = other
        .materials
        .into_iter()
        .map(|m| match into.materials.iter().position(|x| *x == m) {
            Some(at) => at,
            None => {
                into.materials.push(m);
                into.materials.len() - 1
            }
        })
        .collect();
    let components: Vec<usize> = other
        .components
        .into_iter()
        .map(|c| {
            if let Some(at) = into
                .components
                .iter()
                .position(|x| x.name == c.name && x.origin == c.origin)
            {
                return at;
            }
            into.components
                .push(crate::mesh::subgrammar::remap(c, &materials));
            into.components.len() - 1
        })
        .collect();
    // Placements counted per component once, not per placement.
    let mut numbers = vec![0u32; into.components.len()];
    for x in &into.instances {
        numbers[x.component] += 1;
    }
    for mut i in other.instances {
        i.component = components[i.component];
        i.material = materials[i.material];
        i.number = numbers[i.component];
        numbers[i.component] += 1;
        into.instances.push(i);
    }
    for s in other.strokes {
        let material = materials[s.material];
        match into.strokes.iter_mut().find(|x| x.material == material) {
            Some(x) => x.mesh.append(&s.mesh),
            None => into.strokes.push(crate::mesh::Stroke {
                material,
                mesh: s.mesh,
            }),
        }
    }
}
