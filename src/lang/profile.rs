//! The language profile: which of the two notations a model is written in
//! and everything that follows from it, decided once when the model is
//! loaded. Input: the root file's name, its `dialect:` header and any
//! override from the options; output: a [`Profile`] that the loader,
//! resolve, derive, the turtle and the printer read as plain fields.

/// How a file's turtle symbols are read.
///
/// | symbol | `paper` (Table 1)  | `cpfg`                             |
/// |--------|--------------------|------------------------------------|
/// | `%`    | roll 180°          | cut the rest of the branch         |
/// | `$`    | pitch 180°         | roll until the left axis is horizontal |
///
/// `<` and `>` roll in both: cpfg has no module of that name (they mark
/// context there), so no cpfg file can mean anything else by them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// The Pailou paper's Table 1; the standard library is written in it.
    #[default]
    Paper,
    /// cpfg (the Virtual Laboratory) and L-Py.
    Cpfg,
}

impl Dialect {
    pub const ALL: [Dialect; 2] = [Dialect::Paper, Dialect::Cpfg];

    pub fn name(self) -> &'static str {
        match self {
            Dialect::Paper => "paper",
            Dialect::Cpfg => "cpfg",
        }
    }

    pub fn from_name(name: &str) -> Option<Dialect> {
        Dialect::ALL.into_iter().find(|d| d.name() == name)
    }
}

/// Whether a file is a cpfg model file (`.l`): read through cpfg's C
/// preprocessor, with its view file beside it.
pub fn is_cpfg_model_file(name: &str) -> bool {
    name.ends_with(".l")
}

/// Every behaviour that differs between the paper's notation and cpfg's,
/// as one named switch each. Built only by [`Profile::decide`] (or
/// [`Profile::of`] for a dialect), so no stage tests a file name or a
/// dialect of its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Profile {
    /// The dialect the switches below follow.
    pub dialect: Dialect,
    /// The file is a cpfg model (`.l`): cpfg's C preprocessor runs over it
    /// and its includes (taking the `-D` definitions), and its view file and
    /// function files are read. A `.lsys` file keeps lsys's own `#define`
    /// (with tables) even in the cpfg dialect: the preprocessor is a
    /// property of the file format, not of the turtle.
    pub cpfg_model_file: bool,
    /// Module names are lexed as cpfg does: a word that is not in the
    /// alphabet is split into single-character modules (`FF` is two `F`),
    /// turtle commands accept cpfg's extra parameters, `=` in a right
    /// context skips the rest of the branch.
    pub cpfg_names: bool,
    /// Parameters are stored as 32-bit floats after every step, as cpfg
    /// stores them; printed with the shortest form that round-trips an f32.
    pub f32_params: bool,
    /// `%` cuts the rest of its branch during rewriting, not only when the
    /// turtle draws.
    pub cut_in_rewriting: bool,
    /// `ignore:` / `consider:` may pass over brackets in context matching
    /// (context reads through branches).
    pub context_through_brackets: bool,
    /// The fast (and parallel) rewriting path may be used. Only the paper's
    /// rewriting is exactly "first matching production, run its code".
    pub fast_path: bool,
    /// The turtle starts in cpfg's left-handed frame (U = −z) and `@Ts`
    /// bends toward the tropism vector as cpfg does.
    pub cpfg_turtle: bool,
    /// The axiom is decomposed before the first step (step 0 is the
    /// decomposed axiom). cpfg decomposes only after each step's
    /// productions, so its step 0 is the axiom as written: its first
    /// environment pass sees `?E` modules of the axiom, not those its
    /// decomposition would write.
    pub decompose_axiom: bool,
    /// The homomorphism draws its random numbers (`ran`, `nran`, ...) from
    /// the derivation's own generator, as cpfg's turtle does (one
    /// `main_xsubi` for productions and interpretation): every time cpfg
    /// interprets the string (after the axiom and each step when the file
    /// has query modules, and once more for the view before the string is
    /// drawn or printed) it goes on drawing where the last draw left off.
    /// Off, each homomorphism starts a generator of its own, seeded as the
    /// derivation's, so the drawn string depends only on the string.
    pub shared_random_stream: bool,
    /// Stochastic productions as cpfg chooses them. A `seed:` makes the
    /// L-system stochastic: at every module of a step, every production
    /// that matches (condition included) takes part, weighted by its
    /// probability or 1 without one, and one number is drawn from a
    /// generator of its own ([`crate::lang::rng::Rand48::cpfg_choice`]),
    /// even where nothing matches. `seed:` seeds only that generator:
    /// `ran` starts from 0 whatever it says. Without `seed:`, and in the
    /// decomposition and homomorphism, probabilities are not used (the
    /// first match applies). Off: the paper's choice (see `derive`).
    pub cpfg_stochastic: bool,
}

impl Profile {
    /// The profile of a dialect, for a `.lsys` file.
    pub const fn of(dialect: Dialect) -> Profile {
        let cpfg = matches!(dialect, Dialect::Cpfg);
        Profile {
            dialect,
            cpfg_model_file: false,
            cpfg_names: cpfg,
            f32_params: cpfg,
            cut_in_rewriting: cpfg,
            context_through_brackets: cpfg,
            fast_path: !cpfg,
            cpfg_turtle: cpfg,
            decompose_axiom: !cpfg,
            shared_random_stream: false,
            cpfg_stochastic: false,
        }
    }

    /// Decides the profile of a model, once: the override (`--dialect`)
    /// wins, then the root file's `dialect:` header, then its name (cpfg
    /// for `.l`, the paper's otherwise). `text` is the root file's text as
    /// loaded (before any preprocessing).
    pub fn decide(root_name: &str, text: &str, over: Option<Dialect>) -> Profile {
        let model_file = is_cpfg_model_file(root_name);
        let dialect = over
            .or_else(|| header_dialect(text))
            .unwrap_or(if model_file {
                Dialect::Cpfg
            } else {
                Dialect::Paper
            });
        Profile {
            cpfg_model_file: model_file,
            // A cpfg model file is derived as cpfg runs it; a `.lsys` file
            // in the cpfg dialect keeps homomorphisms that depend only on
            // the string and the paper's stochastic choice (and a model
            // file read in the paper's dialect takes the fast path, which
            // knows only the paper's).
            shared_random_stream: model_file,
            cpfg_stochastic: model_file && matches!(dialect, Dialect::Cpfg),
            ..Profile::of(dialect)
        }
    }
}

impl Default for Profile {
    fn default() -> Profile {
        Profile::of(Dialect::Paper)
    }
}

/// The dialect a `dialect: NAME` header line names, read off the text
/// before parsing (the loader needs it before the preprocessor runs). An
/// unknown name gives `None` here; resolve reports it with its span.
fn header_dialect(text: &str) -> Option<Dialect> {
    text.lines().find_map(|line| {
        let line = line.trim_start();
        let rest = line
            .strip_prefix("dialect")
            .or_else(|| line.strip_prefix("Dialect"))?;
        let name = rest.trim_start().strip_prefix(':')?.trim();
        let name = name.split(|c: char| !c.is_alphanumeric() && c != '_');
        Dialect::from_name(name.into_iter().next()?)
    })
}
