//! cpfg language features beyond one L-system per string: `ring
//! lsystem` (context wraps around the string's ends), sub-L-systems
//! (several `Lsystem:` blocks, `?(n,s) ... $`) and contour curves. Our
//! own small models under tests/fixtures/cpfg/, derived through the CLI.

mod common;

use common::{cpfg_fixture as fixture, lsys_in as lsys};

fn derive(dir: &str, args: &[&str]) -> String {
    let out = lsys(&fixture(dir), args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// In a ring L-system the signal that reaches one end of the string comes
/// back at the other, moving right (left context) or left (right
/// context); without `ring lsystem` it leaves the string.
#[test]
fn a_ring_lsystem_wraps_context_around_the_string() {
    let right = derive("ring", &["derive", "--every", "ring.l"]);
    let lines: Vec<&str> = right.lines().collect();
    assert_eq!(lines[1], "S(1) C(0) C(0) C(0) C(0) C(1)");
    assert_eq!(lines[7], "S(2) C(1) C(1) C(1) C(1) C(2)");
    let left = derive("ring", &["derive", "--every", "back.l"]);
    assert_eq!(left.lines().nth(1), Some("C(1) C(0) C(0) C(0) C(0) S(1)"));
    let flat = derive("ring", &["derive", "flat.l"]);
    assert!(!flat.contains('S'), "{flat}");
    insta::assert_snapshot!(format!("{right}---\n{left}---\n{flat}"));
}

/// The homomorphism sees the variables the `Start:` block sets (Ring's
/// angle between spokes).
#[test]
fn the_homomorphism_sees_start_block_variables() {
    let h = derive("ring", &["derive", "--homomorphism", "-n", "0", "ring.l"]);
    assert!(h.contains("+(60)"), "{h}");
}

/// The extent of a built model along x, y, z.
fn extent(dir: &str, file: &str, steps: u32) -> [f32; 3] {
    let g = lsys::Grammar::from_path(fixture(dir).join(file)).expect("compiles");
    let scene = g.build(steps).expect("builds");
    let (lo, hi) = scene.mesh().bounds().expect("something is drawn");
    (hi - lo).to_array()
}

/// Sub-L-systems: the modules between `?(2, s)` and `$` are rewritten by
/// L-system 2 (its own `A` and `F` productions; its axiom and length are
/// for running it alone), and drawn at scale s.
#[test]
fn sub_lsystems_rewrite_and_scale_their_own_modules() {
    let steps = derive("sub", &["derive", "--every", "-n", "4", "stalk.l"]);
    let last = steps.lines().last().unwrap_or_default();
    assert_eq!(
        last, "#(0.2) F(8) F(4) ?(2,0.5) F(1) [ + A(1) ] $ F(4)",
        "{steps}"
    );
    insta::assert_snapshot!(steps);
    // The head alone, from its own axiom.
    let head = derive("sub", &["derive", "-n", "2", "head.l"]);
    assert_eq!(head.trim(), "F(1) [ + A(1) ]");
    // Drawn: 8 + 4 + 0.5 (the head's F(1) at half scale) + 4 up the
    // stalk, and its branch 0.5 × F(1) up at 45° would not reach past it.
    let e = extent("sub", "stalk.l", 4);
    assert!((e[1] - 16.5).abs() < 1e-3, "{e:?}");
}

/// `curveGAL(1)` is the length of the view file's first curve;
/// `curveX/Y(1, s)` its point at arc length s (clamped to 0..1): the
/// ends are the first and last control points (multiplicity 3).
#[test]
fn contour_curves_give_points_by_arc_length() {
    let s = derive("curve", &["derive", "arc.l"]);
    assert!(s.starts_with("Q(0,0,"), "{s}");
    assert!(s.contains("Q(2,2,3.2"), "{s}");
    insta::assert_snapshot!(s);
}

/// Every call of `curveX(1, s)` reads one copy of the curve: a grammar
/// naming it in three productions compiles to one function per axis.
#[test]
fn curve_calls_share_one_function_per_curve_and_axis() {
    let tmp = tempfile::tempdir().unwrap();
    for f in ["arc.v", "arc.con"] {
        std::fs::copy(fixture("curve").join(f), tmp.path().join(f)).unwrap();
    }
    let path = tmp.path().join("arc.l");
    std::fs::write(
        &path,
        "Lsystem: 1\nderivation length: 1\nAxiom: P(0)\nP(s) --> Q(curveX(1, s), curveY(1, s))\nQ(x, y) --> R(curveX(1, x)) R(curveY(1, y))\nR(x) --> R(curveX(1, x))\nendlsystem\n",
    )
    .unwrap();
    let c = lsys::internals::pipeline::compile(
        &lsys::internals::load::Input::Path(path),
        &lsys::internals::load::Options::default(),
    )
    .unwrap_or_else(|_| panic!("compiles"));
    let names: Vec<&str> = c
        .compiled
        .functions
        .iter()
        .map(|f| f.name.as_str())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

/// A missing curve is an error at the call that names it.
#[test]
fn a_curve_the_view_file_does_not_name_is_an_error() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(
        dir.join("m.l"),
        "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> B(curveX(2, 0.5))\nendlsystem\n",
    )
    .unwrap();
    std::fs::write(dir.join("m.v"), "angle factor: 4\n").unwrap();
    let out = lsys(dir, &["check", "m.l"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no `curve:` lines"), "{stderr}");
    assert!(stderr.contains("m.l:4:"), "{stderr}");
}

/// cpfg's `#(w)` and `!(w)` set the width (here 2, then 0.5); `#` and
/// `!` without a parameter add and take away the view file's increment
/// (2.25, then 1.75): the widest tube is 2.25 across.
#[test]
fn line_widths_are_set_as_cpfg_sets_them() {
    let e = extent("lines", "widths.l", 0);
    assert!((e[0] - 2.25).abs() < 1e-3, "{e:?}");
    // Without `initial line width:` lines are one pixel of a window 600
    // pixels across the model: 200 / 600 wide.
    let e = extent("lines", "pixels.l", 0);
    assert!((e[0] - 200.0 / 600.0).abs() < 1e-3, "{e:?}");
}

/// A generalized cylinder goes on into both branches from the branch
/// point, as cpfg's spline stack carries it: the model spans both sides.
#[test]
fn generalized_cylinders_are_carried_into_branches() {
    let g = lsys::Grammar::from_path(fixture("gencyl").join("fork.l")).expect("compiles");
    let scene = g.build(0).expect("builds");
    let (lo, hi) = scene.mesh().bounds().expect("something is drawn");
    // Each branch ends 2 · sin 45° ≈ 1.41 to its side, 2 + 1.41 up.
    assert!(lo.x < -1.3 && hi.x > 1.3, "{lo} {hi}");
    assert!((hi.y - (2.0 + 2f32.sqrt())).abs() < 0.15, "{lo} {hi}");
}

/// `Consider:` lists brackets like any symbol: listed, a branch's `]`
/// ends its modules' right context (Borchert-Slade's pipe model, whose
/// trunk was cut once context ran out of the leaves' branches); not
/// listed, cpfg reads context straight through it.
#[test]
fn brackets_in_a_consider_list_end_the_context() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let model = |consider: &str| {
        format!(
            "Lsystem: 1\nderivation length: 1\nConsider: {consider}\nAxiom: [BA]A\nA > A --> X\nendlsystem\n"
        )
    };
    std::fs::write(dir.join("listed.l"), model("A[]")).unwrap();
    std::fs::write(dir.join("through.l"), model("A")).unwrap();
    let run = |f: &str| String::from_utf8_lossy(&lsys(dir, &["derive", f]).stdout).into_owned();
    assert_eq!(run("listed.l").trim(), "[ B A ] A");
    assert_eq!(run("through.l").trim(), "[ B X ] A");
}

/// cpfg's `{` starts a polygon without recording the turtle's position
/// (only `.`, `F` and `f` do): `{[-f(1)].F(2)}` is the triangle of the
/// three points, one unit wide and two high, not a four-point outline
/// that visits the start twice.
#[test]
fn a_cpfg_polygon_starts_without_a_vertex() {
    let g = lsys::Grammar::from_path(fixture("polygon").join("leaf.l")).expect("compiles");
    let scene = g.build(0).expect("builds");
    insta::assert_snapshot!(format!(
        "triangles {}\nbounds {:?}",
        scene.triangle_count(),
        scene.mesh().bounds()
    ));
}

/// cpfg's scanner reads `@o(1)` as `@` then `o(1)`: the production for
/// `o` also grows the `@o` sphere, and `ignore: ;!@o` lists four single
/// modules, so a plain `o` is passed over in context too.
#[test]
fn an_at_command_is_its_letter_to_productions_and_context() {
    let s = derive("commands", &["derive", "--every", "grow.l"]);
    let lines: Vec<&str> = s.lines().collect();
    assert_eq!(lines[1], "S ; ! @o(2) o(2) X", "{s}");
    assert_eq!(lines[3], "S ; ! @o(4) o(4) X", "{s}");
}

/// `@#(1)` sweeps the view file's `contour: 1 flat.con` along the
/// generalized cylinder: a flat curve 4 units across at half the line
/// width per unit is a ribbon 2 wide and no thicker; `@#` alone is round
/// again (1 across both ways).
#[test]
fn a_contour_is_the_cross_section_of_a_generalized_cylinder() {
    let blade = extent("contour", "blade.l", 0);
    let round = extent("contour", "round.l", 0);
    assert!((blade[1] - 2.0).abs() < 1e-3, "{blade:?}");
    let (wide, thin) = (blade[0].max(blade[2]), blade[0].min(blade[2]));
    assert!((wide - 2.0).abs() < 0.01 && thin < 1e-3, "{blade:?}");
    assert!(
        (round[0] - 1.0).abs() < 0.05 && (round[2] - 1.0).abs() < 0.05,
        "{round:?}"
    );
}
