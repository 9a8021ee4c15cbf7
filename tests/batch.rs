//! `lsys batch` end to end: a 40-item manifest (small grammars with
//! different defines, seeds and steps, a standard library Toukung, a
//! Pailou graph, a guided scene, and one broken grammar) built in one
//! run, in two shards writing to one folder at once, after a resume and
//! after a kill; every output the same bytes as `lsys build -o` writes;
//! the manifest's mistakes as the user reads them.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use common::stderr;
use lsys::driver::batch;
use sha2::{Digest, Sha256};

const PLANT: &str = "\
#define N 2
#define A 25
derivation length: N
axiom: F
F --> F[+(A)F]F[-(A)F]F
";

/// Each seed draws another plant.
const BUSH: &str = "\
angle: 22.5
derivation length: 4
axiom: F
F --> F[+F]F[-F]F : 0.33
F --> F[+F]F : 0.33
F --> F[-F]F : 0.34
";

/// A syntax error on line 2: `F(1` is never closed.
const BROKEN: &str = "\
axiom: F
F --> F(1
";

const BROKEN_ID: &str = "broken";

/// A folder of its own under the target's temporary folder, empty.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("batch")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The grammars and the 40-item manifest in a folder of their own; the
/// manifest's path. Relative grammar paths: they start from the
/// manifest's folder, whatever the folder `lsys` runs in.
fn manifest() -> &'static Path {
    static MANIFEST: OnceLock<PathBuf> = OnceLock::new();
    MANIFEST.get_or_init(|| {
        let dir = fresh("grammars");
        std::fs::create_dir_all(dir.join("g")).unwrap();
        std::fs::write(dir.join("g/plant.lsys"), PLANT).unwrap();
        std::fs::write(dir.join("g/bush.lsys"), BUSH).unwrap();
        std::fs::write(dir.join("g/broken.lsys"), BROKEN).unwrap();
        let mut lines = Vec::new();
        for k in 0..30 {
            let format = match k {
                7 => "obj",
                11 => "gltf",
                _ => "glb",
            };
            let steps = if k % 4 == 0 {
                serde_json::json!(1 + k % 3)
            } else {
                serde_json::Value::Null
            };
            lines.push(serde_json::json!({
                "id": format!("plant-{k:02}"), "grammar": "g/plant.lsys",
                "defines": {"N": 1 + k % 3, "A": format!("{}.5", 15 + k)},
                "steps": steps, "format": format,
            }));
        }
        for seed in 0..5 {
            lines.push(serde_json::json!({
                "id": format!("bush.seed{seed}"), "grammar": "g/bush.lsys", "seed": seed,
            }));
        }
        lines.push(
            serde_json::json!({"id": "toukung-5", "grammar": "std:toukung_middle",
                                      "defines": {"NTL": 5}}),
        );
        lines.push(
            serde_json::json!({"id": "toukung-3", "grammar": "std:toukung_middle",
                                      "defines": {"NTL": 3}}),
        );
        lines.push(
            serde_json::json!({"id": "pailou", "grammar": example("pailou/fig17-4_2-1-3.toml")}),
        );
        lines.push(
            serde_json::json!({"id": "spiral", "grammar": example("guided/spiral.toml"),
                                      "steps": 3}),
        );
        lines.push(serde_json::json!({"id": BROKEN_ID, "grammar": "g/broken.lsys"}));
        assert_eq!(lines.len(), 40);
        let text: String = lines.iter().map(|l| format!("{l}\n")).collect();
        let path = dir.join("manifest.jsonl");
        std::fs::write(&path, text).unwrap();
        path
    })
}

fn example(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(rel)
        .to_string_lossy()
        .into_owned()
}

fn ids() -> Vec<String> {
    let text = std::fs::read_to_string(manifest()).unwrap();
    text.lines()
        .map(|l| {
            serde_json::from_str::<serde_json::Value>(l).unwrap()["id"]
                .as_str()
                .unwrap()
                .to_string()
        })
        .collect()
}

fn lsys(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lsys"));
    c.args(args).env("NO_COLOR", "1");
    c
}

fn batch_into(out: &Path, more: &[&str]) -> Output {
    let mut args = vec![
        "batch",
        manifest().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(more);
    lsys(&args).output().unwrap()
}

/// The index's entries by id; panics when an id is there twice. A line
/// cut short by a kill (not JSON) is no entry.
fn index(out: &Path) -> BTreeMap<String, serde_json::Value> {
    let text = std::fs::read_to_string(out.join(batch::INDEX)).unwrap();
    let mut entries = BTreeMap::new();
    for line in text.lines() {
        let Ok(e) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        let id = e["id"].as_str().unwrap().to_string();
        assert!(entries.insert(id.clone(), e).is_none(), "{id} twice");
    }
    entries
}

/// Every file of `dir` but the index, by name, with its bytes; not the
/// temporary files (`.lsys-XXXXXX`) a killed run leaves.
fn outputs(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    names(dir)
        .into_iter()
        .filter(|n| n != batch::INDEX && !n.starts_with('.'))
        .map(|n| (n.clone(), std::fs::read(dir.join(n)).unwrap()))
        .collect()
}

fn names(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// The folder of one whole run (two jobs), made once for every test.
fn single_run() -> &'static (PathBuf, Output, Duration) {
    static RUN: OnceLock<(PathBuf, Output, Duration)> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = fresh("single");
        let t = Instant::now();
        let o = batch_into(&out, &["--jobs", "2"]);
        (out, o, t.elapsed())
    })
}

fn check_complete(out: &Path) -> BTreeMap<String, serde_json::Value> {
    let entries = index(out);
    let mut want = ids();
    want.sort();
    assert_eq!(entries.keys().cloned().collect::<Vec<_>>(), want);
    entries
}

#[test]
fn one_run_records_every_item_once_and_the_broken_one_with_its_place() {
    let (out, o, took) = single_run();
    eprintln!("40 items, --jobs 2: {took:?}");
    assert_eq!(o.status.code(), Some(65), "{}", stderr(o));
    let entries = check_complete(out);
    let ok: Vec<_> = entries.values().filter(|e| e["status"] == "ok").collect();
    assert_eq!(ok.len(), 39);
    for e in &ok {
        let file = out.join(e["output"].as_str().unwrap());
        let sha = format!("{:x}", Sha256::digest(std::fs::read(&file).unwrap()));
        assert_eq!(e["sha256"], sha.as_str(), "{}", file.display());
        assert!(e["triangles"].as_u64().unwrap() > 0, "{e}");
        assert!(e["bounds"]["min"].as_array().unwrap().len() == 3, "{e}");
    }
    assert!(entries["plant-00"]["modules"].as_u64().unwrap() > 0);
    assert!(out.join("plant-07.obj").exists() && out.join("plant-07.mtl").exists());
    assert!(out.join("plant-11.gltf").exists());
    let broken = &entries[BROKEN_ID];
    assert_eq!(broken["status"], "error");
    assert_eq!(broken["output"], serde_json::Value::Null);
    let d = &broken["diagnostics"][0];
    assert_eq!(d["code"], "lsys::parse::syntax");
    assert_eq!(d["severity"], "error");
    assert_eq!(
        (d["line"].as_u64(), d["column"].as_u64()),
        (Some(2), Some(8))
    );
    assert!(d["file"].as_str().unwrap().ends_with("broken.lsys"), "{d}");
    assert!(!out.join("broken.glb").exists());
    // The failure as it happened, and the summary.
    let err = stderr(o);
    assert!(err.contains("lsys: broken: "), "{err}");
    assert!(err.contains("error[lsys::parse::syntax]"), "{err}");
    assert!(err.contains("39 built, 1 failed, 0 skipped"), "{err}");
    // Nothing half-written is left (the atomic writer's temporaries).
    assert!(names(out).iter().all(|n| !n.starts_with('.')));
}

#[test]
fn two_shards_at_once_into_one_folder_give_the_same_files() {
    let (single, _, _) = single_run();
    let out = fresh("shards");
    let spawn = |shard: &str| {
        lsys(&[
            "batch",
            manifest().to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--shard",
            shard,
        ])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
    };
    let (a, b) = (spawn("0/2"), spawn("1/2"));
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    // The broken item is the 40th (position 39): shard 1's.
    assert_eq!(a.status.code(), Some(0), "{}", stderr(&a));
    assert_eq!(b.status.code(), Some(65), "{}", stderr(&b));
    assert!(stderr(&a).contains("20 built, 0 failed"), "{}", stderr(&a));
    check_complete(&out);
    assert_eq!(outputs(&out), outputs(single));
    // The index's lines (all but the time) are the same too.
    let strip = |mut e: serde_json::Value| {
        e["ms"] = serde_json::Value::Null;
        e
    };
    let (x, y) = (index(&out), index(single));
    for (id, e) in x {
        assert_eq!(strip(e), strip(y[&id].clone()), "{id}");
    }
}

#[test]
fn a_rerun_builds_what_the_index_lacks() {
    let (single, _, _) = single_run();
    let out = fresh("resume");
    let first = batch_into(&out, &["--shard", "1/3"]);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    // Lose three items' lines and files, and cut the last line short as a
    // killed run would.
    let text = std::fs::read_to_string(out.join(batch::INDEX)).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    for line in lines.drain(2..5) {
        let e: serde_json::Value = serde_json::from_str(line).unwrap();
        std::fs::remove_file(out.join(e["output"].as_str().unwrap())).unwrap();
    }
    let last = lines.pop().unwrap();
    let mut damaged = lines.join("\n");
    damaged.push('\n');
    damaged.push_str(&last[..last.len() / 2]);
    std::fs::write(out.join(batch::INDEX), damaged).unwrap();
    let again = batch_into(&out, &["--shard", "1/3"]);
    let err = stderr(&again);
    assert_eq!(again.status.code(), Some(0), "{err}");
    assert!(err.contains("1 damaged line of the index ignored"), "{err}");
    assert!(err.contains("4 built, 0 failed, 9 skipped"), "{err}");
    // The rest of the manifest, and nothing is built twice.
    let rest = batch_into(&out, &[]);
    assert_eq!(rest.status.code(), Some(65), "{}", stderr(&rest));
    assert!(
        stderr(&rest).contains("26 built, 1 failed, 13 skipped"),
        "{}",
        stderr(&rest)
    );
    let done = batch_into(&out, &[]);
    assert_eq!(done.status.code(), Some(65), "{}", stderr(&done));
    assert!(
        stderr(&done).contains("0 built, 0 failed, 40 skipped (1 recorded as failed)"),
        "{}",
        stderr(&done)
    );
    check_complete(&out);
    assert_eq!(outputs(&out), outputs(single));
}

#[test]
fn a_killed_run_resumes() {
    let (single, _, _) = single_run();
    let out = fresh("killed");
    let mut child = lsys(&[
        "batch",
        manifest().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
    .stderr(std::process::Stdio::null())
    .spawn()
    .unwrap();
    let index = out.join(batch::INDEX);
    let t = Instant::now();
    while std::fs::read_to_string(&index).map_or(0, |t| t.lines().count()) < 5
        && t.elapsed() < Duration::from_secs(60)
    {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let recorded = std::fs::read_to_string(&index).unwrap().lines().count();
    eprintln!("killed after {recorded} entries");
    let again = batch_into(&out, &["--jobs", "2"]);
    assert_eq!(again.status.code(), Some(65), "{}", stderr(&again));
    check_complete(&out);
    assert_eq!(outputs(&out), outputs(single));
}

#[test]
fn an_items_file_is_what_lsys_build_writes() {
    let (single, _, _) = single_run();
    let dir = fresh("build");
    let g = manifest().parent().unwrap();
    let same = |args: &[&str], name: &str| {
        let out = dir.join(name);
        let mut all = vec!["build"];
        all.extend_from_slice(args);
        all.extend(["-o", out.to_str().unwrap()]);
        let o = lsys(&all).output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            std::fs::read(&out).unwrap() == std::fs::read(single.join(name)).unwrap(),
            "{name} differs from lsys build {args:?}"
        );
    };
    let plant = g.join("g/plant.lsys");
    let plant = plant.to_str().unwrap();
    same(
        &[plant, "-D", "N=1", "-D", "A=15.5", "-n", "1"],
        "plant-00.glb",
    );
    same(&[plant, "-D", "N=2", "-D", "A=22.5"], "plant-07.obj");
    same(&[plant, "-D", "N=3", "-D", "A=26.5"], "plant-11.gltf");
    let bush = g.join("g/bush.lsys");
    same(&[bush.to_str().unwrap(), "--seed", "3"], "bush.seed3.glb");
    same(&["std:toukung_middle", "-D", "NTL=5"], "toukung-5.glb");
    same(&[&example("pailou/fig17-4_2-1-3.toml")], "pailou.glb");
    same(&[&example("guided/spiral.toml"), "-n", "3"], "spiral.glb");
    // Seeds draw different bushes.
    assert_ne!(
        std::fs::read(single.join("bush.seed0.glb")).unwrap(),
        std::fs::read(single.join("bush.seed1.glb")).unwrap()
    );
}

#[test]
fn the_library_builds_an_item_from_json_as_the_command_does() {
    let (single, _, _) = single_run();
    let out = fresh("library");
    let v = serde_json::json!({"id": "toukung-3", "grammar": "std:toukung_middle",
                               "defines": {"NTL": 3}});
    let item = batch::item_from_json(&v, Path::new("")).unwrap();
    let entry = batch::generate(&item, &out);
    assert!(entry.is_ok(), "{entry:?}");
    assert_eq!(
        std::fs::read(out.join("toukung-3.glb")).unwrap(),
        std::fs::read(single.join("toukung-3.glb")).unwrap()
    );
    let recorded = &index(single)["toukung-3"];
    assert_eq!(recorded["sha256"], entry.sha256.as_deref().unwrap());
    // A missing grammar is an error entry, never a panic.
    let v = serde_json::json!({"id": "x", "grammar": "no/such.lsys"});
    let entry = batch::generate(&batch::item_from_json(&v, &out).unwrap(), &out);
    assert_eq!(entry.status, batch::Status::Error);
    assert_eq!(
        entry.diagnostics[0].code.as_deref(),
        Some("lsys::load::input")
    );
}

/// The manifest's mistakes, every one at its line, before anything is
/// built.
#[test]
fn manifest_mistakes_name_their_line() {
    let dir = fresh("mistakes");
    let text = [
        r#"{"id": "a", "grammar": "std:toukung_middle"}"#,
        r#"{"id": "b", "grammar": "std:toukung_middle",}"#,
        r#"{"id": "a", "grammar": "std:toukung_middle", "seed": 3}"#,
        r#"{"id": "../up", "grammar": "std:toukung_middle"}"#,
        r#"{"id": "c", "grammar": "std:toukung_middle", "sead": 4}"#,
        r#"{"id": "d", "grammar": "std:toukung_middle", "defines": {"NTL": [5]}}"#,
        "",
        r#"{"id": "e", "grammar": "std:toukung_middle", "format": "stl"}"#,
    ]
    .join("\n");
    std::fs::write(dir.join("jobs.jsonl"), text).unwrap();
    let o = lsys(&["batch", "jobs.jsonl", "--out", "out"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(65));
    assert!(!dir.join("out").exists(), "something was built");
    insta::assert_snapshot!(stderr(&o));
    // The library's error is the same diagnostic.
    let e = batch::run(
        &dir.join("jobs.jsonl"),
        &dir.join("out"),
        None,
        1,
        &mut |_| {},
    )
    .unwrap_err();
    let batch::BatchError::Manifest {
        count, mistakes, ..
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!(*count, 6);
    let lines: Vec<usize> = mistakes.iter().map(|m| m.line).collect();
    assert_eq!(lines, [2, 3, 4, 5, 6, 8]);
}

#[test]
fn command_line_mistakes() {
    let dir = fresh("usage");
    let o = lsys(&["batch", "none.jsonl", "--out", "out"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(66));
    insta::assert_snapshot!("missing_manifest", stderr(&o));
    for shard in ["2/2", "0/0", "1", "a/b"] {
        let o = batch_into(&dir.join("out"), &["--shard", shard]);
        assert_eq!(o.status.code(), Some(64), "{shard}: {}", stderr(&o));
    }
    let o = batch_into(&dir.join("out"), &["--jobs", "0"]);
    assert_eq!(o.status.code(), Some(64), "{}", stderr(&o));
}
