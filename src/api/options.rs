//! The options of a [`Grammar`](super::Grammar), set through a builder:
//! defines (namespaced ones reach grammar components), seed, limits,
//! include folders, dialect, component folders and facets. Output: the one
//! options value every stage and every sub-grammar is compiled with.

use std::path::{Path, PathBuf};

use super::Grammar;
use crate::build::BuildOptions;
use crate::diag::Diagnostics;
use crate::lang::Dialect;
use crate::load::Input;

/// Options for compiling, deriving and building a grammar.
///
/// ```
/// let g = lsys::Grammar::options()
///     .define("N", 2)
///     .seed(7)
///     .from_str("g.lsys", "#define N 1\naxiom: A(N)\nA(x) --> A(x + 1)\n")?;
/// assert_eq!(g.derive(1)?.to_string(), "A(3)");
/// # Ok::<(), lsys::Diagnostics>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct GrammarOptions {
    pub(crate) build: BuildOptions,
}

impl GrammarOptions {
    /// `-D NAME=VALUE`: overrides `#define NAME`. `TM.NTL` sets `NTL` in
    /// the grammar component `~TM` (and `TM.A.X` sets `X` in the
    /// component `~A` that `TM` places).
    pub fn define(mut self, name: &str, value: impl ToString) -> Self {
        self.build
            .source
            .defines
            .push((name.to_string(), value.to_string()));
        self
    }

    /// Each of `defines` as [`define`](Self::define), in order (the last
    /// of a name wins): the command line's `-D`s, a graph's `[defines]`.
    pub fn defines_from(self, defines: &[(String, String)]) -> Self {
        defines
            .iter()
            .fold(self, |o, (name, value)| o.define(name, value))
    }

    /// The random generator's seed (overrides the file's `seed:`).
    pub fn seed(mut self, seed: u64) -> Self {
        self.build.derive.seed = Some(seed);
        self
    }

    /// [`seed`](Self::seed) when `seed` is given; the file's `seed:` (or
    /// 0) otherwise.
    pub fn seed_option(mut self, seed: Option<u64>) -> Self {
        self.build.derive.seed = seed;
        self
    }

    /// The largest string, in modules, a step may produce.
    pub fn max_modules(mut self, n: usize) -> Self {
        self.build.derive.max_modules = n;
        self
    }

    /// The most parameter values a string may hold.
    pub fn max_params(mut self, n: usize) -> Self {
        self.build.derive.max_params = n;
        self
    }

    /// A folder `#include "f"` looks in after the including file's own
    /// (and from which files may be included).
    pub fn include_dir(mut self, dir: impl AsRef<Path>) -> Self {
        self.build
            .source
            .include_dirs
            .push(dir.as_ref().to_path_buf());
        self
    }

    /// Read the grammar in this dialect whatever its name and headers say.
    pub fn dialect(mut self, dialect: Dialect) -> Self {
        self.build.source.dialect = Some(dialect);
        self
    }

    /// The environment that answers `?E` when the grammar names none, as
    /// the `environment:` header writes it (`collision(radius: 0.01)`,
    /// `light(transmittance: 0.3)`; see `docs/environments.md`).
    pub fn environment(mut self, spec: &str) -> Self {
        self.build.source.environment = Some(spec.to_string());
        self
    }

    /// A folder components (`~X`: `X.obj`, `X.lsys`) are looked for in,
    /// after `components/` beside the grammar.
    pub fn components_dir(mut self, dir: impl AsRef<Path>) -> Self {
        self.build.components.dirs.push(dir.as_ref().to_path_buf());
        self
    }

    /// Facets around tubes, spheres and discs, the same for every tube
    /// (without it, thin tubes take fewer: see `MeshOptions::adaptive`).
    pub fn facets(mut self, n: u32) -> Self {
        self.build.mesh.sides = n;
        self.build.mesh.adaptive = false;
        self
    }

    /// Overrides the file's `angle:` (degrees).
    pub fn angle(mut self, degrees: f64) -> Self {
        self.build.angle = Some(degrees);
        self
    }

    /// Derivation steps for [`Grammar::build`](super::Grammar::build) and
    /// the driver's jobs; `None` takes the file's `derivation length:`.
    pub fn steps(mut self, steps: Option<u32>) -> Self {
        self.build.steps = steps;
        self
    }

    /// Overrides the file's `step:` (the turtle's default move).
    pub fn step(mut self, length: f64) -> Self {
        self.build.step = Some(length);
        self
    }

    /// Overrides the file's `width:` (the default line width).
    pub fn width(mut self, width: f64) -> Self {
        self.build.width = Some(width);
        self
    }

    /// Component detail, 0 (boxes) to 2 (full models); 1 by default.
    pub fn detail(mut self, level: u8) -> Self {
        self.build.components.detail = level;
        self.build.mesh.detail = level;
        self
    }

    /// Internodes as instances of one cylinder rather than one mesh.
    pub fn instanced(mut self, on: bool) -> Self {
        self.build.mesh.instanced = on;
        self
    }

    /// The most triangles a model may have.
    pub fn max_triangles(mut self, n: usize) -> Self {
        self.build.mesh.max_triangles = n;
        self
    }

    /// How deep `#include`s may nest.
    pub fn max_include_depth(mut self, n: usize) -> Self {
        self.build.source.max_include_depth = n;
        self
    }

    /// The parser's ceilings: nesting of brackets and parentheses, and
    /// operators in one expression.
    pub fn parser_limits(mut self, max_nesting: usize, max_operators: usize) -> Self {
        self.build.source.parse = crate::parse::Limits {
            max_nesting,
            max_operators,
        };
        self
    }

    /// The defines set so far, in order (the last of a name wins).
    pub fn defines(&self) -> &[(String, String)] {
        &self.build.source.defines
    }

    /// Compiles `text`, named `name` in diagnostics (a name ending in `.l`
    /// is read as a cpfg model).
    pub fn from_str(self, name: &str, text: &str) -> Result<Grammar, Diagnostics> {
        Grammar::compile(
            Input::Text {
                name: name.to_string(),
                text: text.to_string(),
            },
            self,
        )
    }

    /// Compiles the grammar file at `path` (and what it includes), or a
    /// standard library grammar named `std:NAME`.
    pub fn from_path(mut self, path: impl AsRef<Path>) -> Result<Grammar, Diagnostics> {
        let path = path.as_ref();
        let input = match path.to_str().and_then(|p| p.strip_prefix("std:")) {
            Some(name) => Input::Std(name.to_string()),
            None => {
                self.build.components.grammar_dir = Some(
                    path.parent()
                        .filter(|d| !d.as_os_str().is_empty())
                        .map_or_else(|| PathBuf::from("."), Path::to_path_buf),
                );
                Input::Path(path.to_path_buf())
            }
        };
        Grammar::compile(input, self)
    }
}
