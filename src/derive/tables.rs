//! What does not change during a derivation: the program, its compiled
//! code and the options in; [`Tables`] out, with each table's productions
//! indexed for dispatch (`matching.rs`'s [`Rules`]), the symbols context
//! passes over, the limits and the dialect's rules of rewriting. Every
//! pass of `derive/` reads it; [`State`](super::state::State) is what
//! changes.

use super::error::{DeriveError, Fail};
use super::matching::Rules;
use super::options::DeriveOptions;
use super::store::MAX_SYMBOLS;
use crate::bytecode::{Compiled, CondCode};
use crate::resolve::{Program, Table, CLOSE_BRACKET, OPEN_BRACKET};

const TABLES: [Table; 3] = [Table::Main, Table::Decomposition, Table::Homomorphism];

pub(crate) fn table_index(t: Table) -> usize {
    match t {
        Table::Main => 0,
        Table::Decomposition => 1,
        Table::Homomorphism => 2,
    }
}

pub(crate) fn table_name(t: Table) -> &'static str {
    match t {
        Table::Main => "production",
        Table::Decomposition => "decomposition",
        Table::Homomorphism => "homomorphism",
    }
}

/// Everything that does not change during a derivation.
pub(crate) struct Tables<'p> {
    pub(crate) program: &'p Program,
    pub(crate) compiled: &'p Compiled,
    pub(crate) rules: [Rules; 3],
    /// `skip[s]`: context matching passes over symbol `s`.
    pub(crate) skip: Vec<bool>,
    pub(crate) max_modules: usize,
    pub(crate) max_params: usize,
    /// cpfg dialect: parameters are stored as 32-bit floats, as cpfg
    /// stores them in its string (expressions still compute in f64).
    pub(crate) f32_params: bool,
    /// cpfg dialect: the symbol `%`, which cuts the rest of its branch
    /// from the string when the next step reads it.
    pub(crate) cut: Option<u32>,
    /// The alphabet has cpfg query modules to fill after each step.
    pub(crate) has_queries: bool,
    /// A file with sub-L-systems: the symbols `?` (with the L-system's
    /// number) and `$` that start and end one in the string.
    pub(crate) sub_open: Option<u32>,
    pub(crate) sub_close: Option<u32>,
    /// A cpfg model file: probabilities are cpfg's (`stochastic.rs`).
    pub(crate) cpfg_choice: bool,
}

impl<'p> Tables<'p> {
    /// Whether a string of `modules` modules and `params` parameter values
    /// is over `--max-modules` or `--max-params`.
    pub(crate) fn over(&self, modules: usize, params: usize) -> bool {
        modules > self.max_modules || params > self.max_params
    }

    pub(crate) fn new(
        program: &'p Program,
        compiled: &'p Compiled,
        opts: &DeriveOptions,
    ) -> Result<Tables<'p>, Fail> {
        let nsyms = program.symbols.len();
        if nsyms > MAX_SYMBOLS {
            return Err(Box::new(DeriveError::TooManySymbols {
                count: nsyms,
                limit: MAX_SYMBOLS,
            }));
        }
        let profile = program.profile;
        let cut = program
            .symbols
            .get("%")
            .filter(|_| profile.cut_in_rewriting);
        let mut rules = TABLES.map(|t| {
            let never: Vec<bool> = compiled
                .table(t)
                .iter()
                .map(|c| matches!(c.cond, CondCode::Never(_)))
                .collect();
            Rules::new(program.table(t), &never, nsyms)
        });
        if let Some(c) = cut {
            // Route `%` to the dispatch loop, where it is cut.
            rules[0].has_rules[c as usize] = true;
        }
        let subs = !program.sub_lsystems.is_empty();
        let sub_open = program.symbols.get("?").filter(|_| subs);
        let sub_close = program.symbols.get("$").filter(|_| subs);
        for s in [sub_open, sub_close].into_iter().flatten() {
            // The dispatch loop switches L-systems at these.
            for r in &mut rules {
                r.has_rules[s as usize] = true;
            }
        }
        Ok(Tables {
            program,
            compiled,
            rules,
            // Outside the cpfg dialect brackets always structure context.
            skip: (0..nsyms as u32)
                .map(|s| {
                    program.skips_in_context(s)
                        && (profile.context_through_brackets
                            || (s != OPEN_BRACKET && s != CLOSE_BRACKET))
                })
                .collect(),
            max_modules: opts.max_modules,
            max_params: opts.max_params.min(u32::MAX as usize),
            f32_params: profile.f32_params,
            cut,
            has_queries: program.symbols.list.iter().any(|s| {
                s.kind == crate::resolve::SymbolKind::Query
                    && matches!(s.name.as_str(), "?P" | "?H" | "?L" | "?U" | "?S")
            }),
            sub_open,
            sub_close,
            cpfg_choice: profile.cpfg_stochastic,
        })
    }

    /// The most parameters any production binds (the size of
    /// [`State::binds`](super::state::State::binds)).
    pub(crate) fn nbinds(&self) -> usize {
        TABLES
            .iter()
            .flat_map(|&t| self.program.table(t))
            .map(|p| p.nparams as usize)
            .max()
            .unwrap_or(0)
    }
}
