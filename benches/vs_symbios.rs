//! Side by side with `symbios` (the reference Rust parametric L-system
//! crate), in the same process and the same run so that the ratio is
//! fair on a shared, noisy machine: W1 (n = 11) and W2 (18 steps), both
//! derived by both crates in alternation, `ROUNDS` times; prints each
//! median, the throughput and lsys's speed-up.
//!
//! A plain harness (not divan): divan reports medians but cannot compute
//! a ratio between two benchmarks.

mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use symbios::System;

const ROUNDS: usize = 15;

fn symbios_system(rules: &[&str], axiom: &str) -> System {
    let mut sys = System::new();
    sys.max_capacity = 10_000_000;
    for r in rules {
        sys.add_rule(r).expect("symbios accepts the rule");
    }
    sys.set_axiom(axiom).expect("symbios accepts the axiom");
    sys
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

struct Case {
    name: &'static str,
    rules: &'static [&'static str],
    axiom: &'static str,
    steps: u32,
    lsys: lsys::internals::pipeline::Compilation,
}

fn main() {
    // `cargo bench` passes `--bench`; a filter may follow.
    let filter: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let cases = [
        Case {
            name: "W1 n=11",
            // symbios reads `FF` as one symbol: modules are spaced.
            rules: &["X -> F [ + X ] F [ - X ] + X", "F -> F F"],
            axiom: "X",
            steps: 11,
            lsys: common::w1(),
        },
        Case {
            name: "W2 18 steps",
            rules: &[
                "A(x) : x < 18 -> F(x)[+(25)A(x+1)][-(25)A(x+1)]",
                "A(x) : x >= 18 -> F(x)",
            ],
            axiom: "A(1)",
            steps: 18,
            lsys: common::w2(18),
        },
    ];
    let pool = common::pool(1);
    // lsys also on two threads (the depth-first expansion splits the
    // string in halves); symbios has one.
    let pool2 = common::pool(2);
    for case in &cases {
        if !filter.is_empty() && !filter.iter().any(|f| case.name.contains(f.as_str())) {
            continue;
        }
        let (mut ours, mut ours2, mut theirs) = (Vec::new(), Vec::new(), Vec::new());
        let mut lens = (0, 0);
        for _ in 0..ROUNDS {
            let t = Instant::now();
            let s = pool.install(|| common::run(&case.lsys, case.steps));
            ours.push(t.elapsed());
            lens.0 = black_box(s).len();
            let t = Instant::now();
            black_box(pool2.install(|| common::run(&case.lsys, case.steps)));
            ours2.push(t.elapsed());

            let mut sys = symbios_system(case.rules, case.axiom);
            let t = Instant::now();
            sys.derive(case.steps as usize).expect("symbios derives");
            theirs.push(t.elapsed());
            lens.1 = black_box(&sys.state).len();
        }
        assert_eq!(
            lens.0, lens.1,
            "{}: both derive the same number of modules",
            case.name
        );
        let (a, a2, b) = (median(ours), median(ours2), median(theirs));
        let rate = |d: Duration| lens.0 as f64 / d.as_secs_f64();
        println!(
            "{:<12} {} modules: lsys {:>9.3} ms ({:.3e} modules/s, 1 thread), symbios {:>9.3} ms ({:.3e} modules/s); lsys is {:.1}x faster (medians of {ROUNDS})",
            case.name,
            lens.0,
            a.as_secs_f64() * 1e3,
            rate(a),
            b.as_secs_f64() * 1e3,
            rate(b),
            b.as_secs_f64() / a.as_secs_f64()
        );
        println!(
            "{:<12} lsys on 2 threads {:>9.3} ms ({:.3e} modules/s): {:.1}x symbios",
            "",
            a2.as_secs_f64() * 1e3,
            rate(a2),
            b.as_secs_f64() / a2.as_secs_f64()
        );
    }
}
