//! The one file watcher, for `lsys watch` and the studio's grammar mode.
//! Input: the files a job read ([`Done::sources`](super::Done::sources),
//! or [`Failure::sources`](super::Failure::sources), and the root grammar
//! before the first build); output: a [`Change`] once one of them has
//! been written, created, removed or renamed over, and the burst of
//! events that came with it has ended.
//!
//! On notify. The directory of each file is watched, not the file (an
//! editor that saves by writing a new file and renaming it over the old
//! one would end a watch on the file), without its subdirectories, and
//! events are kept when they name one of the files, compared as the
//! canonical directory plus the file name ([`key_of`]). Reads, ours
//! among them, are not changes ([`relevant`]). A burst of events is one
//! change once [`DEBOUNCE`] passes without another for one of the files.
//!
//! Nothing is lost while a job runs: events wait in the channel until
//! [`Watcher::wait_for_change`] reads them. So a front end gives the
//! files to [`Watcher::watch_files`] *before* the job reads them (the
//! root grammar, and what the last job read), and again after with what
//! this one read: a save made between the read and the end of the job is
//! the next change, even a save right after opening. An included file
//! met for the first time in another directory is watched only once the
//! job has read it.
//!
//! The watcher is shared between threads (the studio's requests rebuild,
//! its watcher thread waits): every method takes `&self`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use notify::event::{AccessKind, AccessMode};
use notify::{EventKind, RecommendedWatcher, RecursiveMode, Watcher as _};

/// Events closer together than this are one change.
const DEBOUNCE: Duration = Duration::from_millis(100);

/// What [`Watcher::wait_for_change`] saw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// One of the files changed (and the burst ended).
    Changed,
    /// The timeout passed without a change.
    TimedOut,
    /// The watcher stopped: no change will come.
    Closed,
}

/// Why a watch could not start.
#[derive(Debug, thiserror::Error)]
pub enum WatchError {
    /// The system's watcher could not be made (inotify's limits).
    #[error("cannot watch files: {0}")]
    Start(notify::Error),
    /// The file's directory does not exist: nothing to watch.
    #[error("cannot watch {}: its directory does not exist", .0.display())]
    NoDirectory(PathBuf),
    /// The directory could not be watched.
    #[error("cannot watch {}: {error}", dir.display())]
    Watch { dir: PathBuf, error: notify::Error },
}

/// Watches the folders of a set of files and tells a change to one of
/// them (src/driver/watch.rs says how).
pub struct Watcher {
    dirs: Mutex<Dirs>,
    /// The files that count, as [`key_of`] gives them.
    keys: Mutex<BTreeSet<PathBuf>>,
    events: Mutex<Receiver<notify::Result<notify::Event>>>,
}

/// The system's watcher and the directories given to it: `true` when
/// watched, `false` when that failed (tried once, told once).
struct Dirs {
    notify: RecommendedWatcher,
    watched: BTreeMap<PathBuf, bool>,
}

impl Watcher {
    /// A watcher of no files yet.
    pub fn new() -> Result<Watcher, WatchError> {
        let (tx, rx) = mpsc::channel();
        let notify = notify::recommended_watcher(tx).map_err(WatchError::Start)?;
        Ok(Watcher {
            dirs: Mutex::new(Dirs {
                notify,
                watched: BTreeMap::new(),
            }),
            keys: Mutex::new(BTreeSet::new()),
            events: Mutex::new(rx),
        })
    }

    /// From now on, a change is a change to one of `files` (and no
    /// other). Their directories are watched from the moment this
    /// returns; directories no longer needed are left. A file whose
    /// directory does not exist, or whose directory could not be watched
    /// (told once per directory), is an error of the list; the others are
    /// watched all the same.
    pub fn watch_files(&self, files: &[PathBuf]) -> Result<(), Vec<WatchError>> {
        let mut errors = Vec::new();
        let mut keys = BTreeSet::new();
        let mut dirs = BTreeSet::new();
        for f in files {
            let Some(key) = key_of(f) else {
                errors.push(WatchError::NoDirectory(f.clone()));
                continue;
            };
            dirs.insert(key.parent().map(Path::to_path_buf).unwrap_or_default());
            keys.insert(key);
        }
        {
            let mut d = lock(&self.dirs);
            let Dirs { notify, watched } = &mut *d;
            for dir in &dirs {
                if watched.contains_key(dir) {
                    continue;
                }
                let ok = match notify.watch(dir, RecursiveMode::NonRecursive) {
                    Ok(()) => true,
                    Err(error) => {
                        errors.push(WatchError::Watch {
                            dir: dir.clone(),
                            error,
                        });
                        false
                    }
                };
                watched.insert(dir.clone(), ok);
            }
            watched.retain(|dir, ok| {
                let keep = dirs.contains(dir);
                if !keep && *ok {
                    let _ = notify.unwatch(dir);
                }
                keep
            });
        }
        *lock(&self.keys) = keys;
        if errors.is_empty() {
            Ok(())
        } else {
            Err(errors)
        }
    }

    /// Blocks until one of the files changes and the burst of events
    /// ends, or `timeout` (`None`: none) passes first. Events that
    /// arrived before the call, since the last one, count.
    pub fn wait_for_change(&self, timeout: Option<Duration>) -> Change {
        let events = lock(&self.events);
        let deadline = timeout.map(|t| Instant::now() + t);
        loop {
            let event = match deadline {
                None => events.recv().map_err(|_| RecvTimeoutError::Disconnected),
                Some(d) => events.recv_timeout(d.saturating_duration_since(Instant::now())),
            };
            match event {
                Ok(Ok(ev)) if self.counts(&ev) => break,
                Ok(_) => {}
                Err(RecvTimeoutError::Timeout) => return Change::TimedOut,
                Err(RecvTimeoutError::Disconnected) => return Change::Closed,
            }
        }
        // The rest of the burst: until DEBOUNCE passes without another
        // change to one of the files (other events do not hold it back).
        let mut quiet = Instant::now() + DEBOUNCE;
        loop {
            match events.recv_timeout(quiet.saturating_duration_since(Instant::now())) {
                Ok(Ok(ev)) if self.counts(&ev) => quiet = Instant::now() + DEBOUNCE,
                Ok(_) => {}
                Err(RecvTimeoutError::Timeout) => return Change::Changed,
                Err(RecvTimeoutError::Disconnected) => return Change::Changed,
            }
        }
    }

    /// Whether `ev` can be new content of one of the files.
    fn counts(&self, ev: &notify::Event) -> bool {
        if !relevant(&ev.kind) {
            return false;
        }
        let keys = lock(&self.keys);
        ev.paths.iter().any(|p| keys.contains(p))
    }
}

impl std::fmt::Debug for Watcher {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Watcher")
            .field("keys", &*lock(&self.keys))
            .finish_non_exhaustive()
    }
}

/// A lock that survives a panic elsewhere (every value is whole).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// `file` as the watcher reports it: its directory made canonical, then
/// its name (`None` when the directory does not exist).
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

#[cfg(test)]
mod tests {
    use super::*;

    const SOON: Option<Duration> = Some(Duration::from_millis(300));
    const LONG: Option<Duration> = Some(Duration::from_secs(20));

    #[test]
    fn reads_are_not_changes() {
        use notify::event::{CreateKind, ModifyKind};
        assert!(!relevant(&EventKind::Access(AccessKind::Open(
            AccessMode::Any
        ))));
        assert!(!relevant(&EventKind::Access(AccessKind::Close(
            AccessMode::Read
        ))));
        assert!(relevant(&EventKind::Access(AccessKind::Close(
            AccessMode::Write
        ))));
        assert!(relevant(&EventKind::Modify(ModifyKind::Any)));
        assert!(relevant(&EventKind::Create(CreateKind::File)));
    }

    #[test]
    fn a_key_is_the_canonical_directory_and_the_name() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().canonicalize().unwrap();
        let f = dir.path().join("sub/../a.lsys");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        assert_eq!(key_of(&f), Some(real.join("a.lsys")));
        assert_eq!(key_of(&dir.path().join("none/a.lsys")), None);
    }

    /// A save made after `watch_files` and before the wait (a build in
    /// between) is the next change; reads and other files are not.
    #[test]
    fn a_save_before_the_wait_is_kept_and_reads_are_not_changes() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.lsys"), dir.path().join("b.lsys"));
        std::fs::write(&a, "1").unwrap();
        std::fs::write(&b, "1").unwrap();
        let w = Watcher::new().unwrap();
        w.watch_files(std::slice::from_ref(&a)).unwrap();
        std::fs::read_to_string(&a).unwrap();
        std::fs::write(&b, "2").unwrap();
        assert_eq!(w.wait_for_change(SOON), Change::TimedOut);
        std::fs::write(&a, "2").unwrap();
        std::thread::sleep(Duration::from_millis(200));
        assert_eq!(w.wait_for_change(LONG), Change::Changed);
        // The burst was one change.
        assert_eq!(w.wait_for_change(SOON), Change::TimedOut);
    }

    /// Editors that save by renaming a new file over the old one.
    #[test]
    fn a_save_by_rename_is_a_change() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.lsys");
        std::fs::write(&a, "1").unwrap();
        let w = Watcher::new().unwrap();
        w.watch_files(std::slice::from_ref(&a)).unwrap();
        let tmp = dir.path().join(".a.lsys.swp");
        std::fs::write(&tmp, "2").unwrap();
        std::fs::rename(&tmp, &a).unwrap();
        assert_eq!(w.wait_for_change(LONG), Change::Changed);
        // Still watched after the rename.
        std::fs::write(&a, "3").unwrap();
        assert_eq!(w.wait_for_change(LONG), Change::Changed);
    }

    /// The files given last are the ones that count.
    #[test]
    fn the_last_list_of_files_counts() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("inc")).unwrap();
        let (a, b) = (dir.path().join("a.lsys"), dir.path().join("inc/b.lsys"));
        std::fs::write(&a, "1").unwrap();
        std::fs::write(&b, "1").unwrap();
        let w = Watcher::new().unwrap();
        w.watch_files(std::slice::from_ref(&a)).unwrap();
        w.watch_files(&[a.clone(), b.clone()]).unwrap();
        std::fs::write(&b, "2").unwrap();
        assert_eq!(w.wait_for_change(LONG), Change::Changed);
        w.watch_files(std::slice::from_ref(&a)).unwrap();
        std::fs::write(&b, "3").unwrap();
        assert_eq!(w.wait_for_change(SOON), Change::TimedOut);
        let missing = dir.path().join("none/c.lsys");
        let e = w.watch_files(&[a.clone(), missing]).unwrap_err();
        assert!(matches!(&e[..], [WatchError::NoDirectory(_)]), "{e:?}");
        std::fs::write(&a, "2").unwrap();
        assert_eq!(w.wait_for_change(LONG), Change::Changed);
    }
}
