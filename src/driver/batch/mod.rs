//! Many models from one manifest (`lsys batch`, and the Python package's
//! batch runner). Input: a manifest, one JSON object a line, each an
//! [`Item`] (`{"id", "grammar", "defines", "seed", "steps", "format"}`);
//! an output folder; optionally a shard `I/N` and a number of jobs.
//! Output: `DIR/ID.FORMAT` for each item, written atomically by the job
//! `lsys build` runs (the same bytes), and `DIR/index.jsonl`, one
//! [`Entry`] a line (status, output file, SHA-256, figures, time, and a
//! failed item's diagnostics), appended as each item is done.
//!
//! A run skips the items its index records, so a killed run is resumed by
//! running it again, and shards of one manifest may write to one folder
//! at once (`index.rs` says when that is safe). The bytes of an item's
//! file do not depend on the shard, the jobs or a resume. docs/batch.md
//! is the user's guide.

mod entry;
mod error;
mod generate;
mod index;
mod item;
mod manifest;
mod mistake;
mod run;

pub use entry::{Bounds, Entry, ItemDiagnostic, Status};
pub use error::{check_shard, parse_shard, BatchError};
pub use generate::generate;
pub use index::INDEX;
pub use item::{check_id, extension, item_from_json, Item, ItemError, KEYS};
pub use manifest::MISTAKES_TOLD;
pub use mistake::{ManifestError, Mistake};
pub use run::{run, Progress, Summary};
