//! Fuzz target: any bytes -> the parser. Invalid UTF-8 is read the way
//! `lsys` reads a file (lossily); no input may panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lsys::internals::source::{Origin, SourceFile};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    let file = SourceFile::new("fuzz.lsys", Origin::Memory, text);
    let (_ast, errors) = lsys::internals::parse::parse(0, &file);
    // Rendering walks the spans: a span outside the text would panic here.
    for e in &errors {
        let _ = lsys::internals::diag::render_plain(e);
    }
});
