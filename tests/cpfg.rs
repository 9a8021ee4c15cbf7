//! cpfg model objects: a `.l` file with its view file and function files
//! (our own small model under tests/fixtures/cpfg/), derived through the
//! CLI; and the C preprocessor's effect on what the grammar stages see.

mod common;

use common::{cpfg_fixture as fixture, lsys_in as lsys};

#[test]
fn functions_contexts_and_cpfg_names() {
    let out = lsys(&fixture("funcs"), &["derive", "--every", "plant.l"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // `@Q` is kept, drawn as nothing, with one warning naming it.
    assert!(
        stderr.contains("lsys::resolve::ignored_command"),
        "{stderr}"
    );
    insta::assert_snapshot!(String::from_utf8_lossy(&out.stdout));
}

#[test]
fn the_preprocessor_runs_before_the_grammar() {
    let out = lsys(&fixture("macros"), &["derive", "--every", "tree.l"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    insta::assert_snapshot!(String::from_utf8_lossy(&out.stdout));
    // -D reaches the preprocessor: the #ifdef branch changes.
    let out = lsys(&fixture("macros"), &["derive", "-D", "BUSHY=1", "tree.l"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    insta::assert_snapshot!("bushy", String::from_utf8_lossy(&out.stdout));
}

#[test]
fn errors_after_expansion_point_at_the_original_line() {
    let out = lsys(&fixture("macros"), &["check", "broken.l"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    // The bad call is on line 9 of broken.l, inside an expanded macro; the
    // preprocessor's own error is on line 5 of the included file.
    assert!(stderr.contains("broken.l:9:"), "{stderr}");
    assert!(stderr.contains("bad.h:5:1"), "{stderr}");
    assert!(
        stderr.contains("lsys::preprocess::else_without_if"),
        "{stderr}"
    );
    insta::assert_snapshot!(stderr);
}

#[test]
fn query_modules_context_through_brackets_and_cuts() {
    let out = lsys(&fixture("queries"), &["derive", "--every", "plant.l"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    // The position is filled after each step: y grows by one F per step.
    assert!(
        text.lines().nth(2).is_some_and(|l| l.ends_with("?P(0,2)")),
        "{text}"
    );
    insta::assert_snapshot!(text);
}

/// Every file a cpfg model read is in its source map, so `lsys watch`
/// sees them: the model, its view file and the function files the view
/// file names (read before resolve starts).
#[test]
fn the_files_a_model_read_include_its_view_and_function_files() {
    use lsys::internals::load::{Input, Options};
    let root = fixture("funcs").join("plant.l");
    let comp =
        match lsys::internals::pipeline::compile(&Input::Path(root.clone()), &Options::default()) {
            Ok(c) => c,
            Err(_) => panic!("the funcs model compiles"),
        };
    let read = comp.program.sources.disk_paths();
    let dir = fixture("funcs");
    for f in ["plant.l", "plant.v", "ramp.func", "more.fset"] {
        assert!(read.contains(&dir.join(f)), "{f} not in {read:?}");
    }
}

/// An error in a function file points at its line in that file; it is
/// reported where the model calls `func`.
#[test]
fn a_broken_function_file_points_at_its_line() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(
        dir.join("plant.l"),
        "Lsystem: 1\nderivation length: 1\nAxiom: A(0)\nA(t) --> F(func(1, t))\nendlsystem\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("plant.v"),
        "angle factor: 30\nfunction: bad.func\n",
    )
    .unwrap();
    std::fs::write(dir.join("bad.func"), "fver 1 1\nname: bad\nsamples: many\n").unwrap();
    let out = lsys(dir, &["check", "plant.l"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("lsys::load::function_file"), "{stderr}");
    assert!(stderr.contains("bad.func:3:"), "{stderr}");
    // A function file the view file names but that is missing: the view
    // file's line.
    std::fs::write(
        dir.join("plant.v"),
        "angle factor: 30\nfunction: gone.func\n",
    )
    .unwrap();
    let out = lsys(dir, &["check", "plant.l"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("lsys::load::view_file"), "{stderr}");
    assert!(stderr.contains("plant.v:2:"), "{stderr}");
}

/// `~p(2)` draws the Bézier patch of the surface file the view file names
/// (size 1 in the view file, `SIZE: 2` in the file, 2 × 2 units): a 2 × 3
/// grid of quads, both faces, with its contact point at the turtle and
/// its height along the turtle's heading. `~q`, whose file is missing,
/// draws nothing in `build` and is a warning in `check`.
#[test]
fn a_view_file_surface_is_drawn_as_cpfg_places_it() {
    let g = lsys::Grammar::from_path(fixture("surface").join("petal.l")).expect("compiles");
    let scene = g.build(1).expect("builds");
    assert_eq!(scene.instance_count(), 1);
    assert_eq!(scene.triangle_count(), 2 * 3 * 2 * 2);
    let (lo, hi) = scene.mesh().bounds().expect("something is drawn");
    let mut extent = (hi - lo).to_array();
    extent.sort_by(f32::total_cmp);
    for (e, want) in extent.iter().zip([0.0, 2.0, 2.0]) {
        assert!((e - want).abs() < 1e-4, "extent {extent:?}");
    }
    // The contact point is the turtle's position, the origin: the patch
    // starts there along the heading (+y) and spreads ±1 across it.
    assert!(lo.y.abs() < 1e-4 && (hi.y - 2.0).abs() < 1e-4, "{lo} {hi}");
    let out = lsys(&fixture("surface"), &["check", "petal.l"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("lsys::mesh::cpfg_surface") && stderr.contains("missing.s"),
        "{stderr}"
    );
    assert!(!stderr.contains("`~p`"), "{stderr}");
}

/// A cpfg model's colour map (`-m`) and material file (`-M`), named in
/// its `specifications`, colour its indices instead of lsys's palette;
/// the view file's `initial color:` is the turtle's first index. Our own
/// files, written here: map index 2 is red, material 3 is blue.
#[test]
fn colour_maps_and_materials_colour_a_cpfg_model() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let write = |name: &str, bytes: &[u8]| std::fs::write(dir.join(name), bytes).unwrap();
    write(
        "plant.l",
        b"Lsystem: 1\nderivation length: 0\nAxiom: F ; F\nendlsystem\n",
    );
    write("plant.v", b"initial color: 2\n");
    write(
        "specifications",
        b"generate:\n\tcpfg -m plant.map -M plant.mat plant.l plant.v\n",
    );
    let mut map = vec![0u8; 768];
    map[6..9].copy_from_slice(&[255, 0, 0]);
    write("plant.map", &map);
    let mut mat = vec![0u8; 15 * 4];
    for (i, m) in mat.chunks_exact_mut(15).enumerate() {
        m[0] = i as u8;
        m[5..8].copy_from_slice(&[204, 204, 204]);
    }
    mat[45 + 5..45 + 8].copy_from_slice(&[0, 0, 255]);
    write("plant.mat", &mat);
    let g = lsys::Grammar::from_path(dir.join("plant.l")).expect("compiles");
    let scene = g.build(0).expect("builds");
    let mesh = scene.mesh();
    let colours: Vec<[f32; 3]> = mesh
        .strokes
        .iter()
        .map(|s| mesh.materials[s.material].rgb)
        .collect();
    // Materials win over the map for indices 0..=3; index 2 is the
    // material's grey, 3 its blue.
    assert_eq!(colours, vec![[0.8, 0.8, 0.8], [0.0, 0.0, 1.0]]);
    // Without the material file, index 2 is the map's red.
    std::fs::remove_file(dir.join("plant.mat")).unwrap();
    let out = lsys(dir, &["check", "plant.l"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("lsys::load::colour_file"), "{stderr}");
    let g = lsys::Grammar::from_path(dir.join("plant.l")).expect("compiles");
    let scene = g.build(0).expect("builds");
    let mesh = scene.mesh();
    let first = mesh.materials[mesh.strokes[0].material].rgb;
    assert_eq!(first, [1.0, 0.0, 0.0]);
}

/// Writes `files` into a fresh folder and derives `model` there with
/// `lsys derive --cpfg-format` (and `extra`); the string without
/// whitespace, as cpfg's `-str` file reads once its line breaks go.
fn derive_cpfg(files: &[(&str, &str)], model: &str, extra: &[&str]) -> String {
    let tmp = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(tmp.path().join(name), text).unwrap();
    }
    let mut args = vec!["derive", "--cpfg-format"];
    args.extend(extra);
    args.push(model);
    let out = lsys(tmp.path(), &args);
    assert!(out.status.success(), "{}", common::stderr(&out));
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .collect()
}

/// cpfg's `&` moves the heading toward its up vector U (interpret.c:
/// `change_dir(temp, heading, up, ...)`, as `+` moves it toward L), and
/// cpfg's U starts at -z: pitching down from the start heads toward -z.
/// lsys pitched away from U (the paper's rule), toward +z, so every `?P`
/// after a pitch had its z negated (`?P(0,0.866025,0.5)` after `&(30)`),
/// while turns and rolls agreed. Expected: cpfg built from the vlab
/// sources (github.com/AlgorithmicBotany/vlab, commit 9bf820d), `cpfg -g
/// -str`.
#[test]
fn pitch_turns_the_heading_toward_cpfgs_up_vector() {
    let model = "Lsystem: 1\nderivation length: 1\nAxiom: A\n\
        A --> [&(30)F(1)?P(0,0,0)][^(30)F(1)?P(0,0,0)][/(90)+(30)F(1)?P(0,0,0)]\
        [/(40)&(20)+(10)^(70)\\(15)-(33)F(1)?P(0,0,0)?H(0,0,0)?L(0,0,0)?U(0,0,0)]\n\
        endlsystem\n";
    let got = derive_cpfg(&[("p.l", model), ("p.v", "angle factor: 12\n")], "p.l", &[]);
    assert_eq!(
        got,
        "[&(30)F(1)?P(0,0.866025,-0.5)][^(30)F(1)?P(0,0.866025,0.5)][/(90)+(30)F(1)\
         ?P(-3.06162e-17,0.866025,-0.5)][/(40)&(20)+(10)^(70)\\(15)-(33)F(1)\
         ?P(0.00506312,0.726929,0.686694)?H(0.00506312,0.726929,0.686694)\
         ?L(-0.997521,0.0518715,-0.0475558)?U(0.0701895,0.684751,-0.725389)]"
    );
}

/// cpfg sets a string's query modules whenever it interprets the string:
/// before each step (the environment pass) and, after the last step, for
/// the view volume, which `cpfg -g` computes only when the view file has
/// no `box:`. With a box, the `?P` the last step wrote keeps the
/// grammar's parameters (the topiary model's new apices print
/// `?P(0,0,0)`); lsys filled it in either way. Expected: cpfg built from
/// the vlab sources (commit 9bf820d), `cpfg -g -str`.
#[test]
fn a_view_box_leaves_the_last_steps_queries_unset() {
    let model = "Lsystem: 1\nderivation length: 2\nAxiom: A\n\
        A --> F(1)?P(0,0,0)B\nB --> +(90)F(2)?P(0,0,0)\n\
        ?P(x,y,z) --> ?P(x,y,z)C(x+y)\nendlsystem\n";
    let boxed = "angle factor: 4\nbox: x: -4,4 y: -2,7 z:-4,4\n";
    let got = derive_cpfg(&[("b.l", model), ("b.v", boxed)], "b.l", &[]);
    assert_eq!(got, "F(1)?P(0,1,0)C(1)+(90)F(2)?P(0,0,0)");
    let got = derive_cpfg(&[("b.l", model), ("b.v", "angle factor: 4\n")], "b.l", &[]);
    assert_eq!(got, "F(1)?P(0,1,0)C(1)+(90)F(2)?P(-2,1,0)");
}

/// cpfg's scanner reads `@Gc(4)` as `@`, `G`, `c(4)`, so the
/// homomorphism's `@G --> *` (two-trees uses it to drop generalized
/// cylinders) eats the `@G` of `@Gs`, `@Gc(4)`, `@Ge` and of an unknown
/// `@GA`, leaving the rest of each. lsys kept those commands whole (and
/// warned that the production never fires). Expected: cpfg built from the
/// vlab sources (commit 9bf820d), `cpfg -g -homo -str`.
#[test]
fn a_production_for_an_at_command_also_eats_the_start_of_longer_ones() {
    let model = "Lsystem: 1\nderivation length: 1\nAxiom: A\n\
        A --> @GsF(1)@Gc(4)F(1)@Gc(2,3)@Ge@GA\nhomomorphism\n@G --> *\nendlsystem\n";
    let files = [("g.l", model), ("g.v", "angle factor: 12\n")];
    let got = derive_cpfg(&files, "g.l", &["--homomorphism"]);
    assert_eq!(got, "sF(1)c(4)F(1)c(2,3)eA");
    let got = derive_cpfg(&files, "g.l", &[]);
    assert_eq!(got, "@GsF(1)@Gc(4)F(1)@Gc(2,3)@Ge@GA");
}
