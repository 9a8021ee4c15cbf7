//! Fuzz target: any bytes -> compile -> build (derive at most 6 steps,
//! turtle, meshes, small limits) -> a GLB in memory. No input may panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lsys::internals::build::{self, BuildOptions};
use lsys::internals::derive::DeriveOptions;
use lsys::internals::load::{Input, Options};
use lsys::internals::mesh::MeshOptions;
use lsys::internals::pipeline;

fuzz_target!(|data: &[u8]| {
    let input = Input::Text {
        name: "fuzz.lsys".into(),
        text: String::from_utf8_lossy(data).into_owned(),
    };
    let Ok(c) = pipeline::compile(&input, &Options::default()) else {
        return;
    };
    let opts = BuildOptions {
        steps: Some(c.program.derivation_length.min(6)),
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
            let _ = lsys::internals::export::gltf::to_glb(&b.scene);
        }
        Err(e) => {
            let _ = lsys::internals::diag::render_plain(&e);
        }
    }
});
