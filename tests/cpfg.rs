//! cpfg model objects: a `.l` file with its view file and function files
//! (our own small model under tests/fixtures/cpfg/), derived through the
//! CLI; and the C preprocessor's effect on what the grammar stages see.

use std::path::Path;
use std::process::{Command, Output};

fn lsys(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("lsys runs")
}

fn fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/cpfg")
        .join(name)
}

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
