//! Productions that can never fire: the resolved [`Program`] in, a
//! warning out for each production whose predecessor or context names a
//! module that no string of the derivation can hold (issue 35).
//!
//! Which modules can occur is a fixpoint over names *and* parameter
//! counts: the axiom's modules occur; a production of the main or the
//! decomposition table whose predecessor modules all occur may fire, so
//! its successor's modules occur. The homomorphism's predecessors are
//! looked for in those strings and in the homomorphism's own successors.
//! The analysis is conservative: conditions, contexts, probabilities and
//! adjacency are taken to allow firing, so a warning is a certainty (for
//! the axiom of the file; a program that sets another axiom is not seen),
//! and a grammar with sub-L-systems, whose strings mix tables, is not
//! analysed.

use std::collections::{HashMap, HashSet};

use super::error::ResolveError;
use super::ir::{PatItem, PatModule, Production, Program, SuccModule, SymId};

/// A module as patterns match it: its name and its number of parameters.
type Shape = (SymId, usize);

/// The shapes the strings can hold, starting from `start` and closed
/// under `prods` (a production fires once all its predecessor's shapes
/// occur). Linear in the size of the grammar: each production waits on
/// a count of shapes still missing.
fn closure(start: impl IntoIterator<Item = Shape>, prods: &[&Production]) -> HashSet<Shape> {
    let mut waiting: HashMap<Shape, Vec<usize>> = HashMap::new();
    let mut missing: Vec<usize> = Vec::with_capacity(prods.len());
    for (k, p) in prods.iter().enumerate() {
        let need: HashSet<Shape> = p.pred.iter().map(shape).collect();
        missing.push(need.len());
        for s in need {
            waiting.entry(s).or_default().push(k);
        }
    }
    let mut occurs = HashSet::new();
    let mut work: Vec<Shape> = start.into_iter().collect();
    // Productions whose predecessor is empty (never, but harmless).
    for (k, p) in prods.iter().enumerate() {
        if missing[k] == 0 {
            work.extend(p.succ.iter().map(written));
        }
    }
    while let Some(s) = work.pop() {
        if !occurs.insert(s) {
            continue;
        }
        for &k in waiting.get(&s).map_or(&[][..], Vec::as_slice) {
            missing[k] -= 1;
            if missing[k] == 0 {
                work.extend(prods[k].succ.iter().map(written));
            }
        }
    }
    occurs
}

fn shape(m: &PatModule) -> Shape {
    (m.sym, m.arity as usize)
}

fn written(m: &SuccModule) -> Shape {
    (m.sym, m.args.len())
}

/// The warnings for `program`'s productions that can never fire.
pub(super) fn never_fires(program: &Program) -> Vec<ResolveError> {
    if !program.sub_lsystems.is_empty() {
        return Vec::new();
    }
    let derived: Vec<&Production> = program
        .productions
        .iter()
        .chain(&program.decomposition)
        .collect();
    let axiom = program.axiom.iter().map(written);
    let occurs = closure(axiom.clone(), &derived);
    let drawn: Vec<&Production> = program.homomorphism.iter().collect();
    let occurs_drawn = closure(occurs.iter().copied().chain(axiom), &drawn);
    let mut out = Vec::new();
    // Every production after `homomorphism`: the steps rewrite nothing.
    // One step is cpfg's idiom for a scene drawn from its axiom (the
    // corpus has seven), so from two steps on.
    if let (true, Some(first)) = (derived.is_empty(), drawn.first()) {
        if program.derivation_length > 1 {
            out.push(ResolveError::OnlyHomomorphism {
                steps: program.derivation_length,
                src: program.sources.named_source(first.span),
                span: first.head_span.into(),
            });
        }
    }
    for (prods, occurs) in [(&derived, &occurs), (&drawn, &occurs_drawn)] {
        for (i, p) in prods.iter().enumerate() {
            // cpfg's twins of a production (cpfg_commands.rs) share its
            // span: the production fires when one of them can, and is
            // warned about once.
            if prods[..i].iter().any(|q| q.span == p.span) {
                continue;
            }
            // An included file is a library of rules (the hall's parts,
            // shared by halls that each use some of them): only the file
            // built, the first, is held to firing every production.
            if p.span.file != 0 {
                continue;
            }
            if let Some(w) = check(program, p, occurs) {
                if prods[i + 1..]
                    .iter()
                    .filter(|q| q.span == p.span)
                    .all(|q| check(program, q, occurs).is_some())
                {
                    out.push(w);
                }
            }
        }
    }
    out
}

/// The first module of `p`'s pattern that cannot occur, as a warning.
fn check(program: &Program, p: &Production, occurs: &HashSet<Shape>) -> Option<ResolveError> {
    let rctx = p.rctx.iter().filter_map(|i| match i {
        PatItem::Module(m) => Some(m),
        _ => None,
    });
    let (m, role) = p
        .pred
        .iter()
        .map(|m| (m, "predecessor"))
        .chain(p.lctx.iter().map(|m| (m, "left context")))
        .chain(rctx.map(|m| (m, "right context")))
        .find(|(m, _)| !occurs.contains(&shape(m)))?;
    let symbols = &program.symbols;
    let name = symbols.name(m.sym);
    let counts: Vec<usize> = {
        let mut c: Vec<usize> = occurs
            .iter()
            .filter(|(s, _)| *s == m.sym)
            .map(|(_, n)| *n)
            .collect();
        c.sort_unstable();
        c
    };
    let head = program.sources.slice(p.head_span);
    let (why, help) = if let Some(header) = header_like(head).filter(|_| role == "predecessor") {
        (
            format!("`{}` reads as a production, not a header", head.trim()),
            format!("did you mean the header `{header}:`? a line that is not one of the headers is read as a production, here of a predecessor no string holds"),
        )
    } else if counts.is_empty() {
        let near = nearest(program, name, occurs);
        let help = match near {
            Some(n) => format!("did you mean `{n}`? "),
            None => String::new(),
        } + "a production fires only on modules the axiom or a successor writes; write the name as they do, or remove the production";
        (
            format!("`{name}` in its {role} never occurs in the strings"),
            help,
        )
    } else {
        let list: Vec<String> = counts.iter().map(|n| params(*n)).collect();
        (
            format!(
                "`{name}` in its {role} has {}, but every `{name}` the strings hold has {}",
                params(m.arity as usize),
                list.join(" or ")
            ),
            "a pattern matches only modules with exactly as many parameters: give it as many as the axiom and the successors write".to_string(),
        )
    };
    Some(ResolveError::NeverFires {
        why,
        src: program.sources.named_source(m.span),
        span: m.span.into(),
        help,
    })
}

/// The header a production's head most likely misspells: its first word
/// is a multi-word header's first word (`derivation steps`), or the whole
/// is a few letters from a header (`homomorphsm`). The parser's list:
/// near misses of one or two letters are its `misspelt_header` error.
fn header_like(head: &str) -> Option<&'static str> {
    let words: Vec<String> = head.split_whitespace().map(str::to_lowercase).collect();
    let text = words.join(" ");
    if text.len() < 4 {
        return None;
    }
    crate::parse::HEADERS.iter().copied().find(|h| {
        let first = h.split(' ').next().unwrap_or(h);
        (h.contains(' ') && words.len() > 1 && words[0] == first)
            || (text.len() >= 6 && strsim::levenshtein(&text, h) <= h.len() / 5)
    })
}

fn params(n: usize) -> String {
    match n {
        0 => "no parameters".to_string(),
        1 => "1 parameter".to_string(),
        n => format!("{n} parameters"),
    }
}

/// The name written in the strings that `name` most likely meant: the
/// same letters in another case, else one or two edits away.
fn nearest<'p>(program: &'p Program, name: &str, occurs: &HashSet<Shape>) -> Option<&'p str> {
    let mut names: Vec<&str> = occurs
        .iter()
        .map(|(s, _)| program.symbols.name(*s))
        .collect();
    names.sort_unstable();
    names.dedup();
    names
        .iter()
        .find(|n| n.eq_ignore_ascii_case(name))
        .or_else(|| {
            names
                .iter()
                .map(|n| (strsim::levenshtein(n, name), n))
                .filter(|(d, _)| *d <= 2 && *d < name.len())
                .min()
                .map(|(_, n)| n)
        })
        .copied()
}
