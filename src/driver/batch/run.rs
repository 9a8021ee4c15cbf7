//! A batch run: a manifest, an output folder, a shard and a number of
//! jobs -> every selected item not yet in the folder's index built on
//! its own worker thread, its entry appended to the index as it finishes
//! and told to the caller -> a [`Summary`], or the [`BatchError`] that
//! stopped the run (before anything was built, for a manifest with a
//! mistake).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::entry::{Entry, Status};
use super::error::{check_shard, BatchError};
use super::generate::generate_here;
use super::index::Index;
use super::item::Item;
use crate::driver::WORKER_STACK;

/// What a run tells its caller as it goes, on the caller's thread.
#[derive(Debug)]
pub enum Progress<'a> {
    /// The manifest was read and the index too: `total` items to build
    /// now, `skipped` already recorded, `damaged` index lines ignored.
    Start {
        total: usize,
        skipped: usize,
        damaged: usize,
    },
    /// One more item was built (or failed) and recorded: `done` of
    /// `total`.
    Item {
        entry: &'a Entry,
        done: usize,
        total: usize,
    },
}

/// What a run did, over the items of its shard.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Built on this run.
    pub built: usize,
    /// Failed on this run.
    pub failed: usize,
    /// Recorded in the index already, so not built again.
    pub skipped: usize,
    /// Of those, recorded as failed.
    pub failed_before: usize,
    /// Index lines that were not an entry (cut short by a killed run).
    pub damaged: usize,
    pub index: PathBuf,
    pub took: Duration,
}

impl Summary {
    /// Whether every item of the shard is recorded as built.
    pub fn all_ok(&self) -> bool {
        self.failed == 0 && self.failed_before == 0
    }
}

/// Builds the items of `manifest` (those of `shard`, `(I, N)`: the items
/// whose position from 0 modulo N is I) into `out_dir`, `jobs` at a time,
/// skipping those its `index.jsonl` records; tells `observe` of each.
pub fn run(
    manifest: &Path,
    out_dir: &Path,
    shard: Option<(usize, usize)>,
    jobs: usize,
    observe: &mut dyn FnMut(Progress),
) -> Result<Summary, BatchError> {
    let t0 = Instant::now();
    if let Some((i, n)) = shard {
        check_shard(i, n)?;
    }
    let text = std::fs::read_to_string(manifest).map_err(|error| BatchError::Read {
        path: manifest.to_path_buf(),
        error,
    })?;
    let items = super::manifest::read(manifest, text)?;
    let (i, n) = shard.unwrap_or((0, 1));
    let selected = items
        .into_iter()
        .enumerate()
        .filter(|(k, _)| k % n == i)
        .map(|(_, (_, item))| item);
    std::fs::create_dir_all(out_dir).map_err(|error| BatchError::OutDir {
        path: out_dir.to_path_buf(),
        error,
    })?;
    let (mut index, recorded) = Index::open(out_dir)?;
    let mut todo: Vec<Item> = Vec::new();
    let mut summary = Summary {
        built: 0,
        failed: 0,
        skipped: 0,
        failed_before: 0,
        damaged: recorded.damaged,
        index: index.path().to_path_buf(),
        took: Duration::ZERO,
    };
    for item in selected {
        match recorded.status.get(&item.id) {
            Some(status) => {
                summary.skipped += 1;
                summary.failed_before += usize::from(*status == Status::Error);
            }
            None => todo.push(item),
        }
    }
    let total = todo.len();
    observe(Progress::Start {
        total,
        skipped: summary.skipped,
        damaged: summary.damaged,
    });
    let next = AtomicUsize::new(0);
    // Set when the index cannot be written: workers take no more items.
    let stop = AtomicBool::new(false);
    let (send, receive) = mpsc::channel::<Entry>();
    let workers = jobs.max(1).min(total);
    let result = std::thread::scope(|s| {
        let mut started = 0;
        let mut refused = None;
        for w in 0..workers {
            let send = send.clone();
            let (todo, next, stop) = (&todo, &next, &stop);
            // Plain threads, not rayon's pool: a build run from inside a
            // pool of K threads would see K cores (`derive::threads`) and
            // start its grammar components and parallel steps otherwise
            // than `lsys build` does. Each needs the compiler's deep stack.
            let spawned = std::thread::Builder::new()
                .name(format!("lsys batch {w}"))
                .stack_size(WORKER_STACK)
                .spawn_scoped(s, move || {
                    while !stop.load(Ordering::Relaxed) {
                        let Some(item) = todo.get(next.fetch_add(1, Ordering::Relaxed)) else {
                            break;
                        };
                        if send.send(generate_here(item, out_dir)).is_err() {
                            break;
                        }
                    }
                });
            match spawned {
                Ok(_) => started += 1,
                // Fewer workers do the same work; none is an error.
                Err(error) => refused = Some(error),
            }
        }
        drop(send);
        if started == 0 && total > 0 {
            if let Some(error) = refused {
                return Err(BatchError::Threads { error });
            }
        }
        for (n, entry) in receive.into_iter().enumerate() {
            if let Err(e) = index.append(&entry) {
                // Built items not recorded are built again by a rerun.
                stop.store(true, Ordering::Relaxed);
                return Err(e);
            }
            if entry.is_ok() {
                summary.built += 1;
            } else {
                summary.failed += 1;
            }
            observe(Progress::Item {
                entry: &entry,
                done: n + 1,
                total,
            });
        }
        Ok(())
    });
    result?;
    summary.took = t0.elapsed();
    Ok(summary)
}
