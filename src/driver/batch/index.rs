//! `DIR/index.jsonl`, the batch's record: one [`Entry`] a line, appended
//! when its item is done -> on the next run, the ids already recorded
//! (skipped) and how many lines were damaged (ignored).
//!
//! Why it can be trusted after a crash: an entry is appended only after
//! its output file was renamed into place, and as one `write` of one
//! whole line to a file opened with `O_APPEND`. A run killed mid-write
//! leaves at most a last line without its newline; it is not JSON, so
//! it is ignored and its item built again.
//!
//! Why shards may share it: on a local file system the kernel appends
//! each `write` whole, so lines of processes appending at once never
//! interleave. On NFS `O_APPEND` is emulated by each client (seek to the
//! end, then write) and two clients' lines may overwrite each other; give
//! each shard its own output folder there (docs/batch.md).

use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::entry::{Entry, Status};
use super::error::BatchError;

/// The index's name in the output folder.
pub const INDEX: &str = "index.jsonl";

/// The index, open for appending.
pub struct Index {
    file: File,
    path: PathBuf,
}

/// What an index records.
#[derive(Debug, Default)]
pub struct Recorded {
    /// Each id's status, from its first line.
    pub status: HashMap<String, Status>,
    /// Lines that are not an entry (a line cut short by a killed run).
    pub damaged: usize,
}

/// The part of an entry a rerun needs.
#[derive(Deserialize)]
struct Line {
    id: String,
    status: Status,
}

impl Index {
    /// Opens (creating) `dir`'s index and reads what it records. A last
    /// line cut short gets its newline, so that the next entry starts a
    /// line of its own.
    pub fn open(dir: &Path) -> Result<(Index, Recorded), BatchError> {
        let path = dir.join(INDEX);
        let fail = |doing: &'static str| {
            let path = path.clone();
            move |error| BatchError::Index { path, doing, error }
        };
        let mut file = OpenOptions::new()
            .read(true)
            .append(true)
            .create(true)
            .open(&path)
            .map_err(fail("open"))?;
        let mut text = Vec::new();
        file.read_to_end(&mut text).map_err(fail("read"))?;
        let recorded = read(&text);
        if text.last().is_some_and(|&b| b != b'\n') {
            // Should another process be appending this very moment, its
            // line is whole before this newline is: at worst an empty
            // line, which reading skips.
            file.write_all(b"\n").map_err(fail("append to"))?;
        }
        Ok((Index { file, path }, recorded))
    }

    /// Appends `entry` as one line.
    pub fn append(&mut self, entry: &Entry) -> Result<(), BatchError> {
        let line = entry.to_line();
        let fail = |error| BatchError::Index {
            path: self.path.clone(),
            doing: "append to",
            error,
        };
        // One `write` call, so that the kernel appends the line whole (see
        // the module's comment). A regular file takes all of it unless the
        // disk is full; should it take less, the rest follows.
        let n = self.file.write(line.as_bytes()).map_err(fail)?;
        if n < line.len() {
            self.file.write_all(&line.as_bytes()[n..]).map_err(fail)?;
        }
        Ok(())
    }

    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// The entries of an index's text; lines that are not one are counted.
fn read(text: &[u8]) -> Recorded {
    let mut recorded = Recorded::default();
    for line in text.split(|&b| b == b'\n') {
        if line.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        match serde_json::from_slice::<Line>(line) {
            Ok(l) => {
                recorded.status.entry(l.id).or_insert(l.status);
            }
            Err(_) => recorded.damaged += 1,
        }
    }
    recorded
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_cut_short_is_ignored_and_ended() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join(INDEX),
            "{\"id\":\"a\",\"status\":\"ok\"}\n\n{\"id\":\"b\",\"status\":\"error\"}\n{\"id\":\"c\",\"sta",
        )
        .unwrap();
        let (_, recorded) = Index::open(dir.path()).unwrap();
        assert_eq!(recorded.status.len(), 2);
        assert_eq!(recorded.status["b"], Status::Error);
        assert_eq!(recorded.damaged, 1);
        let text = std::fs::read_to_string(dir.path().join(INDEX)).unwrap();
        assert!(text.ends_with("\"sta\n"), "{text}");
    }
}
