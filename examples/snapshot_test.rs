//! The shortest correct use of lsys as a library in a test: derive a
//! grammar step by step and keep each step as an insta snapshot.
//!
//! `cargo test --example snapshot_test` runs the test below (insta writes
//! `examples/snapshots/*.snap`, reviewed and committed like any snapshot);
//! `cargo run --example snapshot_test` prints the same steps.

use lsys::{Diagnostics, Grammar};

/// ABOP Fig 1.24a's bracketed plant, three steps.
const PLANT: &str = "\
derivation length: 3
angle: 25.7
axiom: F
F --> F[+F]F[-F]F
";

/// Every step of the derivation, one per line, as `lsys derive --every`
/// prints them (step number first).
fn steps(text: &str) -> Result<String, Diagnostics> {
    let grammar = Grammar::from_str("plant.lsys", text)?;
    let mut out = String::new();
    for derived in grammar.steps() {
        let derived = derived?;
        out.push_str(&format!("{}: {derived}\n", derived.step()));
    }
    Ok(out)
}

fn main() {
    match steps(PLANT) {
        Ok(text) => print!("{text}"),
        Err(d) => {
            eprint!("{}", d.render_plain());
            std::process::exit(65);
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_plant_step_by_step() {
        insta::assert_snapshot!(super::steps(super::PLANT).unwrap());
    }

    #[test]
    fn a_mistake_is_a_diagnostic_with_file_line_and_column() {
        let err = super::steps("axiom: F(len)\nF(x) --> F(x)[+F(x)]\n").unwrap_err();
        assert!(!err.is_input_error());
        insta::assert_snapshot!(err.render_plain());
    }
}
