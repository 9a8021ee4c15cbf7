//! Scene assembly: a turtle [`Drawing`] -> a [`Scene`]. Tubes, shapes and
//! polygons are merged into one mesh per colour; each component is loaded
//! once, on its first placement, and every placement becomes an instance.

use std::collections::HashMap;

use rustc_hash::FxHashMap;

use super::components::ComponentSearch;
use super::error::MeshError;
use super::internodes;
use super::palette::Palette;
use super::scene::{Component, Instance, Material, Scene, Stroke, TriMesh};
use super::shapes;
use super::tubes::{Facets, Tubes};
use crate::resolve::ir::{Program, SymId};
use crate::support::prefault::{region, Prefault};
use crate::turtle::Drawing;

/// Meshing choices.
#[derive(Clone, Debug)]
pub struct MeshOptions {
    /// Facets around spheres and discs, and the most around tubes.
    pub sides: u32,
    /// Tubes thin against the whole drawing take fewer facets, down to 4
    /// (3 at detail 0), as many as keep them round to half a pixel on a
    /// view of the whole drawing 2048 pixels across (`detail` 1; 512 at 0,
    /// 8192 at 2); off: every tube has `sides`.
    pub adaptive: bool,
    /// `--detail`: 0 a light preview, 1 the default, 2 finer.
    pub detail: u8,
    /// Tubes as placements of one unit cylinder, a placement per straight
    /// segment, exported with `EXT_mesh_gpu_instancing` by glTF (see
    /// [`super::internodes`]); off: baked tubes with shared rings.
    pub instanced: bool,
    /// Refuse to build more triangles than this (as drawn, instances
    /// counted in full).
    pub max_triangles: usize,
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            sides: 8,
            adaptive: true,
            detail: 1,
            instanced: false,
            max_triangles: crate::turtle::DEFAULT_MAX_TRIANGLES,
        }
    }
}

struct Builder<'a> {
    palette: &'a Palette,
    scene: Scene,
    /// Colour index -> material index.
    colour_materials: FxHashMap<u32, usize>,
    /// Material index -> index in `scene.strokes`.
    stroke_of: FxHashMap<usize, usize>,
    /// (colour, `texture i:` index) -> material index.
    textured: FxHashMap<(u32, u32), usize>,
}

impl Builder<'_> {
    fn material(&mut self, colour: u32) -> usize {
        if let Some(&m) = self.colour_materials.get(&colour) {
            return m;
        }
        let (name, rgb) = self.palette.colour(colour);
        let wanted = Material {
            name,
            rgb,
            texture: None,
        };
        // A grammar component may have brought the same colour already.
        let m = match self.scene.materials.iter().position(|m| *m == wanted) {
            Some(m) => m,
            None => {
                self.scene.materials.push(wanted);
                self.scene.materials.len() - 1
            }
        };
        self.colour_materials.insert(colour, m);
        m
    }

    /// The mesh of `colour` under texture `index` (`texture i:`), its
    /// material made on first use.
    fn textured_mesh(&mut self, program: &Program, colour: u32, index: u32) -> &mut TriMesh {
        let material = match self.textured.get(&(colour, index)) {
            Some(&m) => m,
            None => {
                // The turtle checked that the header exists.
                let t = program
                    .turtle
                    .textures
                    .iter()
                    .find(|t| t.index == index as usize)
                    .expect("a @Tex names a texture header");
                let texture = match self.scene.textures.iter().position(|s| s.index == t.index) {
                    Some(k) => k,
                    None => {
                        self.scene.textures.push(t.clone());
                        self.scene.textures.len() - 1
                    }
                };
                let (name, rgb) = self.palette.colour(colour);
                self.scene.materials.push(Material {
                    name: format!("{name}/texture{index}"),
                    rgb,
                    texture: Some(texture),
                });
                let m = self.scene.materials.len() - 1;
                self.textured.insert((colour, index), m);
                m
            }
        };
        let k = *self.stroke_of.entry(material).or_insert_with(|| {
            self.scene.strokes.push(Stroke {
                material,
                mesh: TriMesh::default(),
            });
            self.scene.strokes.len() - 1
        });
        &mut self.scene.strokes[k].mesh
    }

    fn stroke_mesh(&mut self, colour: u32) -> &mut TriMesh {
        let k = self.stroke(colour);
        &mut self.scene.strokes[k].mesh
    }

    /// Index in `scene.strokes` of the mesh for `colour`.
    fn stroke(&mut self, colour: u32) -> usize {
        let material = self.material(colour);
        *self.stroke_of.entry(material).or_insert_with(|| {
            self.scene.strokes.push(Stroke {
                material,
                mesh: TriMesh::default(),
            });
            self.scene.strokes.len() - 1
        })
    }
}

/// Builds the scene of `drawing`. Component symbols are named through
/// `program` (for the file's spans in errors).
pub fn assemble_scene(
    program: &Program,
    drawing: &Drawing,
    palette: &Palette,
    search: &ComponentSearch,
    opts: &MeshOptions,
    grammars: &mut dyn super::GrammarComponents,
) -> Result<Scene, MeshError> {
    let mut b = Builder {
        palette,
        scene: Scene::default(),
        colour_materials: FxHashMap::default(),
        stroke_of: FxHashMap::default(),
        textured: FxHashMap::default(),
    };
    let mut triangles = 0usize;
    let mut check = |added: usize| {
        triangles += added;
        if triangles > opts.max_triangles {
            Err(MeshError::TooManyTriangles {
                limit: opts.max_triangles,
                reached: triangles,
            })
        } else {
            Ok(())
        }
    };
    if opts.instanced {
        internodes(&mut b, drawing, opts, &mut check)?;
    } else {
        let mut tubes = Tubes::new(&drawing.chains, &drawing.origins, opts);
        // Chains come in long runs of one colour: two hash lookups per
        // chain were a sixth of the meshing time.
        let mut last: Option<(u32, usize)> = None;
        // The second core backs the pages of a big mesh while this one
        // fills it: one helper at a time, for a mesh just reserved.
        let mut prefault: Option<Prefault<3>> = None;
        let threads = crate::derive::threads();
        for (i, c) in drawing.chains.iter().enumerate() {
            let k = match last {
                Some((colour, k)) if colour == c.colour => k,
                _ => {
                    prefault = None;
                    let k = b.stroke(c.colour);
                    let mesh = &mut b.scene.strokes[k].mesh;
                    if mesh.positions.is_empty() {
                        tubes.reserve(c.colour, mesh);
                        prefault = Prefault::start(stroke_regions(mesh), threads, LOOK_EVERY);
                    }
                    k
                }
            };
            last = Some((c.colour, k));
            let mesh = &mut b.scene.strokes[k].mesh;
            let before = mesh.triangle_count();
            tubes.add(i, c, mesh);
            if let Some(p) = &mut prefault {
                p.progress(mesh.indices.len(), || stroke_regions(mesh));
            }
            let added = mesh.triangle_count() - before;
            check(added)?;
        }
    }
    for s in &drawing.shapes {
        let mesh = b.stroke_mesh(s.colour);
        let before = mesh.triangle_count();
        shapes::shape(s, opts.sides, mesh);
        let added = mesh.triangle_count() - before;
        check(added)?;
    }
    for p in &drawing.polygons {
        let mesh = match &p.uv {
            Some(uv) => b.textured_mesh(program, p.colour, uv.texture),
            None => b.stroke_mesh(p.colour),
        };
        let before = mesh.triangle_count();
        shapes::polygon_uv(&p.points, p.uv.as_ref().map(|uv| &uv.coords[..]), mesh);
        let added = mesh.triangle_count() - before;
        check(added)?;
    }
    // Grammar components take most of a Pailou's meshing (each is a whole
    // build of its own): let them be built at once, on both cores.
    let mut placed: Vec<SymId> = drawing.placements.iter().map(|p| p.symbol).collect();
    placed.sort_unstable();
    placed.dedup();
    let names: Vec<&str> = placed
        .iter()
        .map(|&s| {
            program.symbols.list[s as usize]
                .name
                .trim_start_matches('~')
        })
        .filter(|name| !program.cpfg_surfaces.iter().any(|s| s.name == *name))
        .collect();
    let wanted = search.grammars_among(names.iter().copied());
    if wanted.len() > 1 {
        grammars.ahead(wanted);
    }
    let mut roofs: HashMap<String, Component> = search
        .roofs_among(names.iter().copied())
        .into_iter()
        .collect();
    // Symbol -> component index, loaded on first placement.
    let mut loaded: FxHashMap<SymId, usize> = FxHashMap::default();
    // Placements so far per component index (`--instanced` has already
    // added its cylinder).
    let mut numbers: Vec<u32> = vec![0; b.scene.components.len()];
    for p in &drawing.placements {
        let component = match loaded.get(&p.symbol) {
            Some(&c) => c,
            None => {
                let symbol = &program.symbols.list[p.symbol as usize];
                let name = symbol.name.trim_start_matches('~');
                // A cpfg model's view file names its surfaces; one whose
                // file could not be used draws nothing, as in cpfg (`lsys
                // check` says why).
                let surface = program.cpfg_surfaces.iter().find(|s| s.name == name);
                let c = match surface {
                    Some(s) => match &s.patches {
                        Ok(patches) => super::surface::surface_component(s, patches),
                        Err(_) => continue,
                    },
                    // A roof was built before the grammar components
                    // were waited for.
                    None => match roofs.remove(name).map(Ok).unwrap_or_else(|| {
                        search.load(name, &mut b.scene.materials, grammars, |searched| {
                            missing(program, p.symbol, name, searched)
                        })
                    }) {
                        Ok(c) => c,
                        // cpfg draws nothing for a surface its view file
                        // does not name.
                        Err(MeshError::MissingComponent(_)) if program.profile.cpfg_model_file => {
                            continue
                        }
                        Err(e) => return Err(e),
                    },
                };
                b.scene.components.push(c);
                numbers.push(0);
                let index = b.scene.components.len() - 1;
                loaded.insert(p.symbol, index);
                index
            }
        };
        check(b.scene.components[component].triangle_count())?;
        let material = b.material(p.colour);
        b.scene.instances.push(Instance {
            component,
            transform: p.transform,
            material,
            number: numbers[component],
        });
        numbers[component] += 1;
    }
    Ok(b.scene)
}

/// The drawing's chains as placements of one unit cylinder.
fn internodes(
    b: &mut Builder,
    drawing: &Drawing,
    opts: &MeshOptions,
    check: &mut dyn FnMut(usize) -> Result<(), MeshError>,
) -> Result<(), MeshError> {
    let facets = Facets::new(opts, &drawing.chains);
    let sides = internodes::sides(&drawing.chains, &facets);
    let cylinder = internodes::unit_cylinder(sides);
    let triangles = cylinder.triangle_count();
    let component = b.scene.components.len();
    b.scene.components.push(cylinder);
    b.scene.gpu_instancing = true;
    let mut number = 0;
    // One buffer for every chain's segments (`segments` takes a closure,
    // and `check` cannot be called from inside it).
    let mut placed = Vec::new();
    for c in &drawing.chains {
        let material = b.material(c.colour);
        internodes::segments(c, |transform| placed.push(transform));
        for transform in placed.drain(..) {
            check(triangles)?;
            b.scene.instances.push(Instance {
                component,
                transform,
                material,
                number,
            });
            number += 1;
        }
    }
    Ok(())
}

/// The grammar text of symbol `sym` and where it first appears, for a
/// diagnostic about what it drew (no place when there is no such symbol).
pub(super) fn symbol_source(
    program: &Program,
    sym: Option<SymId>,
) -> (
    miette::NamedSource<crate::source::SourceText>,
    Option<miette::SourceSpan>,
) {
    let span = sym.and_then(|s| program.symbols.list.get(s as usize)?.span);
    match span {
        Some(s) => (program.sources.named_source(s), Some(s.into())),
        None => (
            miette::NamedSource::new("", crate::source::SourceText::from(String::new())),
            None,
        ),
    }
}

pub(super) fn missing(
    program: &Program,
    sym: SymId,
    name: &str,
    searched: &[std::path::PathBuf],
) -> MeshError {
    let mut places: Vec<String> = searched
        .iter()
        .map(|p| format!("  {}", p.display()))
        .collect();
    places.push("  the built-in components".to_string());
    let builtin: Vec<&str> = crate::stdlib::COMPONENTS
        .iter()
        .chain(crate::stdlib::GRAMMAR_COMPONENTS)
        .map(|(n, _)| *n)
        .chain(["RC", "RE"])
        .collect();
    let (src, span) = symbol_source(program, Some(sym));
    MeshError::MissingComponent(Box::new(super::error::MissingComponent {
        name: name.to_string(),
        searched: places.join("\n"),
        builtin: if builtin.is_empty() {
            "none yet".to_string()
        } else {
            builtin.join(", ")
        },
        src,
        span,
    }))
}

/// Indices written between two looks at a mesh's buffers by the prefault
/// helper (a tube writes vertices and indices together: 16 Ki indices are
/// 64 KiB, with a few dozen KiB of vertices).
const LOOK_EVERY: usize = 16 << 10;

fn stroke_regions(mesh: &TriMesh) -> [crate::support::prefault::Region; 3] {
    [
        region(&mesh.positions),
        region(&mesh.normals),
        region(&mesh.indices),
    ]
}
