//! One item built: an [`Item`] and the output folder -> the model written
//! atomically as `ID.FORMAT`, by the same job `lsys build GRAMMAR -o
//! ID.FORMAT` runs with the same `-D`, `--seed` and `-n` (so the bytes
//! are the same) -> its [`Entry`], `ok` with the file's SHA-256 and the
//! model's figures, or `error` with the diagnostics. Nothing here panics
//! or returns early on bad input: every failure is an entry.

use std::io;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::time::Instant;

use miette::Diagnostic;
use sha2::{Digest, Sha256};
use thiserror::Error;

use super::entry::{Bounds, Entry, Status};
use super::item::Item;
use crate::api::GrammarOptions;
use crate::diag::Diagnostics;
use crate::driver::{
    run, run_guided, toml_file, Failure, GuidedJob, Job, Output, Pailou, PailouError, Picture,
    TomlFile, WORKER_STACK,
};

/// Why an item failed outside the build itself.
#[derive(Debug, Error, Diagnostic)]
enum ItemFailed {
    #[error("cannot read back {path} to hash it: {cause}")]
    #[diagnostic(code(lsys::batch::hash))]
    Hash { path: String, cause: String },

    #[error("cannot create the output folder {path}: {cause}")]
    #[diagnostic(code(lsys::batch::out_dir))]
    OutDir { path: String, cause: String },

    #[error("{0}")]
    #[diagnostic(code(lsys::batch::pailou))]
    Pailou(String),

    #[error("lsys stopped on this item: {0}")]
    #[diagnostic(
        code(lsys::batch::internal),
        help("this is a bug in lsys; please report it with the item")
    )]
    Internal(String),
}

/// What the index tells of a built model.
struct Figures {
    modules: Option<usize>,
    triangles: usize,
    bounds: Option<([f32; 3], [f32; 3])>,
}

/// Builds `item` into `out_dir` (created if missing) and says what became
/// of it. The build runs on a thread of its own with the compiler's deep
/// stack ([`WORKER_STACK`]): the caller's thread (a Python interpreter's,
/// say) may have a small one.
pub fn generate(item: &Item, out_dir: &Path) -> Entry {
    let started = std::thread::scope(|s| {
        std::thread::Builder::new()
            .name(format!("lsys {}", item.id))
            .stack_size(WORKER_STACK)
            .spawn_scoped(s, || generate_here(item, out_dir))
            .map(|h| h.join())
    });
    match started {
        Ok(Ok(entry)) => entry,
        // `generate_here` catches panics; a thread that still ended in one
        // is told as one.
        Ok(Err(_)) => failed(
            item,
            Instant::now(),
            Diagnostics::one(ItemFailed::Internal("the build thread panicked".into())),
        ),
        Err(e) => failed(
            item,
            Instant::now(),
            Diagnostics::one(ItemFailed::Internal(format!(
                "cannot start a thread for the build: {e}"
            ))),
        ),
    }
}

/// [`generate`] on this thread, which must have a [`WORKER_STACK`]-deep
/// stack (the batch's workers have).
pub(super) fn generate_here(item: &Item, out_dir: &Path) -> Entry {
    let t0 = Instant::now();
    let path = out_dir.join(item.output_name());
    let built = catch_unwind(AssertUnwindSafe(|| {
        std::fs::create_dir_all(out_dir).map_err(|e| {
            Diagnostics::one(ItemFailed::OutDir {
                path: out_dir.display().to_string(),
                cause: e.to_string(),
            })
        })?;
        let figures = build(item, &path)?;
        let sha = sha256_of(&path).map_err(|e| {
            Diagnostics::one(ItemFailed::Hash {
                path: path.display().to_string(),
                cause: e.to_string(),
            })
        })?;
        Ok::<_, Diagnostics>((figures, sha))
    }));
    let built = built.unwrap_or_else(|panic| {
        let why = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".into());
        Err(Diagnostics::one(ItemFailed::Internal(why)))
    });
    match built {
        Ok((f, sha)) => Entry {
            id: item.id.clone(),
            status: Status::Ok,
            output: Some(item.output_name()),
            sha256: Some(sha),
            modules: f.modules,
            triangles: Some(f.triangles),
            bounds: f.bounds.map(|(min, max)| Bounds { min, max }),
            ms: crate::driver::ms(t0.elapsed()),
            diagnostics: Vec::new(),
        },
        Err(d) => failed(item, t0, d),
    }
}

/// The `error` entry of `item`, which started at `t0`.
fn failed(item: &Item, t0: Instant, why: Diagnostics) -> Entry {
    Entry {
        id: item.id.clone(),
        status: Status::Error,
        output: None,
        sha256: None,
        modules: None,
        triangles: None,
        bounds: None,
        ms: crate::driver::ms(t0.elapsed()),
        diagnostics: why.messages().map(Into::into).collect(),
    }
}

/// Builds and writes `item` to `path` as `lsys build` would: a `.toml` is
/// a guided scene or a Pailou graph (told apart by its keys), anything
/// else a grammar file or `std:NAME`.
fn build(item: &Item, path: &Path) -> Result<Figures, Diagnostics> {
    // `lsys build`'s flags at their defaults are the options' defaults;
    // an item sets `-D`, `--seed` and `-n`.
    let options = GrammarOptions::default()
        .defines_from(&item.defines)
        .steps(item.steps)
        .seed_option(item.seed);
    let output = Output::File {
        path: path.to_path_buf(),
        format: item.format,
        picture: Picture::default(),
    };
    if !item.grammar.ends_with(".toml") {
        return model(&Job::for_arg(&item.grammar, options).output(output));
    }
    let file = Path::new(&item.grammar);
    let kind = match std::fs::read_to_string(file) {
        Ok(text) => Some((toml_file(file, &text).map_err(Diagnostics::one)?, text)),
        // The guided scene's reader says why it cannot be read, as in
        // `lsys build`.
        Err(_) => None,
    };
    match kind {
        Some((TomlFile::PailouGraph, text)) => {
            let pailou =
                Pailou::graph(&file.display().to_string(), &text, None).map_err(pailou_failed)?;
            model(&pailou.job(options).output(output))
        }
        None | Some((TomlFile::GuidedScene, _)) => {
            let job = GuidedJob {
                path: file.to_path_buf(),
                options,
                guides: false,
                output,
            };
            let done = run_guided(&job).map_err(Failure::diagnostics)?;
            Ok(Figures {
                modules: None,
                triangles: done.triangles,
                bounds: done.bounds,
            })
        }
    }
}

/// Runs a grammar's job; its warnings and progress are not told.
fn model(job: &Job) -> Result<Figures, Diagnostics> {
    let done = run(job, &mut |_| {}).map_err(Failure::diagnostics)?;
    Ok(Figures {
        modules: Some(done.scene.module_count()),
        triangles: done.scene.triangle_count(),
        bounds: done.scene.bounds(),
    })
}

fn pailou_failed(e: PailouError) -> Diagnostics {
    match e {
        PailouError::Graph(d) => Diagnostics::boxed(d),
        other => Diagnostics::one(ItemFailed::Pailou(other.to_string())),
    }
}

/// The SHA-256 of the file at `path`, in hex, read back from the file
/// (the writer streams a model straight into it; reading it again is
/// cheaper than keeping a copy).
fn sha256_of(path: &Path) -> io::Result<String> {
    let mut hasher = Sha256::new();
    io::copy(&mut std::fs::File::open(path)?, &mut hasher)?;
    Ok(format!("{:x}", hasher.finalize()))
}
