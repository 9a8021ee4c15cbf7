//! Bounded time and memory (issue 36): inputs that grew without bound
//! before now end with an answer, run under a memory limit (`ulimit -v`)
//! and a CPU-time limit (`ulimit -t`), so that a regression aborts or is
//! killed instead of taking the machine. The limits are far above what
//! the inputs need now and far below what they took before.

mod common;

use std::path::Path;
use std::process::{Command, Output};

/// Runs `lsys ARGS` in `dir` with at most `mib` MiB of address space and
/// `cpu_s` seconds of CPU time.
fn lsys_limited(dir: &Path, mib: u64, cpu_s: u64, args: &[&str]) -> Output {
    // The command line runs on a 256 MiB stack thread: address space, not
    // memory used, so the limit leaves room for it.
    // One limit per `ulimit`: dash takes no more, and a refused `ulimit`
    // must not let the command run without one.
    let script = format!(
        "ulimit -v {} && ulimit -t {cpu_s} && exec \"$0\" \"$@\"",
        (mib + 512) * 1024
    );
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("sh runs")
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// 10,000 defines, each naming the one before: the expansion stack was
/// copied at each level (50 million names, an abort past 2 GB).
#[test]
fn a_long_chain_of_defines_is_linear() {
    let dir = tempfile::tempdir().unwrap();
    let mut g = String::from("#define D0 1\n");
    for i in 1..=10_000 {
        g.push_str(&format!("#define D{i} (D{} + 1)\n", i - 1));
    }
    g.push_str("Axiom: A(D10000)\nderivation length: 1\nA(x) --> B(x)\n");
    std::fs::write(dir.path().join("chain.lsys"), g).unwrap();
    // `check` evaluates every define for its report, as well.
    let o = lsys_limited(dir.path(), 512, 120, &["check", "chain.lsys"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = lsys_limited(dir.path(), 512, 120, &["derive", "chain.lsys"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(String::from_utf8_lossy(&o.stdout).trim(), "B(10001)");
}

/// Each file includes the next twice, 30 deep: 2^30 inclusions within
/// the depth limit. The run stops at the inclusion limit.
#[test]
fn a_diamond_of_includes_stops_at_the_inclusion_limit() {
    let dir = tempfile::tempdir().unwrap();
    for i in 0..30 {
        let next = format!("#include \"f{}.lsys\"\n", i + 1);
        std::fs::write(dir.path().join(format!("f{i}.lsys")), next.repeat(2)).unwrap();
    }
    std::fs::write(dir.path().join("f30.lsys"), "// the last one\n").unwrap();
    std::fs::write(
        dir.path().join("main.lsys"),
        "#include \"f0.lsys\"\nAxiom: A\nA --> A B\n",
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 512, 120, &["check", "main.lsys"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    assert_eq!(t.matches("lsys::load::include_limit").count(), 1, "{t}");
    assert!(t.contains("10001 files"), "{t}");
    assert!(t.contains("f29.lsys:2:10"), "{t}");
}

/// The same through cpfg's preprocessor (a `.l` model).
#[test]
fn a_diamond_of_cpfg_includes_stops_at_the_inclusion_limit() {
    let dir = tempfile::tempdir().unwrap();
    for i in 0..30 {
        let next = format!("#include \"f{}.h\"\n", i + 1);
        std::fs::write(dir.path().join(format!("f{i}.h")), next.repeat(2)).unwrap();
    }
    std::fs::write(dir.path().join("f30.h"), "/* the last one */\n").unwrap();
    std::fs::write(
        dir.path().join("main.l"),
        "#include \"f0.h\"\nlsystem: 1\nderivation length: 1\nAxiom: A\nA --> AB\nendlsystem\n",
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 512, 120, &["check", "main.l"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    assert_eq!(
        t.matches("lsys::preprocess::include_limit").count(),
        1,
        "{t}"
    );
}

/// A cpfg axiom of 200,000 letters is one word split into modules: the
/// split tried every prefix of the rest of the word (cubic: 20,000
/// letters took 260 s).
#[test]
fn a_long_cpfg_word_is_split_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let axiom = "FG".repeat(100_000);
    std::fs::write(
        dir.path().join("long.l"),
        format!("lsystem: 1\nderivation length: 1\nAxiom: {axiom}\nG --> H\nendlsystem\n"),
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 512, 60, &["derive", "long.l"]);
    assert!(o.status.success(), "{}", text(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let modules: Vec<&str> = out.split_whitespace().collect();
    assert_eq!(modules.len(), 200_000);
    assert_eq!(modules[..4], ["F", "H", "F", "H"]);
}

/// 20,000 syntax errors, each printed with its snippet: miette found each
/// label's line by walking the file from its start (quadratic: 12 s).
#[test]
fn many_errors_print_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let mut g = String::from("Axiom: A\n");
    for i in 0..20_000 {
        g.push_str(&format!("A{i} --> )\n"));
    }
    std::fs::write(dir.path().join("errors.lsys"), g).unwrap();
    let o = lsys_limited(dir.path(), 512, 60, &["check", "errors.lsys"]);
    let t = text(&o);
    assert_eq!(
        o.status.code(),
        Some(65),
        "{}",
        &t[t.len().saturating_sub(2000)..]
    );
    assert!(
        t.contains("errors.lsys: 20000 errors\n"),
        "{}",
        &t[t.len() - 300..]
    );
    // The last error still shows its own line, numbered.
    assert!(
        t.contains("─[errors.lsys:20001:12]"),
        "{}",
        &t[t.len() - 800..]
    );
    assert!(
        t.contains("20001 │ A19999 --> )"),
        "{}",
        &t[t.len() - 800..]
    );
}

/// An axiom line of 4 MiB is parsed in pieces (src/parse/long_axiom.rs):
/// the same modules as parsed whole, in far less memory (pest's queue
/// for the whole statement took 200 bytes per input byte).
#[test]
fn a_long_axiom_is_parsed_in_pieces_with_the_same_modules() {
    let dir = tempfile::tempdir().unwrap();
    let unit = "A(1,2) [ +(30) F(0.5) ] B(-1) ~X(2) ";
    let n = (4 << 20) / unit.len();
    std::fs::write(
        dir.path().join("long.lsys"),
        format!("Axiom: {}\n  C(7)\nA(x,y) --> A(x+1,y)\n", unit.repeat(n)),
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 768, 120, &["derive", "-n", "1", "long.lsys"]);
    assert!(o.status.success(), "{}", text(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let want = "A(2,2) [ +(30) F(0.5) ] B(-1) ~X(2) ".repeat(n) + "C(7)";
    assert_eq!(out.trim().len(), want.len());
    assert!(out.trim() == want, "the modules differ from the axiom's");
}

/// A plain axiom of 8 MiB (`F F F ...`, 4 M modules) derives in 32 bytes
/// of memory per input byte: the limit is its 256 MiB plus the room every
/// run takes. The pieces' tokens are dropped as each is resolved, and the
/// resolved axiom keeps 24 bytes a module (it took 80 bytes a byte).
#[test]
fn a_plain_axiom_takes_at_most_32_bytes_a_byte() {
    let dir = tempfile::tempdir().unwrap();
    let n = 4 << 20;
    std::fs::write(
        dir.path().join("plain.lsys"),
        format!("Axiom: {}\n", "F ".repeat(n)),
    )
    .unwrap();
    let o = lsys_limited(
        dir.path(),
        256,
        300,
        &["derive", "-n", "0", "plain.lsys", "-o", "out.txt"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let out = std::fs::read_to_string(dir.path().join("out.txt")).unwrap();
    assert_eq!(out.split_whitespace().count(), n);
    assert!(out.split_whitespace().all(|m| m == "F"));
}

/// Brackets pair up across the pieces of a long axiom: a branch opened in
/// the first piece and closed in the last is no warning, and a `]` that
/// closes nothing is still the axiom's error, at its column.
#[test]
fn brackets_pair_across_the_pieces_of_a_long_axiom() {
    let dir = tempfile::tempdir().unwrap();
    let body = "F ".repeat(1 << 20);
    std::fs::write(dir.path().join("ok.lsys"), format!("Axiom: [ {body}]\n")).unwrap();
    std::fs::write(dir.path().join("bad.lsys"), format!("Axiom: {body}] F\n")).unwrap();
    let o = lsys_limited(dir.path(), 512, 120, &["check", "ok.lsys"]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(!t.contains("never closed"), "{t}");
    let o = lsys_limited(dir.path(), 512, 120, &["check", "bad.lsys"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    let col = "Axiom: ".len() + body.len() + 1;
    assert!(t.contains("a `]` with no `[` before it"), "{t}");
    assert!(t.contains(&format!("bad.lsys:1:{col}")), "{t}");
}

/// A mistake at the end of such a line is reported as before, at its
/// column: a piece that does not parse leaves the line to the parser.
#[test]
fn a_mistake_in_a_long_axiom_is_located() {
    let dir = tempfile::tempdir().unwrap();
    let unit = "A(1,2) [ +(30) F(0.5) ] B ";
    let n = (2 << 20) / unit.len();
    std::fs::write(
        dir.path().join("long.lsys"),
        format!("Axiom: {} F (1)\n", unit.repeat(n)),
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 1024, 120, &["check", "long.lsys"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    let col = "Axiom: ".len() + unit.len() * n + 4;
    assert!(
        t.contains(&format!("at long.lsys:1:{col} (a line too long to show)")),
        "{t}"
    );
    assert!(t.contains("write `F(1)`, not `F (1)`"), "{t}");
}

/// Function-like macros of cpfg's preprocessor that multiply their
/// argument (10 copies, nested): the expansions stop at the run's token
/// budget with one located error (50 million tokens took 3.7 GB before).
#[test]
fn a_function_macro_bomb_stops_at_the_token_budget() {
    let dir = tempfile::tempdir().unwrap();
    let mut g = String::from(
        "#define A0(x) x x x x x x x x x x\n#define A1(x) A0(A0(x))\n#define A2(x) A1(A1(x))\n#define A3(x) A2(A2(x))\n#define A4(x) A3(A3(x))\nlsystem: 1\nderivation length: 1\nAxiom: F\n",
    );
    for _ in 0..40 {
        g.push_str("F --> A4(F)\n");
    }
    g.push_str("endlsystem\n");
    std::fs::write(dir.path().join("bomb.l"), g).unwrap();
    let o = lsys_limited(dir.path(), 1024, 120, &["check", "bomb.l"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{}", &t[..t.len().min(3000)]);
    assert!(
        t.contains("lsys::preprocess::recursion"),
        "{}",
        &t[..t.len().min(3000)]
    );
}

/// A curve's control point with multiplicity 1e8 was copied 10^8 times
/// (an abort past 1.6 GB); now it is refused with the file's line.
#[test]
fn a_curve_point_multiplicity_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/cpfg/curve");
    for f in ["arc.l", "arc.v"] {
        std::fs::copy(fixture.join(f), dir.path().join(f)).unwrap();
    }
    let con = std::fs::read_to_string(fixture.join("arc.con")).unwrap();
    let bomb = con.replace("\n1 0 0 1\n", "\n1 0 0 100000000\n");
    assert_ne!(con, bomb);
    std::fs::write(dir.path().join("arc.con"), bomb).unwrap();
    let o = lsys_limited(dir.path(), 512, 60, &["derive", "arc.l"]);
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(
        t.contains("multiplicity is at most 16, found 100000000"),
        "{t}"
    );
    assert!(t.contains("arc.con"), "{t}");
}

/// cpfg's loop limit counted the rounds of one run of a block: a `while`
/// of 9 million rounds in a block applied to each of 200 modules ran
/// 1.8 billion rounds. The limit now counts a whole step.
#[test]
fn the_loop_limit_counts_a_whole_step() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("loops.l"),
        format!(
            "lsystem: 1\nderivation length: 1\nAxiom: {}\nB : {{ i = 0; while (i < 9000000) {{ i = i + 1; }} }} --> B\nendlsystem\n",
            "B".repeat(200)
        ),
    )
    .unwrap();
    let o = lsys_limited(dir.path(), 512, 60, &["derive", "loops.l"]);
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(t.contains("lsys::derive::endless_loop"), "{t}");
    assert!(t.contains("more than 10000000 times in the step"), "{t}");
}

/// Three nested repeats of 1,000 pieces each (each under the limit of one
/// repeat) asked for 10^9 blocks and aborted past 2.8 GB: the pieces of
/// all splits of a model are capped together.
#[test]
fn nested_repeats_stop_at_the_piece_limit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("nested.lsys"),
        "Axiom: @Scope(1000,1000,1000) @RX(1) [ @RY(1) [ @RZ(1) [ @Block ] ] ]\n",
    )
    .unwrap();
    let o = lsys_limited(
        dir.path(),
        1024,
        120,
        &["build", "nested.lsys", "-o", "n.glb"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    assert!(t.contains("lsys::turtle::piece_limit"), "{t}");
    assert!(!dir.path().join("n.glb").exists());
}

/// `--max-triangles 1000` on a million blocks: the shapes are counted as
/// they are made, not after all of them are collected (0.9 GB before).
#[test]
fn the_triangle_limit_stops_the_turtle_early() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("blocks.lsys"),
        "Axiom: @Scope(100,100,100) @RX(1) [ @RY(1) [ @RZ(1) [ @Block ] ] ]\n",
    )
    .unwrap();
    let args = [
        "build",
        "blocks.lsys",
        "-o",
        "b.glb",
        "--max-triangles",
        "1000",
    ];
    let o = lsys_limited(dir.path(), 128, 60, &args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(65), "{t}");
    assert!(t.contains("lsys::turtle::too_many_triangles"), "{t}");
    assert!(
        t.contains("1001, and every shape is at least one triangle"),
        "{t}"
    );
}

/// 10,000 seeds in one guide: every query scanned every element of the
/// guide (5,000 seeds took 15 s, 20,000 over two minutes, release build);
/// the pass's grid keeps each query to the elements near it.
#[test]
fn many_guided_seeds_take_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/guided/line.lsys"),
        dir.path().join("line.lsys"),
    )
    .unwrap();
    let mut scene = String::from(
        "steps = 10\n\n[[guide]]\nname = \"g\"\ngrammar = \"line.lsys\"\n\
         points = [[0, 0], [700, 0], [700, 700], [0, 700]]\n",
    );
    for k in 0..10_000 {
        let (i, j) = (k % 100, k / 100);
        scene.push_str(&format!(
            "\n[[seeds]]\nguide = \"g\"\nposition = [{}, {}]\nheading = {}\n",
            3 + 7 * i,
            3 + 7 * j,
            (k * 37) % 360
        ));
    }
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let o = lsys_limited(
        dir.path(),
        1024,
        60,
        &["build", "scene.toml", "-o", "out.obj", "--stats"],
    );
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("\"seeds\":10000"), "{t}");
}

/// The string limits are checked as a step is written: a grammar that
/// multiplies its string twelvefold a step stops at the default module
/// limit (50 million, about 480 MB at its peak), and one of 8-parameter
/// modules at a parameter limit of 50 million (400 MB of values), both
/// with their located error inside 1 GiB instead of aborting.
#[test]
fn the_string_limits_stop_a_derivation_before_its_memory_runs_out() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/derive/err/module_limit.lsys"),
        dir.path().join("modules.lsys"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("params.lsys"),
        "derivation length: 40\nAxiom: A(1,2,3,4,5,6,7,8)\n\
         A(a,b,c,d,e,f,g,h) --> A(a,b,c,d,e,f,g,h) A(b,c,d,e,f,g,h,a)\n",
    )
    .unwrap();
    for (args, code) in [
        (
            &["derive", "modules.lsys"][..],
            "lsys::derive::module_limit",
        ),
        (
            &["derive", "params.lsys", "--max-params", "50000000"][..],
            "lsys::derive::param_limit",
        ),
    ] {
        let o = lsys_limited(dir.path(), 1024, 300, args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(65), "{args:?}: {t}");
        assert!(t.contains(code), "{args:?}: {t}");
    }
}
