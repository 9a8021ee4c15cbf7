//! What a job is: its input, options, check and output, as plain values
//! (no command-line types), so that every front end states a job the same
//! way.

use std::path::{Path, PathBuf};

use crate::api::GrammarOptions;
use crate::export::output::Format;
use crate::export::render::RenderOptions;
use crate::load::Input;

/// One job: a grammar in, a model (or picture) out.
#[derive(Clone, Debug)]
pub struct Job {
    pub input: Input,
    /// How messages name the grammar (the file as the user wrote it).
    pub name: String,
    pub options: GrammarOptions,
    /// The structural check (supports and interpenetration) after the build.
    pub check: Check,
    pub output: Output,
}

/// Whether, and with which relation matrix, the built model's structure is
/// checked (`pailou::structure`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Check {
    #[default]
    None,
    /// The standard library's relation matrix (`grammar/std/relations.csv`).
    Library,
    /// A relation matrix given as text (`lsys pailou --relations FILE`).
    Relations(String),
}

/// Where a job's model goes.
#[derive(Clone, Debug)]
pub enum Output {
    /// Written atomically to a file; the format from its extension (a
    /// picture with these camera and size settings).
    File {
        path: PathBuf,
        format: Format,
        picture: RenderOptions,
    },
    /// Handed back as bytes in [`Done::bytes`](super::Done::bytes) (an
    /// OBJ's materials are not included: its `mtllib` names `model.mtl`).
    Bytes {
        format: Format,
        picture: RenderOptions,
    },
    /// Built and checked, not written.
    Nothing,
}

impl Job {
    /// A job for `input` (named `name` in messages) with `options`, no
    /// check and no output.
    pub fn new(input: Input, name: impl Into<String>, options: GrammarOptions) -> Job {
        Job {
            input,
            name: name.into(),
            options,
            check: Check::None,
            output: Output::Nothing,
        }
    }

    /// A job for the command line's FILE argument: a path, or `std:NAME`.
    pub fn for_arg(arg: &str, options: GrammarOptions) -> Job {
        Job::new(Input::from_arg(arg), arg, options)
    }

    pub fn check(mut self, check: Check) -> Job {
        self.check = check;
        self
    }

    pub fn output(mut self, output: Output) -> Job {
        self.output = output;
        self
    }
}

impl Output {
    /// A file whose extension names the format (.glb, .gltf, .obj, .png),
    /// or the sentence to show when it names none.
    pub fn file(path: impl Into<PathBuf>, picture: RenderOptions) -> Result<Output, String> {
        let path = path.into();
        Ok(Output::File {
            format: format_of(&path)?,
            path,
            picture,
        })
    }

    /// The file it writes, if it writes one.
    pub fn path(&self) -> Option<&Path> {
        match self {
            Output::File { path, .. } => Some(path),
            _ => None,
        }
    }

    pub(super) fn format(&self) -> Option<Format> {
        match self {
            Output::File { format, .. } | Output::Bytes { format, .. } => Some(*format),
            Output::Nothing => None,
        }
    }
}

/// The format `path`'s extension names, or the sentence to show when it
/// names none.
pub fn format_of(path: &Path) -> Result<Format, String> {
    Format::of(path).ok_or_else(|| {
        format!(
            "cannot tell the format of `{}` from its extension; name the output .glb, .gltf, .obj or .png",
            path.display()
        )
    })
}

/// The folder whose `components/` is searched first: the grammar file's.
pub fn grammar_dir(input: &Input) -> Option<PathBuf> {
    match input {
        Input::Path(p) => Some(
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf(),
        ),
        _ => None,
    }
}
