//! cpfg's multi-letter modules as the single modules cpfg's scanner
//! reads: a model file's productions and `ignore:`/`consider:` list in,
//! the productions plus a twin for each that cpfg also applies to the
//! letter of an `@` command, and the list with every command, query and
//! component name cpfg's letters cover, out.
//!
//! cpfg's scanner makes `@o(0.2)` two modules, `@` and `o(0.2)`; the
//! turtle reads the letter after `@`. So a production for the module
//! `o` also rewrites the `o` of every `@o` in the string: Mycelis's
//! `o(r) --> o(r+0.03)` grows its buds' `@o(0.2)` spheres step by step.
//! lsys keeps `@o` one module, so such a production gets a twin whose
//! predecessor and first successor module are `@o`. Only productions
//! cpfg's result stays a command for: a strict predecessor of the one
//! module, no left context (cpfg's would see the `@`) and a successor
//! that starts with the same letter; others stay as they are.
//!
//! The same scanner reads `ignore: ;!@oZG` as nine letters, among them
//! `@` and `o`: in cpfg the `o` of any `@o` and a module `o` of its own
//! are both passed over. lsys passes over a command (`@o`, `@Gc`), query
//! (`?E`) or component (`~w`) name when cpfg would pass over every one of
//! its letters (`ignore:`), or would stop at one of them (`consider:`),
//! and over a one-letter module when its letter is listed, inside a
//! command or not.

use std::collections::HashMap;

use std::collections::HashSet;

use super::ir::{ContextFilter, Production, SymId, Table};
use super::Resolver;

impl Resolver {
    /// Adds the twins of every table's productions (see the module doc).
    pub(super) fn command_twins(&mut self, tables: &mut HashMap<Table, Vec<Production>>) {
        for prods in tables.values_mut() {
            let twins: Vec<Production> = prods
                .iter()
                .filter_map(|p| {
                    let command = self.command_of(p.pred.first()?.sym)?;
                    let twinnable = p.pred.len() == 1
                        && p.lctx.is_empty()
                        && p.succ.first().is_some_and(|m| m.sym == p.pred[0].sym);
                    twinnable.then(|| {
                        let mut twin = p.clone();
                        twin.pred[0].sym = command;
                        twin.succ[0].sym = command;
                        twin
                    })
                })
                .collect();
            prods.extend(twins);
        }
    }

    /// The `@` command the file uses whose letter is symbol `sym`.
    fn command_of(&self, sym: SymId) -> Option<SymId> {
        let name = self.symbols.name(sym);
        if name.chars().count() != 1 {
            return None;
        }
        self.symbols.get(&format!("@{name}"))
    }

    /// Completes a context list as cpfg reads it (see the module doc).
    pub(super) fn cpfg_context_letters(&mut self, filter: &mut ContextFilter) {
        let (list, ignore) = match filter {
            ContextFilter::Ignore(v) => (v, true),
            ContextFilter::Consider(v) => (v, false),
            ContextFilter::All => return,
        };
        let letters: HashSet<char> = list
            .iter()
            .flat_map(|&s| self.symbols.name(s).chars())
            .collect();
        for id in 0..self.symbols.len() as SymId {
            let name = self.symbols.name(id);
            // One letter, or every letter ignored / one considered.
            let covered = if ignore || name.chars().count() == 1 {
                name.chars().all(|c| letters.contains(&c))
            } else {
                name.chars().any(|c| letters.contains(&c))
            };
            if covered && !list.contains(&id) {
                list.push(id);
            }
        }
    }
}
