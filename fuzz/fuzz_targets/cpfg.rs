//! Fuzz target: any bytes as a cpfg model file (`fuzz.l`): cpfg's C
//! preprocessor, then parse, resolve, bytecode and at most 8 derivation
//! steps with small limits, every diagnostic rendered. No input may
//! panic; a limit must end the run with an error.
#![no_main]

mod steps;

use libfuzzer_sys::fuzz_target;
use lsys::internals::diag::render_plain;
use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline;

fuzz_target!(|data: &[u8]| {
    let input = Input::Text {
        name: "fuzz.l".into(),
        text: String::from_utf8_lossy(data).into_owned(),
    };
    let c = match pipeline::compile(&input, &Options::default()) {
        Ok(c) => c,
        Err(d) => {
            let _ = d.render_plain();
            return;
        }
    };
    for w in &c.warnings {
        let _ = render_plain(w.as_ref());
    }
    steps::derive_a_few(&c);
});
