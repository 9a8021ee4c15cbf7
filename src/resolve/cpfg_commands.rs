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

use super::ir::{ContextFilter, Expr, ExprKind, Production, SuccModule, SymId, Table};
use super::Resolver;

impl Resolver {
    /// Adds the twins of every table's productions (see the module doc).
    pub(super) fn command_twins(
        &mut self,
        tables: &mut HashMap<Table, Vec<Production>>,
        axiom: &[SuccModule],
    ) {
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
        self.prefix_twins(tables, axiom);
    }

    /// cpfg's scanner reads `@Gc(4)` as `@`, `G`, `c(4)`, so a production
    /// for `@G` also matches the start of `@Gs`, `@Gc(4)` and `@Ge` and
    /// leaves the rest: two-trees' homomorphism `@G --> *` prints `s`,
    /// `c(4)`, `e`. lsys keeps each command one module; a production whose
    /// strict predecessor is one `@` name without parameters, with no
    /// context, gets a twin for every longer `@` name the file writes (and
    /// every parameter count the axiom and successors write it with, none
    /// if they do not write it) whose successor ends with the remaining
    /// letters, the last one taking the command's parameters.
    fn prefix_twins(&mut self, tables: &mut HashMap<Table, Vec<Production>>, axiom: &[SuccModule]) {
        let mut counts: HashMap<SymId, HashSet<usize>> = HashMap::new();
        for m in tables.values().flatten().flat_map(|p| &p.succ).chain(axiom) {
            counts.entry(m.sym).or_default().insert(m.args.len());
        }
        for prods in tables.values_mut() {
            let mut twins = Vec::new();
            for p in prods.iter() {
                let [pred] = p.pred.as_slice() else {
                    continue;
                };
                let name = self.symbols.name(pred.sym).to_string();
                if !name.starts_with('@') || pred.arity != 0 || p.has_context() {
                    continue;
                }
                let longer: Vec<(SymId, String)> = self
                    .symbols
                    .list
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| s.name.len() > name.len() && s.name.starts_with(&name))
                    .map(|(id, s)| (id as SymId, s.name[name.len()..].to_string()))
                    .collect();
                for (sym, rest) in longer {
                    let mut arities: Vec<usize> = counts
                        .get(&sym)
                        .map_or(vec![0], |c| c.iter().copied().collect());
                    arities.sort_unstable();
                    let letters: Vec<SymId> = rest
                        .chars()
                        .map(|c| self.intern(&c.to_string(), None))
                        .collect();
                    for k in arities {
                        let mut twin = p.clone();
                        twin.pred[0].sym = sym;
                        twin.pred[0].arity = k as u8;
                        twin.pred[0].first_param = p.nparams;
                        twin.nparams = p.nparams + k as u16;
                        twin.param_names
                            .extend((0..k).map(|i| format!("{rest}{i}")));
                        let span = p.head_span;
                        for (j, &l) in letters.iter().enumerate() {
                            let last = j + 1 == letters.len();
                            let args = (0..k)
                                .filter(|_| last)
                                .map(|i| Expr {
                                    kind: ExprKind::Param(p.nparams + i as u16),
                                    span,
                                })
                                .collect();
                            twin.succ.push(SuccModule { sym: l, args, span });
                        }
                        twins.push(twin);
                    }
                }
            }
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
