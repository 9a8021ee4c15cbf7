//! Components: a `~X` symbol -> its model, found beside the grammar, in
//! `--components` directories or in the built-in set, read with tobj and
//! normalised to the unit box (1×1×1, centred at the origin), as the paper
//! defines components.

use std::io::BufReader;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};

use super::error::MeshError;
use super::scene::{Component, Material, Part, TriMesh};
use crate::stdlib;

/// Where components are looked for, in order.
#[derive(Clone, Debug)]
pub struct ComponentSearch {
    /// The grammar file's directory: `components/X.obj` beside it.
    pub grammar_dir: Option<PathBuf>,
    /// `--components DIR`, in the order given.
    pub dirs: Vec<PathBuf>,
    /// The grammar components being built around this search, outermost
    /// first (to refuse cycles).
    pub within: Vec<String>,
    /// Level of detail (`--detail`) of procedural components (roofs: 0
    /// preview, 1 the default, 2 fine) and of the built-in models (0: the
    /// preview set with a third of the segments on every curve).
    pub detail: u8,
}

/// Where a component's model came from.
enum Found {
    File(PathBuf),
    /// A built-in model, decoded at build time (see [`built_in`]).
    BuiltIn(&'static [u8]),
    /// A grammar, derived and built once, then placed like any component.
    Grammar(crate::load::Input),
    /// A roof built on the fly.
    Roof(super::roof::RoofKind),
}

impl Default for ComponentSearch {
    fn default() -> Self {
        ComponentSearch {
            grammar_dir: None,
            dirs: Vec::new(),
            within: Vec::new(),
            detail: DEFAULT_DETAIL,
        }
    }
}

/// The level of detail without `--detail`.
pub const DEFAULT_DETAIL: u8 = 1;

impl ComponentSearch {
    /// The files tried for `name`, in order: in each directory the OBJ
    /// model, then a grammar of that name.
    fn candidates(&self, name: &str) -> Vec<PathBuf> {
        self.grammar_dir
            .iter()
            .map(|d| d.join("components"))
            .chain(self.dirs.iter().cloned())
            .flat_map(|d| {
                [
                    d.join(format!("{name}.obj")),
                    d.join(format!("{name}.lsys")),
                ]
            })
            .collect()
    }

    fn find(&self, name: &str) -> Result<Found, Vec<PathBuf>> {
        let candidates = self.candidates(name);
        if let Some(p) = candidates.iter().find(|p| p.is_file()) {
            return Ok(if p.extension().is_some_and(|e| e == "lsys") {
                Found::Grammar(crate::load::Input::Path(p.clone()))
            } else {
                Found::File(p.clone())
            });
        }
        if let Some(kind) = super::roof::RoofKind::from_name(name) {
            return Ok(Found::Roof(kind));
        }
        if let Some(mesh) = stdlib::decoded_at(name, self.detail) {
            return Ok(Found::BuiltIn(mesh));
        }
        stdlib::grammar_component(name)
            .map(|g| Found::Grammar(crate::load::Input::Std(g.to_string())))
            .ok_or(candidates)
    }

    /// Of the components `names`, the grammar components and the search
    /// each is built with (for [`super::GrammarComponents::ahead`]); a
    /// name that is not one, or would nest in a cycle, is left to `load`.
    pub fn grammars_among<'n>(
        &self,
        names: impl IntoIterator<Item = &'n str>,
    ) -> Vec<super::Wanted> {
        names
            .into_iter()
            .filter_map(|name| match self.find(name) {
                // One outside its folder is left to `load`, which refuses it.
                Ok(Found::Grammar(crate::load::Input::Path(p))) if confined(name, &p).is_err() => {
                    None
                }
                Ok(Found::Grammar(input)) => Some(super::Wanted {
                    name: name.to_string(),
                    search: super::subgrammar::inner_search(name, &input, self).ok()?,
                    input,
                }),
                _ => None,
            })
            .collect()
    }

    /// Of the components `names`, the procedural roofs, built now (they
    /// need nothing of the scene, so they are built while grammar
    /// components started earlier finish on the other core).
    pub fn roofs_among<'n>(
        &self,
        names: impl IntoIterator<Item = &'n str>,
    ) -> Vec<(String, Component)> {
        names
            .into_iter()
            .filter_map(|name| match self.find(name) {
                Ok(Found::Roof(kind)) => Some((
                    name.to_string(),
                    super::roof::roof_component(name, kind, self.detail),
                )),
                _ => None,
            })
            .collect()
    }

    /// Finds every component `program` names (its `~X` symbols) without
    /// reading or building any: `lsys check`'s look-up. One error, with
    /// the places searched, for each component found nowhere.
    pub fn find_all(&self, program: &crate::resolve::Program) -> Vec<MeshError> {
        program
            .symbols
            .list
            .iter()
            .enumerate()
            .filter(|(_, s)| s.kind == crate::resolve::SymbolKind::Component)
            .filter_map(|(id, s)| {
                let name = s.name.trim_start_matches(['~', '∼']);
                // A cpfg model's view file names its surfaces.
                if let Some(surface) = program.cpfg_surfaces.iter().find(|s| s.name == name) {
                    return surface.patches.as_ref().err().map(|why| MeshError::CpfgSurface {
                        name: name.to_string(),
                        why: why.clone(),
                    });
                }
                let searched = self.find(name).err()?;
                if program.profile.cpfg_model_file {
                    return Some(MeshError::CpfgSurface {
                        name: name.to_string(),
                        why: format!(
                            "the view file has no `surface: {name}` line, and no component `{name}.obj` was found"
                        ),
                    });
                }
                Some(super::assemble::missing(
                    program,
                    id as crate::resolve::SymId,
                    name,
                    &searched,
                ))
            })
            .collect()
    }

    /// Loads component `name` (without the `~`). `Err(searched)` lists the
    /// places tried when it is nowhere; materials of its `.mtl` are added
    /// to `materials`.
    pub fn load(
        &self,
        name: &str,
        materials: &mut Vec<Material>,
        grammars: &mut dyn super::subgrammar::GrammarComponents,
        missing: impl FnOnce(&[PathBuf]) -> MeshError,
    ) -> Result<Component, MeshError> {
        let found = self.find(name).map_err(|searched| missing(&searched))?;
        if let Found::File(p) | Found::Grammar(crate::load::Input::Path(p)) = &found {
            confined(name, p)?;
        }
        match found {
            Found::File(path) => match std::fs::read(&path) {
                Ok(bytes) => parse_obj(
                    name,
                    &bytes,
                    &path.display().to_string(),
                    path.parent(),
                    materials,
                ),
                Err(cause) => Err(MeshError::ComponentIo {
                    name: name.to_string(),
                    path: path.display().to_string(),
                    cause,
                }),
            },
            Found::BuiltIn(mesh) => Ok(built_in(name, mesh)),
            Found::Roof(kind) => Ok(super::roof::roof_component(name, kind, self.detail)),
            Found::Grammar(input) => {
                super::subgrammar::grammar_component(name, &input, self, materials, grammars)
            }
        }
    }
}

/// `Err` when the component file `path` resolves (links followed) outside
/// the folder it was found in: a `components/X.lsys` linked to
/// `/etc/passwd` is refused before it is read, so no diagnostic shows its
/// lines (the include rules of docs/limits.md).
fn confined(name: &str, path: &Path) -> Result<(), MeshError> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let (Ok(real), Ok(root)) = (std::fs::canonicalize(path), std::fs::canonicalize(dir)) else {
        // Not there after all: reading it says so.
        return Ok(());
    };
    if real.starts_with(&root) {
        Ok(())
    } else {
        Err(MeshError::ComponentOutside {
            name: name.to_string(),
            path: path.display().to_string(),
            dir: dir.display().to_string(),
        })
    }
}

/// Reads an OBJ model (and the `.mtl` files it names, from `dir`) into a
/// component normalised to the unit box.
pub fn parse_obj(
    name: &str,
    bytes: &[u8],
    origin: &str,
    dir: Option<&Path>,
    materials: &mut Vec<Material>,
) -> Result<Component, MeshError> {
    let bad = |reason: String| MeshError::BadComponent {
        name: name.to_string(),
        path: origin.to_string(),
        reason,
    };
    let opts = super::obj_options::obj_options();
    let (models, mtl) = tobj::load_obj_buf(&mut BufReader::new(bytes), &opts, |mtl_path| {
        let Some(dir) = dir else {
            return Err(tobj::LoadError::OpenFileFailed);
        };
        let text =
            std::fs::read(dir.join(mtl_path)).map_err(|_| tobj::LoadError::OpenFileFailed)?;
        tobj::load_mtl_buf(&mut BufReader::new(text.as_slice()))
    })
    .map_err(|e| bad(locate_obj_error(bytes, e)))?;
    // A missing or broken .mtl only loses colours: the parts then take the
    // turtle's colour, which is what a model without materials gets anyway.
    let mtl = mtl.unwrap_or_default();
    let first_material = materials.len();
    for m in &mtl {
        let rgb = m.diffuse.unwrap_or([0.8, 0.8, 0.8]);
        materials.push(Material {
            name: format!("{name}/{}", m.name),
            rgb: rgb.map(|c| c.clamp(0.0, 1.0)),
            texture: None,
        });
    }
    let meshes = models.into_iter().map(|model| {
        let m = model.mesh;
        ObjMesh {
            positions: m.positions,
            normals: m.normals,
            indices: m.indices,
            material: m
                .material_id
                .filter(|&i| i < mtl.len())
                .map(|i| first_material + i),
        }
    });
    component_of(name, origin, meshes).map_err(bad)
}

/// One mesh of an OBJ model as tobj reads it (flat coordinate lists).
struct ObjMesh {
    positions: Vec<f32>,
    normals: Vec<f32>,
    indices: Vec<u32>,
    /// Index into the scene's materials.
    material: Option<usize>,
}

/// The built-in component `name` from its mesh decoded at build time
/// (build.rs: tobj's reading of the OBJ model, so the component is the one
/// [`parse_obj`] makes of the OBJ text, without parsing text at run time).
fn built_in(name: &str, mut bytes: &[u8]) -> Component {
    let mut word = || {
        let (w, rest) = bytes.split_first_chunk::<4>().expect("build.rs wrote it");
        bytes = rest;
        *w
    };
    let models = u32::from_le_bytes(word());
    let meshes: Vec<ObjMesh> = (0..models)
        .map(|_| {
            let mut floats = || {
                let n = u32::from_le_bytes(word());
                (0..n)
                    .map(|_| f32::from_le_bytes(word()))
                    .collect::<Vec<f32>>()
            };
            let positions = floats();
            let normals = floats();
            let n = u32::from_le_bytes(word());
            let indices = (0..n).map(|_| u32::from_le_bytes(word())).collect();
            ObjMesh {
                positions,
                normals,
                indices,
                material: None,
            }
        })
        .collect();
    component_of(name, "built-in", meshes).expect("a built-in component is a valid model")
}

/// The component of `meshes` (an OBJ model's), normalised to the unit
/// box; `Err(reason)` for a model that is not one.
fn component_of(
    name: &str,
    origin: &str,
    meshes: impl IntoIterator<Item = ObjMesh>,
) -> Result<Component, String> {
    let mut parts = Vec::new();
    for m in meshes {
        if m.indices.is_empty() {
            continue;
        }
        let pos: Vec<Vec3> = m
            .positions
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        if let Some(bad_pos) = pos.iter().find(|p| !p.is_finite()) {
            return Err(format!(
                "a vertex has a coordinate that is not a number ({bad_pos})"
            ));
        }
        let mut mesh = TriMesh::default();
        if m.normals.len() == m.positions.len() {
            mesh.positions = pos;
            mesh.normals = m
                .normals
                .chunks_exact(3)
                .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or(Vec3::Y))
                .collect();
            mesh.indices = m.indices;
        } else {
            // No normals in the file: give each triangle its own flat ones.
            for t in m.indices.chunks_exact(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| pos[i as usize]);
                let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
                let i = mesh.vertex(a, n);
                mesh.vertex(b, n);
                mesh.vertex(c, n);
                mesh.triangle(i, i + 1, i + 2);
            }
        }
        parts.push(Part {
            mesh,
            material: m.material,
        });
    }
    if parts.is_empty() {
        return Err("it has no faces (`f` lines)".to_string());
    }
    let size = super::scene::bounds_of(parts.iter().flat_map(|p| p.mesh.positions.iter().copied()))
        .map(|(lo, hi)| hi - lo);
    normalise(&mut parts);
    let c = Component::new(name, origin, parts);
    Ok(match size {
        Some(size) => c.with_modelled(size),
        None => c,
    })
}

/// Centres the parts at the origin and scales each axis to extent 1. An
/// axis with no extent (a flat model) stays flat.
pub(super) fn normalise(parts: &mut [Part]) -> Mat4 {
    normalise_meshes(parts.iter_mut().map(|p| &mut p.mesh).collect())
}

/// Maps `meshes` together into the unit box centred at the origin (an
/// axis without extent keeps its scale) and returns the map.
pub(super) fn normalise_meshes(mut meshes: Vec<&mut TriMesh>) -> Mat4 {
    let Some((lo, hi)) =
        super::scene::bounds_of(meshes.iter().flat_map(|m| m.positions.iter().copied()))
    else {
        return Mat4::IDENTITY;
    };
    let unit = UnitBox::of(lo, hi);
    for m in &mut meshes {
        unit.apply(m);
    }
    unit.matrix()
}

/// The map of geometry bounded by `lo..hi` into the unit box centred at
/// the origin (an axis without extent keeps its scale).
pub(super) struct UnitBox {
    centre: Vec3,
    scale: Vec3,
    /// Normals scale by the inverse: multiply by the extent.
    inv: Vec3,
}

impl UnitBox {
    pub(super) fn of(lo: Vec3, hi: Vec3) -> UnitBox {
        let extent = hi - lo;
        let wide = extent.cmpgt(Vec3::splat(1e-9));
        UnitBox {
            centre: (lo + hi) * 0.5,
            scale: Vec3::select(wide, extent.recip(), Vec3::ONE),
            inv: Vec3::select(wide, extent, Vec3::ONE),
        }
    }

    pub(super) fn apply(&self, m: &mut TriMesh) {
        for v in &mut m.positions {
            *v = (*v - self.centre) * self.scale;
        }
        for n in &mut m.normals {
            *n = (*n * self.inv).normalize_or(*n);
        }
    }

    pub(super) fn matrix(&self) -> Mat4 {
        Mat4::from_scale(self.scale) * Mat4::from_translation(-self.centre)
    }
}

/// tobj's errors carry no position; find the offending line ourselves for
/// the errors users meet (faces that point past the vertex list).
fn locate_obj_error(bytes: &[u8], e: tobj::LoadError) -> String {
    let text = String::from_utf8_lossy(bytes);
    if e == tobj::LoadError::FaceVertexOutOfBounds {
        let mut vertices = 0i64;
        for (n, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("v") => vertices += 1,
                Some("f") => {
                    for w in words {
                        let Some(Ok(i)) = w.split('/').next().map(str::parse::<i64>) else {
                            continue;
                        };
                        let ok = if i > 0 {
                            i <= vertices
                        } else {
                            i < 0 && -i <= vertices
                        };
                        if !ok {
                            return format!(
                                "line {}: face `{}` refers to vertex {i}, but only {vertices} vertices come before it",
                                n + 1,
                                line.trim()
                            );
                        }
                    }
                }
                _ => {}
            }
        }
    }
    format!("{e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    const TETRA: &str = "v 0 0 0\nv 2 0 0\nv 0 4 0\nv 0 0 8\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

    #[test]
    fn obj_is_normalised_to_the_unit_box() {
        let c = parse_obj("T", TETRA.as_bytes(), "t.obj", None, &mut Vec::new()).unwrap();
        let (lo, hi) = c.parts()[0].mesh.bounds().unwrap();
        assert_eq!(lo, Vec3::splat(-0.5));
        assert_eq!(hi, Vec3::splat(0.5));
        assert_eq!(c.triangle_count(), 4);
        // flat normals were computed: unit length
        assert!(c.parts()[0]
            .mesh
            .normals
            .iter()
            .all(|n| (n.length() - 1.0).abs() < 1e-5));
    }

    /// The meshes build.rs decoded are what reading the OBJ text gives:
    /// every built-in model of both sets, bit for bit.
    #[test]
    fn decoded_built_ins_are_the_obj_models() {
        let sets = [
            (stdlib::COMPONENTS, stdlib::DECODED),
            (stdlib::PREVIEW_COMPONENTS, stdlib::DECODED_PREVIEW),
        ];
        for (texts, decoded) in sets {
            let texts_named: Vec<&str> = texts.iter().map(|(n, _)| *n).collect();
            let decoded_named: Vec<&str> = decoded.iter().map(|(n, _)| *n).collect();
            assert_eq!(texts_named, decoded_named);
            for ((name, text), (_, mesh)) in texts.iter().zip(decoded) {
                let read = parse_obj(name, text.as_bytes(), "built-in", None, &mut Vec::new())
                    .expect("reads");
                let built = built_in(name, mesh);
                assert_eq!(read.parts().len(), built.parts().len(), "{name}");
                for (r, b) in read.parts().iter().zip(built.parts()) {
                    assert_eq!(r.material, b.material, "{name}");
                    let bits = |m: &TriMesh| {
                        let v = |vs: &[Vec3]| {
                            vs.iter()
                                .map(|v| v.to_array().map(f32::to_bits))
                                .collect::<Vec<_>>()
                        };
                        (v(&m.positions), v(&m.normals), m.indices.clone())
                    };
                    assert_eq!(bits(&r.mesh), bits(&b.mesh), "{name}");
                }
                assert_eq!(read.origin, built.origin);
            }
        }
    }

    #[test]
    fn broken_face_names_the_line() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
        let e = parse_obj("B", text.as_bytes(), "b.obj", None, &mut Vec::new()).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("line 5") && msg.contains("vertex 9"), "{msg}");
    }

    #[test]
    fn model_without_faces_is_refused() {
        let e = parse_obj("E", b"v 0 0 0\n", "e.obj", None, &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("no faces"));
    }

    #[test]
    fn search_lists_every_place_tried() {
        let s = ComponentSearch {
            grammar_dir: Some(PathBuf::from("/nowhere/g")),
            dirs: vec![PathBuf::from("/nowhere/extra")],
            ..Default::default()
        };
        let mut tried = Vec::new();
        let found = s.load(
            "Nope",
            &mut Vec::new(),
            &mut super::super::NoGrammars,
            |searched| {
                tried = searched.to_vec();
                MeshError::TooManyTriangles {
                    limit: 0,
                    reached: 0,
                }
            },
        );
        assert!(found.is_err(), "found a component that does not exist");
        assert_eq!(
            tried,
            vec![
                PathBuf::from("/nowhere/g/components/Nope.obj"),
                PathBuf::from("/nowhere/g/components/Nope.lsys"),
                PathBuf::from("/nowhere/extra/Nope.obj"),
                PathBuf::from("/nowhere/extra/Nope.lsys"),
            ]
        );
    }
}
