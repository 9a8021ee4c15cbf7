//! `lsys studio`'s rebuild-to-picture on the server (issue 17, item 4):
//! what one change costs before the page can load the model. Pailou mode:
//! the edited graph read against the relation matrix, the grammar emitted,
//! compiled, built, structurally checked and encoded as GLB (std:pailou's
//! 4-3-7 ridge graph). Grammar mode: a saved grammar compiled, built and
//! encoded (the two Toukungs, std:pailou). Medians are what divan prints.

use divan::{black_box, Bencher};
use lsys::internals::pailou::{self, graph, PailouType};
use lsys::internals::studio::{GrammarSession, PailouSession};

fn main() {
    divan::main();
}

/// Pailou mode: one edit of the 4-3-7 ridge graph, rebuilt.
#[divan::bench]
fn pailou_graph_4_3_7(bencher: Bencher) {
    let layout = pailou::style_layout("4-3-7", PailouType::Ridge).expect("a style");
    let text = graph::emit(&layout, PailouType::Ridge, "4-3-7");
    bencher.bench_local(|| {
        let s = PailouSession::open(
            "g.toml",
            black_box(&text),
            None,
            lsys::internals::studio::DEFAULT_MAX_TRIANGLES,
        );
        assert!(s.error.is_none());
        black_box(s.model.map(|m| m.glb.len()))
    });
}

/// Grammar mode: a save of `name` (a standard library grammar), rebuilt.
fn grammar(bencher: Bencher, name: &str) {
    // A standard library grammar is in no folder (an empty one stands
    // in), and no watcher is told its files (`open` gives none).
    let folder = tempfile::tempdir().unwrap();
    let mut s = GrammarSession::open(folder.path().into(), name.into(), name.into());
    assert!(s.current, "{:?}", s.diagnostics);
    bencher.bench_local(|| {
        s.rebuild();
        black_box(s.model.as_ref().map(|m| m.glb.len()))
    });
}

#[divan::bench]
fn grammar_std_pailou(bencher: Bencher) {
    grammar(bencher, "std:pailou");
}

#[divan::bench]
fn grammar_toukung_middle(bencher: Bencher) {
    grammar(bencher, "std:toukung_middle");
}

#[divan::bench]
fn grammar_toukung_side(bencher: Bencher) {
    grammar(bencher, "std:toukung_side");
}
