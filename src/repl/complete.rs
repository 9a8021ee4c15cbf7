//! The line editor's helper: the text before the cursor and the grammar's
//! names in, completions out (command names, then each command's argument
//! as [`COMMANDS`] says: paths, define names, views; module and define
//! names elsewhere), and Enter held back while brackets are open
//! ([`needs_more`]).

use std::borrow::Cow;

use rustyline::completion::{Completer, FilenameCompleter, Pair};
use rustyline::highlight::Highlighter;
use rustyline::hint::Hinter;
use rustyline::validate::{ValidationContext, ValidationResult, Validator};
use rustyline::Context;

use super::commands::{self, Arg, COMMANDS};
use super::input::needs_more;
use crate::driver::session::Names;
use crate::driver::View;

/// What to complete at the cursor.
#[derive(Debug, PartialEq, Eq)]
pub enum Completion {
    /// Replace the text from byte `start` to the cursor with one of these.
    Words(usize, Vec<String>),
    /// A path: let the file name completer do it.
    Path,
}

/// Completions for `before`, the line up to the cursor.
pub fn complete(before: &str, names: &Names) -> Completion {
    let trimmed = before.trim_start();
    let offset = before.len() - trimmed.len();
    if let Some(rest) = trimmed.strip_prefix(':') {
        let Some(space) = rest.find(char::is_whitespace) else {
            let words = COMMANDS
                .iter()
                .filter(|c| c.name.starts_with(rest))
                .map(|c| c.name.to_string())
                .collect();
            return Completion::Words(offset + 1, words);
        };
        let Ok(cmd) = commands::find(&rest[..space]) else {
            return Completion::Words(before.len(), Vec::new());
        };
        let args = &rest[space..];
        let (start, word) = last_word(before, |c| !c.is_whitespace());
        let n = args.split_whitespace().count();
        let index = if args.ends_with(char::is_whitespace) {
            n
        } else {
            n.saturating_sub(1)
        };
        let first_arg = index == 0;
        return match (cmd.arg, first_arg) {
            (Arg::File, true) => Completion::Path,
            (Arg::File, false) if cmd.name == "render" => Completion::Words(
                start,
                View::ALL
                    .iter()
                    .map(|v| v.name())
                    .filter(|n| n.starts_with(word))
                    .map(String::from)
                    .collect(),
            ),
            (Arg::Define, true) => Completion::Words(
                start,
                sorted(
                    names
                        .defines
                        .iter()
                        .filter(|d| d.starts_with(word))
                        .map(|d| format!("{d}=")),
                ),
            ),
            (Arg::Command, true) => Completion::Words(
                start,
                COMMANDS
                    .iter()
                    .filter(|c| c.name.starts_with(word.trim_start_matches(':')))
                    .map(|c| c.name.to_string())
                    .collect(),
            ),
            _ => Completion::Words(before.len(), Vec::new()),
        };
    }
    let (start, word) = last_word(before, |c| {
        c.is_alphanumeric() || matches!(c, '_' | '@' | '~' | '?')
    });
    if word.is_empty() {
        return Completion::Words(start, Vec::new());
    }
    let words = sorted(
        names
            .modules
            .iter()
            .chain(&names.defines)
            .filter(|n| n.starts_with(word) && n.as_str() != word)
            .cloned(),
    );
    Completion::Words(start, words)
}

/// The run of `is_word` characters that ends `text`, and where it starts.
fn last_word(text: &str, is_word: impl Fn(char) -> bool) -> (usize, &str) {
    let start = text
        .char_indices()
        .rev()
        .take_while(|&(_, c)| is_word(c))
        .last()
        .map_or(text.len(), |(i, _)| i);
    (start, &text[start..])
}

fn sorted(words: impl Iterator<Item = String>) -> Vec<String> {
    let mut v: Vec<String> = words.collect();
    v.sort();
    v.dedup();
    v
}

/// The rustyline helper.
pub struct Helper {
    /// The grammar's names; the REPL refreshes them after every command.
    pub names: Names,
    files: FilenameCompleter,
}

impl Helper {
    pub fn new() -> Helper {
        Helper {
            names: Names::default(),
            files: FilenameCompleter::new(),
        }
    }
}

impl Default for Helper {
    fn default() -> Self {
        Helper::new()
    }
}

impl Completer for Helper {
    type Candidate = Pair;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        match complete(&line[..pos], &self.names) {
            Completion::Path => self.files.complete_path(line, pos),
            Completion::Words(start, words) => Ok((
                start,
                words
                    .into_iter()
                    .map(|w| Pair {
                        display: w.clone(),
                        replacement: w,
                    })
                    .collect(),
            )),
        }
    }
}

impl Validator for Helper {
    fn validate(&self, ctx: &mut ValidationContext<'_>) -> rustyline::Result<ValidationResult> {
        Ok(if needs_more(ctx.input()) {
            ValidationResult::Incomplete
        } else {
            ValidationResult::Valid(None)
        })
    }
}

impl Hinter for Helper {
    type Hint = String;
}

impl Highlighter for Helper {
    fn highlight<'l>(&self, line: &'l str, _pos: usize) -> Cow<'l, str> {
        Cow::Borrowed(line)
    }
}

impl rustyline::Helper for Helper {}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Names {
        Names {
            modules: vec!["Apex".into(), "Axis".into(), "F".into(), "+".into()],
            defines: vec!["NTL".into(), "Angle".into()],
        }
    }

    fn words(before: &str) -> (usize, Vec<String>) {
        match complete(before, &names()) {
            Completion::Words(s, w) => (s, w),
            Completion::Path => panic!("a path for {before}"),
        }
    }

    #[test]
    fn commands_complete_from_the_table() {
        assert_eq!(words(":st"), (1, vec!["step".into(), "stats".into()]));
        assert_eq!(words(":re").1, vec!["reload", "reset", "render"]);
        assert_eq!(words(":help go"), (6, vec!["goto".into()]));
    }

    #[test]
    fn arguments_complete_by_kind() {
        assert_eq!(complete(":load ex", &names()), Completion::Path);
        assert_eq!(complete(":export ", &names()), Completion::Path);
        assert_eq!(words(":set N"), (5, vec!["NTL=".into()]));
        assert_eq!(words(":render a.png t"), (14, vec!["top".into()]));
        assert_eq!(words(":step 3").1, Vec::<String>::new());
    }

    #[test]
    fn modules_and_defines_complete_in_productions() {
        assert_eq!(
            words("A(x) --> A"),
            (9, vec!["Angle".into(), "Apex".into(), "Axis".into()])
        );
        assert_eq!(words("Axiom: F N"), (9, vec!["NTL".into()]));
    }
}
