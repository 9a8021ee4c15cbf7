//! Fuzz target: any bytes -> parse, resolve, bytecode, with every
//! diagnostic rendered. No input may panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lsys::internals::pipeline;
use lsys::internals::load::{Input, Options};

fuzz_target!(|data: &[u8]| {
    let input = Input::Text {
        name: "fuzz.lsys".into(),
        text: String::from_utf8_lossy(data).into_owned(),
    };
    match pipeline::compile(&input, &Options::default()) {
        Ok(c) => {
            for w in &c.warnings {
                let _ = lsys::internals::diag::render_plain(w.as_ref());
            }
            let _ = lsys::internals::bytecode::disasm(&c.program, &c.compiled);
        }
        Err(d) => {
            let _ = d.render_plain();
        }
    }
});
