//! The documentation's examples, run: every block in `README.md` and
//! `docs/*.md` that shows what `lsys` prints is run and compared, so the
//! pages cannot drift from the program.
//!
//! Which blocks are examples (a fenced block is one example):
//! * a `text` block whose first line is `$ lsys ARGS`: the command, run in
//!   a scratch folder where `examples/`, `grammar/` and `tests/` are the
//!   repository's; the other lines are what it prints (standard output,
//!   then standard error). A file named in ARGS that is not in the
//!   repository is the nearest `lsys` block above. For `lsys repl`, lines
//!   starting with the prompt `lsys[N]> ` are typed (with the indented
//!   lines that continue an unclosed bracket) and the rest is printed;
//!   `lsys watch` is stopped after the lines shown;
//! * a `text` block starting with a diagnostic (`×`, `⚠`) right after an
//!   `lsys` block: what `lsys check` says about that block. The lines
//!   shown must appear in this order in the output (the page may leave
//!   out the source snippet);
//! * any block preceded by `<!-- doc-test: $ lsys ARGS -->`: that
//!   command's output.
//!
//! JSON output is compared without white space, so a page may wrap it.
//! In expected output, `...` (or `…`) stands for any text, line breaks
//! included: times, sizes that vary by platform, long output cut short
//! (an ellipsis ending or starting a line also takes the line break).
//! Every other `lsys` block must pass `lsys check` without a word.
//! A block that looks like an example but cannot be run here carries
//! `<!-- doc-test: not run: REASON -->`; a block that looks like an
//! example is never skipped silently.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// One fenced block of a page.
struct Block {
    lang: String,
    line: usize,
    body: Vec<String>,
    /// The `<!-- doc-test: ... -->` comment right above it, if any.
    marker: Option<String>,
}

fn blocks(text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut marker: Option<String> = None;
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i];
        if let Some(m) = l
            .trim()
            .strip_prefix("<!-- doc-test:")
            .and_then(|m| m.strip_suffix("-->"))
        {
            marker = Some(m.trim().to_string());
        } else if let Some(lang) = l.strip_prefix("```") {
            let start = i;
            let mut body = Vec::new();
            i += 1;
            while i < lines.len() && !lines[i].starts_with("```") {
                body.push(lines[i].to_string());
                i += 1;
            }
            out.push(Block {
                lang: lang.trim().to_string(),
                line: start + 1,
                body,
                marker: marker.take(),
            });
        } else if !l.trim().is_empty() {
            marker = None;
        }
        i += 1;
    }
    out
}

/// What a block asks the harness to do.
enum Example {
    /// Run each command, compare everything it prints with its text.
    Run(Vec<Shown>),
    /// `lsys check` the `lsys` block above; `expected`'s lines in order.
    Check { expected: Vec<String> },
}

fn looks_like_output(b: &Block) -> bool {
    let first = b.body.first().map(|s| s.trim_start()).unwrap_or("");
    b.lang == "text"
        && (first.starts_with("$ lsys ")
            || first.starts_with('×')
            || first.starts_with('⚠')
            || first.starts_with("lsys::"))
}

fn split_args(page: &str, line: usize, command: &str) -> Vec<String> {
    let rest = command
        .strip_prefix("$ lsys ")
        .unwrap_or_else(|| panic!("{page}:{line}: a doc-test command starts with `$ lsys `"));
    shlex::split(rest).unwrap_or_else(|| panic!("{page}:{line}: cannot split `{command}`"))
}

fn example(page: &str, b: &Block, prev: Option<&Block>) -> Result<Option<Example>, String> {
    if let Some(m) = &b.marker {
        if m.starts_with("not run:") {
            return Ok(None);
        }
        return Ok(Some(Example::Run(vec![Shown {
            args: split_args(page, b.line, m),
            expected: b.body.join("\n"),
        }])));
    }
    if !looks_like_output(b) {
        return Ok(None);
    }
    let first = b.body[0].trim_start();
    if first.starts_with("$ lsys ") {
        // A block may show several commands, each followed by its output.
        let mut commands: Vec<Shown> = Vec::new();
        for line in &b.body {
            if line.starts_with("$ lsys ") {
                commands.push(Shown {
                    args: split_args(page, b.line, line),
                    expected: String::new(),
                });
            } else if let Some(c) = commands.last_mut() {
                c.expected.push_str(line);
                c.expected.push('\n');
            }
        }
        return Ok(Some(Example::Run(commands)));
    }
    let after_lsys = prev.is_some_and(|p| p.lang == "lsys");
    if !after_lsys || first.starts_with("lsys::") {
        return Err(format!(
            "{page}:{}: this block shows a diagnostic but does not say how to get it: \
         put it right after the `lsys` block it is about, or above it \
         `<!-- doc-test: $ lsys check FILE -->` (or `<!-- doc-test: not run: why -->`)",
            b.line
        ));
    }
    Ok(Some(Example::Check {
        expected: b.body.clone(),
    }))
}

/// One `$ lsys ARGS` and the text shown after it.
struct Shown {
    args: Vec<String>,
    expected: String,
}

/// `text` matches `pattern`, where `...` and `…` stand for any text.
fn matches(pattern: &str, text: &str) -> bool {
    // An ellipsis at the end or start of a line takes the line break too,
    // so that one line of output can be shown cut over several.
    let pattern = pattern
        .replace('…', "...")
        .replace("...\n", "...")
        .replace("\n...", "...");
    let pieces: Vec<&str> = pattern.split("...").collect();
    if pieces.len() == 1 {
        return pattern == text;
    }
    let (first, last) = (pieces[0], pieces[pieces.len() - 1]);
    if !text.starts_with(first) || text.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &text[first.len()..];
    for piece in &pieces[1..pieces.len() - 1] {
        match rest.find(piece) {
            Some(k) => rest = &rest[k + piece.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

/// `actual` is what the page shows as `expected`. JSON output (the
/// `--stats` object) is compared without white space, so that the page
/// may wrap it.
fn same_output(expected: &str, actual: &str) -> bool {
    if actual.trim_start().starts_with('{') {
        let bare = |s: &str| s.split_whitespace().collect::<String>();
        return matches(&bare(expected), &bare(actual));
    }
    matches(&tidy(expected), &tidy(actual))
}

/// Lines without trailing blanks, without leading and trailing empty lines.
fn tidy(text: &str) -> String {
    let lines: Vec<&str> = text.lines().map(str::trim_end).collect();
    lines.join("\n").trim_matches('\n').to_string()
}

fn collapse(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// A scratch folder where the repository's example folders are visible.
fn scratch() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for sub in ["examples", "grammar", "tests"] {
        std::os::unix::fs::symlink(root.join(sub), dir.path().join(sub)).unwrap();
    }
    dir
}

/// The typed lines of a REPL transcript, and the transcript as `--echo`
/// prints it (`> ` before a typed line, `. ` before its continuations).
fn repl_script(expected: &str) -> (String, String) {
    let mut typed = String::new();
    let mut shown = Vec::new();
    let mut open = 0i32;
    for line in expected.lines() {
        let prompt = line
            .strip_prefix("lsys[")
            .and_then(|r| r.split_once("]> "))
            .filter(|(n, _)| n.chars().all(|c| c.is_ascii_digit()));
        if let Some((_, input)) = prompt {
            open = depth(input);
            typed.push_str(input);
            typed.push('\n');
            shown.push(format!("> {input}"));
        } else if open > 0 && line.starts_with(char::is_whitespace) {
            open += depth(line);
            typed.push_str(line);
            typed.push('\n');
            shown.push(format!(". {line}"));
        } else {
            open = 0;
            shown.push(line.to_string());
        }
    }
    (typed, shown.join("\n"))
}

fn depth(s: &str) -> i32 {
    s.chars()
        .map(|c| match c {
            '[' | '(' => 1,
            ']' | ')' => -1,
            _ => 0,
        })
        .sum()
}

fn run(dir: &Path, args: &[String], stdin: Option<&str>) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_lsys"));
    cmd.args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("lsys runs");
    {
        use std::io::Write;
        let mut input = child.stdin.take().unwrap();
        input.write_all(stdin.unwrap_or("").as_bytes()).unwrap();
    }
    let out = child.wait_with_output().unwrap();
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// The kind of block that shows a file named like `arg`.
fn block_kind(arg: &str) -> Option<&'static str> {
    let ext = arg.rsplit_once('.')?.1;
    match ext {
        "lsys" | "l" => Some("lsys"),
        "jsonl" => Some("json"),
        "toml" => Some("toml"),
        _ => None,
    }
}

/// The first `n` lines `lsys ARGS` prints, then it is stopped: for
/// `watch`, which runs until it is.
fn first_lines(dir: &Path, args: &[String], n: usize) -> String {
    use std::io::BufRead;
    let mut child = Command::new(env!("CARGO_BIN_EXE_lsys"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("lsys runs");
    let out = child.stdout.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    let mut text = String::new();
    for _ in 0..n {
        match rx.recv_timeout(std::time::Duration::from_secs(120)) {
            Ok(line) => {
                text.push_str(&line);
                text.push('\n');
            }
            Err(_) => break,
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    text
}

/// Writes, as each file ARGS names that the repository does not have,
/// the nearest block above that shows such a file (`above`: the last
/// block of each kind).
fn provide_files(
    dir: &Path,
    args: &[String],
    above: &HashMap<String, &Block>,
    used: &mut Vec<usize>,
) {
    for a in args {
        let Some(kind) = block_kind(a) else { continue };
        if a.starts_with("std:") || dir.join(a).exists() {
            continue;
        }
        if let Some(src) = above.get(kind) {
            std::fs::write(dir.join(a), src.body.join("\n") + "\n").unwrap();
            used.push(src.line);
        }
    }
}

/// Runs every example of `page`; the failures, described.
fn check_page(page: &Path) -> (usize, Vec<String>) {
    let name = page
        .strip_prefix(env!("CARGO_MANIFEST_DIR"))
        .unwrap_or(page)
        .display()
        .to_string();
    let text = std::fs::read_to_string(page).unwrap();
    let all = blocks(&text);
    let mut failures = Vec::new();
    let mut ran = 0;
    let mut above: HashMap<String, &Block> = HashMap::new();
    // The lines of the `lsys` blocks an example ran.
    let mut used: Vec<usize> = Vec::new();
    for (k, b) in all.iter().enumerate() {
        let prev = k.checked_sub(1).map(|p| &all[p]);
        let example = example(&name, b, prev);
        above.insert(b.lang.clone(), b);
        let example = match example {
            Ok(Some(e)) => e,
            Ok(None) => continue,
            Err(e) => {
                failures.push(e);
                continue;
            }
        };
        ran += 1;
        let dir = scratch();
        match example {
            Example::Run(commands) => {
                for Shown { args, expected } in commands {
                    provide_files(dir.path(), &args, &above, &mut used);
                    let repl = args.first().is_some_and(|a| a == "repl");
                    let watch = args.first().is_some_and(|a| a == "watch");
                    let (actual, expected) = if watch {
                        let lines = expected.trim_end().lines().count();
                        (first_lines(dir.path(), &args, lines), expected)
                    } else if repl {
                        let (typed, shown) = repl_script(&expected);
                        let mut args = args.clone();
                        args.push("--echo".into());
                        (run(dir.path(), &args, Some(&typed)), shown)
                    } else {
                        (run(dir.path(), &args, None), expected)
                    };
                    if !same_output(&expected, &actual) {
                        failures.push(format!(
                            "{name}:{}: `lsys {}` printed\n{}\n--- the page says\n{}\n",
                            b.line,
                            args.join(" "),
                            tidy(&actual),
                            tidy(&expected)
                        ));
                    }
                }
            }
            Example::Check { expected } => {
                let file = "example.lsys".to_string();
                let mut only = HashMap::new();
                if let Some(p) = prev {
                    only.insert("lsys".to_string(), p);
                }
                provide_files(dir.path(), std::slice::from_ref(&file), &only, &mut used);
                let actual = run(dir.path(), &["check".into(), file], None);
                // Each line shown, in order, in the output read as one line:
                // the page may wrap a help text elsewhere or leave out the
                // source snippet.
                let whole = collapse(&actual);
                let mut rest = whole.as_str();
                for want in expected.iter().map(|l| collapse(l)) {
                    if want.is_empty() {
                        continue;
                    }
                    match rest.find(&want) {
                        Some(k) => rest = &rest[k + want.len()..],
                        None => {
                            failures.push(format!(
                                "{name}:{}: `lsys check` does not print `{want}` \
                                 (in this order); it printed\n{actual}",
                                b.line
                            ));
                            break;
                        }
                    }
                }
            }
        }
    }
    // A grammar no example runs must at least pass `lsys check` cleanly.
    for b in &all {
        let skipped = b.marker.as_ref().is_some_and(|m| m.starts_with("not run:"));
        if b.lang != "lsys" || used.contains(&b.line) || skipped {
            continue;
        }
        ran += 1;
        let dir = scratch();
        std::fs::write(dir.path().join("example.lsys"), b.body.join("\n") + "\n").unwrap();
        let actual = run(dir.path(), &["check".into(), "example.lsys".into()], None);
        if !actual.contains("example.lsys: ok (") || actual.contains("warning") {
            failures.push(format!(
                "{name}:{}: this grammar is not clean under `lsys check`: show what \
                 it gives in a block after it, or mark it \
                 `<!-- doc-test: not run: why -->`; it printed\n{actual}",
                b.line
            ));
        }
    }
    (ran, failures)
}

fn pages() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

#[test]
fn every_documented_output_is_what_lsys_prints() {
    let mut failures = Vec::new();
    let mut ran = 0;
    for page in pages() {
        let (n, f) = check_page(&page);
        ran += n;
        failures.extend(f);
    }
    assert!(
        failures.is_empty(),
        "{} of {ran} documented examples differ:\n\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(ran >= 40, "only {ran} documented examples were found");
}

#[test]
fn the_pattern_matcher_reads_ellipses_as_any_text() {
    assert!(matches("a ... c", "a b\nb c"));
    assert!(matches("abc", "abc"));
    assert!(!matches("abc", "abd"));
    assert!(!matches("a ... c", "a b"));
    assert!(!matches("x...x", "x"));
    assert!(matches("in … ms", "in 19 ms"));
    assert!(matches("{a...\nb}", "{a,x,b}"));
    assert!(!matches("{a\nb}", "{ab}"));
}

#[test]
fn repl_transcripts_split_into_what_is_typed_and_what_is_printed() {
    let (typed, shown) =
        repl_script("$x\nlsys[0]> A --> [ +\n    B ]\nreplaced\nlsys[1]> :diff\n  [ 1");
    assert_eq!(typed, "A --> [ +\n    B ]\n:diff\n");
    assert_eq!(
        shown,
        "$x\n> A --> [ +\n.     B ]\nreplaced\n> :diff\n  [ 1"
    );
}
