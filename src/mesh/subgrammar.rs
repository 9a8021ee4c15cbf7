//! Grammars as components: `~TM(s)` where TM is a grammar (a `.lsys` file
//! found like an OBJ model, or a standard library grammar such as the
//! Toukungs) -> one [`Component`]. The grammar is derived and built once; its
//! strokes and placed components are merged per material into the
//! component's parts, normalised to the unit box like any model, and then
//! placed as instances however often the outer grammar asks.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::{Mat3, Mat4, Vec3};

use super::components::{ComponentSearch, UnitBox};
use super::error::MeshError;
use super::scene::{
    bounds_from, Component, Instance, Later, Material, Nested, Part, Scene, TriMesh,
};
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

    /// Told which grammar components a build will ask [`Self::scene`] for,
    /// so that it can build them ahead, at once. The default builds
    /// nothing ahead.
    fn ahead(&mut self, wanted: Vec<Wanted>) {
        let _ = wanted;
    }
}

/// A grammar component a build will ask for: what [`GrammarComponents::
/// scene`] is given for it.
#[derive(Clone, Debug)]
pub struct Wanted {
    /// The symbol that places it, without the `~`.
    pub name: String,
    pub input: Input,
    /// The search it is built with (see [`inner_search`]).
    pub search: ComponentSearch,
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
    let inner = inner_search(name, input, search).map_err(fail)?;
    let scene = grammars.scene(name, input, &inner).map_err(fail)?;
    // The grammar's own colours become materials of the outer scene (the
    // same colour once). Its textures stay its own: a textured material
    // keeps its name (so its mesh stays apart) and shows its colour.
    let map: Vec<usize> = scene
        .materials
        .iter()
        .map(|m| Material {
            texture: None,
            ..m.clone()
        })
        .map(|m| match materials.iter().position(|x| *x == m) {
            Some(i) => i,
            None => {
                materials.push(m);
                materials.len() - 1
            }
        })
        .collect();
    // The strokes merged per material, in the outer scene's materials: the
    // nested scene's own parts, and the start of the flattened ones.
    let mut strokes: BTreeMap<usize, TriMesh> = BTreeMap::new();
    for s in &scene.strokes {
        strokes.entry(map[s.material]).or_default().append(&s.mesh);
    }
    let nested = nest(scene, parts_of(strokes), &map);
    // The flattened parts are built when something reads them (see
    // `super::component`); their size and the normalisation are measured
    // now, walking their vertices in the order they will have.
    let (counts, bounds) = measure(&nested);
    let Some((lo, hi)) = bounds else {
        return Err(fail(
            "it draws nothing (no drawing command in its string)".to_string(),
        ));
    };
    let unit = UnitBox::of(lo, hi);
    let frame = unit.matrix();
    let later = Later {
        vertices: counts.values().map(|c| c.0).sum(),
        triangles: counts.values().map(|c| c.1 / 3).sum(),
        // Every part takes a material of the grammar's own.
        placement_colour: false,
        build: Arc::new(move |nested| {
            let mut parts = nested.map(flatten).unwrap_or_default();
            for p in &mut parts {
                unit.apply(&mut p.mesh);
            }
            parts
        }),
    };
    let mut c = Component::built_later(name, origin, Nested { frame, ..nested }, later);
    c.modelled = Some(hi - lo);
    Ok(c)
}

/// The search grammar component `name` (read from `input`) is built with:
/// components beside its own file first, and `name` added to the chain of
/// grammars being built; `Err` for a cycle or nesting too deep.
pub(super) fn inner_search(
    name: &str,
    input: &Input,
    search: &ComponentSearch,
) -> Result<ComponentSearch, String> {
    if search.within.iter().any(|w| w == name) || search.within.len() >= MAX_NESTING {
        let mut chain = search.within.clone();
        chain.push(name.to_string());
        return Err(format!(
            "components nest in a cycle or deeper than {MAX_NESTING}: ~{}",
            chain.join(" -> ~")
        ));
    }
    let mut within = search.within.clone();
    within.push(name.to_string());
    Ok(ComponentSearch {
        grammar_dir: match input {
            Input::Path(p) | Input::Edited { path: p, .. } => p.parent().map(|d| d.to_path_buf()),
            _ => None,
        },
        dirs: search.dirs.clone(),
        within,
        detail: search.detail,
    })
}

/// The material of a part placed by `inst`.
fn material_of(p: &Part, inst: &Instance) -> usize {
    p.material.unwrap_or(inst.material)
}

/// Vertices and indices per material.
type PerMaterial = BTreeMap<usize, (usize, usize)>;

/// Vertices and indices per material of the flattened parts of `nested`
/// (materials with no triangles are left out, as [`parts_of`] leaves them),
/// and the bounds of their vertices in the order [`flatten`] writes them.
fn measure(nested: &Nested) -> (PerMaterial, Option<(Vec3, Vec3)>) {
    let mut counts = PerMaterial::new();
    let mut add = |material: usize, m: &TriMesh| {
        let c = counts.entry(material).or_default();
        c.0 += m.positions.len();
        c.1 += m.indices.len();
    };
    for p in &nested.parts {
        add(p.material.unwrap_or(0), &p.mesh);
    }
    for inst in &nested.instances {
        for p in nested.components[inst.component].parts() {
            add(material_of(p, inst), &p.mesh);
        }
    }
    counts.retain(|_, c| c.1 > 0);
    let mut bounds = None;
    for &material in counts.keys() {
        for p in nested.parts.iter().filter(|p| p.material == Some(material)) {
            bounds = bounds_from(bounds, p.mesh.positions.iter().copied());
        }
        for inst in &nested.instances {
            let t = inst.transform;
            for p in nested.components[inst.component].parts() {
                if material_of(p, inst) == material {
                    bounds = bounds_from(
                        bounds,
                        p.mesh.positions.iter().map(|&v| t.transform_point3(v)),
                    );
                }
            }
        }
    }
    (counts, bounds)
}

/// The flattened parts of a grammar component's nested scene, before
/// normalisation: per material, its strokes, then every placed part
/// transformed into inner space, in placement order.
fn flatten(nested: &Nested) -> Vec<Part> {
    let mut merged: BTreeMap<usize, TriMesh> = BTreeMap::new();
    for p in &nested.parts {
        merged.insert(p.material.unwrap_or(0), p.mesh.clone());
    }
    // Room for every placed part at once: grown piece by piece, copying
    // the merged meshes as they grew took a third of the merging.
    let mut room = PerMaterial::new();
    for inst in &nested.instances {
        for p in nested.components[inst.component].parts() {
            let r = room.entry(material_of(p, inst)).or_default();
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
    for inst in &nested.instances {
        let t = inst.transform;
        let normals = Mat3::from_mat4(t).inverse().transpose();
        let mirrored = Mat3::from_mat4(t).determinant() < 0.0;
        for p in nested.components[inst.component].parts() {
            // Transformed straight into the merged mesh (no copy of the
            // part per placement: a Pailou's Toukungs place thousands).
            let m = merged.entry(material_of(p, inst)).or_default();
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
    parts_of(merged)
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
fn nest(scene: Scene, strokes: Vec<Part>, map: &[usize]) -> Nested {
    Nested {
        frame: Mat4::IDENTITY,
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
    // Flattened first if left for later: built from the remapped nested
    // scene, its parts could come in another order of materials.
    for p in c.parts_mut() {
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
