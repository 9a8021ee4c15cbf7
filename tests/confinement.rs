//! Confinement and outputs (issue 36): files outside a model's folders
//! are refused unread (guided scenes' grammars, component files linked
//! out of `components/`, includes that are pipes), an output that is an
//! input is refused before anything is written, a signal during a write
//! leaves no temporary file, `-o` through a link writes the link's target,
//! a named pipe without a reader is an error at once, piped input is read
//! only up to the size limit, and a component scaled past the model's
//! numbers is a diagnostic in every format.
//!
//! Every link and pipe here is made inside a temporary folder: no test
//! writes to the machine's `/dev/stdout` or `/dev/null`.

mod common;

use std::io::Write;
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{lsys_in, stderr};

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

fn lsys_cmd(dir: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lsys"));
    c.args(args).current_dir(dir).env("NO_COLOR", "1");
    c
}

/// Waits for `child` at most `secs` seconds; kills it and panics when it
/// is still running (a run that would wait forever).
fn wait_within(mut child: Child, secs: u64, what: &str) -> Output {
    let end = Instant::now() + Duration::from_secs(secs);
    while Instant::now() < end {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    panic!("{what}: still running after {secs} s");
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

const SECRET: &str = "SECRET_TOKEN=abc123\nmore secret lines\n";

const SCENE: &str =
    "steps = 2\n[[guide]]\nname = \"a\"\ngrammar = \"GRAMMAR\"\npoints = [[0,0],[1,0],[1,1]]\n";

#[test]
fn guided_grammar_outside_the_scene_folder_is_refused_unread() {
    let tmp = tempfile::tempdir().unwrap();
    write(&tmp.path().join("secret/s.lsys"), SECRET);
    write(
        &tmp.path().join("scene/s.toml"),
        &SCENE.replace("GRAMMAR", "../secret/s.lsys"),
    );
    let o = lsys_in(tmp.path(), &["build", "scene/s.toml", "-o", "out.glb"]);
    assert_eq!(o.status.code(), Some(65));
    let err = stderr(&o);
    assert!(!err.contains("SECRET"), "{err}");
    assert!(!tmp.path().join("out.glb").exists());
    insta::assert_snapshot!(err);
}

#[cfg(unix)]
#[test]
fn guided_grammar_linked_out_of_the_scene_folder_is_refused_unread() {
    let tmp = tempfile::tempdir().unwrap();
    write(&tmp.path().join("secret/s.lsys"), SECRET);
    write(
        &tmp.path().join("scene/s.toml"),
        &SCENE.replace("GRAMMAR", "plant.lsys"),
    );
    std::os::unix::fs::symlink(
        tmp.path().join("secret/s.lsys"),
        tmp.path().join("scene/plant.lsys"),
    )
    .unwrap();
    let o = lsys_in(tmp.path(), &["build", "scene/s.toml", "-o", "out.glb"]);
    let err = stderr(&o);
    assert!(err.contains("lsys::guided::outside"), "{err}");
    assert!(!err.contains("SECRET"), "{err}");
    // Allowed with --include-dir, it is read (and, not being a grammar,
    // fails to compile): the check is the folder, not the name.
    let o = lsys_in(
        tmp.path(),
        &[
            "build",
            "scene/s.toml",
            "-o",
            "out.glb",
            "--include-dir",
            "secret",
        ],
    );
    assert!(
        !stderr(&o).contains("lsys::guided::outside"),
        "{}",
        stderr(&o)
    );
}

#[cfg(unix)]
#[test]
fn component_grammar_linked_out_of_components_is_refused_unread() {
    let tmp = tempfile::tempdir().unwrap();
    write(&tmp.path().join("secret/X.lsys"), SECRET);
    write(&tmp.path().join("model/g.lsys"), "axiom: F ~X\n");
    std::fs::create_dir_all(tmp.path().join("model/components")).unwrap();
    std::os::unix::fs::symlink(
        tmp.path().join("secret/X.lsys"),
        tmp.path().join("model/components/X.lsys"),
    )
    .unwrap();
    let o = lsys_in(tmp.path(), &["build", "model/g.lsys", "-o", "out.glb"]);
    assert_eq!(o.status.code(), Some(65));
    let err = stderr(&o);
    assert!(!err.contains("SECRET"), "{err}");
    insta::assert_snapshot!(err);
}

#[test]
fn an_output_that_is_an_input_is_refused_before_anything_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let plant = "derivation length: 2\naxiom: F A\nA --> F A\n";
    write(&d.join("plant.lsys"), plant);
    let o = lsys_in(d, &["derive", "plant.lsys", "-o", "plant.lsys"]);
    assert_eq!(o.status.code(), Some(65));
    assert_eq!(
        std::fs::read_to_string(d.join("plant.lsys")).unwrap(),
        plant
    );
    insta::assert_snapshot!(stderr(&o));
    // The same file by another name.
    std::fs::create_dir(d.join("sub")).unwrap();
    let o = lsys_in(d, &["derive", "plant.lsys", "-o", "./sub/../plant.lsys"]);
    assert!(stderr(&o).contains("lsys::export::output_is_input"));
    assert_eq!(
        std::fs::read_to_string(d.join("plant.lsys")).unwrap(),
        plant
    );
    // A file the grammar includes, for derive (and --count) and build.
    write(&d.join("part.glb"), "// part\n");
    write(&d.join("g.lsys"), "#include \"part.glb\"\naxiom: F\n");
    for args in [
        &["derive", "g.lsys", "-o", "part.glb"][..],
        &["derive", "--count", "g.lsys", "-o", "part.glb"],
        &["build", "g.lsys", "-o", "part.glb"],
    ] {
        let o = lsys_in(d, args);
        assert_eq!(o.status.code(), Some(65), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("lsys::export::output_is_input"),
            "{args:?}: {}",
            stderr(&o)
        );
        assert_eq!(
            std::fs::read_to_string(d.join("part.glb")).unwrap(),
            "// part\n"
        );
    }
    assert_eq!(names(d), ["g.lsys", "part.glb", "plant.lsys", "sub"]);
}

/// A derivation that runs until stopped, its output's temporary file
/// open all along (`derive` writes into it as it goes).
#[cfg(unix)]
#[test]
fn a_signal_during_a_write_removes_the_temporary_file() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        &d.join("slow.lsys"),
        "axiom: A(0) A(0) A(0) A(0) A(0) A(0) A(0) A(0)\nA(n) --> A(n+1)\n",
    );
    std::fs::create_dir(d.join("out")).unwrap();
    for (signal, code) in [("TERM", 143), ("INT", 130), ("HUP", 129)] {
        let child = lsys_cmd(
            d,
            &["derive", "slow.lsys", "-n", "2000000000", "-o", "out/s.txt"],
        )
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
        // Until the temporary file is there.
        let end = Instant::now() + Duration::from_secs(20);
        while names(&d.join("out")).is_empty() && Instant::now() < end {
            std::thread::sleep(Duration::from_millis(20));
        }
        assert!(
            names(&d.join("out"))[0].starts_with(".lsys-"),
            "{:?}",
            names(&d.join("out"))
        );
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let o = wait_within(child, 20, signal);
        assert_eq!(o.status.code(), Some(code), "SIG{signal}");
        assert!(
            names(&d.join("out")).is_empty(),
            "SIG{signal} left {:?}",
            names(&d.join("out"))
        );
    }
}

#[cfg(unix)]
#[test]
fn output_through_a_link_writes_its_target_and_keeps_the_link() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        &d.join("g.lsys"),
        "derivation length: 2\naxiom: F A\nA --> F A\n",
    );
    write(&d.join("real.txt"), "old\n");
    std::os::unix::fs::symlink("real.txt", d.join("link.txt")).unwrap();
    let o = lsys_in(d, &["derive", "g.lsys", "-o", "link.txt"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(d.join("link.txt"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(
        std::fs::read_to_string(d.join("real.txt")).unwrap(),
        "F F F A\n"
    );
    // A link to a file not there yet creates the file, keeps the link.
    std::os::unix::fs::symlink("new.glb", d.join("model.glb")).unwrap();
    let o = lsys_in(d, &["build", "g.lsys", "-o", "model.glb"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(d.join("model.glb"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(d.join("new.glb"))
        .unwrap()
        .starts_with(b"glTF"));
    // No temporaries left, nothing else made.
    assert_eq!(
        names(d),
        ["g.lsys", "link.txt", "model.glb", "new.glb", "real.txt"]
    );
}

/// `-o /dev/stdout` as root turned the machine's /dev/stdout into a
/// regular file and left the redirected output empty. Here with a link
/// of our own to what /dev/stdout links to, standard output being a
/// regular file, then a pipe.
#[cfg(target_os = "linux")]
#[test]
fn output_through_a_link_to_standard_output_reaches_it() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        &d.join("g.lsys"),
        "derivation length: 2\naxiom: F A\nA --> F A\n",
    );
    std::os::unix::fs::symlink("/proc/self/fd/1", d.join("stdout")).unwrap();
    let cap = std::fs::File::create(d.join("cap.txt")).unwrap();
    let o = lsys_cmd(d, &["derive", "g.lsys", "-o", "stdout"])
        .stdout(cap)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(d.join("cap.txt")).unwrap(),
        "F F F A\n"
    );
    assert!(std::fs::symlink_metadata(d.join("stdout"))
        .unwrap()
        .file_type()
        .is_symlink());
    let o = lsys_cmd(d, &["derive", "g.lsys", "-o", "stdout"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(String::from_utf8_lossy(&o.stdout), "F F F A\n");
    assert_eq!(names(d), ["cap.txt", "g.lsys", "stdout"]);
}

fn mkfifo(path: &Path) -> bool {
    Command::new("mkfifo")
        .arg(path)
        .status()
        .is_ok_and(|s| s.success())
}

#[cfg(unix)]
#[test]
fn a_named_pipe_without_a_reader_is_an_error_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(&d.join("g.lsys"), "axiom: F\n");
    if !mkfifo(&d.join("pipe.glb")) {
        eprintln!("skipped: no mkfifo");
        return;
    }
    for args in [
        &["derive", "g.lsys", "-o", "pipe.glb"][..],
        &["build", "g.lsys", "-o", "pipe.glb"],
    ] {
        let child = lsys_cmd(d, args).stderr(Stdio::piped()).spawn().unwrap();
        let o = wait_within(child, 20, "writing a pipe nobody reads");
        assert_eq!(o.status.code(), Some(74), "{args:?}");
        assert!(
            stderr(&o).contains("nothing is reading the named pipe pipe.glb"),
            "{}",
            stderr(&o)
        );
    }
    // With a reader it is written through, and stays a pipe.
    let reader = {
        let p = d.join("pipe.glb");
        std::thread::spawn(move || std::fs::read(p).unwrap())
    };
    // The reader opens the pipe first (a writer without one is refused).
    let end = Instant::now() + Duration::from_secs(20);
    loop {
        let o = lsys_cmd(d, &["build", "g.lsys", "-o", "pipe.glb"])
            .output()
            .unwrap();
        if o.status.success() {
            break;
        }
        assert!(Instant::now() < end, "{}", stderr(&o));
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(reader.join().unwrap().starts_with(b"glTF"));
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(d.join("pipe.glb"))
        .unwrap()
        .file_type()
        .is_fifo());
}

#[cfg(unix)]
#[test]
fn an_include_of_a_named_pipe_is_refused_unopened() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(&d.join("g.lsys"), "#include \"pipe.lsys\"\naxiom: F\n");
    if !mkfifo(&d.join("pipe.lsys")) {
        eprintln!("skipped: no mkfifo");
        return;
    }
    let child = lsys_cmd(d, &["check", "g.lsys"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let o = wait_within(child, 20, "including a pipe");
    assert_eq!(o.status.code(), Some(65));
    insta::assert_snapshot!(stderr(&o));
}

/// `lsys check /dev/stdin < big` read the pipe until memory ran out: the
/// 64 MiB limit only looked at a regular file's size.
#[cfg(target_os = "linux")]
#[test]
fn piped_input_is_read_only_up_to_the_size_limit() {
    let tmp = tempfile::tempdir().unwrap();
    let mut child = lsys_cmd(tmp.path(), &["check", "/dev/stdin"])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = child.stdin.take().unwrap();
    let feeder = std::thread::spawn(move || {
        input.write_all(b"axiom: ")?;
        let chunk = vec![b'F'; 1 << 20];
        // 80 MiB, unless lsys stops reading first (a broken pipe).
        for _ in 0..80 {
            input.write_all(&chunk)?;
        }
        Ok::<(), std::io::Error>(())
    });
    let o = wait_within(child, 60, "reading a big pipe");
    let _ = feeder.join().unwrap();
    assert_eq!(o.status.code(), Some(66), "{}", stderr(&o));
    insta::assert_snapshot!(stderr(&o));
    // Under the limit, a pipe is read as a file is.
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "printf 'axiom: F\\n' | {} check /dev/stdin",
            env!("CARGO_BIN_EXE_lsys")
        ))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_component_scaled_past_the_models_numbers_is_a_diagnostic_in_every_format() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(&d.join("big.lsys"), "axiom: F ~Box(1e308)\n");
    for out in ["big.glb", "big.obj", "big.png"] {
        let o = lsys_in(d, &["build", "big.lsys", "-o", out]);
        assert_eq!(o.status.code(), Some(65), "{out}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains("lsys::turtle::component_overflow"),
            "{out}: {err}"
        );
        assert!(!err.contains("bug in lsys"), "{out}: {err}");
    }
    assert_eq!(names(d), ["big.lsys"]);
}

/// The REPL's `:export` into the grammar it has loaded.
#[test]
fn the_repl_does_not_export_over_its_grammar() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(&d.join("g.glb"), "axiom: F\n");
    let mut child = lsys_cmd(d, &["repl", "g.glb"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b":export g.glb\n")
        .unwrap();
    let o = wait_within(child, 60, "the REPL");
    let all = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr(&o));
    assert!(all.contains("lsys::export::output_is_input"), "{all}");
    assert_eq!(
        std::fs::read_to_string(d.join("g.glb")).unwrap(),
        "axiom: F\n"
    );
}

/// A temporary file left by an earlier crash (`kill -9`) is neither
/// reused nor taken for the output, and is left alone.
#[test]
fn a_stale_temporary_file_is_never_taken_for_output() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        &d.join("g.lsys"),
        "derivation length: 2\naxiom: F A\nA --> F A\n",
    );
    write(&d.join(".lsys-AAAAAA"), "half of an old output");
    let o = lsys_in(d, &["derive", "g.lsys", "-o", "out.txt"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(d.join("out.txt")).unwrap(),
        "F F F A\n"
    );
    assert_eq!(
        std::fs::read_to_string(d.join(".lsys-AAAAAA")).unwrap(),
        "half of an old output"
    );
    assert_eq!(names(d), [".lsys-AAAAAA", "g.lsys", "out.txt"]);
}
