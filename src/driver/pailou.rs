//! A Pailou as a job: a style (`6-5-15`, ridge or pillar type) or a
//! component graph (TOML, `docs/pailou.md`) -> [`Pailou`]: its layout
//! chart, its graph, its grammar text, and the [`Job`] that builds it with
//! the graph's defines, the Toukung levels passed on and the structural
//! check against its relation matrix. `lsys pailou` and the studio's
//! Pailou mode both start here.

use std::path::Path;

use miette::Diagnostic;

use super::job::{Check, Job};
use crate::api::GrammarOptions;
use crate::load::Input;
use crate::pailou::{self, graph, Layout, StyleError};

pub use crate::pailou::PailouType;

/// A Pailou ready to build.
#[derive(Clone, Debug)]
pub struct Pailou {
    layout: Layout,
    kind: PailouType,
    /// The grammar's first line says where it came from.
    title: String,
    /// How messages name the grammar.
    name: String,
    /// The graph's `[defines]`.
    defines: Vec<(String, String)>,
    /// A relation matrix other than the library's.
    relations: Option<String>,
    unplaced: Vec<String>,
    /// Each entrance's lintel id and its entrance (i, j) (graphs only).
    lintels: Vec<(String, usize, usize)>,
    /// Every placed component's entrance (graphs only).
    entrance_of: Vec<(String, usize, usize)>,
}

/// Why a Pailou could not be read.
#[derive(Debug)]
pub enum PailouError {
    /// Not a style `NP-NE-NR` the layout rules can build.
    Style { style: String, error: StyleError },
    /// The graph (or its relation matrix) does not read.
    Graph(Box<dyn Diagnostic + Send + Sync>),
    /// A file could not be read.
    Read {
        path: std::path::PathBuf,
        error: std::io::Error,
    },
}

impl std::fmt::Display for PailouError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PailouError::Style { style, error } => {
                write!(f, "cannot build the style {style}: {error}")
            }
            PailouError::Graph(e) => write!(f, "{e}"),
            PailouError::Read { path, error } => {
                write!(f, "cannot read {}: {error}", path.display())
            }
        }
    }
}

impl std::error::Error for PailouError {}

impl Pailou {
    /// The Pailou of a style (`NP-NE-NR`: pillars, entrances, roofs).
    pub fn style(style: &str, kind: PailouType) -> Result<Pailou, PailouError> {
        let layout = pailou::style_layout(style, kind).map_err(|error| PailouError::Style {
            style: style.to_string(),
            error,
        })?;
        let k = kind.name();
        Ok(Pailou {
            layout,
            kind,
            title: format!("style {style}, {k} type"),
            name: format!("pailou-{style}-{k}.lsys"),
            defines: Vec::new(),
            relations: None,
            unplaced: Vec::new(),
            lintels: Vec::new(),
            entrance_of: Vec::new(),
        })
    }

    /// The Pailou of a component graph's text, named `name` in
    /// diagnostics, checked against `relations` (a relation matrix's text;
    /// `None`: the library's).
    pub fn graph(name: &str, text: &str, relations: Option<&str>) -> Result<Pailou, PailouError> {
        let g = graph::read(name, text, relations.unwrap_or(graph::RELATIONS))
            .map_err(|e| PailouError::Graph(e))?;
        let stem = Path::new(name)
            .file_stem()
            .map_or("graph".into(), |s| s.to_string_lossy().into_owned());
        Ok(Pailou {
            layout: g.layout,
            kind: g.kind,
            title: format!("graph {name}"),
            name: format!("{stem}.lsys"),
            defines: g.defines,
            relations: relations.map(str::to_string),
            unplaced: g.unplaced,
            lintels: g.lintels,
            entrance_of: g.entrance_of,
        })
    }

    /// The Pailou of a graph file, with the relation matrix of the file
    /// `relations` (`None`: the library's).
    pub fn graph_file(path: &Path, relations: Option<&Path>) -> Result<Pailou, PailouError> {
        let read = |p: &Path| {
            std::fs::read_to_string(p).map_err(|error| PailouError::Read {
                path: p.to_path_buf(),
                error,
            })
        };
        let text = read(path)?;
        let relations = relations.map(read).transpose()?;
        Pailou::graph(&path.display().to_string(), &text, relations.as_deref())
    }

    /// Names the grammar `name` in messages.
    pub fn named(mut self, name: &str) -> Pailou {
        self.name = name.to_string();
        self
    }

    /// Components of the graph the layout has no place for, one sentence
    /// each.
    pub fn unplaced(&self) -> &[String] {
        &self.unplaced
    }

    /// Each entrance's lintel id in the graph and its entrance (i, j),
    /// counted from 1 (the centre outward, the ground upward); empty for a
    /// style. An entrance's ratios are the grammar's `up[i, j]` and
    /// `side[i - 1]` (docs/pailou.md).
    pub fn lintels(&self) -> &[(String, usize, usize)] {
        &self.lintels
    }

    /// Every placed component's id and its entrance (i, j), sorted by id
    /// (empty for a style): whose per-entrance sizes it takes, `pw[i,j]`
    /// for a pillar, `tk[i,j]` for a Toukung, ... (docs/pailou.md).
    pub fn entrance_of(&self) -> &[(String, usize, usize)] {
        &self.entrance_of
    }

    /// The layout as a chart of rows (`lsys pailou --chart`).
    pub fn chart(&self) -> String {
        self.layout.chart()
    }

    /// The entrances of the layout chart, as the studio draws them.
    pub fn entrances(&self) -> Vec<crate::pailou::Entrance> {
        self.layout.entrances()
    }

    /// The component graph of this Pailou (`lsys pailou --emit-graph`).
    pub fn graph_toml(&self) -> String {
        graph::emit(&self.layout, self.kind, &self.title)
    }

    /// The grammar that builds it (`lsys pailou --emit-lsys`).
    pub fn grammar_text(&self) -> String {
        pailou::source(&self.layout, &self.title)
    }

    /// The job that builds it with `options`: the graph's defines first,
    /// then the options' own (which win), the Toukung levels passed on to
    /// the Toukungs, and the structural check.
    pub fn job(&self, mut options: GrammarOptions) -> Job {
        let mut defines = self.defines.clone();
        defines.append(&mut options.build.source.defines);
        pailou::toukung_levels(&mut defines);
        options.build.source.defines = defines;
        let input = Input::Text {
            name: self.name.clone(),
            text: self.grammar_text(),
        };
        let check = match &self.relations {
            Some(r) => Check::Relations(r.clone()),
            None => Check::Library,
        };
        Job::new(input, self.name.clone(), options).check(check)
    }
}

/// Whether a Pailou define may take `value` (`src/pailou/ranges.rs`): the
/// studio checks the page's values with it.
pub fn check_pailou_define(name: &str, value: f64) -> Result<(), String> {
    crate::pailou::ranges::check(name, value)
}
