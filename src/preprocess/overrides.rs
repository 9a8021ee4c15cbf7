//! Defines given on the command line (`-D NAME=VALUE`, the studio's
//! sliders) for a cpfg model file: the names in, whether a file's own
//! `#define` of one is skipped, and the names no file defines or mentions
//! out. As in `.lsys` files, the option wins over the file (a C
//! preprocessor would let the file's `#define` replace it, so `-D`
//! changed nothing), and a name the model never uses is an error, not a
//! silent no-op (issue 35).

use std::collections::HashSet;

/// The names given, and those a file also `#define`s.
#[derive(Default)]
pub(super) struct Overrides {
    names: Vec<String>,
    defined: HashSet<String>,
}

impl Overrides {
    pub(super) fn new(defines: &[(String, String)]) -> Self {
        Overrides {
            // `SQ(x)=x*x` names `SQ`.
            names: defines
                .iter()
                .map(|(n, _)| n.split('(').next().unwrap_or(n).trim().to_string())
                .collect(),
            defined: HashSet::new(),
        }
    }

    /// Whether a file's `#define name` is replaced by the option: it is
    /// then skipped.
    pub(super) fn claims(&mut self, name: &str) -> bool {
        let given = self.names.iter().any(|n| n == name);
        if given {
            self.defined.insert(name.to_string());
        }
        given
    }

    /// The names given that no file defines and no text mentions (not
    /// even `#ifdef NAME`), with the file macro nearest to each.
    pub(super) fn unmatched<'a>(
        &self,
        texts: impl Iterator<Item = &'a str> + Clone,
        file_macros: &[String],
    ) -> Vec<(String, Option<String>)> {
        self.names
            .iter()
            .filter(|n| !self.defined.contains(*n))
            .filter(|n| !texts.clone().any(|t| mentions(t, n)))
            .map(|n| {
                let near = file_macros
                    .iter()
                    .map(|m| (strsim::levenshtein(m, n), m))
                    .filter(|(d, _)| *d <= 2)
                    .min()
                    .map(|(_, m)| m.clone());
                (n.clone(), near)
            })
            .collect()
    }
}

/// Whether `name` occurs in `text` as a whole identifier.
fn mentions(text: &str, name: &str) -> bool {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.match_indices(name)
        .any(|(i, _)| !text[..i].ends_with(ident) && !text[i + name.len()..].starts_with(ident))
}
