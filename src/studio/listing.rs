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

/// A file of the folder a page asked for by its relative path `rel`: one
/// of `endings`, inside the folder (links resolved), at most `max` bytes.
/// The refusal is an HTTP status and a sentence for the page.
pub fn folder_file(
    root: &Path,
    rel: &str,
    endings: &[&str],
    max: u64,
) -> Result<(std::path::PathBuf, Vec<u8>), (u16, String)> {
    if !endings.iter().any(|e| rel.ends_with(e)) {
        return Err((403, format!("{rel}: not a {} file", endings.join(" or "))));
    }
    let full = super::confine(root, rel).map_err(|e| (403, e.to_string()))?;
    let len = std::fs::metadata(&full)
        .map_err(|e| (404, format!("cannot read {rel}: {e}")))?
        .len();
    if len > max {
        return Err((
            403,
            format!(
                "{rel} is {} MiB; the studio reads at most {} MiB",
                len >> 20,
                max >> 20
            ),
        ));
    }
    let bytes = std::fs::read(&full).map_err(|e| (404, format!("cannot read {rel}: {e}")))?;
    Ok((full, bytes))
}
