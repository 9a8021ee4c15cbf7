//! `lsys infer` on Pailou fronts: elevations drawn by `lsys render --style
//! lines` from `lsys pailou` styles of both types, read back by synthesis
//! (src/driver/infer_pailou.rs): the style and type must be the
//! generator's, each entrance's measured width ratio its `side[i]`, its
//! passage's proportion αEW, its Toukung levels NTL, the
//! tree must hold one bay per ground entrance and only the vocabulary's
//! labels, and the written grammar must build.

mod common;

use std::path::Path;

use common::lsys_ok;
use serde_json::Value;

/// Runs lsys, which must succeed; what it said.
fn run(dir: &Path, args: &[&str]) -> String {
    String::from_utf8_lossy(&lsys_ok(dir, args).stderr).into_owned()
}

fn leaves<'a>(n: &'a Value, out: &mut Vec<&'a Value>) {
    let children = n["children"].as_array().unwrap();
    if children.is_empty() {
        out.push(n);
    }
    for c in children {
        leaves(c, out);
    }
}

#[test]
fn pailou_fronts_are_read_as_their_style() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // (style, type, side[1], αEW) drawn; the defaults are 0.8 and 10/12.
    for (style, kind, side, ew) in [
        ("2-1-2", "pillar", 0.8, 10.0 / 12.0),
        ("4-3-7", "ridge", 0.7, 0.78),
        ("4-3-10", "pillar", 0.8, 0.9),
    ] {
        let stem = format!("{style}-{kind}");
        let grammar = lsys_ok(
            d,
            &["pailou", "--style", style, "--type", kind, "--emit-lsys"],
        );
        std::fs::write(d.join(format!("{stem}.lsys")), &grammar.stdout).unwrap();
        let (lsys, png) = (format!("{stem}.lsys"), format!("{stem}.png"));
        let mut args = vec!["render", &lsys, "--view", "front", "--style", "lines"];
        args.extend(["--size", "1000x600", "-o", &png]);
        let defines = [format!("side[1]={side}"), format!("αEW={ew}")];
        for d in &defines {
            args.extend(["-D", d]);
        }
        run(d, &args);
        let said = run(d, &["infer", &png, "-o", "out.lsys", "--tree", "out.json"]);
        assert!(
            said.contains(&format!("style {style}, {kind} type")),
            "{stem}: {said}"
        );
        let tree: Value =
            serde_json::from_slice(&std::fs::read(d.join("out.json")).unwrap()).unwrap();
        let mut all = Vec::new();
        leaves(&tree["root"], &mut all);
        let ne: usize = style.split('-').nth(1).unwrap().parse().unwrap();
        let bays = all.iter().filter(|n| n["label"] == "bay").count();
        assert_eq!(bays, ne, "{stem}: one bay per ground entrance");
        let known = [
            "column", "bay", "lintel", "wall", "bracket", "roof", "ornament", "other",
        ];
        for n in &all {
            let label = n["label"].as_str().unwrap();
            assert!(known.contains(&label), "{stem}: {label}");
            let b: Vec<i64> = n["box"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_i64().unwrap())
                .collect();
            assert!(
                b[0] >= 0 && b[1] >= 0 && b[2] <= 1000 && b[3] <= 600 && b[0] < b[2],
                "{stem}: {b:?}"
            );
        }
        let columns = all.iter().filter(|n| n["label"] == "column").count();
        assert!(columns > ne, "{stem}: {columns} columns for {ne} entrances");
        assert!(all.iter().any(|n| n["label"] == "roof"), "{stem}: roofs");
        // The measured ratios, written into the grammar, within 0.02 of
        // the generator's: the entrance's width over its height, and the
        // side entrances' width over the central one's; drawn with
        // std:pailou's 5 Toukung levels, read as 5.
        let text = std::fs::read_to_string(d.join("out.lsys")).unwrap();
        let define = |prefix: &str| {
            text.lines()
                .find(|l| l.starts_with(prefix))
                .unwrap_or_else(|| panic!("{stem}: no {prefix}"))
                .to_string()
        };
        assert!(
            define("#define NTL").starts_with("#define NTL 5,"),
            "{stem}"
        );
        let line = define("#define αPW");
        let got: f64 = line
            .split("αEW ")
            .nth(1)
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((got - ew).abs() < 0.02, "{stem}: {line}");
        if ne > 1 {
            let want = side;
            let line = text
                .lines()
                .find(|l| l.starts_with("#define side[1..6]"))
                .unwrap();
            let first: f64 = line
                .split(['{', ','])
                .nth(1)
                .unwrap()
                .trim()
                .parse()
                .unwrap();
            assert!((first - want).abs() < 0.02, "{stem}: {line}");
        }
        run(d, &["build", "out.lsys", "-o", "out.glb"]);
        // The candidates are drawn on every core; the reading must not
        // depend on how many.
        let alone = std::process::Command::new(env!("CARGO_BIN_EXE_lsys"))
            .current_dir(d)
            .env("RAYON_NUM_THREADS", "1")
            .args(["infer", &png, "-o", "one.lsys", "--tree", "one.json"])
            .output()
            .unwrap();
        assert!(alone.status.success(), "{stem}: {alone:?}");
        for (a, b) in [("out.lsys", "one.lsys"), ("out.json", "one.json")] {
            let read = |f: &str| std::fs::read_to_string(d.join(f)).unwrap();
            let (many, one) = (read(a), read(b).replace("one.lsys", "out.lsys"));
            assert!(many == one, "{stem}: {a} differs on one thread");
        }
    }
}

/// A Pailou's front drawn by hand (examples/drawings/three-roof-gateway.svg)
/// standing on a ground line, which closes its passages: read as the
/// 4-3-3 ridge style it was drawn as, with its side entrances' ratio; the
/// same drawing without the ground line reads alike.
#[test]
fn a_hand_drawn_gateway_on_a_ground_line_is_read_as_its_style() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let svg = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/drawings/three-roof-gateway.svg"),
    )
    .unwrap();
    let ground = r#"<line x1="60" y1="540" x2="940" y2="540"/>"#;
    assert!(svg.contains(ground), "the drawing's ground line moved");
    std::fs::write(d.join("ground.svg"), &svg).unwrap();
    std::fs::write(d.join("air.svg"), svg.replace(ground, "")).unwrap();
    for name in ["ground", "air"] {
        let (svg, out) = (format!("{name}.svg"), format!("{name}.lsys"));
        let said = run(d, &["infer", &svg, "-o", &out, "--tree", "t.json"]);
        assert!(said.contains("style 4-3-3, ridge type"), "{name}: {said}");
        let tree: Value =
            serde_json::from_slice(&std::fs::read(d.join("t.json")).unwrap()).unwrap();
        let mut all = Vec::new();
        leaves(&tree["root"], &mut all);
        let bays = all.iter().filter(|n| n["label"] == "bay").count();
        assert_eq!(bays, 3, "{name}: one bay per entrance");
        let text = std::fs::read_to_string(d.join(&out)).unwrap();
        let side = text
            .lines()
            .find(|l| l.starts_with("#define side[1..6]"))
            .unwrap_or_default()
            .to_string();
        // Pillar centres 140, 330, 670, 860: 190 / 340.
        assert!(side.contains("{ 0.559,"), "{name}: {side}");
    }
    run(d, &["build", "ground.lsys", "-o", "g.glb"]);
}

/// The hall drawings of examples/drawings are not taken for Pailous.
#[test]
fn hall_drawings_stay_halls() {
    let dir = tempfile::tempdir().unwrap();
    let drawings = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/drawings");
    for name in [
        "three-bay-hall.svg",
        "gatehouse.svg",
        "seven-bay-palace.svg",
    ] {
        let path = drawings.join(name);
        let said = run(
            dir.path(),
            &["infer", path.to_str().unwrap(), "-o", "out.lsys"],
        );
        assert!(!said.contains("Pailou"), "{name}: {said}");
    }
}
