//! Environments of Open L-systems: the collision (honda81) and light
//! (chiba) programs answer exactly as their definitions say, and a model
//! of our own that runs with an environment file grows as the collision
//! rule implies (Pascal's triangle mod 2).

use std::process::Command;

use lsys::internals::environment::collision::{Collision, Settings as CollisionSettings};
use lsys::internals::environment::light::{Light, Settings as LightSettings};
use lsys::internals::environment::{EnvironmentalProgram, Query};

fn query(params: &[f64], pos: [f32; 3]) -> Query {
    Query {
        index: 0,
        params: params.to_vec(),
        position: Some(pos),
        heading: None,
        left: None,
        up: None,
        line_width: None,
        scale: None,
    }
}

fn collide(radius: f32, three_d: bool, queries: &[Query]) -> Vec<Option<f64>> {
    Collision::new(CollisionSettings { radius, three_d })
        .respond(queries)
        .into_iter()
        .map(|r| r[0])
        .collect()
}

#[test]
fn two_coincident_queries_of_equal_vigor_both_stop() {
    let q = [
        query(&[0.5], [1.0, 2.0, 3.0]),
        query(&[0.5], [1.0, 2.0, 3.0]),
    ];
    assert_eq!(collide(0.0, true, &q), [Some(0.0), Some(0.0)]);
}

#[test]
fn the_stronger_query_goes_on_and_the_weaker_stops() {
    let q = [query(&[0.9], [0.0; 3]), query(&[0.5], [0.0; 3])];
    assert_eq!(collide(0.1, true, &q), [Some(1.0), Some(0.0)]);
}

#[test]
fn a_distance_of_exactly_the_radius_collides_and_beyond_does_not() {
    let at = |d: f32| [query(&[1.0], [0.0; 3]), query(&[1.0], [d, 0.0, 0.0])];
    assert_eq!(collide(0.5, true, &at(0.5)), [Some(0.0), Some(0.0)]);
    assert_eq!(collide(0.5, true, &at(0.5001)), [Some(1.0), Some(1.0)]);
}

#[test]
fn different_groups_never_collide() {
    let q = [query(&[1.0, 1.0], [0.0; 3]), query(&[1.0, 2.0], [0.0; 3])];
    assert_eq!(collide(1.0, true, &q), [Some(1.0), Some(1.0)]);
}

#[test]
fn without_3d_only_x_and_z_count() {
    let q = [
        query(&[1.0], [0.0, 0.0, 0.0]),
        query(&[1.0], [0.0, 5.0, 0.0]),
    ];
    assert_eq!(collide(0.1, false, &q), [Some(0.0), Some(0.0)]);
    assert_eq!(collide(0.1, true, &q), [Some(1.0), Some(1.0)]);
    // A query without a parameter is not the program's: no reply.
    let r = Collision::new(CollisionSettings::default()).respond(&[query(&[], [0.0; 3])]);
    assert_eq!(r, [Vec::<Option<f64>>::new()]);
}

/// One source straight above, the given transmittance and area mode.
fn light(transmittance: f32, estimate_area: bool) -> Light {
    Light::new(LightSettings {
        transmittance,
        estimate_area,
        beam_radius: if estimate_area { 1.0 } else { 0.0 },
        sources: vec![([0.0, 1.0, 0.0], 1.0)],
        grid: [8, 8, 8],
        ..LightSettings::default()
    })
}

#[test]
fn an_isolated_sphere_receives_all_the_light() {
    for area in [false, true] {
        let r = light(0.3, area).respond(&[query(&[1.0], [3.0, 4.0, 5.0])]);
        assert_eq!(r[0][0], Some(1.0), "estimate area {area}");
    }
}

#[test]
fn an_equal_occluder_on_the_light_axis_passes_exactly_the_transmittance() {
    for area in [false, true] {
        let q = [query(&[1.0], [0.0; 3]), query(&[1.0], [0.0, 5.0, 0.0])];
        let r = light(0.25, area).respond(&q);
        assert_eq!(
            r[0][0],
            Some(0.25),
            "estimate area {area}: the lower sphere"
        );
        assert_eq!(r[1][0], Some(1.0), "estimate area {area}: the upper sphere");
    }
}

#[test]
fn four_parameters_get_the_direction_of_most_light() {
    let r = light(0.5, false).respond(&[query(&[1.0, 0.0, 0.0, 0.0], [0.0; 3])]);
    assert_eq!(r[0], [Some(1.0), Some(0.0), Some(1.0), Some(0.0)]);
}

#[test]
fn sierpinski_tentacles_follow_pascals_triangle_mod_2() {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/environment/sierpinski"
    );
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["derive", "sierpinski.l", "-n", "16", "--every"])
        .current_dir(dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    // The environment is found and run: no "needs an environmental
    // program" warning.
    assert!(!err.contains("environment"), "{err}");
    let text = String::from_utf8_lossy(&o.stdout);
    let sensors: Vec<u32> = text
        .lines()
        .map(|l| l.matches("?E").count() as u32)
        .collect();
    // Step 0 is the axiom `A` as written (the cpfg profile decomposes
    // only after each step); after step k >= 1 the string holds the two
    // sensors of each live tip of row k - 1: 2 * 2^popcount(k - 1).
    let expected: Vec<u32> = (0..=16u32)
        .map(|k| if k == 0 { 0 } else { 2 << (k - 1).count_ones() })
        .collect();
    assert_eq!(sensors, expected);
}

/// A 2×2 SGI image, stored verbatim, channels red then green then blue,
/// rows from the bottom.
fn sgi_2x2(red: [u8; 4], green: [u8; 4]) -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[0..2].copy_from_slice(&474u16.to_be_bytes());
    b[2] = 0; // verbatim
    b[3] = 1; // one byte per value
    b[4..6].copy_from_slice(&3u16.to_be_bytes());
    b[6..8].copy_from_slice(&2u16.to_be_bytes());
    b[8..10].copy_from_slice(&2u16.to_be_bytes());
    b[10..12].copy_from_slice(&3u16.to_be_bytes());
    b.extend_from_slice(&red);
    b.extend_from_slice(&green);
    b.extend_from_slice(&[0; 4]);
    b
}

/// The `?E` modules a successful `lsys derive` printed.
fn e_answers(o: &std::process::Output) -> Vec<String> {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    String::from_utf8_lossy(&o.stdout)
        .split_whitespace()
        .filter(|m| m.starts_with("?E"))
        .map(str::to_string)
        .collect()
}

#[test]
fn clover_reads_light_from_its_image_and_leaves_shade_their_cells() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &[u8]| std::fs::write(dir.path().join(name), text).unwrap();
    w("specifications", b"cpfg -e field.e patch.l\n");
    w(
        "field.e",
        b"executable: clover -e field.e field.spec\nturtle position:P:%g %g %g\n",
    );
    w(
        "field.spec",
        b"grid size: 2x2\ngrid position: 0 0\ngrid range: 2x2\ntransmittance: 0.5\ninput image: light.rgb\n",
    );
    // Green (the light) 255, 128 in the bottom row, 64, 0 in the top one;
    // red (the ratio) 64 everywhere.
    w("light.rgb", &sgi_2x2([64; 4], [255, 128, 64, 0]));
    // A leaf (?E(1, area)) on the bottom-left cell comes before the query
    // of that cell in the string: the answers see it.
    w(
        "patch.l",
        b"Lsystem: 1\nderivation length: 1\nAxiom: @M(0.5,0.5,0)?E(1,0.0001)?E(0,0)\
          @M(1.5,0.5,0)?E(0)@M(0.5,1.5,0)?E(0)@M(1.5,1.5,0)?E(0)@M(5,5,0)?E(0)\nendlsystem\n",
    );
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["derive", "patch.l"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let answers = e_answers(&o);
    assert_eq!(
        answers,
        [
            "?E(1,0.0001)", // a leaf: no answer
            "?E(0.5,0.5)",  // full light under one leaf (t = 0.5), ratio 64/128
            "?E(0.501961)", // 128/255, as %g sends it to cpfg
            "?E(0.25098)",  // 64/255
            "?E(0)",        // no light
            "?E(0)",        // outside the grid
        ]
    );
}

#[test]
fn clover_from_a_header_reads_its_image_next_to_the_grammar() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &[u8]| std::fs::write(dir.path().join(name), text).unwrap();
    w("light.rgb", &sgi_2x2([64; 4], [255, 128, 64, 0]));
    // The same field as above, from a `.lsys` header: no leaf this time.
    w(
        "patch.lsys",
        b"environment: clover(grid size: 2x2, grid position: 0 0, grid range: 2x2, \
          transmittance: 0.5, input image: light.rgb)\n\
          axiom: @M(0.5,0.5,0) ?E(0,0) @M(1.5,0.5,0) ?E(0) @M(0.5,1.5,0) ?E(0) @M(1.5,1.5,0) ?E(0)\n",
    );
    let derive = |file: &str| {
        Command::new(env!("CARGO_BIN_EXE_lsys"))
            .args(["derive", file, "-n", "1", "--precision", "4"])
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let o = derive("patch.lsys");
    let answers = e_answers(&o);
    assert_eq!(answers, ["?E(1,0.5)", "?E(0.502)", "?E(0.251)", "?E(0)"]);
    // A missing image is an error that names it, not a dark field.
    w(
        "dark.lsys",
        b"environment: clover(input image: none.rgb)\naxiom: ?E(0)\n",
    );
    let o = derive("dark.lsys");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("none.rgb"), "{err}");
}

/// The tentacle model without an environment of its own.
const TENTACLES: &str = "derivation length: 6\n\
    axiom: A\n\
    ?E(x) : x == 1 --> A\n\
    ?E(x) : x == 0 -->\n\
    decomposition\n\
    A --> [+(45) f(1.41421356) -(45) ?E(1)] [-(45) f(1.41421356) +(45) ?E(1)]\n";

fn sensors(g: &lsys::Grammar) -> Vec<u32> {
    g.steps()
        .map(|d| d.unwrap().modules().filter(|(n, _)| *n == "?E").count() as u32)
        .collect()
}

#[test]
fn an_environment_can_come_from_the_options() {
    let pascal: Vec<u32> = (0..=6u32).map(|k| 2 << k.count_ones()).collect();
    // Without one, `?E` keeps its 1 and every tip grows: 2^(k+1).
    let alone = lsys::Grammar::from_str("t.lsys", TENTACLES).unwrap();
    assert_eq!(
        sensors(&alone),
        (0..=6u32).map(|k| 2 << k).collect::<Vec<_>>()
    );
    let g = lsys::Grammar::options()
        .environment("collision(radius: 0.01, 3d case: on)")
        .from_str("t.lsys", TENTACLES)
        .unwrap();
    assert_eq!(sensors(&g), pascal);
    // The command line's `--environment` is the same option.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("t.lsys");
    std::fs::write(&file, TENTACLES).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["derive", file.to_str().unwrap(), "--every", "--environment"])
        .arg("collision(radius: 0.01, 3d case: on)")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let counts: Vec<u32> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| l.matches("?E").count() as u32)
        .collect();
    assert_eq!(counts, pascal);
}

#[test]
fn a_lsys_file_selects_its_environment_in_a_header() {
    // The tentacle model in the paper's notation: the axiom is decomposed
    // at step 0, so after step k the sensors are those of row k.
    let text = "environment: collision(radius: 0.01, 3d case: on)\n\
                derivation length: 10\n\
                axiom: A\n\
                ?E(x) : x == 1 --> A\n\
                ?E(x) : x == 0 -->\n\
                decomposition\n\
                A --> [+(45) f(1.41421356) -(45) ?E(1)] [-(45) f(1.41421356) +(45) ?E(1)]\n";
    let g = lsys::Grammar::from_str("tentacles.lsys", text).unwrap();
    assert!(
        g.warnings().render_plain().is_empty(),
        "{}",
        g.warnings().render_plain()
    );
    let sensors: Vec<u32> = g
        .steps()
        .map(|d| d.unwrap().modules().filter(|(n, _)| *n == "?E").count() as u32)
        .collect();
    let expected: Vec<u32> = (0..=10u32).map(|k| 2 << k.count_ones()).collect();
    assert_eq!(sensors, expected);
}

#[test]
fn density_is_low_away_from_the_pattern_and_its_gradient_points_away() {
    use lsys::internals::environment::density::{Density, Settings as DensitySettings};
    let at = |p: [f32; 3], params: &[f64]| query(params, p);
    let one_point = DensitySettings {
        one_point: true,
        return_vector: false,
    };
    // Alone: no other part, no source: density 0, no gradient (angle 90).
    let r = Density::new(one_point.clone()).respond(&[at([0.0; 3], &[0.0, 0.0, 0.0])]);
    assert_eq!(r[0], [Some(0.0), Some(90.0), Some(0.0)]);
    // A part one unit along +x: 1/(1+1) here; the field falls away from
    // it, so the gradient (downhill) points along -x: 180 degrees.
    let q = [
        at([0.0; 3], &[0.0, 0.0, 0.0]),
        at([1.0, 0.0, 0.0], &[0.0, 0.0]),
    ];
    let r = Density::new(one_point.clone()).respond(&q);
    assert_eq!(r[0][0], Some(0.5));
    assert_eq!(r[0][1], Some(180.0));
    let expected = 1.0 / (1.0 + 0.25) - 1.0 / (1.0 + 2.25);
    assert!((r[0][2].unwrap() - expected).abs() < 1e-6, "{:?}", r[0]);
    // Two-parameter queries are parts of the pattern, not answered;
    // a one-parameter query is a source: strength / (1 + distance).
    assert_eq!(r[1], [None, None]);
    let src = [at([0.0; 3], &[0.0, 0.0, 0.0]), at([0.0, 1.0, 0.0], &[2.0])];
    let r = Density::new(one_point).respond(&src);
    assert_eq!(r[0][0], Some(1.0));
    assert_eq!(r[1], [None]);
}

/// A light (chiba) model of our own, run as cpfg runs it (`cpfg -M q.mat
/// -e q.e q.l q.v`): spheres after turns, pitches and rolls, and each
/// answer `r` written back as `D(r - 0.1)`. Expected string: cpfg and
/// chiba built from the vlab sources (github.com/AlgorithmicBotany/vlab,
/// commit 9bf820d), `cpfg -g -str`. Two things had to be as cpfg does
/// them. The positions sent: lsys negated z for every query, right after
/// a pitch (lsys's pitch went the other way from cpfg's) and wrong after
/// a roll (`/(90)+(30)` got the light of its mirror image, D(-0.0599957)
/// instead of D(-0.009013)). And the text between the two programs: each
/// parameter crosses as `%g` (6 digits) both ways, so `r` arrives as
/// 0.185836, not 0.185836285 (D(0.085836), not D(0.0858363)).
#[test]
fn chiba_answers_reach_the_model_as_cpfgs_text_protocol_delivers_them() {
    let dir = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    w("specifications", "cpfg -M q.mat -e q.e q.l q.v\n");
    w(
        "q.e",
        "executable: chiba -e q.e light.spec\ncommunication type: pipes\n\
         turtle position:P:%.4g %.4g %.4g\n",
    );
    w(
        "light.spec",
        "transmittance: 0.25\nlower to upper ratio: 0.0\nestimate intersection area: on\n\
         grid size: 8x8x8\nsource direction: 0 100 0 4\nsource direction: 40 100 0 3\n\
         source direction: 0 75 -80 2\n",
    );
    w("q.v", "angle factor: 12\n");
    w(
        "q.l",
        "Lsystem: 1\nderivation length: 2\nAxiom: A\n\
         A --> F(1)?P(0,0,0)?E(1)[+(30)F(1)?E(1)][-(30)F(1)?E(1)][&(30)F(1)?P(0,0,0)?E(1)]\
         [^(30)F(1)?E(1)][/(90)+(30)F(1)?P(0,0,0)?E(1)][\\(90)+(30)F(1)?E(1)]\
         [/(40)&(20)+(10)^(70)\\(15)-(33)F(1)?P(0,0,0)?H(0,0,0)?L(0,0,0)?U(0,0,0)?E(1)]\
         [f(0.7995)f(0.7995)f(0.7995)?E(0.5)]\n\
         ?E(r) --> D(r-0.1)\nendlsystem\n",
    );
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["derive", "--cpfg-format", "q.l"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let got: String = String::from_utf8_lossy(&o.stdout)
        .split_whitespace()
        .collect();
    assert_eq!(
        got,
        "F(1)?P(0,1,0)D(-0.088258)[+(30)F(1)D(-0.0152461)][-(30)F(1)D(0.280225)]\
         [&(30)F(1)?P(0,1.86603,-0.5)D(0.085836)][^(30)F(1)D(0.034854)]\
         [/(90)+(30)F(1)?P(-3.06162e-17,1.86603,-0.5)D(-0.009013)][\\(90)+(30)F(1)D(-0.0599957)]\
         [/(40)&(20)+(10)^(70)\\(15)-(33)F(1)?P(0.00506312,1.72693,0.686694)\
         ?H(0.00506312,0.726929,0.686694)?L(-0.997521,0.0518715,-0.0475558)\
         ?U(0.0701895,0.684751,-0.725389)D(-0.0748173)][f(0.7995)f(0.7995)f(0.7995)D(0.9)]"
    );
}
