//! Snapshot tests of derived strings, as a user of the library writes
//! them: the whole derivation step by step, one step, and a cpfg model.

use lsys::Grammar;

const PLANT: &str = "\
#define ANGLE 22.5
derivation length: 3
angle: ANGLE
axiom: X
X --> F[+X][-X]FX
F --> FF
";

#[test]
fn each_step_of_a_derivation() {
    let g = Grammar::from_str("plant.lsys", PLANT).unwrap();
    let steps: Vec<String> = g
        .steps()
        .map(|d| {
            let d = d.unwrap();
            format!("{}: {d}", d.step())
        })
        .collect();
    insta::assert_snapshot!(steps.join("\n"));
}

#[test]
fn one_step_with_options() {
    let g = Grammar::options()
        .define("N", 4)
        .seed(7)
        .from_str(
            "ran.lsys",
            "#define N 2\naxiom: A(0)\nA(x) : x < N --> A(x + 1) B(ran(1))\n",
        )
        .unwrap();
    insta::assert_snapshot!(g.derive(4).unwrap().display_with(4));
}

#[test]
fn a_cpfg_model_prints_its_f32_parameters_short() {
    let g = Grammar::from_str(
        "third.l",
        "Lsystem: 1\nderivation length: 2\nAxiom: A(1)\nA(x) --> A(x/3) B(x)\nendlsystem\n",
    )
    .unwrap();
    insta::assert_snapshot!(g.derive(2).unwrap().to_string());
}

#[test]
fn mistakes_come_back_as_diagnostics_that_render_plainly() {
    let err = match Grammar::from_str("bad.lsys", "axiom: A(1\n") {
        Ok(_) => panic!("the axiom is unbalanced"),
        Err(e) => e,
    };
    let text = err.render_plain();
    assert!(text.contains("bad.lsys:1:"), "{text}");
    insta::assert_snapshot!(text);
}

#[test]
fn the_library_function_of_this_crate() {
    assert_eq!(
        lsys_api_consumer::algae(4).unwrap().to_string(),
        "A B A A B A B A"
    );
}
