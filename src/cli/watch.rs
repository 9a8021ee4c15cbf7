//! `lsys watch FILE -o OUT`: the arguments of `build` in, a rebuild of OUT
//! (a model, or a picture for .png) every time FILE or a file it includes
//! changes, until Ctrl-C. Each rebuild prints its diagnostics (standard
//! error) or one summary line (standard output; the `--stats` JSON with
//! `--stats`).
//!
//! The directories of all source files are watched (not the files: an
//! editor that saves by writing a new file and renaming it over the old one
//! would end a watch on the file), events are filtered by file name, and a
//! burst of events is taken as one change once 100 ms pass without another.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use notify::event::{AccessKind, AccessMode};
use notify::{EventKind, RecursiveMode, Watcher};

use super::args::BuildArgs;
use super::model::{build_once, format_of, model_job, Report};
use super::{EX_IOERR, EX_NOINPUT, EX_USAGE};
use crate::driver::Input;

/// Events closer together than this are one change.
const DEBOUNCE: Duration = Duration::from_millis(100);

pub fn watch_cmd(b: &BuildArgs, color: bool) -> i32 {
    let format = match format_of(&b.output) {
        Ok(f) => f,
        Err(msg) => {
            eprintln!("{msg}");
            return EX_USAGE;
        }
    };
    let root = match Input::from_arg(&b.model.common.file) {
        Input::Path(p) => p,
        _ => {
            eprintln!("lsys: `watch` needs a grammar file; standard library grammars never change");
            return EX_USAGE;
        }
    };
    let (tx, rx) = mpsc::channel();
    let mut watcher = match notify::recommended_watcher(tx) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("lsys: cannot watch files: {e}");
            return EX_IOERR;
        }
    };
    let mut sources: BTreeSet<PathBuf> = BTreeSet::from([root.clone()]);
    let mut dirs: BTreeSet<PathBuf> = BTreeSet::new();
    // The grammar's own directory before the first build, so that no save
    // made while it runs is missed (events wait in the channel).
    let Some(dir) = key_of(&root).and_then(|k| k.parent().map(Path::to_path_buf)) else {
        eprintln!(
            "lsys: cannot watch {}: its directory does not exist",
            root.display()
        );
        return EX_NOINPUT;
    };
    if let Err(e) = watcher.watch(&dir, RecursiveMode::NonRecursive) {
        eprintln!("lsys: cannot watch {}: {e}", dir.display());
        return EX_IOERR;
    }
    dirs.insert(dir);
    let mut first = true;
    loop {
        let outcome = build_once(
            model_job(&b.model),
            &b.output,
            &b.picture,
            format,
            color,
            Report::Summary,
            b.model.look.stats,
        );
        if let Some(files) = outcome.sources {
            sources = files.into_iter().collect();
            sources.insert(root.clone());
        }
        // What to react to: each source as (its directory, canonical) + name.
        let mut keys = BTreeSet::new();
        for f in &sources {
            let Some(key) = key_of(f) else { continue };
            let dir = key.parent().map(Path::to_path_buf).unwrap_or_default();
            if dirs.insert(dir.clone()) {
                if let Err(e) = watcher.watch(&dir, RecursiveMode::NonRecursive) {
                    eprintln!("lsys: cannot watch {}: {e}", dir.display());
                }
            }
            keys.insert(key);
        }
        if first {
            let n = sources.len();
            eprintln!(
                "lsys: watching {} ({n} file{}); Ctrl-C stops",
                root.display(),
                if n == 1 { "" } else { "s" }
            );
            first = false;
        }
        // Wait for a change to a source, then for the burst to end.
        loop {
            match rx.recv() {
                Ok(Ok(ev)) if relevant(&ev.kind) && ev.paths.iter().any(|p| keys.contains(p)) => {
                    break
                }
                Ok(_) => {}
                Err(_) => return EX_IOERR,
            }
        }
        while rx.recv_timeout(DEBOUNCE).is_ok() {}
    }
}

/// `file` as the watcher reports it: its directory made canonical, then
/// its name.
fn key_of(file: &Path) -> Option<PathBuf> {
    let name = file.file_name()?;
    let dir = file
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    Some(std::fs::canonicalize(dir).ok()?.join(name))
}

/// Whether an event can mean new content (reads, including our own, do not).
fn relevant(kind: &EventKind) -> bool {
    match kind {
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        EventKind::Access(_) => false,
        _ => true,
    }
}
