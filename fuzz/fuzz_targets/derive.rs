//! Fuzz target: any bytes -> compile -> derive (at most 8 steps, small
//! module and parameter limits) -> homomorphism. No input may panic; a
//! limit must end the run with an error.
#![no_main]

mod steps;

use libfuzzer_sys::fuzz_target;
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
    steps::derive_a_few(&c);
});
