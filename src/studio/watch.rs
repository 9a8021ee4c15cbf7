//! Grammar mode's watcher. Input: the opened folder; output: a
//! [`Snapshot`] of its files, which the grammar session takes *before* it
//! reads them, and which the watcher thread compares with the folder's
//! current one to know when to rebuild.
//!
//! Taking the snapshot before the read (and not when the watcher first
//! looks) closes the window in which a save right after opening was
//! taken as the baseline and never shown. Polling, not notify: editors
//! save by rename, and a folder of grammars is small.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// What the watcher compares: every file's (path, modified, length) two
/// levels deep (at most 2000), and a hash of the root grammar's text,
/// because a same-length save within a file system's timestamp tick
/// (a second on some) leaves the first part unchanged.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Snapshot {
    files: Vec<(PathBuf, SystemTime, u64)>,
    root_text: u64,
}

impl Snapshot {
    pub fn take(folder: &Path, root_file: &Path) -> Snapshot {
        let root_text = std::fs::read(root_file)
            .map(|bytes| {
                let mut h = DefaultHasher::new();
                bytes.hash(&mut h);
                h.finish()
            })
            .unwrap_or(0);
        Snapshot {
            files: files(folder),
            root_text,
        }
    }
}

fn files(root: &Path) -> Vec<(PathBuf, SystemTime, u64)> {
    let mut out = Vec::new();
    let mut dirs = vec![(root.to_path_buf(), 0)];
    while let Some((dir, depth)) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            let Ok(meta) = e.metadata() else { continue };
            if meta.is_dir() {
                let name = e.file_name();
                let hidden = name.to_string_lossy().starts_with('.');
                if depth < 2 && !hidden && name != "node_modules" && name != "target" {
                    dirs.push((p, depth + 1));
                }
            } else if out.len() < 2000 {
                let modified = meta.modified().unwrap_or(SystemTime::UNIX_EPOCH);
                out.push((p, modified, meta.len()));
            }
        }
    }
    out.sort();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_same_length_save_changes_the_snapshot() {
        let dir = tempfile::tempdir().unwrap();
        let dir = dir.path();
        let f = dir.join("a.lsys");
        std::fs::write(&f, "#define N 2\n").unwrap();
        let before = Snapshot::take(dir, &f);
        assert_eq!(before, Snapshot::take(dir, &f));
        std::fs::write(&f, "#define N 3\n").unwrap();
        let after = Snapshot::take(dir, &f);
        assert_ne!(before, after);
    }
}
