//! Derivation only (issue 6, W1 and W2): the compiled grammar in, the
//! derived string out. Throughput in modules of the final string per
//! second; "1 thread" runs in a one-thread rayon pool, so the parallel
//! step is off. `common::run` expands the steps depth first (issue 19);
//! the `stepwise` runs build every intermediate string, as before.

mod common;

use divan::counter::ItemsCount;
use divan::{black_box, Bencher};

fn main() {
    divan::main();
}

#[divan::bench(args = [7, 9, 11], sample_count = 20)]
fn w1_1_thread(bencher: Bencher, n: u32) {
    let c = common::w1();
    let pool = common::pool(1);
    let len = common::run(&c, n).len();
    bencher
        .counter(ItemsCount::new(len))
        .bench_local(|| pool.install(|| black_box(common::run(&c, n))));
}

#[divan::bench(args = [7, 9, 11], sample_count = 20)]
fn w1_2_threads(bencher: Bencher, n: u32) {
    let c = common::w1();
    let pool = common::pool(2);
    let len = common::run(&c, n).len();
    bencher
        .counter(ItemsCount::new(len))
        .bench_local(|| pool.install(|| black_box(common::run(&c, n))));
}

#[divan::bench(sample_count = 20)]
fn w2_18_1_thread(bencher: Bencher) {
    let c = common::w2(18);
    let pool = common::pool(1);
    bencher
        .counter(ItemsCount::new(1_048_569usize))
        .bench_local(|| pool.install(|| black_box(common::run(&c, 18))));
}

#[divan::bench(sample_count = 20)]
fn w2_18_2_threads(bencher: Bencher) {
    let c = common::w2(18);
    let pool = common::pool(2);
    bencher
        .counter(ItemsCount::new(1_048_569usize))
        .bench_local(|| pool.install(|| black_box(common::run(&c, 18))));
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn w2_25_1_thread(bencher: Bencher) {
    let c = common::w2(25);
    let pool = common::pool(1);
    bencher
        .counter(ItemsCount::new(134_217_721usize))
        .bench_local(|| pool.install(|| black_box(common::run(&c, 25))));
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn w2_25_2_threads(bencher: Bencher) {
    let c = common::w2(25);
    let pool = common::pool(2);
    bencher
        .counter(ItemsCount::new(134_217_721usize))
        .bench_local(|| pool.install(|| black_box(common::run(&c, 25))));
}

/// W1 n = 11 and W2 derived one step at a time (every intermediate
/// string built), beside the runs above that expand the steps depth first.
#[divan::bench(args = [11, 18], sample_count = 20)]
fn stepwise_1_thread(bencher: Bencher, which: u32) {
    let (c, n) = match which {
        11 => (common::w1(), 11),
        _ => (common::w2(18), 18),
    };
    let pool = common::pool(1);
    let len = common::run_stepwise(&c, n).len();
    bencher
        .counter(ItemsCount::new(len))
        .bench_local(|| pool.install(|| black_box(common::run_stepwise(&c, n))));
}

/// W2 with N = 25 one step at a time (134 M modules).
#[divan::bench(sample_count = 5, sample_size = 1)]
fn stepwise_w2_25_1_thread(bencher: Bencher) {
    let c = common::w2(25);
    let pool = common::pool(1);
    bencher
        .counter(ItemsCount::new(134_217_721usize))
        .bench_local(|| pool.install(|| black_box(common::run_stepwise(&c, 25))));
}

/// `lsys derive` printing W2 (buffered, to a sink that discards).
#[divan::bench(sample_count = 20)]
fn w2_18_print(bencher: Bencher) {
    let c = common::w2(18);
    let s = common::run(&c, 18);
    bencher.counter(ItemsCount::new(s.len())).bench_local(|| {
        let mut out = std::io::sink();
        s.write_string(&c.program.symbols, &mut out)
            .expect("writing to a sink");
    });
}
