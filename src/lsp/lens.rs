//! Code lenses: how many times each production of the root document fired
//! in the file's derivation. Input: an [`Analysis`] whose grammar compiles;
//! output: one lens per main production of the root document, e.g.
//! "fired 40 times in steps 1-4".
//!
//! How it counts: the library's [`Derivation`] is stepped with
//! [`Derivation::counting_firings`], which counts, in the general engine,
//! every time a main production is chosen for a module (after its
//! condition and the stochastic choice). It derives the file's
//! `derivation length:` steps, at most [`MAX_STEPS`], and stops early —
//! counting the steps done — once a step takes the string over
//! [`MAX_MODULES`] modules or the derivation has run [`TIME_BUDGET`]. The
//! derivation alone is run: no environment answers query modules and
//! `End:` is not run, so a model that reads `?P` may count differently
//! from `lsys derive`. Decomposition and homomorphism productions get no
//! count.

use std::time::{Duration, Instant};

use lsp_types::{CodeLens, Command};

use super::analysis::{Analysis, ROOT};
use super::position::LineIndex;
use crate::derive::{Derivation, DeriveOptions};

pub const MAX_STEPS: u32 = 20;
pub const MAX_MODULES: usize = 200_000;
pub const TIME_BUDGET: Duration = Duration::from_millis(250);

/// Firing counts of the main productions and the number of steps run.
pub fn firings(a: &Analysis) -> Option<(Vec<u64>, u32)> {
    let c = a.result.as_ref().ok()?;
    let opts = DeriveOptions {
        max_modules: MAX_MODULES * 8,
        ..DeriveOptions::default()
    };
    let mut d = Derivation::new(&c.program, &c.compiled, opts)
        .ok()?
        .counting_firings();
    let target = c.program.derivation_length.min(MAX_STEPS);
    let start = Instant::now();
    let mut done = 0;
    while done < target {
        if d.step().is_err() {
            break;
        }
        done += 1;
        if d.current().len() > MAX_MODULES || start.elapsed() > TIME_BUDGET {
            break;
        }
    }
    Some((d.firings().to_vec(), done))
}

pub fn lenses(a: &Analysis) -> Vec<CodeLens> {
    let Some((counts, steps)) = firings(a) else {
        return Vec::new();
    };
    let program = a.program().expect("firings needs a program");
    let ix = LineIndex::new(a.text(ROOT));
    let span_text = match steps {
        0 => "in no step (derivation length 0)".to_string(),
        1 => "in step 1".to_string(),
        n => format!("in steps 1-{n}"),
    };
    program
        .productions
        .iter()
        .zip(counts)
        .filter(|(p, _)| p.span.file == ROOT)
        .map(|(p, n)| {
            let start = ix.position(p.span.start as usize);
            CodeLens {
                range: lsp_types::Range::new(start, start),
                command: Some(Command {
                    title: format!(
                        "fired {n} time{} {span_text}",
                        if n == 1 { "" } else { "s" }
                    ),
                    command: String::new(),
                    arguments: None,
                }),
                data: None,
            }
        })
        .collect()
}
