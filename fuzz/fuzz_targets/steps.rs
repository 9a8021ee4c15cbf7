//! Shared by the `derive` and `cpfg` targets: at most 8 derivation steps
//! of a compiled model with small limits, then its homomorphism, every
//! error rendered.

use lsys::internals::derive::{self, DeriveOptions};
use lsys::internals::diag::render_plain;
use lsys::internals::pipeline::Compilation;

pub fn derive_a_few(c: &Compilation) {
    let opts = DeriveOptions {
        max_modules: 20_000,
        max_params: 100_000,
        ..DeriveOptions::default()
    };
    let mut d = match derive::Derivation::new(&c.program, &c.compiled, opts) {
        Ok(d) => d,
        Err(e) => {
            let _ = render_plain(&e);
            return;
        }
    };
    for _ in 0..c.program.derivation_length.min(8) {
        if let Err(e) = d.step() {
            let _ = render_plain(&e);
            return;
        }
    }
    if !c.program.homomorphism.is_empty() {
        if let Err(e) = d.homomorphism() {
            let _ = render_plain(&e);
        }
    }
}
