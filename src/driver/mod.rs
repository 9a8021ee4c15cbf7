//! The driver: one job from its input to its output, for every front end
//! (`lsys build`, `render`, `pailou`, `watch`, the studio, and the batch
//! runner and Python package to come). Input: a [`Job`] — a grammar (a
//! file, `std:NAME` or text), its [`GrammarOptions`](crate::GrammarOptions)
//! as plain values, whether to check the model's structure, and where the
//! output goes (a file, bytes, or nowhere). Output: [`Done`] — the built
//! scene, the bytes written (or the bytes themselves), the structural
//! problems, the timings, the files the grammar read — or a [`Failure`].
//! Warnings and progress are reported through a callback ([`Event`]) as
//! they happen, so that a front end prints them in the order they arise.
//!
//! The sequence it runs: start the grammar components the text places on
//! the other core (`build::Early`), compile, derive, interpret, mesh (the
//! grammar components with the same options), check the structure, warn
//! when nothing was drawn, write.
//!
//! [`batch`] runs many jobs from a manifest (`lsys batch`): each item is
//! the job `lsys build` would run, written into one folder with an index.
//!
//! `painting` turns rectangles painted in five views into parts of a
//! painting session (its `correct.rs` is seed 004's automatic correction)
//! and writes the session as the `.lsys` file `lsys build` rebuilds
//! (`file.rs`; the studio's painting page).
//!
//! [`session`] is the other kind of job: an interactive one (the REPL's),
//! a grammar kept as text that is edited, stepped and inspected one input
//! at a time.

pub mod batch;
mod empty;
mod guided;
mod infer;
mod infer_pailou;
mod job;
mod pailou;
mod painting;
mod run;
mod scene_edit;
pub mod session;
mod stats;
mod structure;
mod toml_file;
#[cfg(feature = "cli")]
mod watch;

pub use guided::{mesh_guided, run_guided, GuidedDone, GuidedJob};
pub use infer::{
    infer_drawing, infer_edited, infer_label, read_drawing, write_inference, Correction,
    InferError, InferFailure, InferNode, InferOptions, Inference, Ink, INFER_LABELS,
};
pub use job::{format_of, grammar_dir, Check, Job, Output};
pub use pailou::{check_pailou_define, Pailou, PailouError, PailouType};
pub use painting::{
    holes, paint, reshape, Component, PaintDoc, PaintError, PaintFileError, PaintView, Painted,
    Part, Photo,
};
pub use run::{model_bytes, run, Done, Event, Failure, Reason};
pub use scene_edit::{check_scene, drag_guides, Drag, DragError, SceneDoc, SceneRun};
pub use stats::ms;
pub use structure::library_rules;
pub use toml_file::{toml_file, NeitherFormat, TomlFile};
#[cfg(feature = "cli")]
pub use watch::{Change, WatchError, Watcher};

pub use crate::build::Stage;
pub use crate::export::output::Format;
pub use crate::export::render::{RenderOptions as Picture, Style, View};
pub use crate::load::Input;
pub use crate::pailou::kinds::is_graph_kind;
pub use crate::pailou::structure::Problem;
pub use crate::pailou::{Entrance, GraphDocument, Roof};

// What a front end needs of the stages besides running jobs: the worker
// thread's stack, rendering a diagnostic, atomic writes of its own
// output, the turtle's command table, a picture size, and the limits'
// defaults its flags show.
pub use crate::build::WORKER_STACK;
pub use crate::diag::render as render_diagnostic;
pub use crate::export::atomic::{remove_temporaries, write_file, OutputIsInput};

/// The painting palette of a compiled session: its `DEPTH_X` defines
/// (painting/mod.rs).
pub fn painting_palette(grammar: &crate::Grammar) -> Vec<Component> {
    let defines: Vec<(String, f64)> = grammar
        .comp
        .program
        .defines
        .iter()
        .filter_map(|d| Some((d.name.clone(), d.value?)))
        .collect();
    painting::palette(&defines)
}

/// Refuses `output` when it is a file `grammar` was read from (the
/// grammar or a file it includes): `lsys derive g.lsys -o g.lsys`.
pub fn refuse_inputs(
    output: &std::path::Path,
    grammar: &crate::Grammar,
) -> Result<(), OutputIsInput> {
    crate::export::atomic::refuse_inputs(output, &grammar.comp.program.sources.disk_paths())
}
pub use crate::export::render::parse_size;
pub use crate::lang::commands::help_text as turtle_commands;

/// The defaults and ceilings of the parser's and loader's limits.
pub mod limits {
    pub use crate::load::MAX_INCLUDE_DEPTH;
    pub use crate::parse::{
        MAX_NESTING, MAX_NESTING_CEILING, MAX_OPERATORS, MAX_OPERATORS_CEILING,
    };
}
