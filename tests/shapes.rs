//! Shape grammars (docs/shapes.md): the examples in examples/shapes/ at
//! several widths, their part counts against counts worked out by hand
//! from the split rules, and the constraint reports as snapshots.

mod common;

use std::path::Path;

use lsys::internals::build::Built;
use lsys::internals::load::{Input, Options};

/// Builds an example with `-D` overrides.
fn build(file: &str, defines: &[(&str, &str)]) -> Built {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let opts = Options {
        defines: defines
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_string()))
            .collect(),
        ..Options::default()
    };
    let comp = lsys::internals::pipeline::compile(&Input::Path(path), &opts)
        .unwrap_or_else(|d| panic!("{file}: {}", d.render_plain()));
    lsys::internals::build::build(&comp, &Default::default())
        .unwrap_or_else(|e| panic!("{file}: {}", lsys::internals::diag::render_plain(&e)))
}

fn primitives(b: &Built, kind: &str) -> usize {
    b.drawing.primitives.get(kind).copied().unwrap_or(0)
}

fn instances(b: &Built, name: &str) -> usize {
    b.scene.instance_counts().get(name).copied().unwrap_or(0)
}

/// Seed 004's veranda: the railing between the side walls is W - 2*0.4
/// wide and holds floor(that / 0.5) pillars of two cylinders each; the
/// platform, the two side walls and the railing's top are the 4 blocks.
#[test]
fn veranda_pillars_follow_the_width() {
    for (w, pillars) in [("4", 6), ("6", 10), ("9", 16)] {
        // (4 - 0.8) / 0.5 = 6.4; (6 - 0.8) / 0.5 = 10.4; (9 - 0.8) / 0.5 = 16.4
        let b = build("examples/shapes/veranda.lsys", &[("W", w)]);
        assert_eq!(primitives(&b, "cylinder"), 2 * pillars, "W={w}");
        assert_eq!(primitives(&b, "block"), 4, "W={w}");
    }
}

/// Three verandas in one scene (4, 6, 9 wide: 6, 10, 16 pillars) and a
/// fourth, 9 wide, whose own spacing 0.8 overrides the rule: 8.2 / 0.8
/// = 10.25, so 10 pillars.
#[test]
fn a_per_instance_value_beats_the_configure_rule() {
    let b = build("examples/shapes/verandas.lsys", &[]);
    assert_eq!(primitives(&b, "cylinder"), 2 * (6 + 10 + 16 + 10));
    // The user's -D changes the rule, not the instance's own value:
    // PILLAR = 1 gives 3 + 5 + 8 pillars, the fourth keeps its 10.
    let b = build("examples/shapes/verandas.lsys", &[("PILLAR", "1")]);
    assert_eq!(primitives(&b, "cylinder"), 2 * (3 + 5 + 8 + 10));
}

/// Seed 003's hall: between the two end bays (1.8) and the centre bay
/// (4.2), each side holds n = floor((W - 3.6 - 4.2) / 6) bays of about 3,
/// so the facade has 2n + 1 bays besides the ends, 2n + 3 in all, and the
/// corridor one column more than that (its only cylinders). One roof.
#[test]
fn hall_bays_stay_symmetric_at_every_width() {
    for (w, n) in [("16", 1), ("24", 2), ("30", 3)] {
        // bays: (16 - 7.8) / 6 = 1.37; (24 - 7.8) / 6 = 2.7; (30 - 7.8) / 6 = 3.7
        let b = build("examples/shapes/hall.lsys", &[("W", w)]);
        let bays = 2 * n + 3;
        assert_eq!(primitives(&b, "cylinder"), bays + 1, "W={w}");
        assert_eq!(primitives(&b, "roof"), 1, "roof at W={w}");
    }
}

/// The extent of the polygons of one colour: (min, max) corners.
fn extent(b: &Built, colour: u32) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in b.drawing.polygons.iter().filter(|p| p.colour == colour) {
        for v in &p.points {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
    }
    (lo, hi)
}

/// Seed 003, Sec 7.1: the roof's height and the purlins' rises (jujia
/// 0.5, 0.65, 0.75, 0.9, eaves 0.9 at the first) give one step's run,
/// bujia = (ROOF - 0.9 * 0.5) / 2.8, and the hall is (9 - 1) bujia deep,
/// so its roof 8 bujia + 2 * 0.9 from eave to eave and W + 1.8 wide. A hip
/// roof's ends come down to the eaves and its corners turn up; a gable's
/// ends stay at the ridge.
#[test]
fn the_hall_is_as_deep_as_its_purlins_make_it() {
    for (roof, hip) in [("3.4", "1"), ("2.6", "1"), ("3.4", "0")] {
        let b = build("examples/shapes/hall.lsys", &[("ROOF", roof), ("HIP", hip)]);
        let r: f32 = roof.parse().unwrap();
        let bujia = (r - 0.45) / 2.8;
        // The shell (colour 26) fills the scope's depth and width; the
        // rows of tiles on it (27) reach the scope's top, ROOF over the
        // shell's lowest edge.
        let (lo, hi) = extent(&b, 26);
        let depth = hi[2] - lo[2];
        assert!(
            (depth - (8.0 * bujia + 1.8)).abs() < 1e-3,
            "ROOF={roof}: {depth}"
        );
        assert!(
            (hi[0] - lo[0] - 25.8).abs() < 1e-3,
            "width {}",
            hi[0] - lo[0]
        );
        let (tlo, thi) = extent(&b, 27);
        assert!(tlo[1] > lo[1] && thi[1] > hi[1]);
        assert!(
            (thi[1] - lo[1] - r).abs() < 1e-3,
            "height {}",
            thi[1] - lo[1]
        );
        // The highest point of the shell within 0.1 of the left end, in
        // the middle half of the depth (away from the corners), and at the
        // front left corner.
        let top_near = |near: &dyn Fn(&glam::Vec3) -> bool| {
            b.drawing
                .polygons
                .iter()
                .filter(|p| p.colour == 26)
                .flat_map(|p| p.points.iter())
                .filter(|v| near(v))
                .map(|v| v[1])
                .fold(f32::NEG_INFINITY, f32::max)
                - lo[1]
        };
        let mid = (lo[2] + hi[2]) / 2.0;
        let rises = top_near(&|v| v[0] < lo[0] + 0.1 && (v[2] - mid).abs() < depth / 4.0);
        let corner = top_near(&|v| v[0] < lo[0] + 0.1 && v[2] < lo[2] + 0.1);
        if hip == "1" {
            assert!(rises < 0.2 * r, "hip roof's end rises {rises}");
            // The corner turns up: half the eaves' run (0.9) over the
            // eaves, with the shell's thickness.
            assert!(
                corner > 0.4 && corner < 0.2 * r + 0.45,
                "corner rises {corner}"
            );
        } else {
            assert!(rises > 0.85 * r, "gable's end rises {rises}");
        }
    }
}

/// The hall's other examples share its parts (hall_parts.lsys): two
/// storeys, each with its corridor of bays + 1 columns (7 bays at W = 24),
/// under a skirt roof and the main roof; a courtyard of four halls of
/// their own widths, each with its own bays: 28 holds 3 bays a side
/// ((28 - 7.8) / 6 = 3.4), 9 in all; 15 holds 1 (5 in all); 11 none (3).
#[test]
fn the_two_storey_hall_and_the_courtyard_reuse_the_parts() {
    let b = build("examples/shapes/hall_two_storey.lsys", &[]);
    assert_eq!(primitives(&b, "roof"), 2);
    assert_eq!(primitives(&b, "cylinder"), 2 * 8);
    let b = build("examples/shapes/courtyard.lsys", &[]);
    assert_eq!(primitives(&b, "roof"), 4);
    assert_eq!(primitives(&b, "cylinder"), 10 + 2 * 6 + 4);
}

/// The off-centre hall (seed 003, Fig 20): an end bay (1.8), DOORAT bays
/// of 3, the door's bay (4.2), the rest in bays, an end bay; the stairs
/// stand under the door, from 1.8 + 3 * DOORAT to 4.2 further. The rest
/// holds floor((24 - 3.6 - 3 * DOORAT - 4.2) / 3) bays: 4, then 3, so
/// 8 bays and 9 columns either way.
#[test]
fn the_off_centre_door_has_its_stairs_under_it() {
    for (at, from) in [("1", 4.8f32), ("2", 7.8)] {
        let b = build("examples/shapes/hall_off_centre.lsys", &[("DOORAT", at)]);
        assert_eq!(primitives(&b, "cylinder"), 9, "DOORAT={at}");
        // The stairs: the stone (16) in front of the platform, which ends
        // 0.6 in front of the hall (the roof's eaves, 26, 0.9 in front).
        let (_, hi) = extent(&b, 26);
        let platform_front = hi[2] - 0.9 + 0.6;
        let xs: Vec<f32> = b
            .drawing
            .polygons
            .iter()
            .filter(|p| p.colour == 16)
            .flat_map(|p| p.points.iter())
            .filter(|v| v[2] > platform_front + 0.01)
            .map(|v| v[0])
            .collect();
        let (x0, x1) = xs
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        assert!(
            (x0 - from).abs() < 1e-3 && (x1 - from - 4.2).abs() < 1e-3,
            "DOORAT={at}: {x0}..{x1}"
        );
    }
}

/// The wall holds floor(W / 2.6) windows, each cutting one opening.
#[test]
fn wall_holes_follow_the_width() {
    for (w, windows) in [("6", 2), ("10", 3), ("14", 5)] {
        let b = build("examples/shapes/wall.lsys", &[("W", w)]);
        let cuts = b
            .drawing
            .constraints
            .iter()
            .filter(|c| c.contains("cut an opening"))
            .count();
        assert_eq!(cuts, windows, "W={w}: {:#?}", b.drawing.constraints);
        // Per window: the frame (4 blocks) and the sill; plus the wall.
        assert_eq!(primitives(&b, "block"), 1 + 5 * windows, "W={w}");
    }
}

/// The Pailou board: floor((W - 1.2) / 1.1) panels (MFB) and
/// floor(W / 0.7) bracket caps (MCa); floor((W + 1.6) / 0.32) tile rows.
#[test]
fn pailou_board_repeats_follow_the_width() {
    for (w, panels, caps, tiles) in [("6", 4, 8, 23), ("8", 6, 11, 30), ("10", 8, 14, 36)] {
        let b = build("examples/shapes/pailou_board.lsys", &[("W", w)]);
        assert_eq!(instances(&b, "MFB"), panels, "W={w}");
        assert_eq!(instances(&b, "MCa"), caps, "W={w}");
        // Two pillars and the tile rows.
        assert_eq!(primitives(&b, "cylinder"), 2 + tiles, "W={w}");
    }
}

#[test]
fn constraint_reports() {
    let wall = build("examples/shapes/wall.lsys", &[]);
    insta::assert_snapshot!("wall_holes", wall.drawing.constraints.join("\n"));
    let snap = build("examples/shapes/snap.lsys", &[]);
    insta::assert_snapshot!("snap", snap.drawing.constraints.join("\n"));
    let off = build("examples/shapes/snap.lsys", &[("SNAP", "0")]);
    assert!(off.drawing.constraints.is_empty());
}

/// `--stats` says which attributes came from the file's configure rules
/// and which from the user, and recomputes rules from the user's values.
#[test]
fn stats_report_default_and_user_attributes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.glb");
    let o = common::lsys(&[
        "build",
        "examples/shapes/veranda.lsys",
        "-D",
        "W=9",
        "-D",
        "H=4",
        "-o",
        out.to_str().unwrap(),
        "--stats",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let mut lines = Vec::new();
    for (name, a) in json["attributes"].as_object().unwrap() {
        lines.push(format!(
            "{name} = {} from {} {}",
            a["value"], a["from"], a["rule"]
        ));
    }
    lines.push(format!("primitives {}", json["primitives"]));
    insta::assert_snapshot!(lines.join("\n"));
}

/// A hole whose own z is a block's x (a window painted on a side wall:
/// the page turns its scope to face the left view) cuts through the
/// block's x when it goes all the way through it; one that does not go
/// through along that axis is reported and left alone, not cut along
/// the block's z (which would slice the block end to end).
#[test]
fn a_hole_cuts_along_its_own_depth() {
    let side = "derivation length: 1\nAxiom: [@M(0,0,0) @Scope(0.3,3,6) @Block] [@M(0.3,1,1) /(-90) @Scope(2,1,0.3) @Hole]\n";
    let scene = lsys::Grammar::from_str("side.lsys", side)
        .unwrap()
        .build(1)
        .unwrap();
    assert_eq!(
        scene.constraints(),
        ["hole (module 10, at 0.3, 1, 1) intersects block (module 4): cut an opening 1 x 2 at (1, 1) of its face, through its depth 0.3"]
    );
    // The same hole in a block 6 long in x: it does not go through.
    let long = side.replace("@Scope(0.3,3,6) @Block", "@Scope(6,3,6) @Block");
    let scene = lsys::Grammar::from_str("long.lsys", &long)
        .unwrap()
        .build(1)
        .unwrap();
    assert_eq!(scene.constraints().len(), 1);
    assert!(
        scene.constraints()[0].contains("across another of its axes"),
        "{:?}",
        scene.constraints()
    );
}

/// The painting page's examples (seed 004, docs/studio.md): every window
/// and door, painted in four views, cuts the wall it is on and only that,
/// through the wall's thickness.
#[test]
fn the_painted_examples_cut_each_hole_through_one_wall() {
    for (file, holes) in [
        ("examples/painting/veranda.lsys", 3),
        ("examples/painting/villa.lsys", 11),
    ] {
        let b = build(file, &[]);
        let cuts: Vec<&String> = b.drawing.constraints.iter().collect();
        assert_eq!(cuts.len(), holes, "{file}: {cuts:#?}");
        assert!(
            cuts.iter().all(|c| c.ends_with("through its depth 0.3")),
            "{file}: {cuts:#?}"
        );
    }
}
