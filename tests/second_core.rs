//! The helpers on the second core (pages backed ahead of the turtle and
//! the mesher, the GLB buffer encoded beside its writer, writeback started
//! while the file is written) change no byte: a model big enough for every
//! one of them, built with two threads and with one, gives the same files.

use std::path::Path;
use std::process::Command;

const W2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/grammars/w2.lsys");

/// `lsys build W2 -D N=16 -o out` (262,137 modules, a 13.5 MB GLB: past
/// every helper's threshold), with `threads` threads.
fn build(out: &Path, threads: &str) {
    let status = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["build", W2, "-D", "N=16", "-o"])
        .arg(out)
        .env("RAYON_NUM_THREADS", threads)
        .status()
        .expect("lsys runs");
    assert!(status.success(), "lsys build -o {} failed", out.display());
}

#[test]
fn two_threads_write_the_files_of_one() {
    // One folder each: an OBJ names its .mtl.
    let (dir1, dir2) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    for ext in ["glb", "obj"] {
        let one = dir1.path().join(format!("w2.{ext}"));
        let two = dir2.path().join(format!("w2.{ext}"));
        build(&one, "1");
        build(&two, "2");
        // Again over the file just written: the rename replaces it.
        build(&two, "2");
        let (a, b) = (std::fs::read(&one).unwrap(), std::fs::read(&two).unwrap());
        assert!(
            a.len() > 8 << 20,
            "{ext}: {} bytes, too few for the helpers",
            a.len()
        );
        assert!(a == b, "{ext}: two threads wrote other bytes than one");
    }
}
