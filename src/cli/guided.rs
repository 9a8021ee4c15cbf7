//! `lsys build SCENE.toml` and `lsys render SCENE.toml`: a guided scene
//! (docs/guided.md) in, a model file or a picture out; `--guides` adds the
//! guides and links, `--stats` prints seeds, messages and time per step.

use std::path::Path;
use std::time::Instant;

use super::args::{ModelArgs, PictureArgs};
use super::commands::report;
use super::model::{component_search, mesh_options, ms, picture, write_failed};
use super::{EX_DATAERR, EX_OK};
use crate::export::output::{write_scene, Format};
use crate::guided;

/// Runs, meshes and writes a guided scene; the exit code.
pub fn build_scene(
    m: &ModelArgs,
    out: &Path,
    pic: &PictureArgs,
    format: Format,
    color: bool,
) -> i32 {
    let path = Path::new(&m.common.file);
    let opts = m.common.source.options(&m.common.define);
    let t0 = Instant::now();
    let mut loaded = match guided::load_file(path, &opts) {
        Ok(l) => l,
        Err(e) => {
            report(e.as_ref(), color);
            return EX_DATAERR;
        }
    };
    if let Some(n) = m.run.steps {
        loaded.spec.steps = n;
    }
    if let Some(s) = m.run.seed {
        loaded.spec.seed = Some(s);
    }
    let t1 = Instant::now();
    let outcome = match guided::run(&loaded) {
        Ok(o) => o,
        Err(e) => {
            report(&e, color);
            return EX_DATAERR;
        }
    };
    let t2 = Instant::now();
    let search = component_search(&m.look, path.parent().map(Path::to_path_buf));
    let mopts = mesh_options(&m.look);
    let scene = match guided::build::scene(&loaded, &outcome, m.look.guides, &search, &mopts) {
        Ok(s) => s,
        Err(e) => {
            report(&e, color);
            return EX_DATAERR;
        }
    };
    match write_scene(&scene, out, format, &picture(pic)) {
        Ok(bytes) => {
            if m.look.stats {
                let steps = loaded.spec.steps.max(1);
                println!(
                    "{}",
                    serde_json::json!({
                        "seeds": outcome.seeds.len(),
                        "messages": outcome.messages.len(),
                        "triangles": scene.triangle_count(),
                        "output": {"path": out.display().to_string(), "bytes": bytes},
                        "timings_ms": {
                            "load": ms(t1 - t0),
                            "run": ms(t2 - t1),
                            "per_step": ms((t2 - t1) / steps),
                        },
                    })
                );
            }
            EX_OK
        }
        Err(e) => write_failed(e, out, color),
    }
}
