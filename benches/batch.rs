//! `lsys batch` throughput (issue 32): a 60-item manifest (15 Pailou
//! graphs of examples/pailou, 5 middle and 18 side Toukungs, 22
//! stochastic bushes) built into a fresh folder by `driver::batch::run`
//! with 1 and 2 worker threads; items per second. Whole-command and
//! Dask/Ray figures are in docs/scale.md.

use std::path::{Path, PathBuf};

use divan::counter::ItemsCount;
use divan::Bencher;
use lsys::driver::batch;

fn main() {
    divan::main();
}

const BUSH: &str =
    "derivation length: 5\nangle: 22.5\nAxiom: F\nF --> F[+F]F[-F]F : 0.33\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.34\n";

/// The manifest in `dir`; its item count.
fn manifest(dir: &Path) -> (PathBuf, usize) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::write(dir.join("bush.lsys"), BUSH).expect("writes");
    let mut lines = Vec::new();
    let mut graphs: Vec<_> = std::fs::read_dir(root.join("examples/pailou"))
        .expect("examples/pailou")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    graphs.sort();
    for g in &graphs {
        let id = g.file_stem().unwrap().to_string_lossy();
        lines.push(format!(
            r#"{{"id":"{id}","grammar":{:?}}}"#,
            g.display().to_string()
        ));
    }
    for n in 1..=5 {
        lines.push(format!(
            r#"{{"id":"tm{n}","grammar":"std:toukung_middle","defines":{{"NTL":{n}}}}}"#
        ));
    }
    for n in 1..=18 {
        lines.push(format!(
            r#"{{"id":"ts{n}","grammar":"std:toukung_side","defines":{{"NTL":{n}}}}}"#
        ));
    }
    for s in 1..=22 {
        lines.push(format!(
            r#"{{"id":"bush{s}","grammar":"bush.lsys","seed":{s}}}"#
        ));
    }
    let path = dir.join("manifest.jsonl");
    std::fs::write(&path, lines.join("\n") + "\n").expect("writes");
    (path, lines.len())
}

#[divan::bench(args = [1, 2], sample_count = 10, sample_size = 1)]
fn batch_run(bencher: Bencher, jobs: usize) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (path, items) = manifest(dir.path());
    let mut round = 0;
    bencher
        .counter(ItemsCount::new(items))
        .with_inputs(|| {
            round += 1;
            dir.path().join(format!("out{round}"))
        })
        .bench_local_values(|out| {
            let s = batch::run(&path, &out, None, jobs, &mut |_| {}).expect("runs");
            assert_eq!(s.failed, 0);
            let _ = std::fs::remove_dir_all(&out);
        });
}
