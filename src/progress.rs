//! Progress on standard error: derivation steps and build stages in, an
//! indicatif bar out, shown only when standard error is a terminal and the
//! work has already taken [`DELAY`]; nothing at all otherwise (pipes, CI,
//! tests). Callers report once per derivation step, never per module, so
//! the engine is not slowed.

use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::build::Stage;

/// Work shorter than this shows no bar.
pub const DELAY: Duration = Duration::from_millis(500);

/// A progress bar that appears after [`DELAY`] and is cleared when dropped.
pub struct Progress {
    bar: Option<(ProgressBar, Arc<Mutex<bool>>)>,
}

impl Progress {
    /// A bar on standard error when `enabled` and standard error is a
    /// terminal; otherwise every call does nothing.
    pub fn new(enabled: bool) -> Progress {
        if !enabled || !std::io::stderr().is_terminal() {
            return Progress { bar: None };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) =
            ProgressStyle::with_template("{spinner} {msg:<14} [{bar:30}] {pos}/{len} {elapsed}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        let done = Arc::new(Mutex::new(false));
        let (b, d) = (bar.clone(), done.clone());
        std::thread::spawn(move || {
            std::thread::sleep(DELAY);
            let finished = d.lock().map(|g| *g).unwrap_or(true);
            if !finished {
                b.set_draw_target(ProgressDrawTarget::stderr());
                b.enable_steady_tick(Duration::from_millis(100));
            }
        });
        Progress {
            bar: Some((bar, done)),
        }
    }

    /// About to derive step `done + 1` of `of`.
    pub fn step(&self, done: u32, of: u32) {
        if let Some((bar, _)) = &self.bar {
            bar.set_length(of as u64);
            bar.set_position(done as u64);
            bar.set_message("deriving");
        }
    }

    /// A build stage has started.
    pub fn stage(&self, stage: Stage) {
        match stage {
            Stage::Derive { done, of } => self.step(done, of),
            other => self.message(other.name()),
        }
    }

    /// Items of a batch: `done` of `of`, with `what` (how many failed).
    pub fn items(&self, done: usize, of: usize, what: String) {
        if let Some((bar, _)) = &self.bar {
            bar.set_length(of as u64);
            bar.set_position(done as u64);
            bar.set_message(what);
        }
    }

    /// Prints `line` on standard error, above the bar if it shows.
    pub fn println(&self, line: &str) {
        match &self.bar {
            Some((bar, _)) => bar.suspend(|| eprintln!("{line}")),
            None => eprintln!("{line}"),
        }
    }

    /// Work after the derivation (`meshing`, `writing`): the bar stays full.
    pub fn message(&self, what: &'static str) {
        if let Some((bar, _)) = &self.bar {
            let len = bar.length().unwrap_or(1).max(1);
            bar.set_length(len);
            bar.set_position(len);
            bar.set_message(what);
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some((bar, done)) = &self.bar {
            // Under the lock, so the delayed thread cannot show the bar
            // after it was cleared.
            let mut d = done.lock().unwrap_or_else(|e| e.into_inner());
            *d = true;
            bar.finish_and_clear();
        }
    }
}
