//! `lsys check` end to end, through the binary: each fixture under
//! `tests/fixtures/check/{ok,err}/` is checked as a user would check it,
//! and its snapshot records the exit code and everything printed on
//! standard error. These are the checks beyond compiling: components
//! found on the search path (without building them).

use std::path::Path;
use std::process::Command;

/// The fixture's path relative to the package, as the user would type it.
fn rel(path: &Path) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    path.strip_prefix(root)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}

#[test]
fn check_fixtures() {
    insta::glob!("fixtures/check/*/*.lsys", |path| {
        let name = rel(path);
        let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
            .args(["--color", "never", "check", &name])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("COLUMNS", "100")
            .output()
            .unwrap();
        let ok = name.contains("/ok/");
        assert_eq!(
            o.status.success(),
            ok,
            "{name}: ok/ fixtures pass `check`, err/ ones do not:\n{}",
            String::from_utf8_lossy(&o.stderr)
        );
        insta::assert_snapshot!(format!(
            "exit {}\n{}",
            o.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&o.stderr)
        ));
    });
}

/// `--components DIR` is searched too, as `build`'s is.
#[test]
fn check_searches_components_dirs() {
    let name = "tests/fixtures/check/err/unknown_component.lsys";
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("Shelf.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["check", "--components", dir.path().to_str().unwrap(), name])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Issue 35: with no `derivation length:` and no `-n`, `lsys derive`
/// notes that 0 steps were derived; with `-n` it says nothing.
#[test]
fn zero_steps_are_noted() {
    let name = "tests/fixtures/check/ok/header_misspelt.lsys";
    let run = |extra: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
            .args(["--color", "never", "derive", name])
            .args(extra)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        assert!(o.status.success());
        (
            String::from_utf8_lossy(&o.stdout).trim().to_string(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let (out, err) = run(&[]);
    assert_eq!(out, "A");
    assert!(
        err.contains("has no `derivation length:`, so 0 steps are derived"),
        "{err}"
    );
    let (out, err) = run(&["-n", "2"]);
    assert_eq!(out, "A B B");
    assert!(!err.contains("so 0 steps are derived"), "{err}");
}

/// Issue 35: a cpfg view file's `angle factor: 0` (360° / 0) was ignored
/// without a word; it is a warning at its line.
#[test]
fn a_zero_angle_factor_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("plant.l"),
        "lsystem: 1\nderivation length: 1\nAxiom: F+F\nendlsystem\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("plant.v"), "angle factor: 0\n").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["--color", "never", "check", "plant.l"])
        .current_dir(dir.path())
        .env("COLUMNS", "100")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("lsys::load::angle_factor"), "{err}");
    assert!(err.contains("plant.v:1:1"), "{err}");
    std::fs::write(dir.path().join("plant.v"), "angle factor: 8\n").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["--color", "never", "check", "plant.l"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&o.stderr).contains("angle_factor"));
}
