//! Components kept as nested scenes (grammar components such as the
//! Toukungs, tiled roofs) build their flattened meshes only when something
//! reads them: writing a GLB does not, and what is built later agrees with
//! what the component said of itself before.

use glam::Vec3;
use lsys::mesh::scene::bounds_of;

#[test]
fn nested_components_are_flattened_only_when_read() {
    let g = lsys::Grammar::from_path("std:pailou").unwrap();
    let scene = g.build(g.derivation_length()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    scene.write_glb(dir.path().join("p.glb")).unwrap();
    let mesh = scene.mesh();
    let nested: Vec<_> = mesh
        .components
        .iter()
        .filter(|c| c.nested.is_some())
        .collect();
    let names: Vec<&str> = nested.iter().map(|c| c.name.as_str()).collect();
    for want in ["TM", "TS", "RC"] {
        assert!(names.contains(&want), "{want} is not nested: {names:?}");
    }
    for c in nested {
        assert!(!c.parts_built(), "writing the GLB flattened {}", c.name);
        let said = (
            c.vertex_count(),
            c.triangle_count(),
            c.uses_placement_colour(),
        );
        let parts = c.parts();
        assert!(c.parts_built());
        let built = (
            parts.iter().map(|p| p.mesh.vertex_count()).sum::<usize>(),
            parts.iter().map(|p| p.mesh.triangle_count()).sum::<usize>(),
            parts.iter().any(|p| p.material.is_none()),
        );
        assert_eq!(said, built, "{}", c.name);
        assert!(built.1 > 0, "{} is empty", c.name);
        // Normalised to the unit box by the frame the nested scene carries.
        let (lo, hi) =
            bounds_of(parts.iter().flat_map(|p| p.mesh.positions.iter().copied())).unwrap();
        let frame = c.nested.as_ref().unwrap().frame;
        for (got, want) in [(lo, Vec3::splat(-0.5)), (hi, Vec3::splat(0.5))] {
            assert!((got - want).abs().max_element() < 1e-5, "{}: {got}", c.name);
        }
        let inner = &c.nested.as_ref().unwrap().parts;
        for p in inner.iter().flat_map(|p| &p.mesh.positions) {
            let q = frame.transform_point3(*p);
            assert!(
                q.cmpge(lo - 1e-5).all() && q.cmple(hi + 1e-5).all(),
                "{}: {q} outside the unit box",
                c.name
            );
        }
    }
}
