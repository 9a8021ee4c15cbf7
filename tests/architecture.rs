//! The crate's import graph reads as the pipeline: a core stage imports
//! only stages before it, and files of different stages never import each
//! other in a circle. Read from the source text (`use crate::X` and
//! `crate::X::` paths), so a new back edge fails here, not in review.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The core stages in pipeline order. Each may import only the stages
/// before it (and itself). `support` is no stage but infrastructure the
/// stages share (memory): first, so that any stage may use it and it may
/// use none.
const STAGES: &[&str] = &[
    "support",
    "source",
    "diag",
    "stdlib",
    "lang",
    "preprocess",
    "parse",
    "load",
    "environment",
    "resolve",
    "bytecode",
    "derive",
    "turtle",
    "simulation",
    "mesh",
    "export",
];

/// Modules above the core stages: front-ends and one-call drivers. They
/// may import any core stage; no core stage may import them.
const ABOVE: &[&str] = &[
    "pipeline",
    "build",
    "guided",
    "pailou",
    "infer",
    "api",
    "driver",
    "exit_code",
    "progress",
    "repl",
    "lsp",
    "studio",
    "cli",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file of `src/` belongs to.
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// Top-level modules `text` refers to as `crate::NAME`.
fn imports(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

fn rank(m: &str) -> Option<usize> {
    STAGES.iter().position(|s| *s == m)
}

#[test]
fn core_stages_import_only_earlier_stages() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut back = Vec::new();
    let mut unknown = BTreeSet::new();
    for f in &files {
        let m = module_of(&src, f);
        if m == "lib" || m == "main" {
            continue;
        }
        if rank(&m).is_none() && !ABOVE.contains(&m.as_str()) {
            unknown.insert(m.clone());
        }
        let Some(r) = rank(&m) else { continue };
        let text = std::fs::read_to_string(f).unwrap();
        for i in imports(&text) {
            let later = rank(&i).is_some_and(|ri| ri > r);
            if later || ABOVE.contains(&i.as_str()) {
                back.push(format!(
                    "{} ({m}) imports crate::{i}",
                    f.strip_prefix(&src).unwrap().display()
                ));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "modules not placed in tests/architecture.rs: {unknown:?}"
    );
    assert!(
        back.is_empty(),
        "imports that run back up the pipeline:\n{}",
        back.join("\n")
    );
}

#[test]
fn no_import_cycle_between_modules() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let m = module_of(&src, f);
        let text = std::fs::read_to_string(f).unwrap();
        let deps = graph.entry(m.clone()).or_default();
        deps.extend(imports(&text).into_iter().filter(|i| *i != m));
    }
    // Depth-first search for a back edge.
    fn visit(
        n: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = stack.iter().position(|s| s == n) {
            let mut c = stack[i..].to_vec();
            c.push(n.to_string());
            return Some(c);
        }
        if done.contains(n) {
            return None;
        }
        stack.push(n.to_string());
        for d in g.get(n).into_iter().flatten() {
            if let Some(c) = visit(d, g, stack, done) {
                return Some(c);
            }
        }
        stack.pop();
        done.insert(n.to_string());
        None
    }
    let mut done = BTreeSet::new();
    for n in graph.keys() {
        let cycle = visit(n, &graph, &mut Vec::new(), &mut done);
        assert!(
            cycle.is_none(),
            "import cycle: {}",
            cycle.unwrap().join(" -> ")
        );
    }
}

/// The front ends drive lsys through its door: the public API (`api`, the
/// crate root's re-exports) and the `driver`. They name no stage module
/// and none of the one-call layers under the driver.
const FRONT_ENDS: &[&str] = &["cli", "studio", "repl"];

/// What a front end may not name.
fn behind_the_door(m: &str) -> bool {
    rank(m).is_some() || ["pipeline", "build", "guided", "pailou", "infer"].contains(&m)
}

#[test]
fn front_ends_go_through_the_door() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut side_doors = Vec::new();
    for front in FRONT_ENDS {
        let mut files = Vec::new();
        rust_files(&src.join(front), &mut files);
        assert!(!files.is_empty(), "src/{front}/ has no files");
        for f in &files {
            let text = std::fs::read_to_string(f).unwrap();
            for i in imports(&text).into_iter().filter(|i| behind_the_door(i)) {
                side_doors.push(format!(
                    "{} names crate::{i}",
                    f.strip_prefix(&src).unwrap().display()
                ));
            }
        }
    }
    assert!(
        side_doors.is_empty(),
        "front ends reaching past the API and the driver:\n{}",
        side_doors.join("\n")
    );
}
