//! The fast and parallel derivation steps (`src/derive/fast.rs`,
//! `parallel.rs`) against the general engine: the same strings, the same
//! errors, and the fallback for grammars the fast path does not take.

use lsys::internals::derive::{Derivation, DeriveOptions};
use lsys::internals::pipeline::Compilation;

mod common;

use common::grammar;

fn compile(text: &str) -> Compilation {
    common::compile_text("fast.lsys", text)
}

/// Every step's string (or the error's text) of `steps` steps.
fn run(c: &Compilation, opts: &DeriveOptions, steps: u32, mode: Mode) -> Vec<String> {
    let mut d = match Derivation::new(&c.program, &c.compiled, opts.clone()) {
        Ok(d) => d,
        Err(e) => return vec![format!("error: {e:?}")],
    };
    d = match mode {
        Mode::General => d.without_fast_path(),
        Mode::Fast => d,
        Mode::Parallel => d.with_parallel_threshold(1),
    };
    let mut out = vec![d.current().display(&c.program.symbols)];
    for _ in 0..steps {
        match d.step() {
            Ok(()) => out.push(d.current().display(&c.program.symbols)),
            Err(e) => {
                out.push(format!("error: {e:?}"));
                break;
            }
        }
    }
    out
}

#[derive(Clone, Copy, Debug)]
enum Mode {
    General,
    Fast,
    Parallel,
}

/// Derives `text` all three ways in a two-thread pool and compares;
/// returns whether the fast path was taken.
fn same(text: &str, steps: u32, opts: DeriveOptions) -> bool {
    let c = compile(text);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let general = run(&c, &opts, steps, Mode::General);
    for mode in [Mode::Fast, Mode::Parallel] {
        let got = pool.install(|| run(&c, &opts, steps, mode));
        assert_eq!(got, general, "{mode:?} differs on\n{text}");
    }
    Derivation::new(&c.program, &c.compiled, opts)
        .map(|d| d.uses_fast_path())
        .unwrap_or(false)
}

fn opts() -> DeriveOptions {
    DeriveOptions::default()
}

#[test]
fn w1_brackets_no_parameters() {
    let g = grammar("X", "X --> F[+X]F[-X]+X\nF --> FF");
    assert!(same(&g, 6, opts()));
}

#[test]
fn w2_conditions_and_brackets() {
    let g = grammar(
        "A(1)",
        "A(x) : x < 7 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]\nA(x) --> F(x)",
    );
    assert!(same(&g, 9, opts()));
}

#[test]
fn several_candidates_else_never_nan_and_arity() {
    let g = common::several_candidates();
    assert!(same(&g, 6, opts()));
}

#[test]
fn faults_give_the_general_engines_error() {
    let g = grammar("A(3)", "A(x) --> A(x - 1) B(1 / x)\nB(y) --> B(y)");
    assert!(same(&g, 5, opts()));
    let g = grammar("A(3)", "A(x) : 1 / (x - 1) > 0 --> A(x - 1) A(x - 1)");
    assert!(same(&g, 5, opts()));
    let g = grammar("A(1)", "A(x) --> A(x * 1e200) B(x)");
    assert!(same(&g, 5, opts()));
}

#[test]
fn limits_give_the_general_engines_error() {
    let g = grammar("X", "X --> F[+X]F[-X]+X\nF --> FF");
    let small = DeriveOptions {
        max_modules: 500,
        ..opts()
    };
    assert!(same(&g, 8, small));
    let g = grammar("A(1)", "A(x) --> A(x) A(x+1) B(x, x)");
    let few = DeriveOptions {
        max_params: 300,
        ..opts()
    };
    assert!(same(&g, 8, few));
}

#[test]
fn decomposition_after_a_fast_step() {
    let text = "Lsystem: 1\nAxiom: A(1)\nA(x) --> A(x+1) B(x)\ndecomposition\nmaximum depth: 3\nB(y) : y > 1 --> C(y) D\nD --> E E\nendlsystem\n";
    assert!(same(text, 6, opts()));
}

#[test]
fn not_taken_stochastic_random_context_multi_module() {
    let s = grammar("A", "A --> A B : 1\nA --> B A : 2\nB --> A");
    assert!(!same(&s, 8, opts()));
    let r = grammar("A(0)", "A(x) --> A(ran(1)) B(x)");
    assert!(!same(&r, 6, opts()));
    let c = grammar("B A A A", "B < A --> B\nA --> A");
    assert!(!same(&c, 4, opts()));
    let m = grammar("A B A B", "A B --> B A A\nB --> A B");
    assert!(!same(&m, 6, opts()));
}

#[test]
fn seeded_stochastic_decomposition_keeps_its_numbers() {
    // The main table is fast; the decomposition draws from the generator,
    // which the fast step must leave exactly as the general one does.
    let text = "Lsystem: 1\nseed: 7\nAxiom: A(1)\nA(x) : x < 50 --> A(x+1) B(x)\ndecomposition\nB(y) --> C(ran(y)) : 1\nB(y) --> D : 1\nendlsystem\n";
    assert!(same(text, 8, opts()));
}

/// `derive::count` against counting the derived string.
fn counts_agree(text: &str, steps: u32) -> bool {
    let c = compile(text);
    let counted = lsys::internals::derive::count(&c.program, &c.compiled, opts(), steps).unwrap();
    let s = lsys::internals::simulation::derive(&c.program, &c.compiled, opts(), steps).unwrap();
    let want: Vec<u64> = s
        .counts(c.program.symbols.len())
        .into_iter()
        .map(|n| n as u64)
        .collect();
    assert_eq!(counted.per_symbol, want, "{text}");
    assert_eq!(counted.total(), s.len() as u64);
    counted.expanded
}

#[test]
fn count_by_expansion_matches_the_string() {
    assert!(counts_agree(
        &grammar("X", "X --> F[+X]F[-X]+X\nF --> FF"),
        7
    ));
    assert!(counts_agree(
        &grammar(
            "A(1) B(2)",
            "A(x) : x < 6 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]\nA(x) --> F(x)\nB(y) : y > 1 --> B(y / 2) B(y / 3) C"
        ),
        9
    ));
    // Not expandable: stochastic, context, decomposition.
    assert!(!counts_agree(
        &grammar("A", "A --> A B : 1\nA --> B A : 2\nB --> A"),
        8
    ));
    assert!(!counts_agree(
        &grammar("B A A A", "B < A --> B\nA --> A"),
        4
    ));
    assert!(!counts_agree(
        "Lsystem: 1\nAxiom: A\nA --> A B\ndecomposition\nB --> C C\nendlsystem\n",
        5
    ));
}

#[test]
fn count_reaches_billions_of_modules_without_building_them() {
    let c = compile(&grammar(
        "A(1)",
        "A(x) : x < 40 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]\nA(x) --> F(x)",
    ));
    let n = lsys::internals::derive::count(&c.program, &c.compiled, opts(), 30).unwrap();
    assert!(n.expanded);
    // Every rewrite of an A adds 8 modules; 2^30 - 1 rewrites.
    assert_eq!(n.total(), 8 * (1u64 << 30) - 7);
}

#[test]
fn not_taken_in_the_cpfg_dialect() {
    let text = "dialect: cpfg\nLsystem: 1\nAxiom: A(1)\nA(x) --> A(x+1) B(x)\nendlsystem\n";
    assert!(!same(text, 4, opts()));
}
