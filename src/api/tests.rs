//! The public surface seen from a caller: typed diagnostics, their short
//! form, and the short `Debug` forms.

use crate::{Grammar, Level, Message};

/// Two unknown names, on lines 1 and 2.
const TWO_ERRORS: &str = "axiom: F(y)\nF(a) --> F(a + x)\n";

/// Two productions that can never apply (warnings; it compiles).
const TWO_WARNINGS: &str = "axiom: F\nF --> F\nF --> G\nF --> H\n";

#[test]
fn each_diagnostic_reads_as_a_typed_message() {
    let err = Grammar::from_str("two.lsys", TWO_ERRORS).unwrap_err();
    let m: Vec<Message> = err.messages().collect();
    assert_eq!(m.len(), 2);
    assert_eq!(m[0].code.as_deref(), Some("lsys::resolve::unknown_name"));
    assert_eq!(m[0].severity, Level::Error);
    assert!(m[0].is_error());
    assert_eq!(m[0].file.as_deref(), Some("two.lsys"));
    assert_eq!((m[0].line, m[0].column), (Some(1), Some(10)));
    assert_eq!(m[0].message, "unknown name `y`");
    assert_eq!(
        m[0].help.as_deref(),
        Some("names here are #defines; define it with `#define NAME value` above its first use")
    );
    assert_eq!((m[1].line, m[1].column), (Some(2), Some(16)));
    assert_eq!(m[1].message, "unknown name `x`");
    // Each rendering is the CLI's for that diagnostic alone.
    assert_eq!(
        format!("{}{}", m[0].rendered(), m[1].rendered()),
        err.render_plain()
    );
    assert!(m[1].rendered().contains("╭─[two.lsys:2:16]"));
}

#[test]
fn a_warning_reads_as_a_warning() {
    let g = Grammar::from_str("warn.lsys", TWO_WARNINGS).unwrap();
    let w = g.warnings();
    assert_eq!(w.len(), 2);
    assert!(!w.is_empty());
    assert!(!w.has_errors());
    let m = w.messages().next().unwrap();
    assert_eq!(m.severity, Level::Warning);
    assert!(!m.is_error());
    assert_eq!(m.code.as_deref(), Some("lsys::resolve::unreachable"));
    // The place is where the diagnostic's first label points ("never
    // reached"), not the earlier production it also labels.
    assert_eq!((m.line, m.column), (Some(3), Some(1)));
}

#[test]
fn counts_of_diagnostics() {
    let err = Grammar::from_str("two.lsys", TWO_ERRORS).unwrap_err();
    assert_eq!(err.len(), 2);
    assert!(err.has_errors());
    let g = Grammar::from_str("fine.lsys", "axiom: F\n").unwrap();
    assert!(g.warnings().is_empty());
    assert_eq!(g.warnings().len(), 0);
    assert!(!g.warnings().has_errors());
}

#[test]
fn display_is_the_first_error_with_its_place_and_how_many_more() {
    let err = Grammar::from_str("two.lsys", TWO_ERRORS).unwrap_err();
    assert_eq!(
        err.to_string(),
        "two.lsys:1:10: error[lsys::resolve::unknown_name]: unknown name `y` (and 1 more error)"
    );
    let one = Grammar::from_str("one.lsys", "axiom: F\nF --> F(z)\n").unwrap_err();
    assert_eq!(
        one.to_string(),
        "one.lsys:2:9: error[lsys::resolve::unknown_name]: unknown name `z`"
    );
    assert_eq!(
        err.messages().nth(1).unwrap().to_string(),
        "two.lsys:2:16: error[lsys::resolve::unknown_name]: unknown name `x`"
    );
}

#[test]
fn display_counts_warnings_when_there_is_no_error() {
    let g = Grammar::from_str("warn.lsys", TWO_WARNINGS).unwrap();
    assert_eq!(
        g.warnings().to_string(),
        "warn.lsys:3:1: warning[lsys::resolve::unreachable]: this production can never apply (and 1 more warning)"
    );
}

#[test]
fn display_of_a_diagnostic_without_a_place() {
    let err = Grammar::options()
        .define("M", 3)
        .from_str("koch.lsys", "#define N 2\naxiom: F\n")
        .unwrap_err();
    let m = err.messages().next().unwrap();
    assert_eq!((&m.file, m.line, m.column), (&None, None, None));
    assert!(
        err.to_string()
            .starts_with("error[lsys::resolve::unknown_override]: "),
        "{err}"
    );
}

#[test]
fn a_failed_compilation_unwraps_to_its_diagnostics() {
    // `unwrap_err` needs `Grammar: Debug`.
    let err = Grammar::from_str("bad.lsys", "axiom: A(1\n").unwrap_err();
    assert_eq!(
        err.messages().next().unwrap().code.as_deref(),
        Some("lsys::parse::syntax")
    );
}

#[test]
fn debug_forms_are_short() {
    let g = Grammar::from_str(
        "koch.lsys",
        "derivation length: 3\naxiom: F\nF --> F+F-F-F+F\nF --> G\n",
    )
    .unwrap();
    assert_eq!(
        format!("{g:?}"),
        "Grammar { name: \"koch.lsys\", derivation_length: 3, alphabet: 6, productions: 2, warnings: 1 }"
    );
    let mut steps = g.steps();
    assert_eq!(
        format!("{steps:?}"),
        "Steps { grammar: \"koch.lsys\", to: 3, ended: false }"
    );
    assert_eq!(steps.by_ref().count(), 4);
    assert_eq!(
        format!("{steps:?}"),
        "Steps { grammar: \"koch.lsys\", to: 3, ended: true }"
    );
    let scene = g.build(1).unwrap();
    let s = format!("{scene:?}");
    assert!(s.starts_with("Scene { modules: 9, triangles: "), "{s}");
    assert!(s.ends_with(", instances: 0 }"), "{s}");
}

#[test]
fn a_define_that_matches_nothing_is_told_in_words_of_no_front_end() {
    let err = Grammar::options()
        .define("M", 3)
        .from_str("koch.lsys", "#define N 2\naxiom: F\n")
        .unwrap_err();
    let m = err.messages().next().unwrap();
    assert_eq!(m.code.as_deref(), Some("lsys::resolve::unknown_override"));
    assert_eq!(
        m.message,
        "the define `M` given as an option matches no #define in koch.lsys"
    );
    assert_eq!(
        m.help.as_deref(),
        Some("did you mean `N`? the grammar defines: N")
    );
    assert!(!m.rendered().contains("-D"), "{}", m.rendered());
}

#[test]
fn a_namespace_that_names_no_component_is_told_in_words_of_no_front_end() {
    let err = Grammar::options()
        .define("TM.NTL", 3)
        .from_str("koch.lsys", "axiom: F\n")
        .unwrap_err();
    let m = err.messages().next().unwrap();
    assert_eq!(m.code.as_deref(), Some("lsys::options::unknown_namespace"));
    assert!(!m.rendered().contains("-D"), "{}", m.rendered());
}

#[test]
fn a_limit_names_the_option_as_the_library_and_the_command_line_spell_it() {
    let g = Grammar::options()
        .max_modules(10)
        .from_str("koch.lsys", "axiom: F\nF --> F F\n")
        .unwrap();
    let m = g.derive(8).unwrap_err().messages().next().unwrap();
    assert_eq!(m.code.as_deref(), Some("lsys::derive::module_limit"));
    let help = m.help.unwrap();
    assert!(help.contains("max_modules"), "{help}");
    assert!(help.contains("--max-modules"), "{help}");
}

/// The code and place of the first diagnostic of a failure.
fn first(d: &crate::Diagnostics) -> (Option<String>, Option<usize>, Level) {
    let m = d.messages().next().expect("a diagnostic");
    (m.code, m.line, m.severity)
}

#[test]
fn derive_errors_carry_their_codes_and_places() {
    let g = Grammar::options()
        .max_modules(10)
        .from_str("grow.lsys", "derivation length: 8\naxiom: F\nF --> F F\n")
        .unwrap();
    let want = (
        Some("lsys::derive::module_limit".to_string()),
        Some(3),
        Level::Error,
    );
    assert_eq!(first(&g.derive(8).unwrap_err()), want);
    let stepped = g.steps().find_map(Result::err).expect("a step fails");
    assert_eq!(first(&stepped), want);
    assert_eq!(first(&g.build(8).unwrap_err()), want);
}

#[test]
fn write_errors_carry_their_codes() {
    let scene = Grammar::from_str("f.lsys", "axiom: F\n")
        .unwrap()
        .build(0)
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let nowhere = dir.path().join("no such folder").join("f.glb");
    let err = scene.write_glb(&nowhere).unwrap_err();
    let m = err.messages().next().unwrap();
    assert_eq!(m.code.as_deref(), Some("lsys::export::write"));
    assert_eq!((m.file, m.line, m.severity), (None, None, Level::Error));
    assert!(m.message.starts_with("cannot write "), "{}", m.message);
    assert!(m.help.is_some());
    assert!(err
        .to_string()
        .starts_with("error[lsys::export::write]: cannot write "));
    let err = scene.write_obj(nowhere.with_extension("obj")).unwrap_err();
    assert_eq!(first(&err).0.as_deref(), Some("lsys::export::write"));
    let err = scene
        .write_png(dir.path().join("f.png"), 0, 10)
        .unwrap_err();
    assert_eq!(first(&err).0.as_deref(), Some("lsys::render::zero_size"));
}

#[test]
fn arrays_are_the_scene_expanded_in_world_space() {
    // A stroke (F) and two instances of a built-in component, one turned.
    let g = Grammar::from_str("t.lsys", "Axiom: F(2) ~MCa +(90) f(3) ~MCa\n").unwrap();
    let scene = g.build(0).unwrap();
    let a = scene.arrays();
    let vertices = a.positions.len() / 3;
    assert_eq!(a.normals.len(), a.positions.len());
    assert_eq!(a.colors.len(), a.positions.len());
    assert_eq!(a.indices.len() / 3, scene.triangle_count());
    assert_eq!(vertices, scene.mesh().vertex_count());
    assert!(a.indices.iter().all(|&i| (i as usize) < vertices));
    let (lo, hi) = scene.bounds().unwrap();
    for (k, c) in a.positions.chunks_exact(3).enumerate() {
        for d in 0..3 {
            assert!(c[d] >= lo[d] - 1e-5 && c[d] <= hi[d] + 1e-5, "vertex {k}");
        }
    }
    for n in a.normals.chunks_exact(3) {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-4, "normal {n:?}");
    }
    let placed = scene.placements();
    assert_eq!(placed.len(), 2);
    assert!(placed.iter().all(|p| p.component == "MCa"));
    // The second box sits 3 units along the turned heading: a different
    // translation column from the first.
    assert_ne!(placed[0].matrix[12..15], placed[1].matrix[12..15]);
}

#[test]
fn a_diagnostic_far_along_a_long_line_is_told_without_the_line() {
    // The error's column (80,008) is past what miette's printer can pad
    // to (65,535): it used to panic rendering it.
    let text = format!("Axiom: {}G(x)\n", "F ".repeat(40_000));
    let err = Grammar::from_str("long.lsys", &text).unwrap_err();
    let shown = err.render(false);
    assert!(shown.contains("lsys::resolve::unknown_name"), "{shown}");
    assert!(
        shown.contains("at long.lsys:1:80010 (a line too long to show)"),
        "{shown}"
    );
    assert!(shown.len() < 2_000, "the line itself is not printed");
    // A short line keeps its snippet.
    let err = Grammar::from_str("short.lsys", "Axiom: G(x)\n").unwrap_err();
    assert!(err.render(false).contains("╭─[short.lsys:1:10]"));
}

#[test]
fn a_warning_marks_at_most_twenty_of_many_brackets() {
    // 30,000 unclosed `[` on short lines: one label each was rendered in
    // quadratic time and size.
    let text = format!("Axiom: A\nA -->\n{}", "  [F\n".repeat(30_000));
    let g = Grammar::from_str("open.lsys", &text).unwrap();
    let shown = g.warnings().render(false);
    assert!(
        shown.contains("30000 `[` are never closed; the first 20 are marked."),
        "{shown}"
    );
    assert_eq!(shown.matches("never closed").count(), 21, "{shown}");
}
