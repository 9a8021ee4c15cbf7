//! Grammars as components: `~TM(s)` where TM is a grammar (a `.lsys` file
//! found like an OBJ model, or a standard library grammar such as the
//! Toukungs) -> one [`Component`]. The grammar is derived and built once; its
//! strokes and placed components are merged per material into the
//! component's parts, normalised to the unit box like any model, and then
//! placed as instances however often the outer grammar asks.

use std::collections::BTreeMap;

use glam::{Mat3, Mat4};

use super::components::{normalise, ComponentSearch};
use super::error::MeshError;
use super::scene::{Component, Instance, Material, Nested, Part, Scene, TriMesh};
use crate::load::Input;

/// Compiles, derives and builds a grammar used as a component. Mesh only
/// merges and places what it returns: the compiler lives above mesh
/// (the back half, `src/build.rs`, implements this with the outer build's options, so
/// `-D TM.NAME=...`, `--seed` and the limits reach the component).
pub trait GrammarComponents {
    /// The scene of grammar `name` read from `input`, built with `search`
    /// for its own components. `Err` holds the rendered diagnostics.
    fn scene(
        &mut self,
        name: &str,
        input: &Input,
        search: &ComponentSearch,
    ) -> Result<Scene, String>;
}

/// For builds that must not nest grammars (none is found).
pub struct NoGrammars;

impl GrammarComponents for NoGrammars {
    fn scene(&mut self, name: &str, _: &Input, _: &ComponentSearch) -> Result<Scene, String> {
        Err(format!("grammar component `{name}` cannot be built here"))
    }
}

/// Grammar components nested deeper than this are refused.
pub const MAX_NESTING: usize = 8;

pub fn grammar_component(
    name: &str,
    input: &Input,
    search: &ComponentSearch,
    materials: &mut Vec<Material>,
    grammars: &mut dyn GrammarComponents,
) -> Result<Component, MeshError> {
    let origin = match input {
        Input::Path(p) | Input::Edited { path: p, .. } => p.display().to_string(),
        Input::Std(n) => format!("std:{n}"),
        Input::Text { name, .. } => name.clone(),
    };
    let fail = |details: String| MeshError::ComponentGrammar {
        name: name.to_string(),
        origin: origin.clone(),
        details,
    };
    if search.within.iter().any(|w| w == name) || search.within.len() >= MAX_NESTING {
        let mut chain = search.within.clone();
        chain.push(name.to_string());
        return Err(fail(format!(
            "components nest in a cycle or deeper than {MAX_NESTING}: ~{}",
            chain.join(" -> ~")
        )));
    }
    let mut within = search.within.clone();
    within.push(name.to_string());
    let inner = ComponentSearch {
        grammar_dir: match input {
            Input::Path(p) | Input::Edited { path: p, .. } => p.parent().map(|d| d.to_path_buf()),
            _ => None,
        },
        dirs: search.dirs.clone(),
        within,
        detail: search.detail,
    };
    let scene = grammars.scene(name, input, &inner).map_err(fail)?;
    // The grammar's own colours become materials of the outer scene (the
    // same colour once).
    let map: Vec<usize> = scene
        .materials
        .iter()
        .map(|m| match materials.iter().position(|x| x == m) {
            Some(i) => i,
            None => {
                materials.push(m.clone());
                materials.len() - 1
            }
        })
        .collect();
    // The strokes merged per material are both the start of the flattened
    // parts and the nested scene's own parts.
    let mut strokes: BTreeMap<usize, TriMesh> = BTreeMap::new();
    for s in &scene.strokes {
        strokes.entry(map[s.material]).or_default().append(&s.mesh);
    }
    let mut merged = strokes.clone();
    // Room for every placed part at once: grown piece by piece, copying
    // the merged meshes as they grew took a third of the merging.
    let mut room: BTreeMap<usize, (usize, usize)> = BTreeMap::new();
    for inst in &scene.instances {
        for p in &scene.components[inst.component].parts {
            let r = room
                .entry(map[p.material.unwrap_or(inst.material)])
                .or_default();
            r.0 += p.mesh.positions.len();
            r.1 += p.mesh.indices.len();
        }
    }
    for (material, (vertices, indices)) in room {
        let m = merged.entry(material).or_default();
        m.positions.reserve_exact(vertices);
        m.normals.reserve_exact(vertices);
        m.indices.reserve_exact(indices);
    }
    for inst in &scene.instances {
        let t = inst.transform;
        let normals = Mat3::from_mat4(t).inverse().transpose();
        let mirrored = Mat3::from_mat4(t).determinant() < 0.0;
        for p in &scene.components[inst.component].parts {
            let material = map[p.material.unwrap_or(inst.material)];
            // Transformed straight into the merged mesh (no copy of the
            // part per placement: a Pailou's Toukungs place thousands).
            let m = merged.entry(material).or_default();
            let base = m.positions.len() as u32;
            let src = &p.mesh;
            m.positions
                .extend(src.positions.iter().map(|&v| t.transform_point3(v)));
            m.normals
                .extend(src.normals.iter().map(|&n| (normals * n).normalize_or(n)));
            if mirrored {
                // A mirror turns faces inside out; keep them outward.
                m.indices.extend(
                    src.indices
                        .chunks_exact(3)
                        .flat_map(|t| [t[0], t[2], t[1]])
                        .chain(src.indices.chunks_exact(3).remainder().iter().copied())
                        .map(|i| i + base),
                );
            } else {
                m.indices.extend(src.indices.iter().map(|i| i + base));
            }
        }
    }
    let mut parts = parts_of(merged);
    if parts.is_empty() {
        return Err(fail(
            "it draws nothing (no drawing command in its string)".to_string(),
        ));
    }
    let frame = normalise(&mut parts);
    let nested = nest(scene, parts_of(strokes), &map, frame);
    Ok(Component {
        name: name.to_string(),
        parts,
        origin,
        nested: Some(Box::new(nested)),
    })
}

/// One part per material that has triangles.
fn parts_of(per_material: BTreeMap<usize, TriMesh>) -> Vec<Part> {
    per_material
        .into_iter()
        .filter(|(_, m)| !m.is_empty())
        .map(|(material, mesh)| Part {
            mesh,
            material: Some(material),
        })
        .collect()
}

/// The inner scene kept as it was built (`strokes`: its strokes merged per
/// material; its components and their placements), in the outer scene's
/// materials.
fn nest(scene: Scene, strokes: Vec<Part>, map: &[usize], frame: Mat4) -> Nested {
    Nested {
        frame,
        parts: strokes,
        components: scene
            .components
            .into_iter()
            .map(|c| remap(c, map))
            .collect(),
        instances: scene
            .instances
            .into_iter()
            .map(|i| Instance {
                material: map[i.material],
                ..i
            })
            .collect(),
        placement_colour: false,
    }
}

/// `c` with its material indices (own parts and nested ones) mapped by
/// `map` (old index -> new), for a component moved into another scene.
pub(crate) fn remap(mut c: Component, map: &[usize]) -> Component {
    for p in &mut c.parts {
        p.material = p.material.map(|m| map[m]);
    }
    if let Some(n) = &mut c.nested {
        for p in &mut n.parts {
            p.material = p.material.map(|m| map[m]);
        }
        let inner = std::mem::take(&mut n.components);
        n.components = inner.into_iter().map(|c| remap(c, map)).collect();
        for i in &mut n.instances {
            i.material = map[i.material];
        }
    }
    c
}
