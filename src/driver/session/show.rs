//! Strings of modules as the REPL prints them: a [`ModuleStore`] and the
//! grammar's symbols in, text out. Long strings are abbreviated (head … tail
//! plus counts per symbol), counts are tabulated, and two successive
//! strings are compared ([`diff`]). Pure functions.

use std::fmt::Write;
use std::ops::Range;

use crate::derive::{Module, ModuleStore, NumberFormat};
use crate::resolve::Symbols;

/// Characters of a string shown before it is abbreviated.
pub const BUDGET: usize = 320;
/// Strings compared module by module in [`diff`] (each at most this long).
pub const DIFF_LIMIT: usize = 300;
/// Strings shown module by module, each change in place, in [`diff`].
pub const WHERE_LIMIT: usize = 100;

/// One module in the CLI's format: `A(1,2.5)`, parameters as `fmt` says.
pub fn token(symbols: &Symbols, fmt: NumberFormat, m: Module<'_>) -> String {
    let mut s = symbols.name(m.sym).to_string();
    if !m.params.is_empty() {
        s.push('(');
        for (k, v) in m.params.iter().enumerate() {
            if k > 0 {
                s.push(',');
            }
            s.push_str(&fmt.format(*v));
        }
        s.push(')');
    }
    s
}

/// Modules `range` of `store`, separated by spaces.
pub fn modules(
    store: &ModuleStore,
    symbols: &Symbols,
    fmt: NumberFormat,
    range: Range<usize>,
) -> String {
    let n = range.end.saturating_sub(range.start);
    let toks: Vec<String> = store
        .iter()
        .skip(range.start)
        .take(n)
        .map(|m| token(symbols, fmt, m))
        .collect();
    toks.join(" ")
}

/// The whole string when it fits in `budget` characters; otherwise its
/// head and tail with the number of modules left out, and a line of
/// counts per symbol.
pub fn abbreviate(
    store: &ModuleStore,
    symbols: &Symbols,
    fmt: NumberFormat,
    budget: usize,
) -> String {
    let half = budget / 2;
    let mut head = String::new();
    let mut shown = 0usize;
    for m in store.iter() {
        let t = token(symbols, fmt, m);
        if head.len() + t.len() + 1 > half && shown > 0 {
            break;
        }
        if shown > 0 {
            head.push(' ');
        }
        head.push_str(&t);
        shown += 1;
        if head.len() > half {
            break;
        }
    }
    if shown == store.len() {
        return head;
    }
    // The tail: at most `half` characters from the end.
    let from = store.len().saturating_sub(half / 2).max(shown);
    let tail_toks: Vec<String> = store
        .iter()
        .skip(from)
        .map(|m| token(symbols, fmt, m))
        .collect();
    let mut tail: Vec<&str> = Vec::new();
    let mut chars = 0;
    for t in tail_toks.iter().rev() {
        if chars + t.len() + 1 > half && !tail.is_empty() {
            break;
        }
        chars += t.len() + 1;
        tail.push(t);
    }
    tail.reverse();
    let omitted = store.len() - shown - tail.len();
    if omitted == 0 {
        return modules(store, symbols, fmt, 0..store.len());
    }
    format!(
        "{head} … ({omitted} more) … {}\n{}",
        tail.join(" "),
        count_line(store, symbols, 8)
    )
}

/// Modules per symbol, most frequent first (ties by name).
pub fn counts(store: &ModuleStore, symbols: &Symbols) -> Vec<(String, usize)> {
    let mut v: Vec<(String, usize)> = store
        .counts(symbols.len())
        .into_iter()
        .enumerate()
        .filter(|&(_, n)| n > 0)
        .map(|(s, n)| (symbols.name(s as u32).to_string(), n))
        .collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v
}

/// `per symbol: F 64, + 32, X 16, …` with at most `most` symbols.
pub fn count_line(store: &ModuleStore, symbols: &Symbols, most: usize) -> String {
    let c = counts(store, symbols);
    let mut parts: Vec<String> = c
        .iter()
        .take(most)
        .map(|(s, n)| format!("{s} {n}"))
        .collect();
    if c.len() > most {
        parts.push(format!("… {} more symbols", c.len() - most));
    }
    format!("per symbol: {}", parts.join(", "))
}

/// The table of `:count`.
pub fn count_table(store: &ModuleStore, symbols: &Symbols) -> String {
    let c = counts(store, symbols);
    let w = c.iter().map(|(s, _)| s.chars().count()).max().unwrap_or(0);
    let nw = c
        .iter()
        .map(|(_, n)| n.to_string().len())
        .max()
        .unwrap_or(1);
    let mut out = String::new();
    for (s, n) in &c {
        let pad = w - s.chars().count();
        let _ = writeln!(out, "{s}{}  {n:>nw$}", " ".repeat(pad));
    }
    let _ = write!(
        out,
        "{} modules, {} parameter values, {} symbols",
        store.len(),
        store.param_count(),
        c.len()
    );
    out
}

/// What changed from `prev` (step `step - 1`) to `cur` (step `step`):
/// module totals, the counts per symbol that changed, and for short
/// strings which modules became what (`rewritable[sym]`: whether a
/// production can rewrite symbol `sym`; the others are copied).
pub fn diff(
    prev: &ModuleStore,
    cur: &ModuleStore,
    symbols: &Symbols,
    fmt: NumberFormat,
    rewritable: &[bool],
    step: u32,
) -> String {
    let mut out = format!(
        "step {} -> {step}: {} -> {} modules ({})",
        step - 1,
        prev.len(),
        cur.len(),
        signed(cur.len() as i64 - prev.len() as i64)
    );
    let before = prev.counts(symbols.len());
    let after = cur.counts(symbols.len());
    let mut changed: Vec<(String, usize, usize)> = (0..symbols.len())
        .map(|s| {
            let b = before.get(s).copied().unwrap_or(0);
            let a = after.get(s).copied().unwrap_or(0);
            (symbols.name(s as u32).to_string(), b, a)
        })
        .filter(|(_, b, a)| a != b)
        .collect();
    changed.sort_by(|x, y| {
        let dx = (x.2 as i64 - x.1 as i64).abs();
        let dy = (y.2 as i64 - y.1 as i64).abs();
        dy.cmp(&dx).then_with(|| x.0.cmp(&y.0))
    });
    let w = changed
        .iter()
        .map(|(s, _, _)| s.chars().count())
        .max()
        .unwrap_or(0);
    for (s, b, a) in &changed {
        let pad = w - s.chars().count();
        let _ = write!(
            out,
            "\n  {s}{}  {b} -> {a} ({})",
            " ".repeat(pad),
            signed(*a as i64 - *b as i64)
        );
    }
    if changed.is_empty() {
        out.push_str("\n  no count changed");
    }
    if prev.len() > DIFF_LIMIT || cur.len() > DIFF_LIMIT {
        let _ = write!(
            out,
            "\n(longer than {DIFF_LIMIT} modules: no module-by-module comparison)"
        );
        return out;
    }
    let p: Vec<String> = prev.iter().map(|m| token(symbols, fmt, m)).collect();
    let r: Vec<bool> = prev
        .iter()
        .map(|m| rewritable.get(m.sym as usize).copied().unwrap_or(false))
        .collect();
    let c: Vec<String> = cur.iter().map(|m| token(symbols, fmt, m)).collect();
    // An alignment is shown only when it is consistent: the same run of
    // modules became the same thing everywhere. Otherwise it is one guess
    // among several (conditions, stochastic rules, or plain ambiguity) and
    // the positional comparison is the honest answer.
    let consistent = |pairs: &Vec<(Range<usize>, Range<usize>)>| {
        let mut seen: std::collections::HashMap<String, String> = Default::default();
        pairs.iter().all(|(a, b)| {
            let (old, new) = (p[a.clone()].join(" "), c[b.clone()].join(" "));
            seen.entry(old).or_insert_with(|| new.clone()) == &new
        })
    };
    match align(&p, &r, &c).filter(consistent) {
        Some(pairs) => {
            let mut rewrites: Vec<(String, String, usize)> = Vec::new();
            let mut parts = Vec::new();
            for (a, b) in pairs {
                let (old, new) = (p[a.clone()].join(" "), c[b].join(" "));
                if old == new {
                    parts.push(old);
                    continue;
                }
                parts.push(mark(&old, &new));
                match rewrites.iter_mut().find(|(o, n, _)| *o == old && *n == new) {
                    Some(e) => e.2 += 1,
                    None => rewrites.push((old, new, 1)),
                }
            }
            out.push_str("\nrewritten:");
            if rewrites.is_empty() {
                out.push_str(" nothing");
            }
            for (old, new, n) in &rewrites {
                let _ = write!(out, "\n  {n}× {}", mark(old, new));
            }
            if cur.len() <= WHERE_LIMIT {
                let _ = write!(out, "\nwhere: {}", parts.join(" "));
            }
        }
        None => {
            let _ = write!(out, "\ncompared: {}", positional(&p, &c));
        }
    }
    out
}

fn signed(n: i64) -> String {
    if n >= 0 {
        format!("+{n}")
    } else {
        n.to_string()
    }
}

/// `«old → new»`.
fn mark(old: &str, new: &str) -> String {
    let o = if old.is_empty() {
        String::new()
    } else {
        format!("{old} ")
    };
    let n = if new.is_empty() {
        String::new()
    } else {
        format!(" {new}")
    };
    format!("«{o}→{n}»")
}

/// Splits `cur` into what each part of `prev` became. Modules that no
/// production rewrites (`rewritable[i]` false) are copied, so each must
/// reappear as it is; each run of rewritable modules became a
/// bracket-balanced chunk (possibly empty). The pairs (prev range, cur
/// range) in order, or `None` when no split fits (unbalanced successors).
fn align(
    p: &[String],
    rewritable: &[bool],
    c: &[String],
) -> Option<Vec<(Range<usize>, Range<usize>)>> {
    // Segments of `prev`: one copied module, or a run of rewritable ones.
    let mut segs: Vec<(Range<usize>, bool)> = Vec::new();
    let mut i = 0;
    while i < p.len() {
        if rewritable[i] {
            let s = i;
            while i < p.len() && rewritable[i] {
                i += 1;
            }
            segs.push((s..i, true));
        } else {
            segs.push((i..i + 1, false));
            i += 1;
        }
    }
    let m = c.len();
    let mut dead = vec![false; (segs.len() + 1) * (m + 1)];
    let mut path = Vec::new();
    fn go(
        segs: &[(Range<usize>, bool)],
        p: &[String],
        c: &[String],
        s: usize,
        j: usize,
        dead: &mut [bool],
        path: &mut Vec<(Range<usize>, Range<usize>)>,
    ) -> bool {
        let m = c.len();
        if s == segs.len() {
            return j == m;
        }
        if dead[s * (m + 1) + j] {
            return false;
        }
        let (range, wild) = &segs[s];
        if !wild {
            if j < m && c[j] == p[range.start] {
                path.push((range.clone(), j..j + 1));
                if go(segs, p, c, s + 1, j + 1, dead, path) {
                    return true;
                }
                path.pop();
            }
        } else {
            // Shortest balanced chunk first.
            let mut depth = 0i64;
            let mut k = j;
            loop {
                if depth == 0 {
                    path.push((range.clone(), j..k));
                    if go(segs, p, c, s + 1, k, dead, path) {
                        return true;
                    }
                    path.pop();
                }
                if k == m {
                    break;
                }
                match c[k].as_str() {
                    "[" => depth += 1,
                    "]" => depth -= 1,
                    _ => {}
                }
                if depth < 0 {
                    break;
                }
                k += 1;
            }
        }
        dead[s * (m + 1) + j] = true;
        false
    }
    go(&segs, p, c, 0, 0, &mut dead, &mut path).then_some(path)
}

/// `a` and `b` aligned by their longest common subsequence; unchanged
/// modules as they are, each changed run as `«old → new»`.
fn positional(a: &[String], b: &[String]) -> String {
    let (n, m) = (a.len(), b.len());
    // lcs[i][j]: length of the LCS of a[i..] and b[j..].
    let mut lcs = vec![0u32; (n + 1) * (m + 1)];
    let at = |i: usize, j: usize| i * (m + 1) + j;
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            lcs[at(i, j)] = if a[i] == b[j] {
                lcs[at(i + 1, j + 1)] + 1
            } else {
                lcs[at(i + 1, j)].max(lcs[at(i, j + 1)])
            };
        }
    }
    let mut parts: Vec<String> = Vec::new();
    let (mut old, mut new): (Vec<&str>, Vec<&str>) = (Vec::new(), Vec::new());
    let flush = |parts: &mut Vec<String>, old: &mut Vec<&str>, new: &mut Vec<&str>| {
        if !old.is_empty() || !new.is_empty() {
            parts.push(mark(&old.join(" "), &new.join(" ")));
            old.clear();
            new.clear();
        }
    };
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        if i < n && j < m && a[i] == b[j] {
            flush(&mut parts, &mut old, &mut new);
            parts.push(a[i].clone());
            i += 1;
            j += 1;
        } else if j < m && (i == n || lcs[at(i, j + 1)] >= lcs[at(i + 1, j)]) {
            new.push(&b[j]);
            j += 1;
        } else {
            old.push(&a[i]);
            i += 1;
        }
    }
    flush(&mut parts, &mut old, &mut new);
    parts.join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn alignment_follows_the_rewriting() {
        // F --> F F, X --> F [ + X ] X; brackets and + are copied.
        let p = toks("F [ + X ] X");
        let r = [true, false, false, true, false, true];
        let c = toks("F F [ + F [ + X ] X ] F [ + X ] X");
        let pairs = align(&p, &r, &c).unwrap();
        let shown: Vec<String> = pairs
            .iter()
            .map(|(a, b)| format!("{} => {}", p[a.clone()].join(" "), c[b.clone()].join(" ")))
            .collect();
        assert_eq!(
            shown,
            [
                "F => F F",
                "[ => [",
                "+ => +",
                "X => F [ + X ] X",
                "] => ]",
                "X => F [ + X ] X"
            ]
        );
        // A copied module that does not reappear: no alignment.
        assert!(align(&toks("A"), &[false], &toks("B")).is_none());
    }

    #[test]
    fn positional_diff_marks_replaced_runs() {
        assert_eq!(positional(&toks("A B C"), &toks("A B C")), "A B C");
        assert_eq!(positional(&toks("A B"), &toks("A C B")), "A «→ C» B");
        assert_eq!(positional(&toks("A X"), &toks("A Y Z")), "A «X → Y Z»");
        assert_eq!(positional(&toks("A X B"), &toks("A B")), "A «X →» B");
    }
}
