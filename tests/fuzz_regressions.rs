//! Every input a fuzzer crashed `lsys` with (tests/fuzz_regressions/,
//! raw bytes, possibly invalid UTF-8) goes through every stage the fuzz
//! targets drive: parse, compile, derive, build, GLB. None may panic; each
//! must end in a model or in diagnostics that render, and none may take
//! long (a fuzzer's timeout is a crash too).

use lsys::internals::build::{self, BuildOptions};
use lsys::internals::derive::DeriveOptions;
use lsys::internals::load::{Input, Options};
use lsys::internals::mesh::MeshOptions;
use lsys::internals::pipeline;
use lsys::internals::source::{Origin, SourceFile};

fn run(bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes).into_owned();
    let file = SourceFile::new("fuzz.lsys", Origin::Memory, text.clone());
    for e in &lsys::internals::parse::parse(0, &file).1 {
        lsys::internals::diag::render_plain(e);
    }
    let input = Input::Text {
        name: "fuzz.lsys".into(),
        text,
    };
    let c = match pipeline::compile(&input, &Options::default()) {
        Ok(c) => c,
        Err(d) => {
            d.render_plain();
            return;
        }
    };
    lsys::internals::bytecode::disasm(&c.program, &c.compiled);
    let opts = BuildOptions {
        steps: Some(c.program.derivation_length.min(8)),
        derive: DeriveOptions {
            max_modules: 20_000,
            max_params: 100_000,
            ..DeriveOptions::default()
        },
        mesh: MeshOptions {
            max_triangles: 200_000,
            ..MeshOptions::default()
        },
        ..BuildOptions::default()
    };
    match build::build(&c, &opts) {
        Ok(b) => {
            lsys::internals::export::gltf::to_glb(&b.scene).expect("a built scene exports");
        }
        Err(e) => {
            lsys::internals::diag::render_plain(&e);
        }
    }
}

#[test]
fn fuzz_regressions_do_not_panic() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let name = path.display().to_string();
        let t0 = std::time::Instant::now();
        if std::panic::catch_unwind(|| run(&bytes)).is_err() {
            panic!("{name} panics");
        }
        let took = t0.elapsed();
        assert!(took.as_secs() < 20, "{name} took {took:?}");
        n += 1;
    }
    assert!(n > 0, "no regression inputs in {}", dir.display());
}
