//! Fuzz target: any bytes -> compile -> derive (at most 8 steps, small
//! module and parameter limits) -> homomorphism. No input may panic; a
//! limit must end the run with an error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lsys::internals::derive::{self, DeriveOptions};
use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline;

fuzz_target!(|data: &[u8]| {
    let input = Input::Text {
        name: "fuzz.lsys".into(),
        text: String::from_utf8_lossy(data).into_owned(),
    };
    let Ok(c) = pipeline::compile(&input, &Options::default()) else {
        return;
    };
    let opts = DeriveOptions {
        max_modules: 20_000,
        max_params: 100_000,
        ..DeriveOptions::default()
    };
    let mut d = match derive::Derivation::new(&c.program, &c.compiled, opts) {
        Ok(d) => d,
        Err(e) => {
            let _ = lsys::internals::diag::render_plain(&e);
            return;
        }
    };
    for _ in 0..c.program.derivation_length.min(8) {
        if let Err(e) = d.step() {
            let _ = lsys::internals::diag::render_plain(&e);
            return;
        }
    }
    if !c.program.homomorphism.is_empty() {
        if let Err(e) = d.homomorphism() {
            let _ = lsys::internals::diag::render_plain(&e);
        }
    }
});
