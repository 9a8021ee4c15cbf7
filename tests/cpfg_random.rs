//! cpfg's random numbers: which generator each draw comes from and in
//! what order. Our own small models under tests/fixtures/cpfg/random/,
//! derived through the CLI, their numbers checked against POSIX
//! `drand48` seeded as cpfg seeds it.

mod common;

use lsys::internals::derive::Rand48;

fn derive(file: &str, args: &[&str]) -> String {
    let mut all = vec!["derive"];
    all.extend(args);
    all.push(file);
    let out = common::lsys_in(&common::cpfg_fixture("random"), &all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Parameter `k` of every `name(...)` module of `s`, in order.
fn params(s: &str, name: &str, k: usize) -> Vec<f64> {
    s.split_whitespace()
        .filter_map(|m| m.strip_prefix(name)?.strip_prefix('('))
        .map(|p| p.split([',', ')']).nth(k).unwrap().parse().unwrap())
        .collect()
}

fn firsts(s: &str, name: &str) -> Vec<f64> {
    params(s, name, 0)
}

/// Draws `n` numbers of cpfg's `ran` generator (`srand48(0)`'s state).
fn draws(n: usize) -> Vec<f64> {
    let mut r = Rand48::new(0);
    (0..n).map(|_| r.next_f64()).collect()
}

fn assert_close(got: &[f64], want: &[f64], s: &str) {
    assert_eq!(got.len(), want.len(), "{s}");
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-6, "{got:?} != {want:?} in {s}");
    }
}

/// With a query module cpfg interprets the string after the axiom and
/// after every step, drawing the homomorphism's `ran` from the
/// derivation's generator; the printed homomorphism goes on from there,
/// and so does the next step's `ran`.
#[test]
fn interpretations_continue_the_derivations_generator() {
    let d = draws(7);
    let s = derive("queried.l", &[]);
    // Step 1 draws d0; its interpretation d1; step 2 draws d2.
    assert_close(&firsts(&s, "B"), &[d[0], d[2]], &s);
    // The interpretation after step 2 moved the turtle up by d3, then d4,
    // to the queries.
    assert_close(&params(&s, "?P", 1), &[d[3], d[3] + d[4]], &s);
    let h = derive("queried.l", &["--homomorphism"]);
    assert_close(&firsts(&h, "f"), &[d[5], d[6]], &h);
}

/// A query module for an environmental program that is not there (`?E`)
/// makes cpfg interpret every string all the same: the whole derivation
/// and the one printed step by step agree, the second step drawing after
/// the first interpretation.
#[test]
fn strings_with_unanswered_queries_are_interpreted_after_every_step() {
    let d = draws(3);
    let s = derive("environment_query.l", &[]);
    assert_close(&firsts(&s, "B"), &[d[0], d[2]], &s);
    let every = derive("environment_query.l", &["--every"]);
    assert_eq!(every.lines().last(), s.lines().last(), "{every}");
}

/// Without query modules the strings are not interpreted between steps;
/// cpfg interprets the final string once for the view before the string
/// it prints or draws.
#[test]
fn the_drawn_string_follows_one_interpretation_for_the_view() {
    let d = draws(6);
    let s = derive("unqueried.l", &[]);
    assert_close(&firsts(&s, "B"), &[d[0], d[1]], &s);
    let h = derive("unqueried.l", &["--homomorphism"]);
    assert_close(&firsts(&h, "f"), &[d[4], d[5]], &h);
}

/// A `seed:` makes a cpfg L-system stochastic as cpfg's is: the choices
/// come from a generator of their own (`seed48({7, 0, 155})`), one draw
/// for every module of a step whether a production matches it or not
/// (the brackets and `B`s here), and `ran` is not seeded by `seed:`, so
/// the `B`s take the first numbers of `srand48(0)`. The expected string
/// was worked out by hand from those rules (C floats for the
/// probabilities): drawing only where a production matches ends in `C`
/// after one branch, seeding the choices with `srand48(7)` grows six.
#[test]
fn a_seed_makes_cpfg_choices_from_their_own_generator() {
    let s = derive("moss.l", &["--cpfg-format"]);
    assert_eq!(
        s.trim(),
        "[ B(0.170828) ] [ B(0.749902) ] [ B(0.0963717) ] [ B(0.870465) ] [ B(0.577304) ] A"
    );
    let d = draws(5);
    assert_close(&firsts(&s, "B"), &d, &s);
}

/// Without `seed:` a cpfg L-system is deterministic: the probabilities
/// are not used and the first production that matches applies.
#[test]
fn without_a_seed_cpfg_ignores_probabilities() {
    assert_eq!(derive("unseeded.l", &[]).trim(), "B B B A");
}
