//! Bracket balance: the module tokens of a successor or the axiom -> a
//! diagnostic when their `[` and `]` do not pair up. An unclosed `[` is a
//! warning (cpfg models sometimes open a branch in one production and
//! close it in another); a `]` with no `[` is an error in the axiom, which
//! is the whole first string, and a warning in a successor.

use super::error::ResolveError;
use super::Resolver;
use crate::parse::ast::{ModuleTok, TokKind};
use crate::source::Span;

/// Where the tokens come from.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Place {
    Axiom,
    Successor,
}

/// The unclosed `[` and the `]` that close nothing, in order, over
/// tokens fed in one or more runs (a long axiom's pieces).
#[derive(Default)]
pub(super) struct Balance {
    open: Vec<Span>,
    stray: Vec<Span>,
}

impl Balance {
    pub(super) fn feed(&mut self, toks: &[ModuleTok]) {
        for t in toks.iter().filter(|t| t.kind == TokKind::Punct) {
            match t.text.as_str() {
                "[" => self.open.push(t.span),
                "]" if self.open.pop().is_none() => self.stray.push(t.span),
                _ => {}
            }
        }
    }
}

/// Brackets marked in one warning: a generated axiom of 100,000 unclosed
/// `[` gave one label each, which the printer renders in quadratic time
/// (1.8 GB of output for 30,000).
const MARKED: usize = 20;

/// The first [`MARKED`] of `spans`, labelled `label`.
fn marked(spans: &[Span], label: &str) -> Vec<miette::LabeledSpan> {
    spans
        .iter()
        .take(MARKED)
        .map(|s| miette::LabeledSpan::new_with_span(Some(label.to_string()), *s))
        .collect()
}

/// `"30000 `[` are never closed; the first 20 are marked. "` when not all
/// are marked, else nothing.
fn how_many(n: usize, what: &str) -> String {
    if n > MARKED {
        format!("{n} {what}; the first {MARKED} are marked. ")
    } else {
        String::new()
    }
}

impl Resolver {
    /// Reports unbalanced brackets in `toks`, at most one diagnostic of
    /// each kind per successor.
    pub(super) fn check_brackets(&mut self, toks: &[ModuleTok], place: Place) {
        let mut balance = Balance::default();
        balance.feed(toks);
        self.report_brackets(balance, place);
    }

    /// Reports what [`Balance`] found.
    pub(super) fn report_brackets(&mut self, balance: Balance, place: Place) {
        let Balance { open, stray } = balance;
        let what = match place {
            Place::Axiom => "the axiom",
            Place::Successor => "this successor",
        };
        if let Some(&first) = stray.first() {
            let what = what.to_string();
            let src = self.sources.named_source(first);
            let spans = marked(&stray, "closes no `[`");
            let help = format!(
                "{}a `]` ends a branch that a `[` began: remove it, or add the `[` where the branch starts",
                how_many(stray.len(), "`]` close nothing")
            );
            match place {
                Place::Axiom => self.error(ResolveError::StrayClose { what, src, spans, help }),
                Place::Successor => self.warn(ResolveError::StrayCloseWarning {
                    what,
                    src,
                    spans,
                    help: help + " (if another production's successor opens the branch, as in some cpfg models, ignore this warning)",
                }),
            }
        }
        if let Some(&first) = open.first() {
            self.warn(ResolveError::UnclosedBracket {
                what: what.to_string(),
                src: self.sources.named_source(first),
                spans: marked(&open, "never closed"),
                help: format!(
                    "{}close the branch with `]` where it ends (e.g. `F[+F]F`); if another production's successor closes it, as in some cpfg models, ignore this warning",
                    how_many(open.len(), "`[` are never closed")
                ),
            });
        }
    }
}
