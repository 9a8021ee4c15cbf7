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

/// The guided modeling queries (docs/guided.md): a grammar that asks them
/// is meant to grow inside a scene, along its guides.
const QUERIES: [&str; 7] = ["?DL", "?DG", "?DA", "?NL", "?NG", "?NA", "?X"];

/// Why a grammar built on its own drew nothing, when it asks guides: the
/// queries it uses, and the scenes beside it that host it (or `None`
/// when it asks no guide).
pub(super) fn built_without_its_guides(
    program: &crate::resolve::Program,
    grammar: Option<&Path>,
) -> Option<String> {
    let asked: Vec<&str> = QUERIES
        .into_iter()
        .filter(|q| program.symbols.get(q).is_some())
        .collect();
    if asked.is_empty() {
        return None;
    }
    let asked = asked.join("`, `");
    let hosts = grammar.map(hosting_scenes).unwrap_or_default();
    Some(match hosts.first() {
        Some(scene) => format!(
            "it asks guides (`{asked}`) and was built without any: build the scene that hosts it, `lsys build {} -o {}.glb` (docs/guided.md)",
            scene.display(),
            scene.file_stem().unwrap_or_default().to_string_lossy()
        ),
        None => format!(
            "it asks guides (`{asked}`) and was built without any: build it from a guided scene (a .toml file, docs/guided.md)"
        ),
    })
}

/// The scenes (`*.toml`) in `grammar`'s folder that name its file, sorted,
/// written as the grammar's path is (relative stays relative).
fn hosting_scenes(grammar: &Path) -> Vec<std::path::PathBuf> {
    let Some(file) = grammar.file_name() else {
        return Vec::new();
    };
    let file = file.to_string_lossy();
    let dir = match grammar.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut scenes: Vec<_> = entries
        .filter_map(|e| e.ok())
        .map(|e| grammar.with_file_name(e.file_name()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| std::fs::read_to_string(p).is_ok_and(|t| t.contains(&*file)))
        .collect();
    scenes.sort();
    scenes
}
