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
/// corridor one column more than that. The roof, W + 1.8 wide, holds
/// floor((W + 1.8) / 0.45) rows of tiles (cylinders too).
#[test]
fn hall_bays_stay_symmetric_at_every_width() {
    for (w, n, tiles) in [("16", 1, 39), ("24", 2, 57), ("30", 3, 70)] {
        // bays: (16 - 7.8) / 6 = 1.37; (24 - 7.8) / 6 = 2.7; (30 - 7.8) / 6 = 3.7
        // tiles: 17.8 / 0.45 = 39.6; 25.8 / 0.45 = 57.3; 31.8 / 0.45 = 70.7
        let b = build("examples/shapes/hall.lsys", &[("W", w)]);
        let bays = 2 * n + 3;
        assert_eq!(primitives(&b, "cylinder"), bays + 1 + tiles, "W={w}");
        assert_eq!(primitives(&b, "prism"), 1, "roof at W={w}");
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
