//! A compiled grammar: text or a file in; derived strings (each step or
//! the last) and built scenes out.

use std::sync::Arc;

use super::derived::Derived;
use super::options::GrammarOptions;
use super::scene::Scene;
use crate::diag::Diagnostics;
use crate::load::Input;
use crate::pipeline::{self, Compilation};
use crate::simulation::Simulation;

/// A grammar, compiled and ready to derive.
///
/// ```
/// use lsys::Grammar;
/// let g = Grammar::from_str("algae.lsys", "derivation length: 3\naxiom: A\nA --> A B\nB --> A\n")?;
/// let steps: Vec<String> = g.steps().map(|d| d.map(|d| d.to_string())).collect::<Result<_, _>>()?;
/// assert_eq!(steps, ["A", "A B", "A B A", "A B A A B"]);
/// # Ok::<(), lsys::Diagnostics>(())
/// ```
///
/// A grammar with mistakes comes back as [`Diagnostics`], one typed
/// [`Message`](crate::Message) each; `Debug` is short (no program):
///
/// ```
/// let err = lsys::Grammar::from_str("bad.lsys", "axiom: A(1\n").unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "bad.lsys:1:9: error[lsys::parse::syntax]: syntax error: unexpected `(` after the end of the statement"
/// );
/// let g = lsys::Grammar::from_str("algae.lsys", "axiom: A\nA --> A B\nB --> A\n").unwrap();
/// assert_eq!(
///     format!("{g:?}"),
///     r#"Grammar { name: "algae.lsys", derivation_length: 0, alphabet: 4, productions: 2, warnings: 0 }"#
/// );
/// ```
pub struct Grammar {
    pub(crate) comp: Arc<Compilation>,
    pub(crate) options: GrammarOptions,
    warnings: Diagnostics,
}

impl Grammar {
    /// Options to compile with; finish with
    /// [`from_str`](GrammarOptions::from_str) or
    /// [`from_path`](GrammarOptions::from_path).
    pub fn options() -> GrammarOptions {
        GrammarOptions::default()
    }

    /// Compiles `text`, named `name` in diagnostics (a name ending in `.l`
    /// is read as a cpfg model).
    #[allow(clippy::should_implement_trait)] // it needs a name, and returns Diagnostics
    pub fn from_str(name: &str, text: &str) -> Result<Grammar, Diagnostics> {
        Grammar::options().from_str(name, text)
    }

    /// Compiles a grammar file (and what it includes), or `std:NAME`.
    pub fn from_path(path: impl AsRef<std::path::Path>) -> Result<Grammar, Diagnostics> {
        Grammar::options().from_path(path)
    }

    pub(crate) fn compile(input: Input, options: GrammarOptions) -> Result<Grammar, Diagnostics> {
        let comp = pipeline::compile(&input, &options.build.source)?;
        Ok(Grammar::compiled(comp, options))
    }

    /// A grammar already compiled with `options` (the driver compiles
    /// its jobs itself); its warnings are kept.
    pub(crate) fn compiled(mut comp: Compilation, options: GrammarOptions) -> Grammar {
        let warnings = Diagnostics::new(std::mem::take(&mut comp.warnings));
        Grammar {
            comp: Arc::new(comp),
            options,
            warnings,
        }
    }

    /// The warnings the grammar compiled with (possibly none).
    pub fn warnings(&self) -> &Diagnostics {
        &self.warnings
    }

    /// The file's `derivation length:` (0 when it gives none).
    pub fn derivation_length(&self) -> u32 {
        self.comp.program.derivation_length
    }

    /// A note when the grammar would derive 0 steps only because the file
    /// gives no `derivation length:` (and it has productions to apply).
    pub fn zero_steps_note(&self) -> Option<String> {
        let p = &self.comp.program;
        (!p.derivation_length_given && !p.productions.is_empty()).then(|| {
            format!(
                "note: {} has no `derivation length:`, so 0 steps are derived and the axiom is the result; add `derivation length: N` to the file or pass `-n N`",
                self.name()
            )
        })
    }

    /// The string after `steps` steps (`End:` runs after the last).
    pub fn derive(&self, steps: u32) -> Result<Derived, Diagnostics> {
        let mut sim = self.simulation(steps)?;
        sim.run(&mut |_, _| {}).map_err(Diagnostics::one)?;
        Ok(self.derived(sim.current().clone(), sim.step_number()))
    }

    /// Derives `steps` steps and builds the model: the homomorphism, the
    /// turtle, meshes and components (grammar components compiled with
    /// these options).
    pub fn build(&self, steps: u32) -> Result<Scene, Diagnostics> {
        let mut opts = self.options.build.clone();
        opts.steps = Some(steps);
        let built = crate::build::build(&self.comp, &opts).map_err(Diagnostics::one)?;
        Ok(Scene { built })
    }

    pub(crate) fn simulation(&self, steps: u32) -> Result<Simulation<'_>, Diagnostics> {
        let p = &self.comp;
        Simulation::new(
            &p.program,
            &p.compiled,
            self.options.build.derive.clone(),
            steps,
        )
        .map_err(Diagnostics::one)
    }

    pub(crate) fn derived(&self, string: crate::derive::ModuleStore, step: u32) -> Derived {
        Derived::new(self.comp.clone(), string, step)
    }

    /// The name the grammar was compiled under (its path, the name given
    /// to `from_str`, or `std:NAME`'s file name).
    pub(crate) fn name(&self) -> &str {
        self.comp
            .program
            .sources
            .files()
            .first()
            .map_or("", |f| f.name.as_str())
    }
}

/// A short form: the name, the derivation length, the size of the alphabet
/// (`[` and `]`, which every grammar has, among it), how many
/// productions and warnings; not the program.
impl std::fmt::Debug for Grammar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.comp.program;
        f.debug_struct("Grammar")
            .field("name", &self.name())
            .field("derivation_length", &p.derivation_length)
            .field("alphabet", &p.symbols.len())
            .field("productions", &p.productions.len())
            .field("warnings", &self.warnings.len())
            .finish()
    }
}
