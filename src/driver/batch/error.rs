//! Why a batch did not run (or stopped): the manifest could not be read
//! or has mistakes, the shard or output folder is wrong, the index could
//! not be read or written. A failing item is no error of the batch: it
//! gets an `error` line in the index.

use std::path::PathBuf;

use miette::Diagnostic;
use thiserror::Error;

use super::mistake::ManifestError;

#[derive(Debug, Error, Diagnostic)]
pub enum BatchError {
    #[error("cannot read the manifest {}: {error}", path.display())]
    #[diagnostic(code(lsys::batch::read))]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },

    #[error("{file} has {count} mistake{}; nothing was built", if *count == 1 { "" } else { "s" })]
    #[diagnostic(
        code(lsys::batch::manifest),
        help("each line is one item: {{\"id\": \"a\", \"grammar\": \"plant.lsys\", \"defines\": {{\"N\": 3}}, \"seed\": 1, \"steps\": 4, \"format\": \"glb\"}} (docs/batch.md)")
    )]
    Manifest {
        file: String,
        /// Every mistake found.
        count: usize,
        /// The first [`MISTAKES_TOLD`](super::manifest::MISTAKES_TOLD).
        #[related]
        mistakes: Vec<ManifestError>,
    },

    #[error("no shard {index}/{count}: {why}")]
    #[diagnostic(
        code(lsys::batch::shard),
        help("--shard I/N builds the items whose position in the manifest (from 0) modulo N is I, for I from 0 to N-1")
    )]
    Shard {
        index: usize,
        count: usize,
        why: &'static str,
    },

    #[error("`{text}` is not a shard I/N")]
    #[diagnostic(
        code(lsys::batch::shard_syntax),
        help("write --shard 0/4, or with a Slurm job array --shard $SLURM_ARRAY_TASK_ID/4")
    )]
    ShardSyntax { text: String },

    #[error("cannot create the output folder {}: {error}", path.display())]
    #[diagnostic(code(lsys::batch::out_dir))]
    OutDir {
        path: PathBuf,
        error: std::io::Error,
    },

    #[error("cannot {doing} the index {}: {error}", path.display())]
    #[diagnostic(
        code(lsys::batch::index),
        help("the index records each item built; the items recorded are kept, and a rerun builds the rest")
    )]
    Index {
        path: PathBuf,
        doing: &'static str,
        error: std::io::Error,
    },

    #[error("cannot start a worker thread: {error}")]
    #[diagnostic(code(lsys::batch::threads), help("try fewer --jobs"))]
    Threads { error: std::io::Error },
}

/// `I/N` from the command line or a caller, checked: `N` at least 1, `I`
/// below `N`.
pub fn parse_shard(text: &str) -> Result<(usize, usize), BatchError> {
    let syntax = || BatchError::ShardSyntax {
        text: text.to_string(),
    };
    let (i, n) = text.split_once('/').ok_or_else(syntax)?;
    let i = i.trim().parse().map_err(|_| syntax())?;
    let n = n.trim().parse().map_err(|_| syntax())?;
    check_shard(i, n)?;
    Ok((i, n))
}

/// Whether shard `index` of `count` exists.
pub fn check_shard(index: usize, count: usize) -> Result<(), BatchError> {
    let why = if count == 0 {
        "there must be at least one shard"
    } else if index >= count {
        "shards count from 0, so I must be below N"
    } else {
        return Ok(());
    };
    Err(BatchError::Shard { index, count, why })
}
