//! Hints about the dialect: the statements of a model -> at most one
//! advice when a command means something else in the other dialect than
//! the file, by its look, probably meant. Today: `$` in a `.lsys` file
//! that reads like ABOP/cpfg (`Lsystem:`, `endlsystem`, `ignore:`,
//! `consider:`) but has no `dialect: cpfg`, where `$` pitches 180° (the
//! paper's meaning) instead of rolling the turtle level (cpfg's); and
//! `%`, a 180° roll in the paper's dialect where ABOP and cpfg cut the
//! rest of the branch.

use super::error::ResolveError;
use super::Resolver;
use crate::lang::Dialect;
use crate::parse::ast::{HeaderKind, Item, ModuleTok, TokKind};
use crate::source::Span;

impl Resolver {
    /// One hint at the first `$`, one at the first `%`, when the file looks like cpfg's but
    /// is read in the paper's dialect by default (no `dialect:` header,
    /// no `--dialect`).
    pub(super) fn dialect_hint(&mut self, items: &[(u32, Item)], chosen: bool) {
        if chosen || self.profile.dialect != Dialect::Paper {
            return;
        }
        let mut looks_cpfg = false;
        // The first `$` and the first `%` of the axiom and successors.
        let mut first: [Option<Span>; 2] = [None, None];
        let mut scan = |toks: &[ModuleTok]| {
            for (k, c) in ["$", "%"].into_iter().enumerate() {
                if first[k].is_none() {
                    first[k] = toks
                        .iter()
                        .find(|t| t.kind == TokKind::Punct && t.text == c)
                        .map(|t| t.span);
                }
            }
        };
        for (_, item) in items {
            match item {
                Item::Header(h) => match &h.kind {
                    HeaderKind::Dialect(..) => return,
                    HeaderKind::Lsystem(_)
                    | HeaderKind::Endlsystem
                    | HeaderKind::Ignore(_)
                    | HeaderKind::Consider(_) => looks_cpfg = true,
                    HeaderKind::Axiom(toks) => scan(toks),
                    _ => {}
                },
                Item::Production(p) => scan(&p.succ),
                _ => {}
            }
        }
        if !looks_cpfg {
            return;
        }
        if let Some(span) = first[0] {
            self.warn(ResolveError::DollarDialect {
                src: self.sources.named_source(span),
                span: span.into(),
            });
        }
        if let Some(span) = first[1] {
            self.warn(ResolveError::PercentDialect {
                src: self.sources.named_source(span),
                span: span.into(),
            });
        }
    }
}
