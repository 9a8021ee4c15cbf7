//! Which of lsys's two TOML formats a file is: its text -> a guided scene
//! (`[[guide]]` tables, docs/guided.md) or a Pailou component graph
//! (`[components]`, docs/pailou.md), told apart by their keys; a file
//! that is neither is refused by name, with what each format starts with.

use std::path::Path;

use miette::Diagnostic;
use thiserror::Error;

/// The two TOML formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TomlFile {
    GuidedScene,
    PailouGraph,
}

/// A `.toml` file that is neither format.
#[derive(Debug, Error, Diagnostic)]
#[error("{file} is neither a guided scene nor a Pailou component graph")]
#[diagnostic(
    code(lsys::driver::unknown_toml),
    help("a guided scene has [[guide]] tables (docs/guided.md); a Pailou graph has `type`, `centre`, [components] and [attach] (docs/pailou.md)")
)]
pub struct NeitherFormat {
    pub file: String,
}

/// Which format `text` (the file at `path`) is. Text that is not TOML is
/// taken for what its table headers say (a guided scene if they say
/// nothing), so that the format's own reader reports the syntax error
/// with its place.
pub fn toml_file(path: &Path, text: &str) -> Result<TomlFile, NeitherFormat> {
    let (scene, graph) = match text.parse::<toml::Table>() {
        Ok(t) => (
            t.contains_key("guide") || t.contains_key("seeds"),
            t.contains_key("components") || t.contains_key("attach"),
        ),
        Err(_) => {
            let header = |h: &str| text.lines().any(|l| l.trim_start().starts_with(h));
            let graph = header("[components]") || header("[attach]");
            (!graph, graph)
        }
    };
    match (scene, graph) {
        (true, _) => Ok(TomlFile::GuidedScene),
        (false, true) => Ok(TomlFile::PailouGraph),
        (false, false) => Err(NeitherFormat {
            file: path.display().to_string(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_graphs_and_neither_are_told_apart() {
        let p = Path::new("x.toml");
        let scene = "steps = 3\n[[guide]]\nname = \"g\"\n";
        let graph = "type = \"ridge\"\ncentre = \"L\"\n[components]\nL = \"lintel\"\n";
        assert_eq!(toml_file(p, scene).unwrap(), TomlFile::GuidedScene);
        assert_eq!(toml_file(p, graph).unwrap(), TomlFile::PailouGraph);
        let e = toml_file(p, "[package]\nname = \"x\"\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.toml is neither a guided scene nor a Pailou component graph"
        );
        // Broken TOML goes to the reader its headers name.
        assert_eq!(
            toml_file(p, "[components]\nL = \n").unwrap(),
            TomlFile::PailouGraph
        );
        assert_eq!(toml_file(p, "steps = \n").unwrap(), TomlFile::GuidedScene);
    }
}
