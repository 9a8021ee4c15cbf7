//! The depth-first expansion of the last steps (`src/derive/depth_first.rs`,
//! `Derivation::run_steps`, issue 19) against stepping one step at a time:
//! the same final string, the same errors, on grammars with brackets,
//! parameters, conditions, several candidates, faults, limits, strings
//! that shrink, and derivations longer than the depth it expands; on one
//! thread and on two (the string split in halves).

use lsys::internals::derive::{Derivation, DeriveOptions};
use lsys::internals::pipeline::Compilation;

mod common;

use common::grammar;

fn compile(text: &str) -> Compilation {
    common::compile_text("depth.lsys", text)
}

/// The final string (or the error) of `steps` steps, stepping.
fn stepping(c: &Compilation, opts: &DeriveOptions, steps: u32) -> String {
    let mut d = match Derivation::new(&c.program, &c.compiled, opts.clone()) {
        Ok(d) => d,
        Err(e) => return format!("error: {e:?}"),
    };
    for _ in 0..steps {
        if let Err(e) = d.step() {
            return format!("error: {e:?}");
        }
    }
    format!(
        "{} {}",
        d.step_number(),
        d.current().display(&c.program.symbols)
    )
}

/// The same through `run_steps` (depth first where allowed).
fn expanded(c: &Compilation, opts: &DeriveOptions, steps: u32) -> String {
    let mut d = match Derivation::new(&c.program, &c.compiled, opts.clone()) {
        Ok(d) => d,
        Err(e) => return format!("error: {e:?}"),
    };
    if let Err(e) = d.run_steps(steps) {
        return format!("error: {e:?}");
    }
    format!(
        "{} {}",
        d.step_number(),
        d.current().display(&c.program.symbols)
    )
}

/// Derives `text` both ways for every step count up to `steps`, also
/// through `simulation::derive` (what `lsys build` and `lsys derive -o`
/// run); returns the final string of `steps` steps.
fn same(text: &str, steps: u32, opts: DeriveOptions) -> String {
    let c = compile(text);
    for n in 0..=steps {
        let want = stepping(&c, &opts, n);
        // One thread, and two (the string split in halves).
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let got = pool.install(|| expanded(&c, &opts, n));
            assert_eq!(got, want, "{n} steps of\n{text} on {threads} threads");
        }
        let sim = lsys::internals::simulation::derive(&c.program, &c.compiled, opts.clone(), n);
        let each = lsys::internals::simulation::derive_each(
            &c.program,
            &c.compiled,
            opts.clone(),
            n,
            |_, _| {},
        );
        match (sim, each) {
            (Ok(a), Ok(b)) => assert_eq!(a, b, "{n} steps of\n{text}"),
            (Err(a), Err(b)) => assert_eq!(format!("{a:?}"), format!("{b:?}")),
            (a, b) => panic!("{n} steps of\n{text}: {a:?} against {b:?}"),
        }
    }
    stepping(&c, &opts, steps)
}

fn opts() -> DeriveOptions {
    DeriveOptions::default()
}

#[test]
fn w1_and_w2() {
    let w1 = same(&grammar("X", "X --> F[+X]F[-X]+X\nF --> FF"), 6, opts());
    assert!(
        w1.starts_with(&format!("6 {}[ + F F", "F ".repeat(32))),
        "{w1}"
    );
    let w2 = same(
        &grammar(
            "A(1)",
            "A(x) : x < 7 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]\nA(x) --> F(x)",
        ),
        9,
        opts(),
    );
    assert!(w2.starts_with("9 F(1) [ +(25) F(2) [ +(25) F(3)"), "{w2}");
}

#[test]
fn parameters_conditions_and_several_candidates() {
    let g = common::several_candidates();
    same(&g, 7, opts());
    // A module no production applies to stays, among others that grow.
    let g = grammar(
        "B(5) A(0) B(1)",
        "A(x) : x < 4 --> A(x + 1) [ B(x) ] A(x * 0.5)\nB(y) : y > 3 --> B(y - 1) B(y / 3)",
    );
    same(&g, 8, opts());
}

#[test]
fn faults_and_non_finite_values_give_the_steps_error() {
    let g = grammar("A(3)", "A(x) --> A(x - 1) B(1 / x)\nB(y) --> B(y)");
    assert!(same(&g, 5, opts()).starts_with("error"));
    let g = grammar("A(3)", "A(x) : 1 / (x - 1) > 0 --> A(x - 1) A(x - 1)");
    same(&g, 5, opts());
    let g = grammar("A(1)", "A(x) --> A(x * 1e200) B(x)");
    assert!(same(&g, 5, opts()).starts_with("error"));
}

#[test]
fn limits_of_any_step_give_the_steps_error() {
    let g = grammar("X", "X --> F[+X]F[-X]+X\nF --> FF");
    let small = DeriveOptions {
        max_modules: 500,
        ..opts()
    };
    assert!(same(&g, 8, small).starts_with("error"));
    let g = grammar("A(1)", "A(x) --> A(x) A(x+1) B(x, x)");
    let few = DeriveOptions {
        max_params: 300,
        ..opts()
    };
    assert!(same(&g, 8, few).starts_with("error"));
    // The string of step 1 is over the limit, the final one is empty: the
    // expansion must not skip the step in between.
    let shrinks = grammar("A", "A --> B B B B B B\nB --> ");
    let four = DeriveOptions {
        max_modules: 4,
        ..opts()
    };
    assert!(same(&shrinks, 2, four.clone()).starts_with("error"));
    let params = grammar("A(1)", "A(x) --> B(x) B(x) B(x) B(x)\nB(y) --> C");
    let three = DeriveOptions {
        max_params: 3,
        ..opts()
    };
    assert!(same(&params, 2, three).starts_with("error"));
    // Over the limit only with the modules kept from the axiom.
    let kept = grammar("C C C A", "A --> B B\nB --> ");
    assert!(same(&kept, 2, four.clone()).starts_with("error"));
    // Over the limit only with both halves of a split string together
    // (distinct modules: a repetitive string is not split; 65,536 modules
    // out: a first slice of 8 writes enough for the rest to be split).
    let distinct: String = (0..64).map(|i| format!("A({i}) ")).collect();
    let halves = grammar(&distinct, "A(x) --> B(x) B(x)\nB(x) --> B(x) B(x)");
    let limit = DeriveOptions {
        max_modules: 40_000,
        ..opts()
    };
    assert!(same(&halves, 10, limit).starts_with("error"));
    assert!(same(&halves, 9, opts()).starts_with("9 "));
    // Within the limits the same grammars derive.
    assert_eq!(same(&shrinks, 2, opts()), "2 ");
}

/// Repeated modules (the same symbol and parameters with as many steps to
/// go) are copied from their first expansion: the copies carry the kept
/// modules and the counts of every level, so strings and limit errors are
/// those of stepping; a module that differs only in a parameter (or in the
/// sign of a zero) is expanded on its own.
#[test]
fn repeated_subtrees_are_copied_exactly() {
    let rules = "A(x) : x < 6 --> A(x + 1) [ K(x) ] A(x + 1) A(x * 2) B(x)\nB(y) --> C(y) C(y)\nC(y) : y > 2 -->";
    // Not repetitive at the top: split in halves on two threads.
    let distinct: String = (0..64)
        .map(|i| format!("A({}) ", f64::from(i) / 10.0))
        .collect();
    same(&grammar(&distinct, rules), 8, opts());
    let g = grammar(&format!("{}A(0) A(-0) A(1)", "A(1) ".repeat(64)), rules);
    let full = same(&g, 8, opts());
    // A(0) and A(-0) were expanded each on its own.
    assert!(
        full.contains("[ K(0) ]") && full.contains("[ K(-0) ]"),
        "{}",
        &full[..200]
    );
    for (modules, params) in [(300, usize::MAX), (5_000, usize::MAX), (usize::MAX, 2_000)] {
        let o = DeriveOptions {
            max_modules: modules,
            max_params: params,
            ..opts()
        };
        same(&g, 8, o);
    }
}

/// A limit that only a middle step's string passes, through modules that
/// copies of repeated subtrees write there and the next step erases: the
/// copies must count them as their first expansion did.
#[test]
fn repeated_subtrees_count_the_strings_in_between() {
    let g = grammar(
        "A(0)",
        "A(x) : x < 7 --> A(x + 1) [ K(x) ] A(x + 1) B(x) B(x) B(x)\nB(y) -->",
    );
    let c = compile(&g);
    let mut d = Derivation::new(&c.program, &c.compiled, opts()).unwrap();
    let mut sizes = Vec::new();
    for _ in 0..8 {
        d.step().unwrap();
        sizes.push(d.current().len());
    }
    let last = *sizes.last().unwrap();
    let widest = *sizes.iter().max().unwrap();
    assert!(widest > last, "{sizes:?}");
    let o = DeriveOptions {
        max_modules: last,
        ..opts()
    };
    assert!(same(&g, 8, o).starts_with("error"));
}

#[test]
fn longer_than_the_depth_expanded() {
    let g = grammar("A(0)", "A(x) : x < 1000 --> A(x + 1) B\nB --> C");
    let s = same(&g, 70, opts());
    assert!(s.starts_with("70 A(70) B C C"), "{s}");
}

#[test]
fn decomposition_and_stochastic_grammars_step() {
    let text = "Lsystem: 1\nAxiom: A(1)\nA(x) --> A(x+1) B(x)\ndecomposition\nmaximum depth: 3\nB(y) : y > 1 --> C(y) D\nD --> E E\nendlsystem\n";
    same(text, 6, opts());
    same(
        &grammar("A", "A --> A B : 1\nA --> B A : 2\nB --> A"),
        8,
        opts(),
    );
    same(&grammar("A(0)", "A(x) --> A(ran(1)) B(x)"), 6, opts());
}
