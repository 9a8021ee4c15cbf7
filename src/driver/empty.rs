//! Why a built model is empty: the module string and the program -> one
//! warning sentence, with a hint when the grammar asks guides and was
//! built without a scene (docs/guided.md).

use std::path::{Path, PathBuf};

use crate::resolve::Program;

/// The warning for a model of `modules` modules that drew no triangle.
pub(super) fn warning(
    name: &str,
    modules: usize,
    program: &Program,
    path: Option<&Path>,
) -> String {
    let hint = built_without_its_guides(program, path)
        .map(|h| format!("\n  help: {h}"))
        .unwrap_or_default();
    let why = match modules {
        0 => "its module string is empty".to_string(),
        1 => "its string of 1 module has no drawing command with a size".to_string(),
        n => format!("its string of {n} modules has no drawing command with a size"),
    };
    format!("{name} draws nothing ({why}); the output is empty{hint}")
}

/// The guided modeling queries (docs/guided.md): a grammar that asks them
/// is meant to grow inside a scene, along its guides.
const QUERIES: [&str; 7] = ["?DL", "?DG", "?DA", "?NL", "?NG", "?NA", "?X"];

/// Why a grammar built on its own drew nothing, when it asks guides: the
/// queries it uses, and the scenes beside it that host it (or `None`
/// when it asks no guide).
fn built_without_its_guides(program: &Program, grammar: Option<&Path>) -> Option<String> {
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
fn hosting_scenes(grammar: &Path) -> Vec<PathBuf> {
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
