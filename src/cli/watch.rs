//! `lsys watch FILE -o OUT`: the arguments of `build` in, a rebuild of OUT
//! (a model, or a picture for .png) every time FILE or a file it includes
//! changes, until Ctrl-C. Each rebuild prints its diagnostics (standard
//! error) or one summary line (standard output; the `--stats` JSON with
//! `--stats`).
//!
//! The watching is the driver's ([`crate::driver::Watcher`], shared with
//! the studio): the grammar's own file before the first build, then every
//! file the last build read (or, when a build could not read the grammar,
//! the ones before); a burst of writes is one change after 100 ms of quiet.

use std::collections::BTreeSet;
use std::path::PathBuf;

use super::args::BuildArgs;
use super::model::{build_once, format_of, model_job, Report};
use super::{EX_IOERR, EX_NOINPUT, EX_USAGE};
use crate::driver::{Change, Input, WatchError, Watcher};

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
    let watcher = match Watcher::new() {
        Ok(w) => w,
        Err(e) => {
            eprintln!("lsys: {e}");
            return EX_IOERR;
        }
    };
    let mut sources: BTreeSet<PathBuf> = BTreeSet::from([root.clone()]);
    // The grammar's own directory before the first build, so that no save
    // made while it runs is missed (events wait in the channel).
    if let Err(errors) = watcher.watch_files(std::slice::from_ref(&root)) {
        for e in &errors {
            eprintln!("lsys: {e}");
        }
        return match errors[0] {
            WatchError::NoDirectory(_) => EX_NOINPUT,
            _ => EX_IOERR,
        };
    }
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
        // What to react to: every source (a directory that is gone is
        // not watched, and not told).
        let files: Vec<PathBuf> = sources.iter().cloned().collect();
        if let Err(errors) = watcher.watch_files(&files) {
            for e in errors {
                if !matches!(e, WatchError::NoDirectory(_)) {
                    eprintln!("lsys: {e}");
                }
            }
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
        if watcher.wait_for_change(None) == Change::Closed {
            return EX_IOERR;
        }
    }
}
