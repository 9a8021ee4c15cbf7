//! `lsys batch MANIFEST --out DIR [--shard I/N] [--jobs K]`: the
//! driver's batch run with a progress bar on a terminal, each failed item
//! told in one line as it fails, one summary line at the end -> exit 0
//! when every item of the shard is built, 65 when one failed or the
//! manifest has a mistake (docs/batch.md).

use super::args::BatchArgs;
use super::report::report;
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK, EX_OSERR, EX_USAGE};
use crate::driver::batch::{self, BatchError, Summary};
use crate::progress::Progress as Bar;

pub fn batch_cmd(b: &BatchArgs, color: bool) -> i32 {
    let bar = Bar::new(true);
    let mut failed = 0;
    let result = batch::run(&b.manifest, &b.out, b.shard, b.jobs, &mut |p| match p {
        batch::Progress::Start { total, damaged, .. } => {
            if damaged > 0 {
                bar.println(&format!(
                    "lsys: warning: {damaged} damaged line{} of the index ignored (a run was killed while writing it); {} built again",
                    if damaged == 1 { "" } else { "s" },
                    if damaged == 1 { "its item is" } else { "their items are" }
                ));
            }
            bar.items(0, total, "building".into());
        }
        batch::Progress::Item { entry, done, total } => {
            if !entry.is_ok() {
                failed += 1;
                let why = entry
                    .diagnostics
                    .first()
                    .map_or("failed".to_string(), |d| d.to_string());
                bar.println(&format!("lsys: {}: {why}", entry.id));
            }
            let what = match failed {
                0 => "building".to_string(),
                n => format!("{n} failed"),
            };
            bar.items(done, total, what);
        }
    });
    drop(bar);
    match result {
        Ok(s) => {
            eprintln!("{}", summary_line(&s));
            if s.all_ok() {
                EX_OK
            } else {
                EX_DATAERR
            }
        }
        Err(e) => {
            report(&e, color);
            exit_code(&e)
        }
    }
}

/// `out/index.jsonl: 39 built, 1 failed, 0 skipped in 2.4 s`.
fn summary_line(s: &Summary) -> String {
    let skipped = match s.failed_before {
        0 => format!("{} skipped", s.skipped),
        n => format!("{} skipped ({n} recorded as failed)", s.skipped),
    };
    format!(
        "{}: {} built, {} failed, {skipped} in {:.1} s",
        s.index.display(),
        s.built,
        s.failed,
        s.took.as_secs_f64()
    )
}

fn exit_code(e: &BatchError) -> i32 {
    match e {
        BatchError::Read { .. } => EX_NOINPUT,
        BatchError::Manifest { .. } => EX_DATAERR,
        BatchError::Shard { .. } | BatchError::ShardSyntax { .. } => EX_USAGE,
        BatchError::OutDir { .. } | BatchError::Index { .. } => EX_IOERR,
        BatchError::Threads { .. } => EX_OSERR,
    }
}
