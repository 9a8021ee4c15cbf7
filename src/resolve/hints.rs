//! Hints about the dialect: the statements of a model -> at most one
//! advice when a command means something else in the other dialect than
//! the file, by its look, probably meant. Today: `$` in a `.lsys` file
//! that reads like ABOP/cpfg (`Lsystem:`, `endlsystem`, `ignore:`,
//! `consider:`) but has no `dialect: cpfg`, where `$` pitches 180° (the
//! paper's meaning) instead of rolling the turtle level (cpfg's).

use super::error::ResolveError;
use super::Resolver;
use crate::lang::Dialect;
use crate::parse::ast::{HeaderKind, Item, ModuleTok, TokKind};

impl Resolver {
    /// One hint, at the first `$`, when the file looks like cpfg's but
    /// is read in the paper's dialect by default (no `dialect:` header,
    /// no `--dialect`).
    pub(super) fn dialect_hint(&mut self, items: &[(u32, Item)], chosen: bool) {
        if chosen || self.profile.dialect != Dialect::Paper {
            return;
        }
        let mut looks_cpfg = false;
        let mut dollar = None;
        let first_dollar = |toks: &[ModuleTok]| {
            toks.iter()
                .find(|t| t.kind == TokKind::Punct && t.text == "$")
                .map(|t| t.span)
        };
        for (_, item) in items {
            match item {
                Item::Header(h) => match &h.kind {
                    HeaderKind::Dialect(..) => return,
                    HeaderKind::Lsystem(_)
                    | HeaderKind::Endlsystem
                    | HeaderKind::Ignore(_)
                    | HeaderKind::Consider(_) => looks_cpfg = true,
                    HeaderKind::Axiom(toks) => dollar = dollar.or_else(|| first_dollar(toks)),
                    _ => {}
                },
                Item::Production(p) => dollar = dollar.or_else(|| first_dollar(&p.succ)),
                _ => {}
            }
        }
        if let (true, Some(span)) = (looks_cpfg, dollar) {
            self.warn(ResolveError::DollarDialect {
                src: self.sources.named_source(span),
                span: span.into(),
            });
        }
    }
}
