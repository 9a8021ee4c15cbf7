//! cpfg language features beyond one L-system per string: `ring
//! lsystem` (context wraps around the string's ends), sub-L-systems
//! (several `Lsystem:` blocks, `?(n,s) ... $`) and contour curves. Our
//! own small models under tests/fixtures/cpfg/, derived through the CLI.

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
