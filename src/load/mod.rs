//! Load: the root input in, every file the model reads out, read and
//! parsed, before resolve starts: the root and the files it includes (a
//! cpfg `.l` root through the C preprocessor of [`crate::preprocess`]),
//! their statements flattened in include order (an `#include "f"` line is
//! replaced by the statements of `f`, as the C preprocessor would), and a
//! model's side files (the cpfg view file and its function files, the
//! environment's communication and specification files). Every
//! file read is in the [`SourceMap`]; no later stage reads the disk for the
//! grammar.

mod colours;
mod contours;
mod cpfg;
mod curves;
mod environment;
mod error;
mod include;
mod loader;
mod surface;
mod view;

use std::path::{Path, PathBuf};

use miette::Report;

pub use contours::Contour;
pub use environment::{EnvironmentFiles, HeaderImage};
pub use error::{InputError, LoadError};
pub use include::MAX_SOURCE_BYTES;
pub use surface::{CpfgSurface, Patch as SurfacePatch};
pub use view::{SideFiles, ViewFunctions, ViewLines};

use crate::parse::ast::Item;
use crate::source::{FileId, Origin, SourceFile, SourceMap, Span};
use crate::stdlib;

/// Includes nested deeper than this are refused (a runaway generator, not
/// a grammar); `--max-include-depth` changes it.
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// What to compile.
#[derive(Clone, Debug)]
pub enum Input {
    /// A file on disk.
    Path(PathBuf),
    /// `std:NAME`: a standard library file.
    Std(String),
    /// Text from memory (tests, the REPL).
    Text { name: String, text: String },
    /// A file's text as edited in memory (the REPL): named like the file,
    /// with its `#include "..."` resolved beside it.
    Edited { path: PathBuf, text: String },
}

impl Input {
    /// Reads a command-line argument: `std:NAME` or a path.
    pub fn from_arg(arg: &str) -> Input {
        match arg.strip_prefix("std:") {
            Some(name) => Input::Std(name.to_string()),
            None => Input::Path(PathBuf::from(arg)),
        }
    }
}

/// Options of one compilation. Loading reads them all; resolve reads the
/// `-D` definitions again when the preprocessor did not take them (a
/// `.lsys` file's `#define`s are resolve's).
#[derive(Clone, Debug)]
pub struct Options {
    /// `-D NAME=VALUE` overrides, in command-line order (the last wins).
    pub defines: Vec<(String, String)>,
    /// `--include-dir DIR`: where `#include "f"` looks after the including
    /// file's folder; files below them may be included too.
    pub include_dirs: Vec<PathBuf>,
    /// Longest chain of nested includes (`--max-include-depth`).
    pub max_include_depth: usize,
    /// Nesting and expression limits of the parser (`--max-nesting`,
    /// `--max-operators`).
    pub parse: crate::parse::Limits,
    /// `--dialect`: overrides the profile the file's name and `dialect:`
    /// header would give.
    pub dialect: Option<crate::lang::Dialect>,
    /// Files being edited and not saved (an editor's open documents), by
    /// canonical path: an include of one of them reads this text instead
    /// of the file on disk.
    pub unsaved: std::sync::Arc<std::collections::HashMap<PathBuf, String>>,
    /// `--environment SPEC`: the environment that answers `?E` when the
    /// grammar chooses none (`collision(radius: 0.01)`, as the header).
    pub environment: Option<String>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            defines: Vec::new(),
            include_dirs: Vec::new(),
            max_include_depth: MAX_INCLUDE_DEPTH,
            parse: crate::parse::Limits::default(),
            dialect: None,
            unsaved: Default::default(),
            environment: None,
        }
    }
}

/// Every file of one compilation and their statements in include order.
pub struct Loaded {
    /// Every file read: the root, its includes, then the side files.
    pub sources: SourceMap,
    pub items: Vec<(FileId, Item)>,
    pub errors: Vec<Report>,
    pub warnings: Vec<Report>,
    /// The first lines of statements that did not parse (see
    /// [`crate::parse::ast::File::broken`]).
    pub broken: Vec<Span>,
    /// The `#include` lines (their path's span) whose file could not be
    /// loaded: names it would have defined are not reported one by one.
    pub failed_includes: Vec<Span>,
    /// Every `#include` line that loaded a file: its path's span (in the
    /// including file) and the file it loaded (editors link the two).
    pub includes: Vec<(Span, FileId)>,
    /// The files went through the C preprocessor (a cpfg `.l` root), which
    /// took the `-D` definitions.
    pub preprocessed: bool,
    /// The language profile, decided here once for the whole model.
    pub profile: crate::lang::Profile,
    /// What the model's view file gives (cpfg): its angle, its functions.
    pub side: SideFiles,
    /// The cpfg environment files (`-e FILE.e` and its program's
    /// specification), when the model runs with an environmental program.
    pub environment: Option<EnvironmentFiles>,
    /// The images an `environment:` header or `--environment` names
    /// (`clover(input image: light.rgb)`), as the name written and the bytes
    /// or why they could not be read.
    pub environment_images: Vec<(String, HeaderImage)>,
}

/// Loads `input`, what it includes and its side files. A cpfg file (`.l`)
/// goes through the C preprocessor first, with the `-D` definitions defined
/// before its first line.
pub fn load(input: &Input, opts: &Options) -> Result<Loaded, InputError> {
    let root = root_file(input)?;
    let profile = crate::lang::Profile::decide(&root.name, &root.text, opts.dialect);
    // Includes stay inside the top-level file's folder (or, for text and
    // library grammars, the working folder).
    let root_dir = match &root.origin {
        Origin::Disk(p) => p.parent().map(Path::to_path_buf),
        _ => None,
    }
    .filter(|d| !d.as_os_str().is_empty())
    .unwrap_or_else(|| PathBuf::from("."));
    let finder =
        include::IncludeFinder::new(root_dir.clone(), &opts.include_dirs, opts.unsaved.clone());
    let model = match &root.origin {
        Origin::Disk(p) => Some(p.clone()),
        _ => None,
    };
    let mut loader = loader::Loader::new(profile, finder.clone(), opts);
    let root = if profile.cpfg_model_file {
        loader.preprocess(root, &opts.defines)
    } else {
        root
    };
    loader.root(root);
    let mut loaded = loader.finish();
    loaded.environment_images = environment::read_header_images(
        &loaded.items,
        opts.environment.as_deref(),
        &root_dir,
        &finder,
        &loaded.sources,
    );
    if let Some(model) = model {
        loaded.side = view::read_side_files(&model, &profile, &finder, &mut loaded.sources);
        let view = loaded
            .side
            .view
            .map(|v| loaded.sources.get(v).name.clone())
            .unwrap_or_default();
        if let (true, Some(id)) = (profile.cpfg_model_file, loaded.side.view) {
            if let Some(span) = view::zero_angle_factor(loaded.sources.get(id), id) {
                loaded
                    .warnings
                    .push(Report::new(LoadError::ZeroAngleFactor {
                        src: loaded.sources.named_source(span),
                        span: span.into(),
                    }));
            }
        }
        for why in std::mem::take(&mut loaded.side.contour_problems) {
            let view = view.clone();
            loaded
                .warnings
                .push(Report::new(LoadError::ContourFile { view, why }));
        }
        if profile.cpfg_model_file {
            let (env, errors) =
                environment::read_environment_files(&model, &finder, &mut loaded.sources);
            loaded.environment = env;
            loaded.errors.extend(errors);
            let (colours, warnings) = colours::read_colour_files(&model, &finder, &loaded.sources);
            loaded.side.colours = colours;
            loaded.warnings.extend(warnings);
        }
    }
    Ok(loaded)
}

/// The root input as a source file, or why it cannot be read at all.
fn root_file(input: &Input) -> Result<SourceFile, InputError> {
    Ok(match input {
        Input::Path(p) => {
            let path = p.display().to_string();
            let text = include::read_source(p, false).map_err(|e| match e {
                // Asked only once reading failed: a build pays no stat for it.
                include::Unread::Io(_) if p.is_dir() => InputError::Folder {
                    path,
                    help: folder_help(p),
                },
                include::Unread::Io(e) => InputError::NotFound {
                    path,
                    cause: e.to_string(),
                },
                include::Unread::NotSource(why) => InputError::NotSource { path, why },
            })?;
            SourceFile::new(
                p.display().to_string(),
                Origin::Disk(p.clone()),
                String::from_utf8_lossy(&text).into_owned(),
            )
        }
        Input::Std(name) => {
            let text = stdlib::get(name).ok_or_else(|| InputError::UnknownStd {
                name: name.clone(),
                help: stdlib::unknown_help(name, |n| format!("std:{n}")),
            })?;
            SourceFile::new(format!("std:{name}"), Origin::Std(name.clone()), text)
        }
        Input::Text { name, text } => SourceFile::new(name.clone(), Origin::Memory, text.clone()),
        Input::Edited { path, text } => SourceFile::new(
            path.display().to_string(),
            Origin::Disk(path.clone()),
            text.clone(),
        ),
    })
}

/// `-D NAME=VALUE` pairs in command-line order.
pub type Defines = Vec<(String, String)>;

impl Options {
    /// The options of grammar component `name`: its own namespaced
    /// defines (`name.X=V` becomes `X=V`, `name.A.X=V` becomes `A.X=V`),
    /// everything else the same.
    pub fn for_namespace(&self, name: &str) -> Options {
        let prefix = format!("{name}.");
        Options {
            defines: self
                .defines
                .iter()
                .filter_map(|(n, v)| Some((n.strip_prefix(&prefix)?.to_string(), v.clone())))
                .collect(),
            ..self.clone()
        }
    }

    /// The defines for this grammar itself (no namespace), and the
    /// namespaced ones (`TM.NTL`), which are for its grammar components.
    pub fn split_defines(&self) -> (Defines, Defines) {
        self.defines
            .iter()
            .cloned()
            .partition(|(n, _)| !n.contains('.'))
    }
}

/// What to give instead of folder `dir`: the grammars in it, if any.
fn folder_help(dir: &std::path::Path) -> String {
    let mut grammars: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_type().is_ok_and(|t| !t.is_dir()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".lsys") || n.ends_with(".l"))
        .collect();
    grammars.sort();
    const SHOWN: usize = 5;
    match grammars.len() {
        0 => "give lsys a grammar file (.lsys, or cpfg's .l); this folder holds none".to_string(),
        n if n <= SHOWN => format!("give lsys one of its grammars: {}", grammars.join(", ")),
        n => format!(
            "give lsys one of its {n} grammars: {}, ...",
            grammars[..SHOWN].join(", ")
        ),
    }
}
