//! The options of a derivation: its limits and its seed
//! ([`DeriveOptions`]), set by the caller (`--seed`, `--max-modules`,
//! `--max-params`) and read where a derivation starts (`engine.rs`) and
//! where its tables are built (`tables.rs`).

use crate::lang::rng::{Rand48, DEFAULT_SEED};
use crate::resolve::Program;

/// Limits and seed of a derivation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeriveOptions {
    /// Overrides the program's `seed:`; with neither, [`DEFAULT_SEED`] (0).
    pub seed: Option<u64>,
    /// Largest string (in modules) a step may produce (`--max-modules`).
    pub max_modules: usize,
    /// Largest number of parameter values a string may hold
    /// (`--max-params`); at most `u32::MAX`.
    pub max_params: usize,
}

impl Default for DeriveOptions {
    fn default() -> DeriveOptions {
        DeriveOptions {
            seed: None,
            max_modules: 50_000_000,
            max_params: 200_000_000,
        }
    }
}

impl DeriveOptions {
    /// The seed of `ran` and the paper's choices for `program`:
    /// `--seed`, else `seed:`, else 0. In a cpfg model file `seed:` seeds
    /// only the stochastic choices ([`DeriveOptions::choice_generator`]),
    /// so `ran` starts from `--seed` or 0.
    pub fn effective_seed(&self, program: &Program) -> u64 {
        let file = program.seed.filter(|_| !program.profile.cpfg_stochastic);
        self.seed.or(file).unwrap_or(DEFAULT_SEED)
    }

    /// cpfg's separate generator of stochastic choices, for a cpfg model
    /// file with a `seed:` (`--seed` stands for its value); `None`
    /// otherwise.
    pub fn choice_generator(&self, program: &Program) -> Option<Rand48> {
        let seed = program.seed.filter(|_| program.profile.cpfg_stochastic)?;
        Some(Rand48::cpfg_choice(self.seed.unwrap_or(seed)))
    }
}
