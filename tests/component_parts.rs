//! Components kept as nested scenes (grammar components such as the
//! Toukungs, tiled roofs) build their flattened meshes only when something
//! reads them: writing a GLB does not, and what is built later agrees with
//! what the component said of itself before.

use glam::Vec3;
use lsys::internals::mesh::scene::bounds_of;

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

/// Compiles `input` as `lsys build` does (`-D` defines none).
fn compile(input: &lsys::internals::load::Input) -> lsys::internals::pipeline::Compilation {
    lsys::internals::pipeline::compile(input, &Default::default()).unwrap()
}

/// What a build gives: the GLB's bytes, or the rendered diagnostics.
fn glb_or_error(
    c: &lsys::internals::pipeline::Compilation,
    opts: &lsys::internals::build::BuildOptions,
) -> String {
    match lsys::internals::build::build(c, opts) {
        Ok(b) => format!(
            "{:?}",
            lsys::internals::export::gltf::to_glb(&b.scene).unwrap()
        ),
        Err(e) => lsys::internals::diag::render_plain(&e),
    }
}

/// Grammar components started before their grammar compiles (what `lsys
/// build` does on two cores, `build::Early`) are the ones the build then
/// takes, and give the same file, or the same diagnostics when one fails,
/// as components built when placed.
#[test]
fn components_started_early_give_the_same_model_and_errors() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| {
        let pailou = lsys::internals::load::Input::Std("pailou".into());
        let text = lsys::internals::stdlib::get("pailou").unwrap();
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("components")).unwrap();
        std::fs::write(
            dir.path().join("components/Bad.lsys"),
            "axiom: F(1\nderivation length: 1\n",
        )
        .unwrap();
        let bad_text = "axiom: ~Bad(1, 1, 1)\n";
        let bad = lsys::internals::load::Input::Text {
            name: "bad.lsys".into(),
            text: bad_text.into(),
        };
        for (input, text, search) in [
            (
                pailou,
                text,
                lsys::internals::mesh::ComponentSearch::default(),
            ),
            (
                bad,
                bad_text,
                lsys::internals::mesh::ComponentSearch {
                    grammar_dir: Some(dir.path().to_path_buf()),
                    ..Default::default()
                },
            ),
        ] {
            let c = compile(&input);
            let opts = lsys::internals::build::BuildOptions {
                components: search,
                ..Default::default()
            };
            let placed = glb_or_error(&c, &opts);
            let mut early = opts.clone();
            early.early = lsys::internals::build::Early::start(text, &early);
            let started = early.early.waiting();
            assert!(!started.is_empty(), "nothing started for {text:.40}");
            let taken = glb_or_error(&c, &early);
            assert_eq!(early.early.waiting(), Vec::<String>::new(), "not taken");
            assert!(
                taken == placed,
                "{started:?}: {taken:.300}\nagainst\n{placed:.300}"
            );
        }
    });
}
