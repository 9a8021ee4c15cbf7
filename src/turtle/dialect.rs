//! Turtle dialects: which meaning the symbols that the paper and cpfg
//! disagree on (`%`, `$`) take in a file. Input: the `dialect:` header (or
//! the file name); output: a [`Dialect`] the turtle reads.

/// How a file's turtle symbols are read.
///
/// | symbol | `paper` (Table 1)  | `cpfg`                             |
/// |--------|--------------------|------------------------------------|
/// | `%`    | roll 180°          | cut the rest of the branch         |
/// | `$`    | pitch 180°         | roll until the left axis is horizontal |
///
/// `<` and `>` roll in both: cpfg has no module of that name (they mark
/// context there), so no cpfg file can mean anything else by them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
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

    /// The dialect of a file that does not say: cpfg for cpfg's own `.l`
    /// files, the paper's otherwise.
    pub fn for_file_name(name: &str) -> Dialect {
        if crate::cpfg::is_model_file(name) {
            Dialect::Cpfg
        } else {
            Dialect::Paper
        }
    }
}
