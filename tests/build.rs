//! `lsys build` and `lsys render` end to end, through the binary: formats
//! by extension, `--stats`, atomic outputs, and the geometry of real
//! examples checked against what the derivation says it must be.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{lsys, stderr};

fn path_str(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Component placements per symbol, counted in the derived string itself.
fn placements_in_string(args: &[&str]) -> BTreeMap<String, u64> {
    let mut full = vec!["derive"];
    full.extend_from_slice(args);
    let o = lsys(&full);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut counts = BTreeMap::new();
    for m in String::from_utf8_lossy(&o.stdout).split_whitespace() {
        if let Some(rest) = m.strip_prefix('~') {
            let name = rest.split('(').next().unwrap().to_string();
            // A zero scale switches a component off: it is not placed.
            if !m.contains("(0)") {
                *counts.entry(name).or_insert(0) += 1;
            }
        }
    }
    counts
}

#[test]
fn stats_count_every_placement_of_the_derived_string() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.glb");
    let o = lsys(&[
        "build",
        "std:toukung_middle",
        "-D",
        "NTL=7",
        "-o",
        path_str(&out),
        "--stats",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let instances: BTreeMap<String, u64> =
        serde_json::from_value(stats["instances"].clone()).unwrap();
    let expected = placements_in_string(&["std:toukung_middle", "-D", "NTL=7"]);
    assert_eq!(instances, expected);
    assert!(instances.len() == 5, "{instances:?}");
    let bytes = std::fs::metadata(&out).unwrap().len();
    assert_eq!(stats["output"]["bytes"].as_u64(), Some(bytes));
    for stage in ["parse", "derive", "interpret", "mesh", "write"] {
        assert!(
            stats["timings_ms"][stage].as_f64().unwrap() >= 0.0,
            "{stage}"
        );
    }
    let [lo, hi] = [0, 1].map(|i| stats["bounds"][i].as_array().unwrap().clone());
    for k in 0..3 {
        assert!(lo[k].as_f64().unwrap() <= hi[k].as_f64().unwrap());
    }
    // Instancing: the file holds each component once, far less than the
    // triangles drawn would need as copies (12 bytes a vertex at least).
    let drawn = stats["vertices"].as_u64().unwrap();
    assert!(
        bytes < drawn * 12,
        "{bytes} bytes for {drawn} drawn vertices"
    );
}

#[test]
fn every_format_is_written_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let bush = "examples/abop/fig1_24d.lsys";
    for ext in ["glb", "gltf", "obj", "png"] {
        let out = dir.path().join(format!("bush.{ext}"));
        let o = lsys(&["build", bush, "-o", path_str(&out)]);
        assert!(o.status.success(), "{ext}: {}", stderr(&o));
        let bytes = std::fs::read(&out).unwrap();
        match ext {
            "glb" | "gltf" => {
                let doc = gltf::Gltf::from_slice(&bytes).unwrap();
                let names: Vec<_> = doc
                    .nodes()
                    .filter_map(|n| n.name().map(String::from))
                    .collect();
                assert_eq!(names, ["strokes"]);
            }
            "obj" => {
                let mtl = dir.path().join("bush.mtl");
                assert!(mtl.is_file(), "no .mtl beside the .obj");
                let (models, materials) = tobj::load_obj(&out, &tobj::GPU_LOAD_OPTIONS).unwrap();
                assert!(!models.is_empty());
                assert!(!materials.unwrap().is_empty());
            }
            _ => {
                let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
                let reader = decoder.read_info().unwrap();
                assert_eq!((reader.info().width, reader.info().height), (1024, 768));
            }
        }
    }
    // Nothing but the outputs: no temporary files left behind.
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["bush.glb", "bush.gltf", "bush.mtl", "bush.obj", "bush.png"]
    );
}

#[test]
fn a_failed_build_keeps_the_old_output() {
    let dir = tempfile::tempdir().unwrap();
    let grammar = dir.path().join("g.lsys");
    std::fs::write(&grammar, "Axiom: F ~Missing(2)\n").unwrap();
    let out = dir.path().join("model.glb");
    std::fs::write(&out, b"previous model").unwrap();
    let o = lsys(&["build", path_str(&grammar), "-o", path_str(&out)]);
    assert_eq!(o.status.code(), Some(65), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("component `~Missing` not found"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"previous model");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn unknown_extension_and_render_to_a_model_are_usage_errors() {
    let o = lsys(&["build", "examples/abop/fig1_24d.lsys", "-o", "bush.stl"]);
    assert_eq!(o.status.code(), Some(64));
    assert!(
        stderr(&o).contains(".glb, .gltf, .obj or .png"),
        "{}",
        stderr(&o)
    );
    let o = lsys(&["render", "examples/abop/fig1_24d.lsys", "-o", "bush.glb"]);
    assert_eq!(o.status.code(), Some(64));
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bush.glb")
        .exists());
}

#[test]
fn components_are_found_in_components_dirs() {
    let dir = tempfile::tempdir().unwrap();
    let grammar = dir.path().join("g.lsys");
    std::fs::write(&grammar, "Axiom: ~Tri(2) f(2) ~Tri\n").unwrap();
    let extra: PathBuf = dir.path().join("parts");
    std::fs::create_dir(&extra).unwrap();
    std::fs::write(
        extra.join("Tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let out = dir.path().join("m.glb");
    // Without the directory: an error that lists where it looked.
    let o = lsys(&["build", path_str(&grammar), "-o", path_str(&out)]);
    assert_eq!(o.status.code(), Some(65));
    assert!(stderr(&o).contains("components/Tri.obj"), "{}", stderr(&o));
    let o = lsys(&[
        "build",
        path_str(&grammar),
        "--components",
        path_str(&extra),
        "-o",
        path_str(&out),
        "--stats",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(stats["instances"]["Tri"], 2);
    assert_eq!(stats["triangles"], 8);
    // The unit-high second tetrahedron stands on the first, 2 high.
    assert_eq!(stats["bounds"][1][1], 3.0);
}

#[test]
fn grammar_components_build_once_and_refuse_cycles() {
    let dir = tempfile::tempdir().unwrap();
    let parts = dir.path().join("parts");
    std::fs::create_dir(&parts).unwrap();
    std::fs::write(parts.join("Loop.lsys"), "Axiom: F ~Loop\n").unwrap();
    let grammar = dir.path().join("g.lsys");
    std::fs::write(&grammar, "Axiom: ~Loop\n").unwrap();
    let out = dir.path().join("m.glb");
    let o = lsys(&[
        "build",
        path_str(&grammar),
        "--components",
        path_str(&parts),
        "-o",
        path_str(&out),
    ]);
    assert_eq!(o.status.code(), Some(65));
    assert!(stderr(&o).contains("~Loop -> ~Loop"), "{}", stderr(&o));
    assert!(!out.exists());
    // The standard library's Toukungs are components too: two middle
    // Toukungs are two nodes placing the same block and arm meshes.
    std::fs::write(&grammar, "Axiom: ~TM(1) f(2) ~TM(2) ~TS\n").unwrap();
    let o = lsys(&["build", path_str(&grammar), "-o", path_str(&out), "--stats"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(stats["instances"]["TM"], 2);
    assert_eq!(stats["instances"]["TS"], 1);
    let doc = gltf::Gltf::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let inner = |placement: &str| -> Vec<(String, usize)> {
        let mut v: Vec<(String, usize)> = doc
            .nodes()
            .filter_map(|n| {
                let rest = n.name()?.strip_prefix(placement)?.to_string();
                Some((rest, n.mesh()?.index()))
            })
            .collect();
        v.sort();
        v
    };
    let (first, second) = (inner("TM#0/"), inner("TM#1/"));
    assert!(first.len() > 10, "{first:?}");
    assert_eq!(first, second);
    // The side Toukung's caps are the middle ones' mesh: stored once.
    let cap = |p: &str| {
        inner(p)
            .into_iter()
            .find(|(n, _)| n.starts_with("MCa#"))
            .unwrap()
            .1
    };
    assert_eq!(cap("TM#0/"), cap("TS#0/"));
}

/// Table 3's polygon counts, per figure.
const TABLE_3_POLYGONS: &[(&str, f64)] = &[
    ("fig17-1", 2.23e5),
    ("fig17-2", 1.15e6),
    ("fig17-3", 8.94e5),
    ("fig17-4", 6.88e5),
    ("fig18-1", 1.07e6),
    ("fig18-2", 2.11e6),
    ("fig18-3", 1.84e6),
    ("fig18-4", 6.86e5),
    ("fig18-5", 8.71e5),
    ("fig18-6", 2.48e6),
    ("fig19-1", 7.74e5),
    ("fig19-2", 9.15e5),
    ("fig19-3", 1.23e6),
    ("fig19-4", 2.51e6),
    ("fig19-5", 1.78e6),
];

/// The 15 Pailous of the paper's Table 3 (`examples/pailou/*.toml`, named
/// by figure and style) build through `lsys pailou GRAPH` with the pillars
/// and roofs their names promise, without a structural warning, with 0.5–2×
/// the paper's polygons at the default detail, and pass the glTF validator
/// when it is installed.
#[test]
fn table_3_pailous_build_with_their_pillars_and_roofs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let graphs = common::files("examples/pailou", "toml");
    assert_eq!(graphs.len(), 15, "Table 3 has 15 Pailous");
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    let mut known = String::new();
    for graph in &graphs {
        let stem = graph.file_stem().unwrap().to_string_lossy().into_owned();
        let style = stem.split('_').nth(1).unwrap();
        let out = dir.path().join(format!("{stem}.glb"));
        let o = lsys(&["pailou", path_str(graph), "-o", path_str(&out), "--stats"]);
        assert!(o.status.success(), "{stem}: {}", stderr(&o));
        // No structural warning (tests/pailou.rs has the details) but
        // issue 37's roof defects, listed below.
        let err = stderr(&o);
        let (roofs, other): (Vec<&str>, Vec<&str>) =
            err.lines().partition(|l| common::is_known_roof_defect(l));
        assert!(
            !other.iter().any(|l| l.contains("warning")),
            "{stem}: {err}"
        );
        for l in roofs {
            known += &format!(
                "{stem}: {}\n",
                l.trim_start_matches("lsys: warning: structure: ")
            );
        }
        let stats: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let n: Vec<u64> = style.split('-').map(|x| x.parse().unwrap()).collect();
        let count = |c: &str| stats["instances"][c].as_u64().unwrap_or(0);
        // Ground pillars stand on bases; upper entrances' pillars do not.
        assert_eq!(count("MPB"), n[0], "{stem} pillar bases");
        assert_eq!(count("RE") + count("RC"), n[2], "{stem} roofs");
        let fig = stem.split('_').next().unwrap();
        let paper = TABLE_3_POLYGONS.iter().find(|(f, _)| *f == fig).unwrap().1;
        let ratio = stats["triangles"].as_f64().unwrap() / paper;
        assert!(
            (0.5..=2.0).contains(&ratio),
            "{stem}: {} triangles, {ratio:.2}× Table 3's {paper} polygons",
            stats["triangles"]
        );
        if stem.starts_with("fig17") {
            assert_eq!(count("RE"), 0, "{stem}: the pillar type has no eaves roofs");
        }
        files.push(out);
    }
    insta::assert_snapshot!("issue_37_roof_defects_table_3", known);
    let npm = root.join("target/npm");
    if npm.join("node_modules/gltf-validator").is_dir() {
        let o = Command::new("node")
            .arg(root.join("scripts/gltf-validate.mjs"))
            .args(&files)
            .env("GLTF_VALIDATOR_DIR", &npm)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    }
}

#[test]
fn illegal_attachments_and_styles_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let graph = dir.path().join("g.toml");
    std::fs::write(
        &graph,
        "centre = \"L11\"\n[components]\nL11 = \"lintel\"\nP1R = \"pillar\"\nP1L = \"pillar\"\nIB = \"inscribed_board\"\n[attach]\nL11 = [\"P1R\", \"P1L\"]\nIB = [\"P1R\"]\n",
    )
    .unwrap();
    let o = lsys(&["pailou", path_str(&graph), "-o", "x.glb"]);
    assert_eq!(o.status.code(), Some(65));
    let e = stderr(&o);
    assert!(
        e.contains("`IB` (inscribed_board) cannot attach to `P1R` (pillar)"),
        "{e}"
    );
    assert!(e.contains("g.toml:9:"), "the line of the attachment: {e}");
    let o = lsys(&["pailou", "--style", "4-3-5", "-o", "x.glb"]);
    assert_eq!(o.status.code(), Some(64));
    assert!(stderr(&o).contains("2NE+1 (7)"), "{}", stderr(&o));
}

/// Input deep enough to exhaust a stack is a diagnostic (exit 65), never
/// an abort: parentheses nested 100 000 deep, and 100 000 unary minuses.
#[test]
fn deep_input_is_refused_with_a_diagnostic() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in [
        (
            "parens",
            format!(
                "Axiom: A({}1{})\n",
                "(".repeat(100_000),
                ")".repeat(100_000)
            ),
        ),
        ("minus", format!("Axiom: A({}1)\n", "-".repeat(100_000))),
    ] {
        let path = dir.path().join(format!("{name}.lsys"));
        std::fs::write(&path, text).unwrap();
        let o = lsys(&["check", path_str(&path)]);
        assert_eq!(o.status.code(), Some(65), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains("lsys::parse::too_deep"), "{name}");
        assert!(!stderr(&o).contains("no axiom"), "{name}: no echo errors");
    }
}

/// An #include cannot leave the top-level grammar's folder, not even
/// through a symbolic link; inside it (subfolders too) it works.
#[cfg(unix)]
#[test]
fn includes_stay_inside_the_grammar_folder() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("project");
    std::fs::create_dir_all(inner.join("parts")).unwrap();
    std::fs::write(dir.path().join("secret.lsys"), "#define s 1\n").unwrap();
    std::fs::write(inner.join("parts/ok.lsys"), "#define k 2\n").unwrap();
    std::os::unix::fs::symlink(dir.path().join("secret.lsys"), inner.join("link.lsys")).unwrap();
    let grammar = inner.join("g.lsys");
    std::fs::write(&grammar, "#include \"parts/ok.lsys\"\nAxiom: A(k)\n").unwrap();
    let o = lsys(&["check", path_str(&grammar)]);
    assert!(o.status.success(), "{}", stderr(&o));
    for target in ["../secret.lsys", "link.lsys"] {
        std::fs::write(&grammar, format!("#include \"{target}\"\nAxiom: A(s)\n")).unwrap();
        let o = lsys(&["check", path_str(&grammar)]);
        assert_eq!(o.status.code(), Some(65), "{target}");
        assert!(
            stderr(&o).contains("lsys::load::include_outside"),
            "{target}: {}",
            stderr(&o)
        );
    }
}

/// A model that draws nothing is still written, with a warning that says
/// why and counts the modules in words that agree with the count.
#[test]
fn a_model_that_draws_nothing_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let grammar = dir.path().join("g.lsys");
    let out = dir.path().join("g.glb");
    for (text, why) in [
        (
            "derivation length: 1\naxiom: A\nA --> *\n",
            "(its module string is empty)",
        ),
        ("axiom: A\n", "(its string of 1 module has no drawing"),
        ("axiom: A B(1)\n", "(its string of 2 modules has no drawing"),
    ] {
        std::fs::write(&grammar, text).unwrap();
        let o = lsys(&["build", path_str(&grammar), "-o", path_str(&out)]);
        assert!(o.status.success(), "{text}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("draws nothing {why}")),
            "{text}: {}",
            stderr(&o)
        );
        assert!(out.exists(), "{text}");
    }
}

/// A grammar that asks guides, built on its own, draws nothing: the
/// warning names the queries and the scene beside it that hosts it.
#[test]
fn a_guided_grammar_built_alone_points_to_its_scene() {
    let dir = tempfile::tempdir().unwrap();
    let grammar = dir.path().join("leaf.lsys");
    std::fs::write(
        &grammar,
        "derivation length: 3\naxiom: A\nA --> ?DL(0, 0, 0, 0, 0, 1)\n?DL(f, d, b, id, t, s) -->\n",
    )
    .unwrap();
    let out = dir.path().join("leaf.glb");
    let build = || lsys(&["build", path_str(&grammar), "-o", path_str(&out)]);
    let o = build();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "help: it asks guides (`?DL`) and was built without any: build it from a guided scene"
        ),
        "{}",
        stderr(&o)
    );
    std::fs::write(dir.path().join("other.toml"), "# names no grammar\n").unwrap();
    let scene = dir.path().join("garden.toml");
    std::fs::write(&scene, "[[seed]]\ngrammar = \"leaf.lsys\"\n").unwrap();
    let o = build();
    let expected = format!(
        "build the scene that hosts it, `lsys build {} -o garden.glb`",
        scene.display()
    );
    assert!(stderr(&o).contains(&expected), "{}", stderr(&o));
}

/// `~X(s)` draws the unit box scaled alike on every axis: an elongated
/// model becomes a cube, which is warned at the placement; three scales in
/// the model's proportions, or a model that is nearly a cube, are not.
#[test]
fn a_uniform_scale_that_squashes_a_component_is_warned() {
    let dir = tempfile::tempdir().unwrap();
    let run = |axiom: &str| {
        std::fs::write(
            dir.path().join("g.lsys"),
            format!("#include TM, MCa\nAxiom: {axiom}\n"),
        )
        .unwrap();
        let o = common::lsys_in(dir.path(), &["build", "g.lsys", "-o", "g.glb"]);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let squashed = run("~TM(1.4) f ~TM(2)");
    insta::assert_snapshot!("uniform_toukung", squashed);
    assert_eq!(
        squashed.matches("distorted_component").count(),
        1,
        "once per component"
    );
    assert!(!run("~TM(0.29, 0.45, 1.4)").contains("distorted_component"));
    assert!(!run("~MCa(2)").contains("distorted_component"));
}

/// ABOP's Fig. 2.6 with its pixel widths (`!(10)`) and steps of 1 is a
/// blob of tubes: warned, with what to scale; with ABOP's own step
/// lengths (100) the same widths are in scale and nothing is said.
#[test]
fn line_widths_that_dwarf_the_model_are_warned() {
    let dir = tempfile::tempdir().unwrap();
    let run = |axiom: &str| {
        let grammar = format!(
            "#define r1 0.9\n#define r2 0.6\n#define d 137.5\n#define wr 0.707\n\
             derivation length: 10\nAxiom: {axiom}\n\
             A(l,w) --> !(w)F(l)[&(45)B(l*r2,w*wr)]/(d)A(l*r1,w*wr)\n\
             B(l,w) --> !(w)F(l)[-(45)$C(l*r2,w*wr)]C(l*r1,w*wr)\n\
             C(l,w) --> !(w)F(l)[+(45)$B(l*r2,w*wr)]B(l*r1,w*wr)\n"
        );
        std::fs::write(dir.path().join("tree.lsys"), grammar).unwrap();
        let o = common::lsys_in(dir.path(), &["build", "tree.lsys", "-o", "tree.glb"]);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    insta::assert_snapshot!("pixel_widths", run("A(1,10)"));
    assert_eq!(run("A(100,30)"), "");
}
