//! A derived string as the library hands it out: the modules of one step,
//! printed exactly as `lsys derive` prints them.

use std::fmt;
use std::sync::Arc;

use crate::derive::{ModuleStore, NumberFormat, NumberStyle};
use crate::pipeline::Compilation;

/// The string of one derivation step. `Display` prints it as `lsys derive`
/// does: modules separated by one space, parameters as `A(1,2.5)` with the
/// shortest digits that read back as the value stored (f32 in the cpfg
/// dialect).
#[derive(Clone)]
pub struct Derived {
    comp: Arc<Compilation>,
    string: ModuleStore,
    step: u32,
}

impl Derived {
    pub(crate) fn new(comp: Arc<Compilation>, string: ModuleStore, step: u32) -> Derived {
        Derived { comp, string, step }
    }

    /// The step this string is the result of (0: the axiom).
    pub fn step(&self) -> u32 {
        self.step
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.string.len()
    }

    /// Whether the string is empty.
    pub fn is_empty(&self) -> bool {
        self.string.is_empty()
    }

    /// The modules in order: each symbol's name and its parameters.
    pub fn modules(&self) -> impl Iterator<Item = (&str, &[f64])> {
        let symbols = &self.comp.program.symbols;
        self.string.iter().map(|m| (symbols.name(m.sym), m.params))
    }

    /// Printed with every parameter rounded to `decimals` places (trailing
    /// zeros dropped, never `-0`): stable snapshots across last-digit
    /// changes (`lsys derive --precision N`).
    pub fn display_with(&self, decimals: u8) -> String {
        self.print(self.format().with_style(NumberStyle::Decimals(decimals)))
    }

    /// Printed as cpfg's `-str` output prints parameters (C's `%g`;
    /// `lsys derive --cpfg-format`).
    pub fn display_cpfg(&self) -> String {
        self.print(self.format().with_style(NumberStyle::PrintfG))
    }

    fn format(&self) -> NumberFormat {
        NumberFormat::for_program(&self.comp.program)
    }

    fn print(&self, fmt: NumberFormat) -> String {
        self.string.display_with(&self.comp.program.symbols, fmt)
    }
}

impl fmt::Display for Derived {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.print(self.format()))
    }
}

impl fmt::Debug for Derived {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Derived(step {}: {self})", self.step)
    }
}
