//! The alphabet: the names a grammar defines (predecessors, `module`
//! declarations, `#include` components) and the turtle's commands -> a
//! splitter that turns raw module runs (`FF`, `CAOCAOPM2`, `@GsF`) into
//! module names by longest match.

use std::collections::HashSet;

use crate::lang as turtle;
use crate::parse::ast::{self, Item, PatTok, TokKind};
use crate::source::FileId;

/// One piece of a split run.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    pub name: String,
    /// Byte range inside the run.
    pub start: usize,
    pub end: usize,
    /// The piece is a single character that matched nothing in the
    /// alphabet (cpfg's inert letters).
    pub fallback: bool,
}

#[derive(Debug, Default)]
pub struct Alphabet {
    /// Names made of word characters (letters, digits, `_`).
    words: HashSet<String>,
    /// `@` commands.
    at: HashSet<String>,
    /// Declared component names, without `~`.
    components: HashSet<String>,
    /// The grammar uses names longer than one character (the paper's
    /// style); then an unmatched piece is an error, not an inert letter.
    pub multi_char: bool,
    /// Bytes of the longest name in any of the sets: no longer prefix is
    /// looked up. Trying every prefix of the rest of a run was cubic in
    /// the run's length (a cpfg axiom of 20,000 letters took 260 s).
    longest_name: usize,
}

impl Alphabet {
    pub fn new() -> Alphabet {
        let mut a = Alphabet::default();
        for c in turtle::all() {
            a.longest_name = a.longest_name.max(c.symbol.len());
            if let Some(rest) = c.symbol.strip_prefix('@') {
                a.at.insert(rest.to_string());
            } else if c.symbol.chars().all(is_word_char) {
                a.words.insert(c.symbol.to_string());
            }
        }
        a
    }

    /// Adds a name the grammar defines.
    pub fn add_word(&mut self, name: &str) {
        if name.chars().count() > 1 {
            self.multi_char = true;
        }
        self.longest_name = self.longest_name.max(name.len());
        self.words.insert(name.to_string());
    }

    pub fn add_component(&mut self, name: &str) {
        self.longest_name = self.longest_name.max(name.len());
        self.components.insert(name.to_string());
    }

    /// The declared components (`#include MP, MPB`), sorted.
    pub fn components(&self) -> Vec<&str> {
        let mut c: Vec<&str> = self.components.iter().map(String::as_str).collect();
        c.sort_unstable();
        c
    }

    /// The longest declared component that `name` (without `~`) starts
    /// with but is not: `MP` for `MPX` when `MP` is declared.
    pub fn component_prefix<'a>(&self, name: &'a str) -> Option<&'a str> {
        if self.components.contains(name) {
            return None;
        }
        longest(name, self.longest_name, |s| self.components.contains(s)).map(|n| &name[..n])
    }

    pub fn contains_word(&self, name: &str) -> bool {
        self.words.contains(name)
    }

    /// All defined word names, for "did you mean" suggestions.
    pub fn words(&self) -> impl Iterator<Item = &str> {
        self.words.iter().map(String::as_str)
    }

    /// Splits a run written as `kind` into module names.
    pub fn split(&self, text: &str, kind: TokKind) -> Vec<Piece> {
        match kind {
            TokKind::Punct => vec![Piece {
                name: text.to_string(),
                start: 0,
                end: text.len(),
                fallback: false,
            }],
            TokKind::Word => self.split_words(text, 0),
            TokKind::At => {
                // `@` + the longest command name; the rest is ordinary words.
                let rest = &text[1..];
                match longest(rest, self.longest_name, |s| self.at.contains(s)) {
                    Some(n) => {
                        let mut out = vec![Piece {
                            name: format!("@{}", &rest[..n]),
                            start: 0,
                            end: 1 + n,
                            fallback: false,
                        }];
                        out.extend(self.split_words(&rest[n..], 1 + n));
                        out
                    }
                    None => vec![Piece {
                        name: text.to_string(),
                        start: 0,
                        end: text.len(),
                        fallback: true,
                    }],
                }
            }
            TokKind::Query => {
                // `?` + one letter (`?P`, `?H`, ...); the rest is words.
                // The guided modeling queries `?DL ?DG ?DA ?NL ?NG ?NA`
                // (docs/guided.md) are two letters.
                let rest = &text[1..];
                let guided = ["DL", "DG", "DA", "NL", "NG", "NA"]
                    .iter()
                    .any(|g| rest.starts_with(g));
                let n = if guided {
                    2
                } else {
                    rest.chars().next().map_or(0, char::len_utf8)
                };
                let mut out = vec![Piece {
                    name: format!("?{}", &rest[..n]),
                    start: 0,
                    end: 1 + n,
                    fallback: false,
                }];
                out.extend(self.split_words(&rest[n..], 1 + n));
                out
            }
            TokKind::Tilde => {
                // `~` + the longest declared component; without one, the
                // whole word names the component (cpfg's one-letter
                // surfaces are whole words too).
                let rest = &text[1..];
                let n = longest(rest, self.longest_name, |s| self.components.contains(s))
                    .unwrap_or(rest.len());
                let mut out = vec![Piece {
                    name: format!("~{}", &rest[..n]),
                    start: 0,
                    end: 1 + n,
                    fallback: false,
                }];
                out.extend(self.split_words(&rest[n..], 1 + n));
                out
            }
        }
    }

    fn split_words(&self, text: &str, offset: usize) -> Vec<Piece> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < text.len() {
            let rest = &text[i..];
            let (n, fallback) = match longest(rest, self.longest_name, |s| self.words.contains(s)) {
                Some(n) => (n, false),
                None => (rest.chars().next().map_or(1, char::len_utf8), true),
            };
            out.push(Piece {
                name: rest[..n].to_string(),
                start: offset + i,
                end: offset + i + n,
                fallback,
            });
            i += n;
        }
        out
    }
}

/// Byte length of the longest prefix of `s` (at a char boundary, at most
/// `max` bytes) accepted by `has`.
fn longest(s: &str, max: usize, has: impl Fn(&str) -> bool) -> Option<usize> {
    let mut ends: Vec<usize> = s
        .char_indices()
        .map(|(i, c)| i + c.len_utf8())
        .take_while(|&e| e <= max)
        .collect();
    ends.reverse();
    ends.into_iter().find(|&e| has(&s[..e]))
}

pub fn is_word_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The names a grammar defines, as resolve splits module runs with them:
/// predecessors written as whole words (except with cpfg's one-character
/// names), `module` declarations and `#include` components. Resolve and
/// the language server both build their alphabet here.
pub fn grammar_alphabet(items: &[(FileId, Item)], cpfg_names: bool) -> Alphabet {
    let mut alphabet = Alphabet::new();
    for (_, item) in items {
        match item {
            Item::Production(p) => {
                for t in &p.pred {
                    if let PatTok::Module(m) = t {
                        if m.kind == TokKind::Word && !cpfg_names {
                            alphabet.add_word(&m.text);
                        }
                    }
                }
            }
            Item::Header(h) => {
                if let ast::HeaderKind::Module(ds) = &h.kind {
                    for d in ds {
                        alphabet.add_word(&d.name.name);
                    }
                }
            }
            Item::Include(ast::Include::Components(cs)) => {
                for c in cs {
                    alphabet.add_component(&c.name);
                }
            }
            _ => {}
        }
    }
    alphabet
}
