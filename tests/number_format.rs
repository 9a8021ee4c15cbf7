//! How parameters are printed (`src/derive/number.rs`): the shortest form
//! of the value as stored (f64, or f32 in the cpfg dialect), rounded to N
//! decimals (`lsys derive --precision N`), or C's `%g` (`--cpfg-format`).
//! The `%g` expectations were computed with C's formatting (Python's
//! `'%g' % x`) and are written out here.

use std::process::{Command, Output};

use lsys::internals::derive::{DeriveOptions, ModuleStore, NumberFormat, NumberStyle};
use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline::{self, Compilation};

const F64: NumberFormat = NumberFormat {
    f32: false,
    style: NumberStyle::Shortest,
};
const F32: NumberFormat = NumberFormat {
    f32: true,
    style: NumberStyle::Shortest,
};

fn decimals(n: u8) -> NumberFormat {
    F64.with_style(NumberStyle::Decimals(n))
}

fn g() -> NumberFormat {
    F64.with_style(NumberStyle::PrintfG)
}

fn check(fmt: NumberFormat, cases: &[(f64, &str)]) {
    for &(v, want) in cases {
        assert_eq!(fmt.format(v), want, "{v:e} in {fmt:?}");
    }
}

#[test]
fn the_default_is_rusts_shortest_f64() {
    assert_eq!(NumberFormat::default(), F64);
    for v in [
        0.0,
        -0.0,
        1.0,
        -25.0,
        0.1,
        1.0 / 3.0,
        0.49999999999999994,
        5.695309162139893,
        -1e-7,
        1e21,
        9_007_199_254_740_993.0,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        assert_eq!(F64.format(v), format!("{v}"), "{v:e}");
    }
    assert_eq!(F64.format(f64::NAN), "NaN");
}

#[test]
fn f32_prints_the_shortest_form_of_the_f32() {
    check(
        F32,
        &[
            (5.695309162139893, "5.695309"),
            (0.9985358715057373, "0.9985359"),
            (0.0009765615104697645, "0.0009765615"),
            (0.1, "0.1"),
            (0.10000000149011612, "0.1"),
            (1.0 / 3.0, "0.33333334"),
            (-2.5, "-2.5"),
            (0.0, "0"),
            (-0.0, "-0"),
            (42.0, "42"),
            (-16_777_215.0, "-16777215"),
            // Whole numbers from 2^24 on: the f32's shortest digits.
            (16_777_217.0, "16777216"),
            (1_099_511_627_776.0, "1099511600000"),
            (1e-7, "0.0000001"),
            (1e30, "1000000000000000000000000000000"),
            (f64::INFINITY, "inf"),
            (1e300, "inf"),
        ],
    );
}

#[test]
fn decimals_round_and_drop_trailing_zeros() {
    check(
        decimals(6),
        &[
            (0.9799999999999999, "0.98"),
            (0.49999999999999994, "0.5"),
            (1.0 / 3.0, "0.333333"),
            (-2.0 / 3.0, "-0.666667"),
            (123.4560001, "123.456"),
            (0.1, "0.1"),
            (2.0, "2"),
            (-7.0, "-7"),
            (1e21, "1000000000000000000000"),
            (1e-7, "0"),
            // Negative zero, and what rounds to zero, print as 0.
            (-0.0, "0"),
            (-1e-9, "0"),
            (-0.0000016, "-0.000002"),
            (f64::INFINITY, "inf"),
            (f64::NAN, "NaN"),
        ],
    );
    // Never more digits than the shortest form.
    check(
        decimals(20),
        &[(0.1, "0.1"), (1e-20, "0.00000000000000000001")],
    );
    // The exact binary value is rounded; exact ties go to even.
    check(
        decimals(0),
        &[
            (2.5, "2"),
            (3.5, "4"),
            (-0.5, "0"),
            (0.75, "1"),
            (-1.5, "-2"),
        ],
    );
    check(decimals(1), &[(1.25, "1.2"), (1.35, "1.4"), (0.05, "0.1")]);
    check(decimals(2), &[(1.005, "1"), (123.456, "123.46")]);
    // With f32 the f32 is rounded (0.1f32 is 0.100000001490116...).
    let f = F32.with_style(NumberStyle::Decimals(3));
    check(
        f,
        &[(5.695309162139893, "5.695"), (0.1, "0.1"), (-0.0001, "0")],
    );
    let f = F32.with_style(NumberStyle::Decimals(10));
    check(f, &[(5.695309162139893, "5.695309"), (0.1, "0.1")]);
}

#[test]
fn printf_g_matches_c() {
    check(
        g(),
        &[
            (0.0, "0"),
            (-0.0, "-0"),
            (1.0, "1"),
            (-1.0, "-1"),
            (123456.0, "123456"),
            (999999.0, "999999"),
            (1e6, "1e+06"),
            (-1e6, "-1e+06"),
            (1234567.0, "1.23457e+06"),
            (1234565.0, "1.23456e+06"),
            (1234575.0, "1.23458e+06"),
            (0.5, "0.5"),
            (2.5, "2.5"),
            (0.1, "0.1"),
            (1.0 / 3.0, "0.333333"),
            (-2.0 / 3.0, "-0.666667"),
            (1.5e-5, "1.5e-05"),
            (0.0001, "0.0001"),
            (0.00001, "1e-05"),
            (0.000099999999, "0.0001"),
            (9.999995e-5, "0.0001"),
            (999999.5, "1e+06"),
            (999999.4, "999999"),
            (123456.7, "123457"),
            (100000.2, "100000"),
            (std::f64::consts::PI, "3.14159"),
            (2.71234567, "2.71235"),
            (1e100, "1e+100"),
            (-1e-100, "-1e-100"),
            (f64::MAX, "1.79769e+308"),
            (5e-324, "4.94066e-324"),
            (0.30000000000000004, "0.3"),
            (12345.65, "12345.6"),
            (0.9799999999999999, "0.98"),
            (1e21, "1e+21"),
            (65536.5, "65536.5"),
            (9_007_199_254_740_992.0, "9.0072e+15"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (f64::NAN, "nan"),
        ],
    );
    // cpfg prints its floats so: the f32 widened gives the same digits.
    let f = F32.with_style(NumberStyle::PrintfG);
    check(f, &[(5.695309162139893, "5.69531"), (0.1, "0.1")]);
}

fn compile(name: &str, text: &str) -> Compilation {
    let input = Input::Text {
        name: name.into(),
        text: text.into(),
    };
    pipeline::compile(&input, &Options::default())
        .unwrap_or_else(|_| panic!("does not compile:\n{text}"))
}

const THIRDS: &str =
    "derivation length: 2\naxiom: I(1) F(0.1)\nI(x) --> I(x*1.1+1/3)\nF(x) --> F(x/3)\n";

fn derived(c: &Compilation) -> ModuleStore {
    lsys::internals::simulation::derive(
        &c.program,
        &c.compiled,
        DeriveOptions::default(),
        c.program.derivation_length,
    )
    .unwrap()
}

#[test]
fn the_dialect_decides_f32() {
    let paper = compile("t.lsys", THIRDS);
    let f = NumberFormat::for_program(&paper.program);
    assert_eq!(f, F64);
    let s = derived(&paper);
    // Paper: exactly what `display` printed before.
    assert_eq!(
        s.display_with(&paper.program.symbols, f),
        s.display(&paper.program.symbols)
    );
    assert_eq!(
        s.display(&paper.program.symbols),
        "I(1.9100000000000001) F(0.011111111111111112)"
    );

    let cpfg = compile("t.lsys", &format!("dialect: cpfg\n{THIRDS}"));
    let f = NumberFormat::for_program(&cpfg.program);
    assert_eq!(f, F32);
    let s = derived(&cpfg);
    assert_eq!(
        s.display_with(&cpfg.program.symbols, f),
        "I(1.91) F(0.011111111)"
    );
    // `.l` files are cpfg's.
    let l = compile("t.l", THIRDS);
    assert_eq!(NumberFormat::for_program(&l.program), F32);

    // `write_string_with` and `display_with` agree in every style.
    for fmt in [
        f,
        f.with_style(NumberStyle::Decimals(3)),
        f.with_style(NumberStyle::PrintfG),
    ] {
        let mut v = Vec::new();
        s.write_string_with(&cpfg.program.symbols, fmt, &mut v)
            .unwrap();
        assert_eq!(v, s.display_with(&cpfg.program.symbols, fmt).as_bytes());
    }
}

fn lsys(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NO_COLOR", "1")
        .output()
        .expect("lsys runs")
}

fn stdout(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout.clone()).unwrap()
}

#[test]
fn derive_precision_and_cpfg_format_flags() {
    let dir = tempfile::tempdir().unwrap();
    let paper = dir.path().join("thirds.lsys");
    std::fs::write(&paper, THIRDS).unwrap();
    let paper = paper.to_str().unwrap();
    assert_eq!(
        stdout(&lsys(&["derive", paper])),
        "I(1.9100000000000001) F(0.011111111111111112)\n"
    );
    assert_eq!(
        stdout(&lsys(&["derive", "--precision", "6", paper])),
        "I(1.91) F(0.011111)\n"
    );
    assert_eq!(
        stdout(&lsys(&["derive", "--precision", "2", "--every", paper])),
        "I(1) F(0.1)\nI(1.43) F(0.03)\nI(1.91) F(0.01)\n"
    );
    assert_eq!(
        stdout(&lsys(&["derive", "--cpfg-format", paper])),
        "I(1.91) F(0.0111111)\n"
    );
    // A fixture's 0.49999999999999994 (sin 30°) prints as 0.5.
    let trig = "tests/fixtures/derive/ok/arithmetic_and_trig_degrees.lsys";
    let out = stdout(&lsys(&["derive", "--precision", "6", trig]));
    assert_eq!(out, "F(1) F(8) F(-4) F(0.5) F(45) F(5) F(-1) F(20)\n");

    // The cpfg dialect prints f32s, in every form.
    let cpfg = dir.path().join("thirds.l");
    std::fs::write(&cpfg, THIRDS).unwrap();
    let cpfg = cpfg.to_str().unwrap();
    assert_eq!(stdout(&lsys(&["derive", cpfg])), "I(1.91) F(0.011111111)\n");
    assert_eq!(
        stdout(&lsys(&["derive", "--precision", "4", cpfg])),
        "I(1.91) F(0.0111)\n"
    );
    assert_eq!(
        stdout(&lsys(&["derive", "--cpfg-format", "--homomorphism", cpfg])),
        "I(1.91) F(0.0111111)\n"
    );

    // The two forms exclude each other, and neither goes with --count.
    for args in [
        &["derive", "--precision", "2", "--cpfg-format", paper][..],
        &["derive", "--count", "--precision", "2", paper][..],
        &["derive", "--count", "--cpfg-format", paper][..],
        &["derive", "--precision", "-1", paper][..],
    ] {
        let o = lsys(args);
        assert_eq!(o.status.code(), Some(64), "{args:?}");
    }
}
