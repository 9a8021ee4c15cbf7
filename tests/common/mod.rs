//! Helpers shared by the test binaries that run `lsys` as a user would.
#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs the `lsys` binary with `args` in the package's folder.
pub fn lsys(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

/// What a run printed on standard error.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
