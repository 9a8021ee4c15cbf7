//! Modules: raw module tokens of the AST -> symbols of the alphabet, with
//! parameter counts checked against predecessors, `module` declarations
//! and the turtle table.

use super::alphabet::Piece;
use super::error::ResolveError;
use super::expr::{suggest, Scope};
use super::ir::*;
use super::Resolver;
use crate::lang as turtle;
use crate::parse::ast::{self, HeaderKind, Item, ModuleTok, PatTok, TokKind};
use crate::source::Span;

/// A module token split into one module, with its arguments (only the last
/// piece of a run carries the run's argument list).
pub(super) struct Split<'a> {
    pub name: String,
    pub span: Span,
    pub args: Option<&'a [ast::Expr]>,
}

impl Resolver {
    /// Collects the names the grammar defines: predecessors (whole words as
    /// written), `module` declarations and `#include` components.
    pub(super) fn build_alphabet(&mut self, items: &[(u32, Item)]) {
        self.alphabet = super::alphabet::grammar_alphabet(items, self.profile.cpfg_names);
        // The predecessors' names, in file order, become the first symbols.
        let mut preds: Vec<(String, Span)> = Vec::new();
        for (_, item) in items {
            let Item::Production(p) = item else { continue };
            for t in &p.pred {
                let PatTok::Module(m) = t else { continue };
                if self.profile.cpfg_names && m.kind == TokKind::Word {
                    // cpfg's names are single characters.
                    preds.extend(m.text.chars().map(|c| (c.to_string(), m.span)));
                } else {
                    preds.push((m.text.clone(), m.span));
                }
            }
        }
        // Brackets first, so that their ids are the fixed OPEN/CLOSE.
        self.intern("[", None);
        self.intern("]", None);
        for (name, span) in preds {
            self.intern(&name, Some(span));
        }
    }

    /// The id of `name`, creating the symbol on first sight.
    pub(super) fn intern(&mut self, name: &str, span: Option<Span>) -> SymId {
        if let Some(id) = self.symbols.get(name) {
            return id;
        }
        let kind = if turtle::lookup(name).is_some() {
            SymbolKind::Turtle
        } else if name.starts_with('~') {
            SymbolKind::Component
        } else if name.starts_with('?') {
            SymbolKind::Query
        } else if self.alphabet.contains_word(name) {
            SymbolKind::User
        } else {
            SymbolKind::Inert
        };
        let id = self.symbols.list.len() as SymId;
        self.symbols.list.push(Symbol {
            name: name.to_string(),
            kind,
            span,
        });
        self.symbols.by_name.insert(name.to_string(), id);
        id
    }

    /// Splits a token into modules by longest match. Reports pieces that
    /// match nothing in a grammar that uses multi-character names.
    pub(super) fn split<'a>(&mut self, tok: &'a ModuleTok) -> Vec<Split<'a>> {
        let pieces: Vec<Piece> = if tok.kind == TokKind::At {
            let p = self.alphabet.split(&tok.text, tok.kind);
            if p[0].fallback {
                if self.profile.cpfg_names {
                    // cpfg has more `@` commands than the turtle draws
                    // (textures, contours, ...): keep it, drawing nothing.
                    self.unknown_turtle_warning(tok);
                    return vec![Split {
                        name: tok.text.clone(),
                        span: tok.span,
                        args: tok.args.as_deref(),
                    }];
                }
                self.unknown_turtle(tok);
            }
            p
        } else {
            if tok.kind == TokKind::Tilde && self.unknown_component(tok) {
                return Vec::new();
            }
            self.alphabet.split(&tok.text, tok.kind)
        };
        let n = pieces.len();
        let base = tok.name_span.start as usize;
        let multi = tok.text.chars().count() > 1;
        let mut out = Vec::with_capacity(n);
        for (i, p) in pieces.into_iter().enumerate() {
            let last = i + 1 == n;
            let end = if last {
                tok.span.end as usize
            } else {
                base + p.end
            };
            let span = Span::new(tok.span.file, base + p.start, end);
            if p.fallback && multi && self.alphabet.multi_char && tok.kind == TokKind::Word {
                self.unknown_module(tok);
                return Vec::new();
            }
            out.push(Split {
                name: p.name,
                span,
                args: if last { tok.args.as_deref() } else { None },
            });
        }
        out
    }

    fn unknown_turtle(&mut self, tok: &ModuleTok) {
        let ats: Vec<&str> = turtle::all()
            .map(|c| c.symbol)
            .filter(|s| s.starts_with('@'))
            .collect();
        self.error(ResolveError::UnknownModule {
            name: tok.text.clone(),
            src: self.sources.named_source(tok.name_span),
            span: tok.name_span.into(),
            help: format!("the turtle's `@` commands are {}", ats.join(" ")),
        });
    }

    /// `~MPX` where only `MP` and `MPB` are declared: longest match would
    /// place `~MP` and a module `X`, silently. Reported instead; `true`
    /// when it was.
    fn unknown_component(&mut self, tok: &ModuleTok) -> bool {
        let name = tok.text.trim_start_matches(['~', '∼']);
        let Some(prefix) = self.alphabet.component_prefix(name) else {
            return false;
        };
        let declared = self.alphabet.components();
        let near = suggest(name, declared.iter().copied().filter(|c| *c != prefix))
            .map(|c| format!("did you mean `~{c}`? "))
            .unwrap_or_default();
        let rest = &name[prefix.len()..];
        let args = self
            .sources
            .slice(Span::new(
                tok.span.file,
                tok.name_span.end as usize,
                tok.span.end as usize,
            ))
            .to_string();
        let help = format!(
            "{near}the grammar declares {} (`#include {}`); to place `~{prefix}` followed by the module `{rest}`, write them apart: `~{prefix} {rest}{args}`",
            declared.iter().map(|c| format!("`~{c}`")).collect::<Vec<_>>().join(", "),
            declared.join(", "),
        );
        self.error(ResolveError::UnknownComponent {
            name: name.to_string(),
            src: self.sources.named_source(tok.name_span),
            span: tok.name_span.into(),
            help,
        });
        true
    }

    /// A production parameter named like a `#define` hides it inside the
    /// production (the divergence angle `d` becomes the parameter `d`).
    fn param_hides_define(&mut self, name: &str, span: Span) {
        let Some(d) = self.defines.get(name) else {
            return;
        };
        if d.params.is_some() || d.dims.is_some() || !self.warned_at.insert(format!("param {name}"))
        {
            return;
        }
        let define = d.span;
        self.warn(ResolveError::ParamHidesDefine {
            name: name.to_string(),
            src: self.sources.named_source(span),
            span: span.into(),
            define: (define.file == span.file).then(|| define.into()),
        });
    }

    /// A word that is the name of a `#define` written as a module: it is
    /// read as modules (`LEAF` as `L E A F`), not as the define's value.
    fn define_as_module(&mut self, tok: &ModuleTok, pieces: &[Split<'_>]) {
        if tok.kind != TokKind::Word || tok.args.is_some() {
            return;
        }
        let Some(d) = self.defines.get(&tok.text) else {
            return;
        };
        if d.params.is_some()
            || d.dims.is_some()
            || !self.warned_at.insert(format!("define {}", tok.text))
        {
            return;
        }
        let define = d.span;
        let modules: Vec<&str> = pieces.iter().map(|s| s.name.as_str()).collect();
        self.warn(ResolveError::DefineAsModule {
            name: tok.text.clone(),
            modules: modules.join(" "),
            src: self.sources.named_source(tok.name_span),
            span: tok.name_span.into(),
            define: (define.file == tok.span.file).then(|| define.into()),
        });
    }

    fn unknown_turtle_warning(&mut self, tok: &ModuleTok) {
        if !self.warned_at.insert(tok.text.clone()) {
            return;
        }
        self.warn(ResolveError::IgnoredCommand {
            name: tok.text.clone(),
            src: self.sources.named_source(tok.name_span),
            span: tok.name_span.into(),
        });
    }

    fn unknown_module(&mut self, tok: &ModuleTok) {
        let words: Vec<String> = self.alphabet.words().map(str::to_string).collect();
        let mut help = suggest(&tok.text, words.iter().map(String::as_str))
            .map(|s| format!("did you mean `{s}`? "))
            .unwrap_or_default();
        help.push_str(&format!(
            "this grammar uses multi-letter names, so `{0}` must be one: give it a production, or declare it with `module {0}`; to mean single-letter modules, separate them with spaces",
            tok.text
        ));
        self.error(ResolveError::UnknownModule {
            name: tok.text.clone(),
            src: self.sources.named_source(tok.name_span),
            span: tok.name_span.into(),
            help,
        });
    }

    /// Lowers successor (or axiom) tokens to modules. `*` alone erases.
    pub(super) fn successor(&mut self, toks: &[ModuleTok], scope: &Scope) -> Vec<SuccModule> {
        if let [only] = toks {
            if only.kind == TokKind::Punct && only.text == "*" && only.args.is_none() {
                return Vec::new();
            }
        }
        let mut out = Vec::new();
        for tok in toks {
            if tok.kind == TokKind::Punct && tok.text == "*" {
                self.error(ResolveError::Misplaced {
                    what: "`*` inside a successor".to_string(),
                    src: self.sources.named_source(tok.span),
                    span: tok.span.into(),
                    help: "a successor that is just `*` erases the predecessor; inside a longer successor `*` means nothing, so remove it".to_string(),
                });
                continue;
            }
            let pieces = self.split(tok);
            self.define_as_module(tok, &pieces);
            for s in pieces {
                let sym = self.intern(&s.name, Some(s.span));
                let args = s.args.unwrap_or(&[]);
                self.check_arity(sym, args.len(), s.span);
                let mut args: thin_vec::ThinVec<_> = args
                    .iter()
                    .filter_map(|a| match &a.kind {
                        ast::ExprKind::Str(s) => Some(self.string_param(s, a.span)),
                        _ => self.expr(a, scope),
                    })
                    .collect();
                // Collecting grows by doubling from 4.
                args.shrink_to_fit();
                out.push(SuccModule {
                    sym,
                    args,
                    span: s.span,
                });
            }
        }
        out
    }

    /// Checks a use of `sym` with `n` parameters.
    pub(super) fn check_arity(&mut self, sym: SymId, n: usize, span: Span) {
        let symbol = &self.symbols.list[sym as usize];
        let name = symbol.name.clone();
        match symbol.kind {
            SymbolKind::Turtle => {
                let c = turtle::lookup(&name).expect("turtle symbols are in the table");
                // A turtle command with productions of its own (`F(x) --> ...`)
                // may carry whatever its productions expect.
                let declared = self
                    .arities
                    .get(&sym)
                    .is_some_and(|a| a.counts.contains(&n));
                // cpfg reads the parameters a command knows and ignores
                // the rest (`+(20,0)`).
                let too_many = n > c.max_args as usize && !self.profile.cpfg_names;
                if !declared && (n < c.min_args as usize || too_many) {
                    let expected = range_text(c.min_args as usize, c.max_args as usize);
                    self.error(ResolveError::Arity {
                        name: name.clone(),
                        expected,
                        found: params_text(n),
                        src: self.sources.named_source(span),
                        span: span.into(),
                        decl: None,
                        help: format!("`{name}` is the turtle command: {}", c.doc),
                    });
                }
            }
            SymbolKind::Component if n == 2 || n > 3 => {
                self.error(ResolveError::Arity {
                    name: name.clone(),
                    expected: "0, 1 or 3 parameters".to_string(),
                    found: params_text(n),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    decl: None,
                    help: format!("place a component with `{name}`, `{name}(s)` (uniform scale) or `{name}(sx,sy,sz)`"),
                });
            }
            SymbolKind::User => {
                let Some(info) = self.arities.get(&sym).cloned() else {
                    return;
                };
                if info.counts.contains(&n) {
                    return;
                }
                let forms: Vec<String> = info
                    .names
                    .iter()
                    .map(|ps| {
                        if ps.is_empty() {
                            name.clone()
                        } else {
                            format!("{name}({})", ps.join(","))
                        }
                    })
                    .collect();
                let expected = match info.counts.as_slice() {
                    [one] => params_text(*one),
                    _ => format!("{} parameters", join_or(&info.counts)),
                };
                let decl = info.decl.filter(|d| d.file == span.file);
                self.error(ResolveError::Arity {
                    name: name.clone(),
                    expected,
                    found: params_text(n),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    decl: decl.map(Into::into),
                    help: format!(
                        "its productions match {}; a module with another number of parameters would never be rewritten. Write the parameters, e.g. `{}`",
                        forms.join(" or "),
                        forms[0]
                    ),
                });
            }
            _ => {}
        }
    }

    /// Lowers predecessor/context tokens to pattern modules, binding their
    /// parameter names to consecutive slots in `params`.
    pub(super) fn pattern(
        &mut self,
        toks: &[PatTok],
        allow_brackets: bool,
        params: &mut Vec<(String, u16)>,
        param_spans: &mut Vec<Span>,
        whole_words: bool,
    ) -> Vec<PatItem> {
        let mut out = Vec::new();
        for t in toks {
            match t {
                PatTok::Open(s) | PatTok::Close(s) if !allow_brackets => {
                    self.error(ResolveError::Unsupported {
                        what: "a bracket here".to_string(),
                        src: self.sources.named_source(*s),
                        span: (*s).into(),
                        help: "brackets may appear only in a right context (`A > [B]C`); a left context already skips branches and climbs out of its own".to_string(),
                    });
                }
                PatTok::Open(s) => out.push(PatItem::Open(*s)),
                PatTok::Close(s) => out.push(PatItem::Close(*s)),
                PatTok::Module(m) => {
                    // cpfg: `*` as a context means "no context" (`* < F > Y`).
                    if m.kind == TokKind::Punct && m.text == "*" && !whole_words && m.args.is_none()
                    {
                        continue;
                    }
                    // cpfg: `=` in a right context skips the rest of the
                    // branch (`F > [+D=]`), which the `]` after it does here.
                    if self.profile.cpfg_names
                        && allow_brackets
                        && m.kind == TokKind::Punct
                        && m.text == "="
                    {
                        continue;
                    }
                    if m.kind == TokKind::Punct && m.text == "*" {
                        self.error(ResolveError::Unsupported {
                            what: "`*` in a predecessor".to_string(),
                            src: self.sources.named_source(m.span),
                            span: m.span.into(),
                            help: "`*` alone stands for an empty context (`* < A > B`); a predecessor must name its modules".to_string(),
                        });
                        continue;
                    }
                    let pieces =
                        if whole_words && m.kind == TokKind::Word && !self.profile.cpfg_names {
                            vec![Split {
                                name: m.text.clone(),
                                span: m.span,
                                args: m.args.as_deref(),
                            }]
                        } else {
                            self.split(m)
                        };
                    for s in pieces {
                        let sym = self.intern(&s.name, Some(s.span));
                        let first = params.len() as u16;
                        let args = s.args.unwrap_or(&[]);
                        for a in args {
                            let ast::ExprKind::Name(n) = &a.kind else {
                                self.error(ResolveError::PatternParam {
                                    src: self.sources.named_source(a.span),
                                    span: a.span.into(),
                                });
                                continue;
                            };
                            if let Some(i) = params.iter().position(|(p, _)| p == n) {
                                self.error(ResolveError::DuplicateParam {
                                    name: n.clone(),
                                    src: self.sources.named_source(a.span),
                                    span: a.span.into(),
                                    first: param_spans[i].into(),
                                });
                                continue;
                            }
                            self.param_hides_define(n, a.span);
                            params.push((n.clone(), params.len() as u16));
                            param_spans.push(a.span);
                        }
                        out.push(PatItem::Module(PatModule {
                            sym,
                            arity: args.len().min(255) as u8,
                            first_param: first,
                            span: s.span,
                        }));
                    }
                }
            }
        }
        out
    }

    /// Records the parameter counts predecessors and `module` declarations
    /// give each user symbol, before any successor is checked.
    pub(super) fn record_arities(&mut self, items: &[(u32, Item)]) {
        for (_, item) in items {
            match item {
                Item::Production(p) => {
                    for t in &p.pred {
                        if let PatTok::Module(m) = t {
                            let names: Vec<String> = m
                                .args
                                .iter()
                                .flatten()
                                .map(|a| match &a.kind {
                                    ast::ExprKind::Name(n) => n.clone(),
                                    _ => "_".to_string(),
                                })
                                .collect();
                            self.add_arity(&m.text, names, m.span);
                        }
                    }
                }
                Item::Header(h) => {
                    if let HeaderKind::Module(ds) = &h.kind {
                        for d in ds {
                            let names = d.params.iter().map(|p| p.name.clone()).collect();
                            self.add_arity(&d.name.name, names, d.span);
                        }
                    }
                }
                _ => {}
            }
        }
    }

    fn add_arity(&mut self, name: &str, names: Vec<String>, span: Span) {
        let sym = self.intern(name, Some(span));
        let info = self.arities.entry(sym).or_default();
        if !info.counts.contains(&names.len()) {
            info.counts.push(names.len());
            info.names.push(names);
        }
        info.decl.get_or_insert(span);
    }
}

fn params_text(n: usize) -> String {
    match n {
        0 => "no parameters".to_string(),
        1 => "1 parameter".to_string(),
        n => format!("{n} parameters"),
    }
}

fn range_text(lo: usize, hi: usize) -> String {
    if lo == hi {
        params_text(lo)
    } else if lo == 0 && hi == 1 {
        "at most 1 parameter".to_string()
    } else {
        format!("{lo} to {hi} parameters")
    }
}

fn join_or(v: &[usize]) -> String {
    let s: Vec<String> = v.iter().map(usize::to_string).collect();
    match s.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => s.join(""),
    }
}
