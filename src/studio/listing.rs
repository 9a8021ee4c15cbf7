//! The opened folder's files a page may open: a folder and the endings
//! wanted -> relative `/`-separated paths, four folders deep, without
//! hidden folders and build output, links not followed.

use std::path::Path;

/// The folder's files (to [`LIST_DEPTH`]) whose names end in one of
/// `endings`, by path.
pub fn files_ending(root: &Path, endings: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    list(root, "", 0, endings, &mut out);
    out.sort();
    out
}

/// Folders below the opened one that are listed.
const LIST_DEPTH: usize = 4;
/// Files listed at most (a folder opened by mistake, such as `~`).
const LIST_MAX: usize = 2000;

fn list(dir: &Path, prefix: &str, depth: usize, endings: &[&str], out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = entries.flatten().collect();
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        if out.len() >= LIST_MAX {
            return;
        }
        let name = e.file_name().to_string_lossy().into_owned();
        // Links are not followed (the folder's confinement), nor hidden
        // folders and build output.
        let Ok(kind) = e.file_type() else { continue };
        if kind.is_dir() {
            let skipped =
                name.starts_with('.') || ["target", "node_modules"].contains(&name.as_str());
            if depth < LIST_DEPTH && !skipped {
                list(
                    &e.path(),
                    &format!("{prefix}{name}/"),
                    depth + 1,
                    endings,
                    out,
                );
            }
        } else if kind.is_file() && endings.iter().any(|x| name.ends_with(x)) {
            out.push(format!("{prefix}{name}"));
        }
    }
}
