//! Editing the grammar from the REPL: a typed production (added, or
//! replacing the one with the same predecessor and condition), `:drop`,
//! `:axiom`, `:set` and `:seed`, and a typed module string rewritten once.
//! Input: the session and what was typed; output: what changed, then the
//! status at the same step. Every edit is made to the grammar's text
//! ([`super::grammar`]) and compiled; a text with errors is refused and
//! the grammar stays as it was.

use super::same::{is_catch_all, pred_eq, same_rule};
use super::{grammar, show, Out, Session};
use crate::bytecode::one_line;
use crate::parse::ast::{HeaderKind, Item};
use crate::pipeline::Compilation;
use crate::resolve::{Production, Table};
use crate::simulation::Simulation;
use crate::source::{Origin, SourceFile};

impl Session {
    /// A typed statement: a production is added (or replaces the one with
    /// the same predecessor and condition); `Axiom: ...` sets the axiom.
    pub(super) fn statement(&mut self, text: &str) -> Out {
        let file = SourceFile::new("<input>", Origin::Memory, text);
        let (ast, errors) = crate::parse::parse(0, &file);
        self.last_production = Some(text.to_string());
        if !errors.is_empty() {
            return Err(errors
                .iter()
                .map(|e| crate::driver::render_diagnostic(e, self.color))
                .collect());
        }
        match ast.items.as_slice() {
            [Item::Production(_)] => self.add_production(text),
            [Item::Header(h)]
                if matches!(h.kind, HeaderKind::Axiom(_) | HeaderKind::LongAxiom(_)) =>
            {
                self.last_production = None;
                let succ = text[h.keyword.end as usize..]
                    .split_once(':')
                    .map_or("", |(_, r)| r);
                self.set_axiom(succ.trim())
            }
            [] => Ok(String::new()),
            _ => {
                self.last_production = None;
                Err("only productions, `Axiom: MODULES` and module strings can be typed here; \
                     `:set NAME=VALUE` overrides a #define, other changes go in the file (then `:reload`)"
                    .into())
            }
        }
    }

    /// Adds a production typed by the user, or replaces the one with the
    /// same predecessor, context and condition (for stochastic productions:
    /// and the same successor, so that typing it changes its weight). A new
    /// conditional production goes before the catch-all production of its
    /// predecessor, so that it can apply.
    pub fn add_production(&mut self, typed: &str) -> Out {
        let typed = typed.trim();
        if self.grammar.is_none() {
            return Err(
                "there is no grammar yet: give it an axiom first (`:axiom MODULES`), or `:load FILE`"
                    .into(),
            );
        }
        let (source, text) = self.base();
        let at = grammar::default_insertion(&text);
        let (candidate, start) = grammar::insert_at(&text, at, typed);
        let comp = self.compile(&source, &candidate, &self.overrides)?;
        let prods = &comp.program.productions;
        let Some(new_i) = prods
            .iter()
            .position(|p| p.span.file == 0 && p.span.start as usize == start)
        else {
            return Err("only productions of the main table can be typed; put decomposition and homomorphism productions in the file".into());
        };
        let new = &prods[new_i];
        let (text, start, replaced) =
            if let Some(j) = (0..prods.len()).find(|&j| j != new_i && same_rule(&prods[j], new)) {
                let old = &prods[j];
                if old.span.file != 0 {
                    return Err(format!(
                        "rule {} ({}) is in {}: edit it there and `:reload`",
                        j + 1,
                        one_line(comp.program.sources.slice(old.span)),
                        comp.program.sources.get(old.span.file).name
                    ));
                }
                let old_text = one_line(comp.program.sources.slice(old.span));
                let (t, s) =
                    grammar::replace(&text, old.span.start as usize..old.span.end as usize, typed);
                (t, s, Some(old_text))
            } else if let Some(k) = (0..new_i).find(|&k| {
                !is_catch_all(new)
                    && is_catch_all(&prods[k])
                    && pred_eq(&prods[k].pred, &new.pred)
                    && prods[k].span.file == 0
            }) {
                let ls = grammar::line_start(&text, prods[k].span.start as usize);
                let (t, s) = grammar::insert_at(&text, ls, typed);
                (t, s, None)
            } else {
                (candidate.clone(), start, None)
            };
        let comp = if text == candidate {
            comp
        } else {
            self.compile(&source, &text, &self.overrides)?
        };
        let n = comp
            .program
            .productions
            .iter()
            .position(|p| p.span.file == 0 && p.span.start as usize == start)
            .map_or(0, |i| i + 1);
        let line = one_line(typed);
        let mut what = match &replaced {
            Some(old) => {
                self.typed.retain(|t| t != old);
                format!("replaced rule {n}: {line}  (was {old})")
            }
            None => format!("added rule {n}: {line}"),
        };
        let prods = &comp.program.productions;
        if let Some(i) = n
            .checked_sub(1)
            .and_then(|j| super::shadow::shadowed_beyond_resolve(prods, j))
        {
            what.push_str(&format!(
                "
warning: rule {n} can never apply: rule {} ({}) comes first and applies wherever rule {n} would (`:rules` shows the order); narrow rule {}'s condition, or `:drop {}` and type it again: a typed rule goes after the other rules for its predecessor",
                i + 1,
                one_line(comp.program.sources.slice(prods[i].span)),
                i + 1,
                i + 1,
            ));
        }
        self.typed.push(line);
        let rest = self.install(source, text, comp, true)?;
        Ok(format!("{what}\n{rest}"))
    }

    /// `:drop N`: removes rule N (as numbered by `:rules`).
    pub fn drop_rule(&mut self, n: usize) -> Out {
        let g = self.grammar()?;
        let p = rule(&g.comp, n)?;
        let sources = &g.comp.program.sources;
        let line = one_line(sources.slice(p.span));
        if p.span.file != 0 {
            return Err(format!(
                "rule {n} is in {}: edit it there and `:reload`",
                sources.get(p.span.file).name
            ));
        }
        let text = grammar::remove_lines(&g.text, p.span.start as usize..p.span.end as usize);
        let source = g.source.clone();
        let comp = self.compile(&source, &text, &self.overrides)?;
        self.typed.retain(|t| *t != line);
        let rest = self.install(source, text, comp, true)?;
        Ok(format!("dropped rule {n}: {line}\n{rest}"))
    }

    /// `:axiom MODULES`.
    pub fn set_axiom(&mut self, modules: &str) -> Out {
        if modules.is_empty() {
            let g = self.grammar()?;
            let p = &g.comp.program;
            let text: Vec<&str> = p.axiom.iter().map(|m| p.sources.slice(m.span)).collect();
            return Ok(format!("axiom: {}", text.join(" ")));
        }
        let (source, text) = self.base();
        let (text, _) = grammar::set_axiom(&text, modules);
        let comp = self.compile(&source, &text, &self.overrides)?;
        let rest = self.install(source, text, comp, true)?;
        Ok(format!("axiom: {modules}\n{rest}"))
    }

    /// A module string typed: rewritten once with the current rules.
    pub fn rewrite_once(&mut self, modules: &str) -> Out {
        let (source, text) = self.base();
        let (probe, _) = grammar::set_axiom(&text, &modules.replace('\n', " "));
        let comp = self.compile(&source, &probe, &self.overrides)?;
        let mut d = Simulation::new(&comp.program, &comp.compiled, self.opts.clone(), 1)
            .map_err(|e| crate::driver::render_diagnostic(&e, self.color))?;
        d.step()
            .map_err(|e| crate::driver::render_diagnostic(&e, self.color))?;
        Ok(show::abbreviate(
            d.current(),
            &comp.program.symbols,
            self.numbers(&comp.program),
            show::BUDGET,
        ))
    }

    /// `:set NAME=VALUE` (or `:set NAME` to go back to the file's value).
    pub fn set_define(&mut self, arg: &str) -> Out {
        let g = self.grammar()?;
        let (name, value) = match arg.split_once('=') {
            Some((n, v)) if !n.trim().is_empty() && !v.trim().is_empty() => {
                (n.trim(), Some(v.trim()))
            }
            None if !arg.trim().is_empty() => (arg.trim(), None),
            _ => {
                return Err("write `:set NAME=VALUE` (or `:set NAME` for the file's value)".into())
            }
        };
        let mut ov = self.overrides.clone();
        ov.retain(|(n, _)| n != name);
        if let Some(v) = value {
            ov.push((name.to_string(), v.to_string()));
        }
        let (source, text, edited) = (g.source.clone(), g.text.clone(), g.edited);
        let comp = self.compile(&source, &text, &ov)?;
        let shown = comp
            .program
            .defines
            .iter()
            .find(|d| d.name == name)
            .and_then(|d| d.value)
            .map_or_else(|| value.unwrap_or("?").to_string(), |v| v.to_string());
        self.overrides = ov;
        let rest = self.install(source, text, comp, edited)?;
        let what = match value {
            Some(_) => format!("{name} = {shown}"),
            None => format!("{name} = {shown} (the file's value)"),
        };
        Ok(format!("{what}\n{rest}"))
    }

    /// `:seed [N]`.
    pub fn set_seed(&mut self, arg: &str) -> Out {
        let g = self.grammar()?;
        if arg.is_empty() {
            return Ok(format!(
                "seed {}",
                self.opts.effective_seed(&g.comp.program)
            ));
        }
        let seed: u64 = arg
            .parse()
            .ok()
            .filter(|&s| s <= u32::MAX as u64)
            .ok_or_else(|| format!("`{arg}` is not a seed (0 to 4294967295)"))?;
        self.opts.seed = Some(seed);
        let keep = self.pos;
        Ok(format!("seed {seed}\n{}", self.rederive(keep)?))
    }
}

/// Rule `n` (1-based, main productions, then decomposition, then
/// homomorphism, as `:rules` lists them).
pub(super) fn rule(comp: &Compilation, n: usize) -> Result<&Production, String> {
    let p = &comp.program;
    let all: Vec<&Production> = [Table::Main, Table::Decomposition, Table::Homomorphism]
        .into_iter()
        .flat_map(|t| p.table(t))
        .collect();
    if n == 0 || n > all.len() {
        return Err(format!(
            "there is no rule {n}: the rules are numbered 1 to {} (`:rules` lists them)",
            all.len()
        ));
    }
    Ok(all[n - 1])
}
