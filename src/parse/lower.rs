//! Lowering: pest pairs of one statement -> AST nodes with file spans.

use pest::iterators::Pair;

use super::ast::*;
use super::error::PResult;
use super::{ParseError, Rule};
use crate::source::{FileId, SourceFile, Span};

/// Context for lowering one statement that was parsed from `file` starting
/// at byte `base`.
pub(crate) struct Lower<'a> {
    pub file_id: FileId,
    pub base: usize,
    pub file: &'a SourceFile,
}

impl Lower<'_> {
    pub fn span(&self, p: &Pair<Rule>) -> Span {
        let s = p.as_span();
        Span::new(self.file_id, self.base + s.start(), self.base + s.end())
    }

    pub fn ident(&self, p: Pair<Rule>) -> Ident {
        Ident {
            name: p.as_str().to_string(),
            span: self.span(&p),
        }
    }

    pub fn statement(&self, stmt: Pair<Rule>) -> PResult<Item> {
        let p = stmt.into_inner().next().expect("statement has one child");
        let span = self.span(&p);
        Ok(match p.as_rule() {
            Rule::define => Item::Define(
                p.into_inner()
                    .map(|d| self.define(d))
                    .collect::<Result<_, _>>()?,
            ),
            Rule::include => {
                let inner = p.into_inner().next().expect("include has a target");
                let ispan = self.span(&inner);
                Item::Include(match inner.as_rule() {
                    Rule::include_path => Include::Path {
                        path: inner.into_inner().as_str().to_string(),
                        span: ispan,
                    },
                    Rule::include_std => Include::Std {
                        name: inner.into_inner().as_str().to_string(),
                        span: ispan,
                    },
                    _ => Include::Components(inner.into_inner().map(|i| self.ident(i)).collect()),
                })
            }
            Rule::other_directive => {
                let name = p.into_inner().next().expect("directive name");
                Item::OtherDirective {
                    name: self.ident(name),
                    span,
                }
            }
            Rule::production => Item::Production(Box::new(self.production(p)?)),
            _ => Item::Header(self.header(p)?),
        })
    }

    fn define(&self, d: Pair<Rule>) -> PResult<Define> {
        let span = self.span(&d);
        let mut inner = d.into_inner();
        let mut head = inner.next().expect("define head").into_inner();
        let name = self.ident(head.next().expect("define name"));
        let (mut params, mut dims) = (None, None);
        if let Some(h) = head.next() {
            if h.as_rule() == Rule::table_dims {
                dims = Some(
                    h.into_inner()
                        .map(|d| self.table_dim(d))
                        .collect::<PResult<Vec<_>>>()?,
                );
            } else {
                params = Some(h.into_inner().map(|i| self.ident(i)).collect());
            }
        }
        let (mut value, mut elems) = (None, None);
        if let Some(v) = inner.next() {
            if v.as_rule() == Rule::table_values {
                let vspan = self.span(&v);
                let mut out = Vec::new();
                self.table_values(v, &mut out)?;
                elems = Some((out, vspan));
            } else {
                value = Some(self.expr(v)?);
            }
        }
        Ok(Define {
            name,
            params,
            value,
            dims,
            elems,
            span,
        })
    }

    /// `lo..hi` or `n` (0..n-1).
    fn table_dim(&self, d: Pair<Rule>) -> PResult<(i64, i64)> {
        let span = self.span(&d);
        let ints: Vec<i64> = d
            .into_inner()
            .map(|i| {
                i.as_str()
                    .replace('−', "-")
                    .parse::<i64>()
                    .unwrap_or(i64::MAX)
            })
            .collect();
        let (lo, hi) = match ints[..] {
            [n] => (0, n.saturating_sub(1)),
            [lo, hi] => (lo, hi),
            _ => unreachable!("a dimension has one or two bounds"),
        };
        if hi < lo || hi - lo >= 1_000_000 || lo.abs() > 1_000_000_000 || hi.abs() > 1_000_000_000 {
            return Err(Box::new(ParseError::bad_table_dim(self.file, span)));
        }
        Ok((lo, hi))
    }

    pub(super) fn table_values(&self, v: Pair<Rule>, out: &mut Vec<Expr>) -> PResult<()> {
        for item in v.into_inner() {
            match item.as_rule() {
                Rule::table_values => self.table_values(item, out)?,
                // A number alone (see `table_value` in grammar/lsys.pest):
                // what its `expr` would have been.
                Rule::number => out.push(self.primary(item)?),
                _ => out.push(self.expr(item)?),
            }
        }
        Ok(())
    }

    fn header(&self, h: Pair<Rule>) -> PResult<Header> {
        let span = self.span(&h);
        let rule = h.as_rule();
        let mut inner = h.into_inner();
        // `endlsystem` is atomic and has no keyword child.
        let kw = inner.next();
        let keyword = kw.as_ref().map_or(span, |k| self.span(k));
        let kind = match rule {
            Rule::lsystem_h => {
                HeaderKind::Lsystem(inner.next().map_or("", |r| r.as_str()).trim().to_string())
            }
            Rule::dlength_h => HeaderKind::DerivationLength(self.expr(next(&mut inner))?),
            Rule::axiom_h => HeaderKind::Axiom(self.modules(next(&mut inner))?),
            Rule::ignore_h => HeaderKind::Ignore(self.pattern(inner)?),
            Rule::consider_h => HeaderKind::Consider(self.pattern(inner)?),
            Rule::seed_h => HeaderKind::Seed(self.expr(next(&mut inner))?),
            Rule::maxdepth_h => HeaderKind::MaximumDepth(self.expr(next(&mut inner))?),
            Rule::endlsystem_h => HeaderKind::Endlsystem,
            Rule::ring_h => HeaderKind::Ring,
            Rule::homomorphism_h => HeaderKind::Homomorphism,
            Rule::decomposition_h => HeaderKind::Decomposition,
            Rule::module_h => {
                // The keyword was the first child; the rest are declarations.
                let decls = kw
                    .into_iter()
                    .filter(|p| p.as_rule() == Rule::module_decl)
                    .chain(inner)
                    .map(|d| {
                        let span = self.span(&d);
                        let mut it = d.into_inner();
                        let name = self.ident(next(&mut it));
                        let params = it
                            .next()
                            .map(|ps| ps.into_inner().map(|i| self.ident(i)).collect())
                            .unwrap_or_default();
                        ModuleDecl { name, params, span }
                    })
                    .collect();
                HeaderKind::Module(decls)
            }
            Rule::block_h => {
                let kw = kw.map_or("", |k| k.as_str()).to_string();
                HeaderKind::Block(kw, self.block(next(&mut inner))?)
            }
            Rule::angle_h => HeaderKind::Angle(self.expr(next(&mut inner))?),
            Rule::step_h => HeaderKind::Step(self.expr(next(&mut inner))?),
            Rule::width_h => HeaderKind::Width(self.expr(next(&mut inner))?),
            Rule::environment_h => {
                let text = next(&mut inner);
                HeaderKind::Environment(text.as_str().to_string(), self.span(&text))
            }
            Rule::dialect_h => {
                let name = next(&mut inner);
                HeaderKind::Dialect(name.as_str().to_string(), self.span(&name))
            }
            Rule::colour_h => {
                let index = self.expr(next(&mut inner))?;
                let hex = next(&mut inner);
                HeaderKind::Colour(index, hex.as_str().to_string(), self.span(&hex))
            }
            Rule::texture_h => {
                let index = self.expr(next(&mut inner))?;
                let file = next(&mut inner);
                let name = file.as_str().trim_matches('"').to_string();
                HeaderKind::Texture(index, name, self.span(&file))
            }
            other => unreachable!("statement child {other:?} is not a header"),
        };
        Ok(Header {
            kind,
            keyword,
            span,
        })
    }

    fn production(&self, p: Pair<Rule>) -> PResult<Production> {
        let span = self.span(&p);
        let mut inner = p.into_inner();
        let head = next(&mut inner);
        let mut head_span = self.span(&head);
        // pest's span of `head` takes in the blanks before `:`/`-->`.
        head_span.end -= (head.as_str().len() - head.as_str().trim_end().len()) as u32;
        let (mut lctx, mut pred, mut rctx) = (Vec::new(), Vec::new(), Vec::new());
        for part in head.into_inner() {
            let rule = part.as_rule();
            let pats = self.pattern(part.into_inner())?;
            match rule {
                Rule::lctx => lctx = pats,
                Rule::pred => pred = pats,
                _ => rctx = pats,
            }
        }
        let form = next(&mut inner);
        let arrow_form = form.as_rule() == Rule::arrow_form;
        let (mut cond, mut arrow, mut succ, mut succ_span, mut prob) =
            (None, None, None, None, None);
        let (mut pre, mut post) = (None, None);
        for part in form.into_inner() {
            match part.as_rule() {
                Rule::condition => {
                    let c = next(&mut part.into_inner());
                    cond = Some(match c.as_rule() {
                        Rule::cond_else => Condition::Else(self.span(&c)),
                        Rule::cond_always => Condition::Always(self.span(&c)),
                        _ => Condition::Expr(self.expr(c)?),
                    });
                }
                Rule::paper_cond => {
                    let first = part.clone().into_inner().next();
                    cond = Some(match first {
                        Some(c) if c.as_rule() == Rule::cond_else => Condition::Else(self.span(&c)),
                        _ => Condition::Expr(self.paper_cond(part)?),
                    });
                }
                Rule::arrow => {
                    let at = self.span(&part);
                    self.dashes_before_arrow(at)?;
                    arrow = Some(at);
                }
                // A block before the condition (or the only block, with no
                // condition) runs first; one after the condition runs once
                // it holds.
                Rule::stmt_block => {
                    let b = self.block(next(&mut part.into_inner()))?;
                    if cond.is_none() && pre.is_none() {
                        pre = Some(b);
                    } else {
                        post = Some(b);
                    }
                }
                Rule::nl_indent => {}
                Rule::successor => {
                    succ_span = Some(self.span(&part));
                    succ = Some(self.modules(part)?);
                }
                Rule::probability => prob = Some(self.expr(next(&mut part.into_inner()))?),
                other => unreachable!("production child {other:?}"),
            }
        }
        debug_assert_eq!(arrow_form, arrow.is_some());
        let succ_span = succ_span.unwrap_or(Span::new(
            self.file_id,
            span.end as usize,
            span.end as usize,
        ));
        if !arrow_form {
            self.paper_form_slip(succ_span, cond.is_some())?;
        }
        Ok(Production {
            lctx,
            pred,
            rctx,
            cond,
            pre,
            post,
            arrow,
            succ: succ.unwrap_or_default(),
            succ_span,
            prob,
            head_span,
            span,
        })
    }

    /// In the arrowless form the successor starts where the condition
    /// stops, so a slip in the condition's words becomes modules: `Else C`
    /// (E l s e C), `x > 0 adn x < 3 B` (a d n x < 3 B), `x = 2 B`.
    fn paper_form_slip(&self, succ: Span, has_cond: bool) -> PResult<()> {
        let text = &self.file.text[succ.start as usize..succ.end as usize];
        let lead = text.len() - text.trim_start().len();
        let body = text.trim_start();
        let word_len = body
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(body.len());
        let word = &body[..word_len];
        let rest = body[word_len..].trim_start();
        let lower = word.to_ascii_lowercase();
        let compares = ["<", ">", "==", "!="].iter().any(|op| rest.contains(op));
        let (message, help) = if lower == "else" && word != "else" {
            (
                format!("`{word}` reads as modules of the successor"),
                "the arrowless form's `else` is written in lower case: `A(x) : else C`".to_string(),
            )
        } else if has_cond
            && compares
            && ["and", "or"].iter().any(|k| {
                lower != *k && strsim::damerau_levenshtein(&lower, k) <= 1
                    || lower == *k && word != *k
            })
        {
            let meant = if strsim::damerau_levenshtein(&lower, "and") <= 1 {
                "and"
            } else {
                "or"
            };
            (
                format!("`{word}` reads as modules of the successor, not as `{meant}`"),
                format!("did you mean `{meant}`? in the arrowless form the condition ends at the first word that does not continue it, and the rest is the successor"),
            )
        } else if word_len > 0 && rest.starts_with('=') && !rest.starts_with("==") {
            (
                format!("`{word} =` reads as modules of the successor"),
                format!("`=` is not a comparison: write `{word} == ...` (e.g. `A(x) : x == 2 B`)"),
            )
        } else {
            return Ok(());
        };
        let from = succ.start as usize + lead;
        Err(Box::new(ParseError::Syntax {
            message,
            src: self.file.named_source(),
            span: Span::new(self.file_id, from, from + word_len.max(1)).into(),
            label: "here".to_string(),
            help: Some(help),
            offset: from,
        }))
    }

    /// `A ---> B` parses as the predecessor `A -` and the arrow `-->`:
    /// dashes right before an arrow are a mistyped arrow.
    fn dashes_before_arrow(&self, arrow: Span) -> PResult<()> {
        let text = &self.file.text;
        let start = arrow.start as usize;
        let dashes = text[..start].len() - text[..start].trim_end_matches('-').len();
        if dashes == 0 || !text[start..].starts_with('-') {
            return Ok(());
        }
        let from = start - dashes;
        Err(Box::new(ParseError::Syntax {
            message: format!("`{}` is not an arrow", &text[from..arrow.end as usize]),
            src: self.file.named_source(),
            span: Span::new(self.file_id, from, arrow.end as usize).into(),
            label: "not an arrow".to_string(),
            help: Some(
                "the arrow of a production is `-->` (or `->`): remove the extra dashes".to_string(),
            ),
            offset: from,
        }))
    }

    fn pattern<'i>(&self, items: impl Iterator<Item = Pair<'i, Rule>>) -> PResult<Vec<PatTok>> {
        items
            .filter(|it| it.as_rule() != Rule::nl_indent)
            .map(|it| {
                Ok(match it.as_rule() {
                    Rule::open_br => PatTok::Open(self.span(&it)),
                    Rule::close_br => PatTok::Close(self.span(&it)),
                    _ => PatTok::Module(self.module(it)?),
                })
            })
            .collect()
    }

    pub(super) fn modules(&self, seq: Pair<Rule>) -> PResult<Vec<ModuleTok>> {
        seq.into_inner()
            .filter(|m| m.as_rule() != Rule::cont)
            .map(|m| self.module(m))
            .collect()
    }

    fn module(&self, m: Pair<Rule>) -> PResult<ModuleTok> {
        let span = self.span(&m);
        let mut inner = m.into_inner();
        let sym = next(&mut inner);
        let name_span = self.span(&sym);
        let raw = sym.as_str();
        let first = raw.chars().next().expect("symbols are non-empty");
        let (kind, text) = match first {
            '@' => (TokKind::At, raw.to_string()),
            '?' => (TokKind::Query, raw.to_string()),
            '~' | '∼' if raw.chars().count() > 1 => {
                (TokKind::Tilde, format!("~{}", &raw[first.len_utf8()..]))
            }
            c if c.is_alphanumeric() || c == '_' => (TokKind::Word, raw.to_string()),
            c => (TokKind::Punct, canonical_punct(c).to_string()),
        };
        let args = inner
            .next()
            .map(|a| a.into_inner().map(|e| self.arg(e)).collect())
            .transpose()?;
        Ok(ModuleTok {
            text,
            kind,
            name_span,
            args,
            span,
        })
    }
}

/// Typographic characters from the paper's PDF stand for ASCII commands.
fn canonical_punct(c: char) -> char {
    match c {
        '−' => '-',
        '∧' => '^',
        '∼' => '~',
        c => c,
    }
}

pub(crate) fn next<'i>(it: &mut impl Iterator<Item = Pair<'i, Rule>>) -> Pair<'i, Rule> {
    it.next().expect("the grammar guarantees this child")
}
