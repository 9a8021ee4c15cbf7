//! Shared by the benchmarks: the issue-6 workloads compiled from
//! `benches/grammars/` (or the standard library / Pailou generator).
#![allow(dead_code)]

use lsys::internals::derive::{DeriveOptions, ModuleStore};
use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline::{self, Compilation};

/// Compile `input` with `-D` overrides; panics on any error (the
/// workloads are fixed).
pub fn compile(input: Input, defines: &[(&str, &str)]) -> Compilation {
    let opts = Options {
        defines: defines
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
        ..Options::default()
    };
    match pipeline::compile(&input, &opts) {
        Ok(c) => c,
        Err(_) => panic!("benchmark grammar {input:?} does not compile"),
    }
}

/// A grammar in `benches/grammars/`.
pub fn grammar(name: &str, defines: &[(&str, &str)]) -> Compilation {
    let path = format!("{}/benches/grammars/{name}", env!("CARGO_MANIFEST_DIR"));
    compile(Input::Path(path.into()), defines)
}

/// W1: `X --> F[+X]F[-X]+X`, `F --> FF`.
pub fn w1() -> Compilation {
    grammar("w1.lsys", &[])
}

/// W2: the parametric binary tree with `A(x) : x < n`.
pub fn w2(n: u32) -> Compilation {
    grammar("w2.lsys", &[("N", &n.to_string())])
}

/// Options that let the largest workload (W2, N = 25) through.
pub fn big() -> DeriveOptions {
    DeriveOptions {
        max_modules: 200_000_000,
        max_params: 400_000_000,
        ..DeriveOptions::default()
    }
}

/// Derive `steps` steps of `c`.
pub fn run(c: &Compilation, steps: u32) -> ModuleStore {
    lsys::internals::simulation::derive(&c.program, &c.compiled, big(), steps)
        .expect("workload derives")
}

/// Derive `steps` steps of `c` one step at a time, every intermediate
/// string built (as `--every` and the REPL do): the engine before the
/// depth-first expansion of issue 19.
pub fn run_stepwise(c: &Compilation, steps: u32) -> ModuleStore {
    lsys::internals::simulation::derive_each(&c.program, &c.compiled, big(), steps, |_, _| {})
        .expect("workload derives")
}

/// A rayon pool of `n` threads (1: the single-threaded figures).
pub fn pool(n: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .expect("thread pool")
}
