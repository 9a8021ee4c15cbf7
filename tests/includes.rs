//! `#include` confinement on real folders: a symbolic link that leads out
//! of the grammar's folder is refused without showing the target's text,
//! and `--include-dir` folders are searched and allowed.

use std::path::Path;

use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline;

fn compile(root: &Path, include_dirs: &[&Path]) -> Result<String, String> {
    let opts = Options {
        include_dirs: include_dirs.iter().map(|d| d.to_path_buf()).collect(),
        ..Options::default()
    };
    match pipeline::compile(&Input::Path(root.to_path_buf()), &opts) {
        Ok(c) => Ok(c
            .program
            .defines
            .iter()
            .map(|d| format!("{}={:?};", d.name, d.value))
            .collect()),
        Err(d) => Err(d.render_plain()),
    }
}

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

#[cfg(unix)]
#[test]
fn a_link_out_of_the_folder_is_refused_and_its_text_not_shown() {
    let tmp = tempfile::tempdir().unwrap();
    let secret = tmp.path().join("elsewhere/secret.txt");
    write(&secret, "password: hunter2\n");
    let root = tmp.path().join("grammar/main.lsys");
    write(&root, "#include \"inc/params.lsys\"\nAxiom: F\n");
    std::fs::create_dir_all(tmp.path().join("grammar/inc")).unwrap();
    std::os::unix::fs::symlink(&secret, tmp.path().join("grammar/inc/params.lsys")).unwrap();
    let err = compile(&root, &[]).unwrap_err();
    assert!(err.contains("lsys::load::include_outside"), "{err}");
    assert!(!err.contains("hunter2"), "{err}");
    // Allowing the folder with --include-dir lets it in (and it is then an
    // ordinary, if broken, source).
    let err = compile(&root, &[&tmp.path().join("elsewhere")]).unwrap_err();
    assert!(!err.contains("include_outside"), "{err}");
}

#[test]
fn include_dirs_are_searched_after_the_including_folder_and_allowed() {
    let tmp = tempfile::tempdir().unwrap();
    let lib = tmp.path().join("lib");
    write(&lib.join("common.lsys"), "#define LEN 3\n");
    write(&lib.join("local.lsys"), "#define WHERE 2\n");
    let root = tmp.path().join("grammar/main.lsys");
    write(
        &root,
        "#include \"common.lsys\"\n#include \"local.lsys\"\nderivation length: LEN\nAxiom: F\n",
    );
    // Beside the grammar wins over the include folder.
    write(&tmp.path().join("grammar/local.lsys"), "#define WHERE 1\n");

    let err = compile(&root, &[]).unwrap_err();
    assert!(err.contains("lsys::load::include_not_found"), "{err}");
    let ok = compile(&root, &[&lib]).unwrap();
    assert_eq!(ok, "LEN=Some(3.0);WHERE=Some(1.0);");

    // A path that climbs out of the grammar's folder is fine when it lands
    // in an --include-dir, refused otherwise.
    write(&root, "#include \"../lib/common.lsys\"\nAxiom: F\n");
    let err = compile(&root, &[]).unwrap_err();
    assert!(err.contains("lsys::load::include_outside"), "{err}");
    assert!(err.contains("--include-dir"), "{err}");
    compile(&root, &[&lib]).unwrap();
}

/// The command line passes `--include-dir`, `--max-include-depth` and
/// `--max-nesting` through to the compiler.
#[test]
fn the_command_line_options_reach_the_compiler() {
    let tmp = tempfile::tempdir().unwrap();
    let lib = tmp.path().join("lib");
    write(&lib.join("common.lsys"), "#define LEN 3\n");
    let root = tmp.path().join("grammar/main.lsys");
    write(
        &root,
        "#include \"common.lsys\"\nderivation length: LEN\nAxiom: F((1))\nF --> FF\n",
    );
    let lsys = |args: &[&str]| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_lsys"))
            .args(args)
            .env("NO_COLOR", "1")
            .output()
            .unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let root = root.to_str().unwrap();
    let lib = lib.to_str().unwrap();
    let (code, err) = lsys(&["check", root]);
    assert_eq!(code, Some(65), "{err}");
    assert!(err.contains("include_not_found"), "{err}");
    let (code, err) = lsys(&["check", "--include-dir", lib, root]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = lsys(&[
        "check",
        "--include-dir",
        lib,
        "--max-include-depth",
        "1",
        root,
    ]);
    assert_eq!(code, Some(65), "{err}");
    assert!(err.contains("--max-include-depth"), "{err}");
    let (code, err) = lsys(&["check", "--include-dir", lib, "--max-nesting", "1", root]);
    assert_eq!(code, Some(65), "{err}");
    assert!(err.contains("--max-nesting"), "{err}");
}

/// A file larger than a grammar can be (a log, a disk image) is refused
/// unread, as the grammar and as an include: nothing is loaded into memory.
#[test]
fn huge_files_are_refused_unread() {
    let tmp = tempfile::tempdir().unwrap();
    let big = tmp.path().join("big.lsys");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(lsys::internals::load::MAX_SOURCE_BYTES + 1)
        .unwrap(); // sparse
    let err = compile(&big, &[]).unwrap_err();
    assert!(err.contains("lsys::load::input_not_source"), "{err}");
    assert!(err.contains("67108865 bytes long"), "{err}");
    let root = tmp.path().join("main.lsys");
    write(&root, "#include \"big.lsys\"\nAxiom: F\n");
    let err = compile(&root, &[]).unwrap_err();
    assert!(err.contains("lsys::load::include_not_source"), "{err}");
}

/// A cpfg file's includes go through the C preprocessor, which finds them
/// with the same finder: a file over the limit is refused unread there too.
#[test]
fn huge_cpfg_includes_are_refused_unread() {
    let tmp = tempfile::tempdir().unwrap();
    let big = tmp.path().join("big.h");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(lsys::internals::load::MAX_SOURCE_BYTES + 1)
        .unwrap(); // sparse
    let root = tmp.path().join("main.l");
    write(
        &root,
        "#include \"big.h\"\nLsystem: 1\nAxiom: F\nendlsystem\n",
    );
    let err = compile(&root, &[]).unwrap_err();
    assert!(err.contains("lsys::preprocess::include_not_found"), "{err}");
    assert!(err.contains("67108865 bytes"), "{err}");
    assert!(err.contains("not an L-system source"), "{err}");
}

#[test]
fn a_failed_compilation_names_every_file_it_read() {
    // `lsys watch` watches these after a failed build, so that fixing the
    // include (not only the root) rebuilds.
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("g.lsys");
    write(&root, "#include \"part.lsys\"\naxiom: A\n");
    write(&dir.path().join("part.lsys"), "A --> B(\n");
    let err = match pipeline::compile(&Input::Path(root.clone()), &Options::default()) {
        Ok(_) => panic!("the include has a syntax error"),
        Err(e) => e,
    };
    let names: Vec<String> = err
        .files()
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["g.lsys", "part.lsys"]);
}

/// A misspelt library name, on the command line or in an `#include`, is
/// answered with the name meant, written as it would be there.
#[test]
fn misspelt_library_names_get_the_name_meant() {
    let opts = Options::default();
    let std_err = match pipeline::compile(&Input::Std("toukung-side".into()), &opts) {
        Ok(_) => panic!("std:toukung-side compiled"),
        Err(d) => d.render_plain(),
    };
    assert!(
        std_err.contains("did you mean `std:toukung_side`?"),
        "{std_err}"
    );
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("g.lsys");
    write(&root, "#include <pailu>\naxiom: F\n");
    let include_err = compile(&root, &[]).unwrap_err();
    assert!(
        include_err.contains("did you mean `#include <pailou>`?"),
        "{include_err}"
    );
    write(&root, "#include <nothing_like_it>\naxiom: F\n");
    let far = compile(&root, &[]).unwrap_err();
    assert!(!far.contains("did you mean"), "{far}");
    assert!(far.contains("the standard library has: "), "{far}");
}

/// A folder given as the grammar is refused by name, with the grammars
/// it holds (the first five) or the news that it holds none.
#[test]
fn a_folder_is_not_a_grammar() {
    let dir = tempfile::tempdir().unwrap();
    let err = compile(dir.path(), &[]).unwrap_err();
    assert!(err.contains("lsys::load::input_is_folder"), "{err}");
    assert!(err.contains("is a folder, not a grammar"), "{err}");
    assert!(err.contains("this folder holds none"), "{err}");
    for name in ["b.lsys", "a.lsys", "notes.txt", "c.l"] {
        write(&dir.path().join(name), "axiom: F\n");
    }
    let err = compile(dir.path(), &[]).unwrap_err();
    assert!(
        err.contains("give lsys one of its grammars: a.lsys, b.lsys, c.l"),
        "{err}"
    );
    for k in 0..6 {
        write(&dir.path().join(format!("g{k}.lsys")), "axiom: F\n");
    }
    let err = compile(dir.path(), &[]).unwrap_err();
    assert!(
        err.contains("one of its 9 grammars: a.lsys, b.lsys, c.l, g0.lsys, g1.lsys, ..."),
        "{err}"
    );
}
