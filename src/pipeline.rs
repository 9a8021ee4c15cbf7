//! The front half of the compiler in one call: input -> load (and parse)
//! -> resolve -> bytecode, with every diagnostic collected. The CLI, the tests and the
//! REPL all go through here.

use miette::Report;

use crate::bytecode::{self, Compiled};
use crate::load::{self, Input, InputError};
use crate::resolve::{self, Options, Program};

/// A grammar ready to derive.
pub struct Compilation {
    pub program: Program,
    pub compiled: Compiled,
    /// Warnings (the grammar still compiled).
    pub warnings: Vec<Report>,
}

/// Why a grammar did not compile.
pub enum Failure {
    /// The root input could not be read (exit code 66).
    Input(InputError),
    /// The grammar has errors; all of them, with any warnings.
    Diagnostics { diagnostics: Vec<Report> },
}

pub fn compile(input: &Input, opts: &Options) -> Result<Compilation, Failure> {
    let loaded = load::load(input, opts).map_err(Failure::Input)?;
    let resolved = match resolve::resolve(loaded, opts) {
        Err(f) => {
            return Err(Failure::Diagnostics {
                diagnostics: f.diagnostics,
            })
        }
        Ok(r) => r,
    };
    match bytecode::compile(&resolved.program) {
        Ok(compiled) => Ok(Compilation {
            program: resolved.program,
            compiled,
            warnings: resolved.warnings,
        }),
        Err(e) => {
            let mut diagnostics = vec![Report::new(e)];
            diagnostics.extend(resolved.warnings);
            Err(Failure::Diagnostics { diagnostics })
        }
    }
}
