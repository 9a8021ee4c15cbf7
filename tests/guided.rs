//! Guided procedural modeling (docs/guided.md): the examples of
//! `examples/guided/` derived, their strings snapshotted, and the paper's
//! properties checked.

use std::path::Path;

use lsys::internals::guided::{self, Loaded, Origin, Outcome};

fn load(name: &str) -> Loaded {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/guided")
        .join(name);
    match guided::load_file(&p, &Default::default(), &[]) {
        Ok(l) => l,
        Err(e) => panic!("{}", lsys::internals::diag::render_plain(e.as_ref())),
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

fn seeds_in(o: &Outcome, l: &Loaded, guide: &str) -> usize {
    let g = l.spec.guides.iter().position(|g| g.name == guide).unwrap();
    o.seeds.iter().filter(|s| s.guide == g).count()
}

#[test]
fn palm_example() {
    let l = load("palm.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

#[test]
fn the_palm_trunk_is_cut_at_its_guide() {
    let l = load("palm.toml");
    let o = run(&l);
    let trunk = &o.seeds[0];
    // Nothing but segments is left: the tip after the touching ?X is cut.
    assert!(!trunk.string.contains('?'), "{}", trunk.string);
    let pts = points(&o, 0, 0);
    let last = pts.last().unwrap();
    // The last segment reaches the top edge (y = 8) or a little past it.
    assert!(last.1 >= 8.0 - 1e-6 && last.1 < 8.3, "{last:?}");
    assert_eq!(o.messages.iter().filter(|m| m.0.link == 0).count(), 1);
}

#[test]
fn the_palm_sends_one_seed_per_token_and_none_over_a_zero_token_link() {
    let l = load("palm.toml");
    let o = run(&l);
    assert_eq!(
        seeds_in(&o, &l, "crown"),
        1,
        "navigation links never seed the crown"
    );
    for leaf in [
        "leaf_right",
        "leaf_upper_right",
        "leaf_upper_left",
        "leaf_left",
    ] {
        assert_eq!(seeds_in(&o, &l, leaf), 1, "{leaf}");
    }
    // The frond sent to link 15 (no tokens) reached its edge ...
    let crown = o.seeds.iter().find(|s| s.guide == 1).unwrap();
    assert_eq!(crown.string.matches('[').count(), 5);
    // ... and seeded nothing.
    assert_eq!(seeds_in(&o, &l, "leaf_top"), 0);
    assert_eq!(o.tokens[5].used, 0);
}

/// Three parallel lines reach the right edge of g1, whose link to g2 has
/// two tokens: two seeds in g2, the first two lines in string order.
const TOKENS: &str = r#"
steps = 20
[[guide]]
name = "g1"
grammar = "line.lsys"
points = [[0, 0], [2, 0], [2, 3], [0, 3]]
[[guide]]
name = "g2"
grammar = "line.lsys"
points = [[2, 0], [4, 0], [4, 3], [2, 3]]
[[link]]
from = "g1"
from_edge = 1
to = "g2"
to_edge = 3
tokens = 2
continuity = "C1"
[[seeds]]
guide = "g1"
position = [0, 2.5]
heading = 0
[[seeds]]
guide = "g1"
position = [0, 1.5]
heading = 0
[[seeds]]
guide = "g1"
position = [0, 0.5]
heading = 0
"#;

#[test]
fn a_link_sends_as_many_messages_as_it_has_tokens() {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/guided");
    let l = guided::load_text("tokens.toml", TOKENS, &base, &Default::default()).unwrap();
    let o = run(&l);
    assert_eq!(seeds_in(&o, &l, "g2"), 2);
    let ys: Vec<f64> = o
        .seeds
        .iter()
        .filter(|s| s.guide == 1)
        .map(|s| s.at.origin.y)
        .collect();
    assert_eq!(ys, vec![2.5, 1.5]);
    assert_eq!((o.tokens[0].used, o.tokens[0].free()), (2, 0));
}

#[test]
fn spiral_example() {
    let l = load("spiral.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

#[test]
fn the_spiral_sends_one_lateral_branch_per_link() {
    let l = load("spiral.toml");
    let o = run(&l);
    let main = &o.seeds[0];
    // The tip passes within reach of each link for many steps; the
    // reservation keeps it to one branch each.
    assert_eq!(main.string.matches('[').count(), 3, "{}", main.string);
    for g in ["east", "north", "west"] {
        assert_eq!(seeds_in(&o, &l, g), 1, "{g}");
    }
    assert!(o
        .tokens
        .iter()
        .all(|t| t.used == 1 && t.reserved.is_empty()));
    // The main spiral shrinks by 0.995 a step and stops below S0 / 3.
    assert!(main.string.ends_with("F(0.1001)"), "{}", main.string);
}

#[test]
fn street_example() {
    let l = load("street.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

#[test]
fn the_street_keeps_its_heading_across_guides() {
    let l = load("street.toml");
    let o = run(&l);
    // Each quarter's arterial starts where the centre's crossed the edge,
    // heading as the centre's did.
    for (name, heading) in [
        ("east", 30.0),
        ("north", 120.0),
        ("west", -150.0),
        ("south", -60.0),
    ] {
        let g = l.spec.guides.iter().position(|g| g.name == name).unwrap();
        let seed = o.seeds.iter().find(|s| s.guide == g).unwrap();
        let h: f64 = seed.at.heading;
        assert!((h - heading).abs() < 1e-6, "{name}: {h}");
        let p = seed.at.origin;
        let dir = (heading.to_radians().cos(), heading.to_radians().sin());
        assert!(
            off_line((p.x, p.y), (0.0, 0.0), dir) < 1e-6,
            "{name}: {p:?}"
        );
        // The quarter's first segment continues the line.
        let pts = points(&o, g, 0);
        assert!(
            off_line(pts[1], (0.0, 0.0), dir) < 1e-5,
            "{name}: {:?}",
            pts[1]
        );
    }
}

#[test]
fn tree_example() {
    let l = load("tree.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

/// The modules outside brackets: the main axis.
fn main_axis(s: &str) -> Vec<&str> {
    let mut depth = 0;
    let mut out = Vec::new();
    for m in s.split(' ') {
        match m {
            "[" => depth += 1,
            "]" => depth -= 1,
            _ if depth == 0 => out.push(m),
            _ => {}
        }
    }
    out
}

#[test]
fn the_tree_passes_the_level_through_x() {
    let l = load("tree.toml");
    let o = run(&l);
    let trunk = &o.seeds[0].string;
    let segments = main_axis(trunk)
        .iter()
        .filter(|m| m.starts_with('F'))
        .count();
    let crown = o.seeds.iter().find(|s| s.guide == 1).unwrap();
    // The level reached at the crown's link: the trunk's segments.
    assert_eq!(crown.payload, vec![segments as f64]);
    // The boughs leave the trunk at 3 and 7 segments and cross their
    // links a few segments later; each seed got its own level.
    let right = o.seeds.iter().find(|s| s.guide == 2).unwrap().payload[0];
    let left = o.seeds.iter().find(|s| s.guide == 3).unwrap().payload[0];
    assert!(
        right > 3.0 && right < left && left < segments as f64,
        "{right} {left}"
    );
    // A higher level leaves fewer levels to grow: the crown's cluster is
    // the smallest of the three though its guide is the largest.
    let fs = |g: usize| {
        o.seeds
            .iter()
            .find(|s| s.guide == g)
            .unwrap()
            .string
            .matches('F')
            .count()
    };
    assert!(
        fs(1) < fs(2) && fs(1) < fs(3),
        "{} {} {}",
        fs(1),
        fs(2),
        fs(3)
    );
}

#[test]
fn pailou_entrance_example() {
    let l = load("pailou_entrance.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

/// Bracket caps per row (placements of the rows' seed, by height).
fn caps_per_row(o: &Outcome) -> Vec<usize> {
    let mut rows: std::collections::BTreeMap<i64, usize> = Default::default();
    for p in &o.seeds[0].drawing.placements {
        let y = p.transform.w_axis.y;
        *rows.entry((y * 100.0).round() as i64).or_default() += 1;
    }
    rows.into_values().collect()
}

#[test]
fn the_toukung_rows_stop_at_their_guide() {
    let l = load("pailou_entrance.toml");
    let o = run(&l);
    let rows = caps_per_row(&o);
    assert_eq!(rows.len(), 6, "{rows:?}");
    assert!(rows.windows(2).all(|w| w[0] >= w[1]), "{rows:?}");
    assert!(rows[0] > rows[5], "{rows:?}");
    let guide = &l.spec.guides[0].points;
    for p in &o.seeds[0].drawing.placements {
        let c = glam::DVec2::new(p.transform.w_axis.x as f64, p.transform.w_axis.y as f64);
        assert!(guided::geometry::inside(c, guide), "{c:?}");
    }
    // A wider trapezoid: the same grammar fills longer rows.
    let mut wide = load("pailou_entrance.toml");
    for p in &mut wide.spec.guides[0].points {
        p.x *= 1.5;
    }
    let more = caps_per_row(&run(&wide));
    assert!(
        more.iter().zip(&rows).all(|(m, r)| m > r),
        "{more:?} {rows:?}"
    );
}

/// One guide (id 1), a link (id 2) on its right edge, a seed at (1, 1)
/// heading up (+y).
const QUERIES: &str = r#"
steps = 1
[[guide]]
name = "g"
grammar = "queries.lsys"
points = [[0, 0], [4, 0], [4, 4], [0, 4]]
[[guide]]
name = "h"
grammar = "queries.lsys"
points = [[4, 0], [8, 0], [8, 4], [4, 4]]
[[link]]
from = "g"
from_edge = 1
to = "h"
to_edge = 3
tokens = 0
continuity = "C1"
[[seeds]]
guide = "g"
position = [1, 1]
heading = 90
"#;

#[test]
fn the_query_modules_answer_in_one_layout() {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/guided");
    let l = guided::load_text("queries.toml", QUERIES, &base, &Default::default()).unwrap();
    let o = run(&l);
    // Outputs first (found, d, beta, id_out), then inputs; the closest
    // link is 3 to the right (beta -90), the closest boundary 1 behind
    // (beta 180, the bottom edge before the left one), the boundary 3
    // ahead; a short ?X hits nothing, a long one the top edge (id 1);
    // id_test 99 names nothing. ?X's payload (7) passes through.
    insta::assert_snapshot!(o.strings(&l), @"g#0 (explicit): ?DL(1,3,-90,3,0) ?DG(1,1,180,1,0) ?DA(1,1,180,1,0) ?NL(0,0,0,0) ?NG(1,3,1,0) ?NA(1,3,1,0) ?X(0,0,0.5,0,0,7) ?X(1,1,5,0,0,7) ?DL(0,0,0,0,99) ?NL(0,0,0,99)");
}

fn lsys(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

#[test]
fn lsys_render_and_build_read_a_scene() {
    let dir = std::env::temp_dir().join(format!("lsys-guided-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("links.png");
    let o = lsys(&[
        "render",
        "examples/guided/links.toml",
        "-o",
        png.to_str().unwrap(),
        "--guides",
        "--size",
        "64x48",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::metadata(&png).unwrap().len() > 0);
    let glb = dir.join("links.glb");
    let o = lsys(&[
        "build",
        "examples/guided/links.toml",
        "-o",
        glb.to_str().unwrap(),
        "--stats",
    ]);
    assert!(o.status.success());
    let stats = String::from_utf8_lossy(&o.stdout);
    assert!(
        stats.contains("\"seeds\":4") && stats.contains("\"messages\":2"),
        "{stats}"
    );
    // A mistake in the scene is a located diagnostic and exit code 65.
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "steps = 1\n[[guide]]\nname = \"g\"\ngrammar = \"x.lsys\"\npoints = [[0, 0], [1, 1]]\n",
    )
    .unwrap();
    let o = lsys(&["build", bad.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(65));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("lsys::guided::scene") && err.contains("at least 3"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_local_update_of_the_palm_equals_a_full_recompute() {
    let l = load("palm.toml");
    let before = run(&l);
    // A leaf guide stretched: only that leaf re-derives.
    let mut leaf = load("palm.toml");
    for p in leaf.spec.guides[2].points.iter_mut().skip(2) {
        p.x += 1.0;
    }
    // Its navigation link back to the crown has no tokens: it sends
    // nothing, so nothing is downstream of the leaf.
    assert_eq!(
        guided::run::downstream(&leaf, 2),
        std::collections::BTreeSet::from([2])
    );
    let updated = guided::update(&leaf, &before, 2).unwrap();
    assert_eq!(updated, run(&leaf));
    assert_ne!(updated.seeds[2], before.seeds[2]);
    assert_eq!(updated.seeds[0], before.seeds[0]);
    // The crown widened: the crown and the four leaves its links with
    // tokens reach (the link to leaf_top has none).
    let mut crown = load("palm.toml");
    crown.spec.guides[1].points[3].x += 0.5;
    assert_eq!(guided::run::downstream(&crown, 1).len(), 5);
    assert_eq!(guided::update(&crown, &before, 1).unwrap(), run(&crown));
}

#[test]
fn an_element_tagged_by_x_answers_with_its_id() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    // Seed 0 asks `?X` about a wall of length 2 with id_in 7, then draws
    // it; seed 1 looks for anything with id 7, with id 8, and for anything.
    w(
        "tag.lsys",
        "derivation length: 4\naxiom: S(0)\n\
         S(r) : r == 1 --> ?X(0, 0, 2, 7, 0)\n\
         S(r) : r == 2 --> ?DA(0, 0, 0, 0, 7) ?DA(0, 0, 0, 0, 8) ?DA(0, 0, 0, 0, 0)\n\
         ?X(f, i, d, a, t) --> F(d)\n",
    );
    w(
        "scene.toml",
        "steps = 4\n[[guide]]\nname = \"g\"\ngrammar = \"tag.lsys\"\nid = 100\n\
         points = [[0, 0], [10, 0], [10, 10], [0, 10]]\n\
         [[seeds]]\nguide = \"g\"\nposition = [1, 5]\nheading = 0\nparameters = [1]\n\
         [[seeds]]\nguide = \"g\"\nposition = [5, 1]\nheading = 90\nparameters = [2]\n",
    );
    let l = match guided::load_file(&dir.path().join("scene.toml"), &Default::default(), &[]) {
        Ok(l) => l,
        Err(e) => panic!("{}", lsys::internals::diag::render_plain(e.as_ref())),
    };
    let o = run(&l);
    let probe = &o.seeds.iter().find(|s| s.index == 1).unwrap().string;
    let queries: Vec<&str> = probe.split_whitespace().collect();
    // The wall runs (1,5)-(3,5): its nearest point (3,5) is √20 away, to
    // the left of the probe's heading; the guide's bottom edge is 1 away.
    let d = 20f64.sqrt();
    let beta = 2f64.atan2(4.0).to_degrees();
    assert_eq!(queries.len(), 3, "{probe}");
    let nums = |q: &str| -> Vec<f64> {
        q.trim_start_matches("?DA(")
            .trim_end_matches(')')
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let tagged = nums(queries[0]);
    assert_eq!(tagged[0], 1.0, "{probe}");
    assert!((tagged[1] - d).abs() < 1e-4, "{probe}");
    assert!((tagged[2] - beta).abs() < 1e-3, "{probe}");
    assert_eq!(tagged[3], 7.0, "{probe}");
    assert_eq!(nums(queries[1])[0], 0.0, "no element has id 8: {probe}");
    let any = nums(queries[2]);
    assert_eq!((any[0], any[1], any[3]), (1.0, 1.0, 100.0), "{probe}");
}

#[test]
fn each_seed_places_the_components_of_its_own_grammar() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    // Two grammars in two guides, each placing built-in Pailou parts; the
    // second grammar's symbol table differs (an extra module first).
    w(
        "a.lsys",
        "axiom: ~MCa(0.4, 0.4, 0.4) F(1) ~MCa(0.4, 0.4, 0.4)\n",
    );
    w(
        "b.lsys",
        "axiom: X ~MP(0.3, 1, 0.3) F(1) ~MCa(0.4, 0.4, 0.4)\n",
    );
    w(
        "scene.toml",
        "steps = 1\n\
         [[guide]]\nname = \"a\"\ngrammar = \"a.lsys\"\npoints = [[0, 0], [4, 0], [4, 4], [0, 4]]\n\
         [[guide]]\nname = \"b\"\ngrammar = \"b.lsys\"\npoints = [[4, 0], [8, 0], [8, 4], [4, 4]]\n\
         [[seeds]]\nguide = \"a\"\nposition = [2, 1]\nheading = 90\n\
         [[seeds]]\nguide = \"b\"\nposition = [6, 1]\nheading = 90\n",
    );
    let l = guided::load_file(&dir.path().join("scene.toml"), &Default::default(), &[]).unwrap();
    let o = run(&l);
    let search = lsys::internals::mesh::ComponentSearch {
        grammar_dir: Some(dir.path().to_path_buf()),
        dirs: Vec::new(),
        within: Vec::new(),
        detail: Default::default(),
    };
    let scene = guided::build::scene(
        &l,
        &o,
        false,
        &search,
        &lsys::internals::mesh::MeshOptions::default(),
        &mut lsys::internals::mesh::NoGrammars,
    )
    .unwrap();
    let counts = scene.instance_counts();
    assert_eq!(counts.get("MCa"), Some(&3), "{counts:?}");
    assert_eq!(counts.get("MP"), Some(&1), "{counts:?}");
    // One MCa component, its three instances numbered 0, 1, 2.
    let mca = scene
        .components
        .iter()
        .position(|c| c.name == "MCa")
        .unwrap();
    let mut numbers: Vec<u32> = scene
        .instances
        .iter()
        .filter(|i| i.component == mca)
        .map(|i| i.number)
        .collect();
    numbers.sort();
    assert_eq!(numbers, [0, 1, 2]);
}

#[test]
fn queries_stand_where_the_homomorphism_draws_them() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    // `A` is drawn as F(3): the `?DG` after it stands 3 units up, 4 from
    // the guide's bottom edge (it would be 1 at the seed itself).
    w(
        "h.lsys",
        "derivation length: 1\naxiom: A ?DG(0, 0, 0, 0, 0)\nhomomorphism\nA --> F(3)\n",
    );
    w(
        "scene.toml",
        "steps = 1\n[[guide]]\nname = \"g\"\ngrammar = \"h.lsys\"\n\
         points = [[0, 0], [10, 0], [10, 10], [0, 10]]\n\
         [[seeds]]\nguide = \"g\"\nposition = [5, 1]\nheading = 90\n",
    );
    let l = guided::load_file(&dir.path().join("scene.toml"), &Default::default(), &[]).unwrap();
    let o = run(&l);
    // β 180: the closest point is straight behind the heading.
    assert_eq!(o.seeds[0].string, "A ?DG(1,4,180,1,0)");
}

/// A seed's grammar may place a grammar component (`~TS`: the standard
/// library's side Toukung, a whole build of its own), as a grammar built
/// alone may: the scene has its instances and the Toukung's parts.
#[test]
fn a_seed_places_a_grammar_component() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    w("g.lsys", "axiom: F(1) ~TS(1)\n");
    w(
        "scene.toml",
        "steps = 1\n\
         [[guide]]\nname = \"a\"\ngrammar = \"g.lsys\"\npoints = [[0, 0], [4, 0], [4, 4], [0, 4]]\n\
         [[seeds]]\nguide = \"a\"\nposition = [2, 1]\nheading = 90\n",
    );
    let job = lsys::driver::GuidedJob {
        path: dir.path().join("scene.toml"),
        options: lsys::Grammar::options().define("TS.NTL", 2),
        guides: false,
        output: lsys::driver::Output::Bytes {
            format: lsys::driver::Format::Glb,
            picture: Default::default(),
        },
    };
    let done = lsys::driver::run_guided(&job).unwrap_or_else(|f| panic!("{}", f.diagnostics()));
    let bytes = done.bytes.unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).unwrap();
    let names: Vec<String> = glb
        .nodes()
        .filter_map(|n| n.name().map(str::to_string))
        .collect();
    assert!(
        names.iter().any(|n| n.starts_with("TS#")),
        "no placement of TS: {names:?}"
    );
    assert!(
        done.triangles > 100,
        "the Toukung was meshed: {}",
        done.triangles
    );
}

/// A seed's drawn segments (clipped), as point pairs.
fn segments(s: &guided::SeedRun) -> Vec<(glam::DVec2, glam::DVec2, f32)> {
    s.drawing
        .chains
        .iter()
        .flat_map(|c| {
            c.points.windows(2).map(|w| {
                (
                    glam::DVec2::new(w[0].pos.x as f64, w[0].pos.y as f64),
                    glam::DVec2::new(w[1].pos.x as f64, w[1].pos.y as f64),
                    w[0].radius,
                )
            })
        })
        .collect()
}

/// The centre a polygon is clipped by (its vertex centroid, in the plane).
fn centroid(p: &lsys::internals::turtle::drawing::Polygon) -> glam::DVec2 {
    let c = p.points.iter().copied().sum::<glam::Vec3>() / p.points.len() as f32;
    glam::DVec2::new(c.x as f64, c.y as f64)
}

/// Every drawn segment's middle and every polygon's centroid is inside
/// the seed's guide (on the boundary counts).
fn assert_clipped_to_guides(l: &Loaded, o: &Outcome) {
    for s in &o.seeds {
        let guide = &l.spec.guides[s.guide];
        for (a, b, _) in segments(s) {
            let m = (a + b) * 0.5;
            assert!(
                guided::geometry::inside(m, &guide.points),
                "{}: {m:?}",
                guide.name
            );
        }
        for p in &s.drawing.polygons {
            let c = centroid(p);
            assert!(
                guided::geometry::inside(c, &guide.points),
                "{}: {c:?}",
                guide.name
            );
        }
    }
}

/// The id of the link a seed came through (None: an explicit seed).
fn link_in(l: &Loaded, s: &guided::SeedRun) -> Option<i64> {
    match s.origin {
        Origin::Message { link, .. } => Some(l.spec.links[link].id),
        Origin::Explicit(_) => None,
    }
}

/// The dinosaur's leaf seeds have strings of megabytes: they are
/// summarised by the number of leaves they draw; the stems' strings are
/// in full.
fn dinosaur_summary(l: &Loaded, o: &Outcome) -> String {
    o.strings(l)
        .lines()
        .zip(&o.seeds)
        .map(|(line, s)| match line.split_once(": ") {
            Some((head, _)) if !s.drawing.polygons.is_empty() => {
                format!("{head}: {} leaves\n", s.drawing.polygons.len())
            }
            _ => format!("{line}\n"),
        })
        .collect()
}

#[test]
fn dinosaur_example() {
    let l = load("dinosaur.toml");
    let o = run(&l);
    insta::assert_snapshot!(dinosaur_summary(&l, &o));
}

#[test]
fn the_dinosaur_grows_from_its_body_through_the_links() {
    let l = load("dinosaur.toml");
    let o = run(&l);
    // Seven explicit seeds in the body (the leaves, six stems), one seed
    // per link in every other guide: body -> neck -> head, body -> tail
    // -> tail tip, body -> each leg.
    assert_eq!((o.seeds.len(), o.messages.len()), (15, 8));
    let seed_of = |name: &str| {
        let g = l.spec.guides.iter().position(|g| g.name == name).unwrap();
        let mut it = o.seeds.iter().filter(|s| s.guide == g);
        let s = it.next().expect(name);
        assert!(it.next().is_none(), "{name} has one seed");
        s
    };
    for (guide, link) in [
        ("neck", 11),
        ("head", 12),
        ("tail", 21),
        ("tail_tip", 22),
        ("leg_back_far", 31),
        ("leg_back_near", 32),
        ("leg_front_far", 33),
        ("leg_front_near", 34),
    ] {
        assert_eq!(link_in(&l, seed_of(guide)), Some(link), "{guide}");
    }
    assert!(seed_of("head").birth > seed_of("neck").birth);
    assert!(seed_of("tail_tip").birth > seed_of("tail").birth);
    assert_clipped_to_guides(&l, &o);
    // Leaves (polygons) in the body, the head and the tail tip only; one
    // stem, unbroken, in the neck, the tail and each leg.
    let mut leaves = 0;
    for s in &o.seeds {
        let name = l.spec.guides[s.guide].name.as_str();
        if l.grammar_names[s.grammar].ends_with("dino_leaves.lsys") {
            assert!(["body", "head", "tail_tip"].contains(&name), "{name}");
            assert!(s.drawing.chains.is_empty(), "{name}");
            leaves += s.drawing.polygons.len();
        } else {
            assert!(s.drawing.polygons.is_empty(), "{name}");
            assert_eq!(s.drawing.chains.len(), 1, "{name}");
        }
    }
    assert!(leaves > 5000, "{leaves}");
    let body = &o.seeds[0].drawing.polygons;
    // Random colours (the four entries 16-19) and rotations (the leaves'
    // axes point into all eight octants).
    let colours: std::collections::BTreeSet<u32> = body.iter().map(|p| p.colour).collect();
    assert_eq!(colours, [16, 17, 18, 19].into());
    let octants: std::collections::BTreeSet<i32> = body
        .iter()
        .map(|p| {
            let axis = p.points[2] - p.points[0];
            (axis.y.atan2(axis.x).to_degrees() / 45.0).floor() as i32
        })
        .collect();
    assert_eq!(octants.len(), 8, "{octants:?}");
    // A stem follows its guide: every point but the last (the one that
    // touches the far edge) is inside, and it is as thick as the guide is
    // wide: the tail's tube narrows toward the tip. The legs reach the
    // ground (y = 0) within a segment (0.15).
    for s in o.seeds.iter().filter(|s| !s.drawing.chains.is_empty()) {
        let guide = &l.spec.guides[s.guide];
        let pts = &s.drawing.chains[0].points;
        for p in &pts[..pts.len() - 1] {
            let q = glam::DVec2::new(p.pos.x as f64, p.pos.y as f64);
            assert!(
                guided::geometry::inside(q, &guide.points),
                "{}: {q:?}",
                guide.name
            );
        }
        if guide.name.starts_with("leg") {
            let foot = pts[pts.len() - 1].pos.y;
            assert!(foot.abs() <= 0.15 + 1e-4, "{}: {foot}", guide.name);
        }
    }
    let tail = &seed_of("tail").drawing.chains[0].points;
    let (root, tip) = (tail[0].radius, tail[tail.len() - 1].radius);
    assert!(root > 1.5 * tip, "{root} {tip}");
}

/// The modules of `s` before its first branch.
fn before_first_branch(s: &str) -> Vec<&str> {
    s.split(' ').take_while(|m| *m != "[").collect()
}

/// For each polygon `{` of a string, the number of segments `F` on the
/// path from the root to it.
fn polygon_depths(s: &str) -> Vec<usize> {
    let mut stack = vec![0];
    let mut out = Vec::new();
    for m in s.split(' ') {
        match m {
            "[" => stack.push(*stack.last().unwrap()),
            "]" => {
                stack.pop();
            }
            "{" => out.push(*stack.last().unwrap()),
            _ if m.starts_with("F(") => *stack.last_mut().unwrap() += 1,
            _ => {}
        }
    }
    out
}

#[test]
fn tree_single_example() {
    let l = load("tree_single.toml");
    let o = run(&l);
    // The string is 300 kB of leaves: its main axis and its counts.
    let s = &o.seeds[0];
    insta::assert_snapshot!(format!(
        "{} segments, {} leaves\nmain axis: {}\n",
        segments(s).len(),
        s.drawing.polygons.len(),
        main_axis(&s.string).join(" ")
    ));
}

#[test]
fn the_single_tree_branches_above_its_trunk_and_fills_its_guide() {
    let l = load("tree_single.toml");
    let o = run(&l);
    assert_eq!((o.seeds.len(), o.messages.len()), (1, 0));
    let tree = &o.seeds[0];
    // The trunk: T0 = 9 segments before the first branch.
    let trunk = before_first_branch(&tree.string);
    assert_eq!(
        trunk.iter().filter(|m| m.starts_with("F(")).count(),
        9,
        "{trunk:?}"
    );
    // Leaves from LEAF = 15 segments from the root on, and only there
    // (some hang out of the guide and are clipped).
    let depths = polygon_depths(&tree.string);
    assert!(depths.len() >= tree.drawing.polygons.len());
    assert!(depths.len() > 1000, "{}", depths.len());
    assert!(depths.iter().all(|&d| d >= 15), "{:?}", depths.iter().min());
    // The clusters bend down: a leaf's tip (its third vertex) below its
    // base (its first), for more than 85% of the leaves.
    let hanging = tree
        .drawing
        .polygons
        .iter()
        .filter(|p| p.points[2].y < p.points[0].y)
        .count();
    let drawn = tree.drawing.polygons.len();
    assert!(hanging * 20 > drawn * 17, "{hanging} of {drawn}");
    assert_clipped_to_guides(&l, &o);
    // The crown fills its guide: branches reach within two segments of
    // its widest points (x = ±5.2) and of its top (y = 12.3).
    let reach = |o: &Outcome| {
        let segs = segments(&o.seeds[0]);
        let xs = segs.iter().flat_map(|(a, b, _)| [a.x, b.x]);
        let (lo, hi) = xs.fold((0f64, 0f64), |(lo, hi), x| (lo.min(x), hi.max(x)));
        let top = segs
            .iter()
            .map(|(a, b, _)| a.y.max(b.y))
            .fold(0f64, f64::max);
        (lo, hi, top)
    };
    let (lo, hi, top) = reach(&o);
    assert!(
        lo < -5.2 + 0.56 && hi > 5.2 - 0.56 && top > 12.3 - 0.56,
        "{lo} {hi} {top}"
    );
    // A wider crown (x 1.3 about the trunk's axis): the same grammar
    // grows wider.
    let mut wide = load("tree_single.toml");
    for p in wide.spec.guides[0].points.iter_mut().filter(|p| p.y > 2.6) {
        p.x *= 1.3;
    }
    let wide_o = run(&wide);
    assert_clipped_to_guides(&wide, &wide_o);
    let (wlo, whi, _) = reach(&wide_o);
    assert!(wlo < lo - 1.0 && whi > hi + 1.0, "{wlo} {whi} {lo} {hi}");
}

#[test]
fn palm_edited_example() {
    let l = load("palm_edited.toml");
    let o = run(&l);
    insta::assert_snapshot!(o.strings(&l));
}

/// The bounding box of a drawing's points: (min x, min y, max x, max y).
fn bounds(o: &Outcome) -> (f64, f64, f64, f64) {
    o.seeds
        .iter()
        .flat_map(segments)
        .flat_map(|(a, b, _)| [a, b])
        .fold(
            (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
            |(x0, y0, x1, y1), p| (x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y)),
        )
}

#[test]
fn the_edited_palm_is_the_palm_grown_in_edited_guides() {
    let (pl, el) = (load("palm.toml"), load("palm_edited.toml"));
    let (po, eo) = (run(&pl), run(&el));
    // The same three grammar files, unchanged: only the guides differ.
    let names = |l: &Loaded| {
        let mut n = l.grammar_names.clone();
        n.sort();
        n
    };
    assert_eq!(names(&pl), names(&el));
    assert_eq!(names(&el).len(), 3);
    // The upper left leaf guide and its link (13) are gone: its frond
    // finds no link and is erased (an empty branch); three leaves grow.
    assert_eq!((eo.seeds.len(), eo.messages.len()), (5, 4));
    assert!(el.spec.guides.iter().all(|g| g.name != "leaf_upper_left"));
    let crown = eo.seeds.iter().find(|s| s.guide == 1).unwrap();
    assert_eq!(crown.string.matches("[ ]").count(), 1, "{}", crown.string);
    assert_eq!(seeds_in(&eo, &el, "leaf_top"), 0);
    assert_clipped_to_guides(&el, &eo);
    // The trunk meets its edited top edge square, in its middle
    // (-2.664, 10.8), not palm.toml's (2.1, 8).
    let (a, top, _) = *segments(&eo.seeds[0]).last().unwrap();
    assert!(
        top.distance(glam::DVec2::new(-2.664, 10.8)) < 0.35,
        "{top:?}"
    );
    let heading = (top - a).y.atan2((top - a).x).to_degrees();
    assert!((heading - 105.0).abs() < 0.5, "{heading}");
    // The drawing follows the guides: taller, and reaching further left
    // (the longer left leaf).
    let (p, e) = (bounds(&po), bounds(&eo));
    assert!(e.3 > p.3 + 2.0, "top {} {}", e.3, p.3);
    assert!(e.0 < p.0 - 3.0, "left {} {}", e.0, p.0);
    assert_ne!(eo.drawing(), po.drawing());
}

#[test]
fn the_bridge_reshaped_by_the_springs_keeps_its_hangers_spacing() {
    use glam::DVec2;
    use lsys::internals::guided::springs::Springs;
    let l = load("bridge.toml");
    let before = run(&l);
    let spec = &l.spec;
    // Held as in the studio: the cable guides' feet on the deck, the
    // towers and the deck; the middle of the cable dragged up by 1.2.
    let s = Springs::new(spec);
    let mut held = Vec::new();
    let mut middle = None;
    for (g, guide) in spec.guides.iter().enumerate() {
        for (k, p) in guide.points.iter().enumerate() {
            let cable = guide.name.starts_with("cable");
            if !cable || (p.y - 0.6).abs() < 1e-9 {
                held.push(s.particle(g, k).unwrap());
            }
            if guide.name == "cable_4" && p.x == 0.0 && p.y > 1.0 {
                middle = s.particle(g, k);
            }
        }
    }
    let (x, _) = s.relax(middle.unwrap(), DVec2::new(0.0, 2.4), &held);
    let moved = s.guide_points(&x);
    // examples/guided/bridge_moved.toml is that drag, saved by the studio
    // (to four decimals), seeds carried along.
    let m = load("bridge_moved.toml");
    for (g, guide) in m.spec.guides.iter().enumerate() {
        for (p, q) in guide.points.iter().zip(&moved[g]) {
            assert!(p.distance(*q) < 1e-4, "{}: {p} vs {q}", guide.name);
        }
    }
    for (a, b) in spec.seeds.iter().zip(&m.spec.seeds) {
        let (q, heading) = s.carry(a.guide, &x, a.position, a.heading);
        assert!(q.distance(b.position) < 1e-4 && (heading - b.heading).abs() < 1e-3);
    }
    // The neighbours followed: their shared corners rose, and no held
    // vertex moved.
    let cable = |name: &str| spec.guides.iter().position(|g| g.name == name).unwrap();
    let c3 = cable("cable_3");
    assert!(moved[c3][2].y > spec.guides[c3].points[2].y + 0.02);
    for &h in &held {
        assert_eq!(x[h], s.particles[h]);
    }
    // The same grammars: every cable guide draws as many pieces (a hanger
    // and a piece of cable every 0.25 along the deck), and the middle's
    // cable reaches higher.
    let after = run(&m);
    let count = |o: &Outcome, g: usize| guided::run::guide_elements(o, g).len();
    let top = |o: &Outcome, g: usize| {
        guided::run::guide_elements(o, g)
            .iter()
            .map(|e| e.a.y.max(e.b.y))
            .fold(f64::MIN, f64::max)
    };
    for (g, guide) in spec.guides.iter().enumerate() {
        assert_eq!(count(&before, g), count(&after, g), "{}", guide.name);
    }
    let c4 = cable("cable_4");
    assert_eq!(count(&before, c4), 16, "8 hangers and 8 pieces of cable");
    // The cable reaches the dragged corner (0.02 under it, as drawn).
    let (b, a) = (top(&before, c4), top(&after, c4));
    assert!((a - (2.4 - 0.02)).abs() < 1e-3 && a > b + 0.8, "{b} -> {a}");
}
