//! A derivation the caller drives: a compiled [`Grammar`] and a target
//! step in; each step's string (or the string the turtle draws) written
//! straight to a writer as `lsys derive` prints it, with the warnings and
//! errors as diagnostics. For strings too large to copy: `lsys derive`
//! prints fifty million modules through it. Also here: a string's module
//! counts without building it ([`Grammar::count`]) and the bytecode
//! listing ([`Grammar::disasm`]).

use std::io::{self, Write};

use super::grammar::Grammar;
use crate::derive::{ModuleStore, NumberFormat, NumberStyle};
use crate::diag::Diagnostics;
use crate::simulation::Simulation;

/// How parameters are printed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Numbers {
    /// The shortest digits that read back as the value stored (f32 in the
    /// cpfg dialect).
    #[default]
    Shortest,
    /// Rounded to this many decimals, trailing zeros dropped, never `-0`
    /// (`lsys derive --precision N`).
    Decimals(u8),
    /// As cpfg's `-str` output prints them: C's `%g` (`--cpfg-format`).
    Cpfg,
}

/// A derivation in progress ([`Grammar::derivation`]).
pub struct Derivation<'g> {
    grammar: &'g Grammar,
    sim: Simulation<'g>,
    target: u32,
}

impl Grammar {
    /// A derivation towards step `steps`, at the axiom.
    pub fn derivation(&self, steps: u32) -> Result<Derivation<'_>, Diagnostics> {
        Ok(Derivation {
            grammar: self,
            sim: self.simulation(steps)?,
            target: steps,
        })
    }

    /// The module counts of the string after `steps` steps, by symbol
    /// name in symbol order (symbols absent from it left out), counted
    /// without building the string where the grammar allows (`lsys derive
    /// --count`). Counts saturate at `u64::MAX`.
    pub fn count(&self, steps: u32) -> Result<Vec<(String, u64)>, Diagnostics> {
        let comp = &self.comp;
        let counts = crate::derive::count(
            &comp.program,
            &comp.compiled,
            self.options.build.derive.clone(),
            steps,
        )
        .map_err(Diagnostics::one)?;
        let symbols = &comp.program.symbols;
        Ok(counts
            .per_symbol
            .iter()
            .enumerate()
            .filter(|(_, &n)| n > 0)
            .map(|(s, &n)| (symbols.name(s as u32).to_string(), n))
            .collect())
    }

    /// The compiled productions as documented instructions (`lsys disasm`).
    pub fn disasm(&self) -> String {
        crate::bytecode::disasm(&self.comp.program, &self.comp.compiled)
    }

    /// The components the grammar places that cannot be found where a
    /// build would look (`components/` beside the grammar, then the
    /// options' folders), as `lsys check` reports them; nothing is read
    /// or built.
    pub fn missing_components(&self) -> Diagnostics {
        Diagnostics::all(self.options.build.components.find_all(&self.comp.program))
    }

    /// Productions, decomposition and homomorphism rules.
    pub fn rule_count(&self) -> usize {
        let p = &self.comp.program;
        p.productions.len() + p.decomposition.len() + p.homomorphism.len()
    }

    /// Symbols of the alphabet (`[` and `]` included).
    pub fn symbol_count(&self) -> usize {
        self.comp.program.symbols.len()
    }

    /// Writes `string` as `lsys derive` prints it, parameters as `numbers`
    /// says (no newline).
    fn write_string(
        &self,
        string: &ModuleStore,
        numbers: Numbers,
        out: &mut dyn Write,
    ) -> io::Result<()> {
        let style = match numbers {
            Numbers::Shortest => NumberStyle::Shortest,
            Numbers::Decimals(n) => NumberStyle::Decimals(n),
            Numbers::Cpfg => NumberStyle::PrintfG,
        };
        let fmt = NumberFormat::for_program(&self.comp.program).with_style(style);
        string.write_string_with(&self.comp.program.symbols, fmt, &mut &mut *out)
    }
}

impl Derivation<'_> {
    /// The step the current string is the result of (0: the axiom).
    pub fn step_number(&self) -> u32 {
        self.sim.step_number()
    }

    /// The step it derives towards.
    pub fn target(&self) -> u32 {
        self.target
    }

    /// Derives one more step.
    pub fn step(&mut self) -> Result<(), Diagnostics> {
        self.sim.step().map_err(Diagnostics::one)
    }

    /// Derives up to the target, telling `observe` each step as it starts
    /// (done, of); the steps may be expanded depth first without building
    /// the strings in between.
    pub fn run(&mut self, observe: &mut dyn FnMut(u32, u32)) -> Result<(), Diagnostics> {
        self.sim.run(observe).map_err(Diagnostics::one)
    }

    /// Runs `End:` (after the last step).
    pub fn finish(&mut self) -> Result<(), Diagnostics> {
        self.sim.finish().map_err(Diagnostics::one)
    }

    /// Depth-limit warnings of the decomposition so far.
    pub fn warnings(&self) -> Diagnostics {
        Diagnostics::all(self.sim.derivation().warnings().iter().cloned())
    }

    /// Writes the current string (no newline).
    pub fn write_current(&self, numbers: Numbers, out: &mut dyn Write) -> io::Result<()> {
        self.grammar.write_string(self.sim.current(), numbers, out)
    }

    /// The string the turtle draws from the current one (the homomorphism
    /// applied; in a cpfg model file it continues the derivation's
    /// generator, as each of cpfg's interpretations does).
    pub fn drawn(&mut self) -> Result<Drawn<'_>, Diagnostics> {
        let h = self.sim.drawn().map_err(Diagnostics::one)?;
        Ok(Drawn {
            grammar: self.grammar,
            modules: h.modules,
            warnings: Diagnostics::all(h.warnings),
        })
    }
}

/// The string the turtle draws ([`Derivation::drawn`]).
pub struct Drawn<'g> {
    grammar: &'g Grammar,
    modules: ModuleStore,
    /// Depth warnings of its homomorphism.
    pub warnings: Diagnostics,
}

impl Drawn<'_> {
    /// Writes it (no newline).
    pub fn write(&self, numbers: Numbers, out: &mut dyn Write) -> io::Result<()> {
        self.grammar.write_string(&self.modules, numbers, out)
    }
}
