//! `lsys repl` and `lsys watch` through the binary: scripted sessions
//! (standard input piped, `--echo`) as insta transcripts, one of which
//! uses every command; the session API for what a transcript cannot show
//! (Ctrl-C, stochastic stepping, a file changing under `:reload`); and
//! `watch` rebuilding when a grammar or its include changes.

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::atomic::Ordering;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use lsys::internals::repl::{execute, Session, Settings};

const TREE: &str = "\
// A small parametric tree: the REPL transcripts' grammar.
#include \"params.lsys\"
derivation length: N
angle: 30
Axiom: A(1)
A(s) : s < N --> F(1) [+A(s+1)] [-A(s+1)]
A(s) : else  --> L
F(x) --> F(x*R)
homomorphism
L --> [ +F(0.3) ]
";

const PARAMS: &str = "#define N 3, R 1.5\n";

const BROKEN: &str = "Axiom: A(1)\nA(s) --> B(t)\n";

/// A directory with the grammars of the transcripts.
fn workdir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tree.lsys"), TREE).unwrap();
    std::fs::write(dir.path().join("params.lsys"), PARAMS).unwrap();
    std::fs::write(dir.path().join("broken.lsys"), BROKEN).unwrap();
    dir
}

/// Runs `lsys repl ARGS --echo` in `dir` with `script` on standard input;
/// the output with times replaced by `<t>`, and the exit code.
fn session(dir: &Path, args: &[&str], script: &str) -> (String, i32) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .arg("repl")
        .args(args)
        .arg("--echo")
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(script.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.stderr.is_empty(),
        "nothing goes to standard error: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    (redact_times(&text), out.status.code().unwrap_or(-1))
}

/// `12.5 ms` -> `<t> ms`: times differ from run to run.
fn redact_times(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find(" ms") {
        let head = &rest[..i];
        let num_start = head
            .char_indices()
            .rev()
            .take_while(|&(_, c)| c.is_ascii_digit() || c == '.')
            .last()
            .map_or(i, |(k, _)| k);
        out.push_str(&head[..num_start]);
        if num_start < i {
            out.push_str("<t>");
        } else {
            out.push_str(&head[num_start..]);
        }
        out.push_str(" ms");
        rest = &rest[i + 3..];
    }
    out.push_str(rest);
    out
}

/// Every command, in the order a user might meet them.
const TOUR: &str = "\
// the tour: every command of the table
:load tree.lsys
:help
:help goto
:defines
:rules
:step
:step 2
:diff
:count
:show
:show 2..6
:show 3
:show all
:back
:goto 3
:reset
:goto 2
// a typed production goes before the catch-all of its predecessor
A(s) : s == 2 --> F(2) A(s+1)
// an indented line continues the production just typed (and replaces it)
    [-A(s+1)]
:rules
:diff
// a line that ends inside brackets continues too
F(x) --> F(x*R) [ +
  F(x/2) ]
// the same predecessor and condition: replaced
F(x) --> F(x*R)
:rules
// modules typed are rewritten once with the current rules
A(1) F(2) L
:drop 3
:axiom A(1) F(1)
:axiom
:set N=2
:defines
:set N
:seed 7
:seed
// takes back the last edit (here `:seed 7`)
:undo
:disasm 2
:disasm
:export tree.glb
:export tree.obj
:render tree.png front
:stats
// parameters as `lsys derive --precision 2` prints them, then as before
:precision 2
:precision off
// the edits typed, written to a file the session then goes on from
:save copy.lsys
:reload
:quit
:step
";

#[test]
fn tour_of_every_command() {
    let dir = workdir();
    let (text, code) = session(dir.path(), &[], TOUR);
    insta::assert_snapshot!("tour", text);
    assert_eq!(code, 0, "every input of the tour succeeds");
    for f in ["tree.glb", "tree.obj", "tree.mtl", "tree.png"] {
        let len = std::fs::metadata(dir.path().join(f)).unwrap().len();
        assert!(len > 50, "{f} has {len} bytes");
    }
    // Every command of the table is in the tour.
    for c in lsys::internals::repl::COMMANDS {
        assert!(
            TOUR.lines().any(|l| l.starts_with(&format!(":{}", c.name))),
            ":{} is not in the tour",
            c.name
        );
    }
}

/// Issue 16: a typed rule that an earlier, more general one shadows is
/// reported (and marked by `:rules`); `:undo` takes edits back one by
/// one; `:export` to a folder that does not exist names the path given.
#[test]
fn shadowed_rules_undo_and_bad_export_paths() {
    let dir = workdir();
    let script = "\
// `s < N` holds wherever `s < 2` does: the new rule can never apply
A(s) : s < 2 --> F(9)
// a context does not help when the earlier rule has none
L < A(s) : s < N --> F(8)
:rules
// a narrower rule before the general one is fine
:drop 1
:rules
:undo
:undo
:undo
:rules
:undo
:set N=2
:axiom A(2)
:undo
:undo
:defines
:export no/such/folder/tree.obj
";
    let (text, code) = session(dir.path(), &["tree.lsys"], script);
    insta::assert_snapshot!("shadowed_undo_export", text);
    assert_eq!(
        code, 65,
        "the failed :undo and :export make the exit code 65"
    );
}

#[test]
fn errors_never_end_the_session_nor_lose_its_state() {
    let dir = workdir();
    let script = "\
:step 2
:zz
:s
:goto x
:drop 99
A(s) --> F(s,)
A(s) --> F(t)
A
:set Z=1
:export tree.stl
:render tree.glb
:load missing.lsys
:load broken.lsys
:reload
// still the tree, still at step 2
:show
// a production that fails at run time: kept, the derivation stops
F(x) : x > 1.2 --> F(x/(x-x))
:rules
:step
:drop 4
:step
";
    let (text, code) = session(dir.path(), &["tree.lsys"], script);
    insta::assert_snapshot!("errors", text);
    assert_eq!(code, 65, "a scripted session with errors exits 65");
}

#[test]
fn a_stray_bracket_at_export_names_the_step_that_wrote_it() {
    let dir = workdir();
    std::fs::write(
        dir.path().join("late.lsys"),
        "derivation length: 4\nAxiom: A(0)\n\
         A(n) : n < 2 --> F A(n+1)\nA(n) : n >= 2 --> F ] A(n+1)\n",
    )
    .unwrap();
    // Step 4 has two stray `]`; the first was written by step 3.
    let (out, code) = session(dir.path(), &["late.lsys"], ":goto 4\n:export late.glb\n");
    assert!(out.contains("first written by derivation step 3"), "{out}");
    assert_eq!(code, 65, "{out}");
    assert!(!dir.path().join("late.glb").exists());
}

#[test]
fn a_session_can_start_from_nothing() {
    let dir = workdir();
    let script = "\
:step
F --> F F
:axiom F X
X --> F [+X] [-X]
:step 2
:rules
:count
";
    let (text, code) = session(dir.path(), &[], script);
    insta::assert_snapshot!("from_nothing", text);
    assert_eq!(code, 65, "the first `:step` has no grammar");
}

#[test]
fn stochastic_steps_repeat_after_going_back() {
    let mut s = Session::new(Settings::default());
    s.start("examples/abop/stochastic_1_27.lsys", 0).unwrap();
    let straight = s.goto(5).unwrap();
    s.goto(2).unwrap();
    execute(&mut s, ":step 3");
    assert_eq!(s.goto(5).unwrap(), straight);
    // Derived again from the axiom after an edit undone, still the same.
    assert!(execute(&mut s, ":seed 1").ok);
    assert_eq!(s.goto(5).unwrap(), straight);
    assert!(execute(&mut s, ":seed 2").ok);
    assert_ne!(s.goto(5).unwrap(), straight);
}

#[test]
fn an_interrupt_stops_the_derivation_between_steps() {
    let mut s = Session::new(Settings::default());
    s.start("examples/abop/fig1_24d.lsys", 0).unwrap();
    s.interrupt_flag().store(true, Ordering::SeqCst);
    let e = s.goto(6).unwrap_err();
    assert!(e.starts_with("interrupted: stopped at step 0"), "{e}");
    assert_eq!(s.step(), 0);
    // The flag is spent: the next command derives.
    assert!(execute(&mut s, ":goto 6").ok);
    assert_eq!(s.step(), 6);
}

#[test]
fn reload_reads_the_changed_file_and_keeps_the_grammar_on_errors() {
    let dir = workdir();
    let tree = dir.path().join("tree.lsys");
    let mut s = Session::new(Settings::default());
    s.start(tree.to_str().unwrap(), 2).unwrap();
    let before = execute(&mut s, ":show all").text;
    std::fs::write(&tree, TREE.replace("[-A(s+1)]", "[-A(t)]")).unwrap();
    let r = execute(&mut s, ":reload");
    assert!(!r.ok, "t is unknown: {}", r.text);
    assert!(
        r.text.contains("keeping the previous grammar"),
        "{}",
        r.text
    );
    assert_eq!(execute(&mut s, ":show all").text, before);
    std::fs::write(&tree, TREE.replace("F(1) [", "F(2) [")).unwrap();
    let r = execute(&mut s, ":reload");
    assert!(r.ok, "{}", r.text);
    assert_eq!(s.step(), 2, "the step is kept");
    assert!(execute(&mut s, ":show all").text.starts_with("F(3)"));
}

/// Lines of a child's standard output, as they come.
fn lines_of(stdout: std::process::ChildStdout) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

/// The next line that starts with `prefix`, within a generous time.
fn expect_line(rx: &mpsc::Receiver<String>, prefix: &str) -> String {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(l) if l.starts_with(prefix) => return l,
            Ok(_) => {}
            Err(e) => panic!("no line starting with `{prefix}`: {e}"),
        }
    }
}

#[test]
fn watch_rebuilds_when_the_grammar_or_an_include_changes() {
    let dir = workdir();
    let mut child = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(["watch", "tree.lsys", "-o", "out.obj"])
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let rx = lines_of(child.stdout.take().unwrap());
    let modules = |line: &str| -> usize {
        let after = line.split(": ").nth(1).unwrap();
        after.split(' ').next().unwrap().parse().unwrap()
    };
    let first = expect_line(&rx, "wrote out.obj: ");
    assert_eq!(modules(&first), 37, "{first}");
    // The include changes: N 3 -> 4 makes a bigger tree.
    std::thread::sleep(Duration::from_millis(300));
    std::fs::write(dir.path().join("params.lsys"), "#define N 4, R 1.5\n").unwrap();
    let second = expect_line(&rx, "wrote out.obj: ");
    assert_eq!(modules(&second), 81, "{second}");
    // The grammar itself changes, saved the way editors do: a new file
    // renamed over the old one.
    std::thread::sleep(Duration::from_millis(300));
    let tmp = dir.path().join(".tree.lsys.swp");
    std::fs::write(
        &tmp,
        TREE.replace("derivation length: N", "derivation length: 1"),
    )
    .unwrap();
    std::fs::rename(&tmp, dir.path().join("tree.lsys")).unwrap();
    let third = expect_line(&rx, "wrote out.obj: ");
    assert_eq!(modules(&third), 9, "{third}");
    child.kill().unwrap();
    child.wait().unwrap();
}

#[test]
fn cpfg_dialect_strings_show_f32_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let thirds = dir.path().join("thirds.l");
    std::fs::write(
        &thirds,
        "derivation length: 2\naxiom: I(1) F(0.1)\nI(x) --> I(x*1.1+1/3)\nF(x) --> F(x/3)\n",
    )
    .unwrap();
    let mut s = Session::new(Settings::default());
    s.start(thirds.to_str().unwrap(), 2).unwrap();
    // Stored as f32s: shown in the f32's shortest form.
    assert_eq!(execute(&mut s, ":show all").text, "I(1.91) F(0.011111111)");
    assert!(execute(&mut s, ":show")
        .text
        .ends_with("\nI(1.91) F(0.011111111)"));
    let d = execute(&mut s, ":diff").text;
    assert!(
        d.contains("«I(1.4333333) F(0.033333335) → I(1.91) F(0.011111111)»"),
        "{d}"
    );
    let r = execute(&mut s, "I(1.4333333)").text;
    assert_eq!(r, "I(1.91)");
}

/// `:save` writes the typed edits and the defines set into the file, the
/// session goes on from it; `:reload` after a failed `:load` reads the
/// grammar in use; `:precision` prints as `lsys derive --precision`.
#[test]
fn save_precision_and_reload_after_a_failed_load() {
    let dir = workdir();
    let g = dir.path().join("g.lsys");
    std::fs::write(
        &g,
        "#define K 2\nderivation length: 1\nAxiom: A(0.1) B\nA(x) --> A(x*0.75*K)\n",
    )
    .unwrap();
    let mut s = Session::new(Settings::default());
    s.start(g.to_str().unwrap(), 1).unwrap();
    assert!(execute(&mut s, ":show all")
        .text
        .contains("A(0.15000000000000002)"));
    let r = execute(&mut s, ":precision 3");
    assert!(r.ok && r.text.contains("A(0.15) B"), "{}", r.text);
    assert!(!execute(&mut s, ":precision x").ok);
    assert!(execute(&mut s, "B --> C").ok);
    assert!(execute(&mut s, ":set K=5").ok);
    let saved = dir.path().join("saved.lsys");
    let r = execute(&mut s, &format!(":save {}", saved.display()));
    assert!(r.ok, "{}", r.text);
    assert_eq!(
        std::fs::read_to_string(&saved).unwrap(),
        "#define K 5\nderivation length: 1\nAxiom: A(0.1) B\nA(x) --> A(x*0.75*K)\nB --> C\n"
    );
    assert!(r.text.contains("A(0.375) C"), "{}", r.text);
    // A failed :load keeps the grammar, and :reload reads the saved file.
    let r = execute(&mut s, ":load nothere.lsys");
    assert!(
        !r.ok && r.text.contains("keeping the previous grammar"),
        "{}",
        r.text
    );
    let r = execute(&mut s, ":reload");
    assert!(r.ok && r.text.contains("loaded"), "{}", r.text);
    assert!(r.text.contains("saved.lsys"), "{}", r.text);
    assert!(execute(&mut s, ":precision off")
        .text
        .contains("A(0.37500000000000006) C"));
    // Not over a file the grammar includes; std: grammars need a name.
    std::fs::write(dir.path().join("inc.lsys"), "#define J 1\n").unwrap();
    std::fs::write(&g, "#include \"inc.lsys\"\nAxiom: F(J)\n").unwrap();
    assert!(execute(&mut s, &format!(":load {}", g.display())).ok);
    let inc = dir.path().join("inc.lsys");
    let r = execute(&mut s, &format!(":save {}", inc.display()));
    assert!(!r.ok, "{}", r.text);
    assert_eq!(std::fs::read_to_string(&inc).unwrap(), "#define J 1\n");
    assert!(execute(&mut s, ":load std:toukung").ok || execute(&mut s, ":load std:pailou").ok);
    assert!(!execute(&mut s, ":save").ok);
}
