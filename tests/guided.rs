//! Guided procedural modeling (docs/guided.md): the examples of
//! `examples/guided/` derived, their strings snapshotted, and the paper's
//! properties checked.

use std::path::Path;

use lsys::guided::{self, Loaded, Origin, Outcome};

fn load(name: &str) -> Loaded {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/guided")
        .join(name);
    match guided::load_file(&p, &Default::default()) {
        Ok(l) => l,
        Err(e) => panic!("{}", lsys::diag::render_plain(e.as_ref())),
    }
}

fn run(l: &Loaded) -> Outcome {
    guided::run(l).unwrap()
}

#[test]
fn links_example() {
    let l = load("links.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

/// The drawn points of a seed, in order.
fn points(o: &Outcome, guide: usize, index: usize) -> Vec<(f64, f64)> {
    let s = o
        .seeds
        .iter()
        .find(|s| s.guide == guide && s.index == index)
        .expect("the seed");
    s.drawing
        .chains
        .iter()
        .flat_map(|c| c.points.iter().map(|p| (p.pos.x as f64, p.pos.y as f64)))
        .collect()
}

/// Distance of `p` from the line through `a` with direction `dir`.
fn off_line(p: (f64, f64), a: (f64, f64), dir: (f64, f64)) -> f64 {
    let (dx, dy) = (p.0 - a.0, p.1 - a.1);
    (dx * dir.1 - dy * dir.0).abs() / (dir.0.hypot(dir.1))
}

#[test]
fn a_c1_link_keeps_a_straight_line_straight() {
    let l = load("links.toml");
    let o = run(&l);
    let g2 = points(&o, 1, 0);
    assert!(g2.len() > 2);
    let dir = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    for p in points(&o, 0, 0).into_iter().chain(g2.iter().copied()) {
        assert!(off_line(p, (0.5, 1.0), dir) < 1e-5, "{p:?} leaves the line");
    }
    // The seed starts on the shared edge, where the line crosses it.
    let y = 1.0 + 3.5 * 30f64.to_radians().tan();
    assert!((g2[0].0 - 4.0).abs() < 1e-5 && (g2[0].1 - y).abs() < 1e-5);
}

#[test]
fn a_c0_link_keeps_only_the_point() {
    let l = load("links.toml");
    let o = run(&l);
    let g3 = points(&o, 2, 0);
    let x = 0.5 + 1.5 / 80f64.to_radians().tan();
    assert!(
        (g3[0].0 - x).abs() < 1e-5 && (g3[0].1 - 4.0).abs() < 1e-5,
        "{g3:?}"
    );
    // The heading is g3's inward normal (+y), not the incoming 80°.
    for p in &g3 {
        assert!((p.0 - x).abs() < 1e-5, "{p:?}");
    }
    assert!(o
        .seeds
        .iter()
        .any(|s| s.origin == Origin::Message { link: 1, pass: 4 }));
}

#[test]
fn an_element_whose_centre_leaves_the_guide_is_clipped() {
    let l = load("links.toml");
    let o = run(&l);
    // g1's first line derives 9 segments; the ninth's centre is past x = 4.
    let s = &o.seeds[0];
    assert_eq!(s.string.matches('F').count(), 9);
    let pts = points(&o, 0, 0);
    assert_eq!(pts.len(), 9, "8 segments drawn: {pts:?}");
    assert!(pts.iter().all(|p| p.0 <= 4.0 + 1e-9));
}

#[test]
fn the_run_is_deterministic() {
    let l = load("links.toml");
    assert_eq!(run(&l), run(&l));
}

#[test]
fn a_local_update_equals_a_full_recompute() {
    let l = load("links.toml");
    let before = run(&l);
    // g3 (index 2) shortened: only g3 re-derives; g1 replays its message.
    let mut l3 = load("links.toml");
    l3.spec.guides[2].points = vec![
        glam::DVec2::new(0.0, 4.0),
        glam::DVec2::new(4.0, 4.0),
        glam::DVec2::new(4.0, 6.0),
        glam::DVec2::new(0.0, 6.0),
    ];
    assert_eq!(guided::run::downstream(&l3, 2).len(), 1);
    let updated = guided::update(&l3, &before, 2).unwrap();
    assert_eq!(updated, run(&l3));
    assert_ne!(updated, before);
    // g1 moved its top edge down: g1, g2 and g3 all re-derive.
    let mut l1 = load("links.toml");
    l1.spec.guides[0].points[2].y = 3.5;
    l1.spec.guides[0].points[3].y = 3.5;
    assert_eq!(guided::run::downstream(&l1, 0).len(), 3);
    let updated = guided::update(&l1, &before, 0).unwrap();
    assert_eq!(updated, run(&l1));
    assert_ne!(updated, before);
}
