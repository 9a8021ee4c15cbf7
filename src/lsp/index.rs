//! The editor's index of a loaded model. Input: every file's statements
//! in include order ([`crate::load::Loaded`]'s items) and the `#include`
//! links; output: an [`Index`] of every named occurrence (modules, turtle
//! commands, components, defines, parameters, includes) with its span,
//! whether it defines the name, and its scope. Module runs (`FF`, `AB`)
//! are split as resolve splits them, with resolve's own alphabet.
//!
//! The index is built from the syntax, so it exists even when the grammar
//! does not compile: navigation keeps working while the user types.

use std::collections::{HashMap, HashSet};

use crate::lang;
use crate::lang::Profile;
use crate::parse::ast::{
    self, CStmt, Condition, Expr, ExprKind, HeaderKind, Item, ModuleTok, PatTok, TokKind,
};
use crate::resolve::alphabet::Alphabet;
use crate::source::{FileId, Span};

/// What a name is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    /// A module of the grammar (a predecessor or a `module` declaration).
    Module,
    /// A turtle command (`F`, `+`, `@O`); may have productions too.
    Turtle,
    /// A query module (`?P`).
    Query,
    /// A component (`~MP`), without the `~`.
    Component,
    Define,
    Param,
    /// The path of an `#include` line.
    Include,
}

impl Kind {
    /// Modules and turtle commands share one namespace (`F` may be both).
    fn class(self) -> Kind {
        match self {
            Kind::Turtle => Kind::Module,
            k => k,
        }
    }
}

/// One named occurrence.
#[derive(Clone, Debug)]
pub struct Occ {
    pub span: Span,
    pub kind: Kind,
    pub name: String,
    /// A defining occurrence: a predecessor, a `module` declaration, a
    /// `#define`, a formal parameter, a declared component.
    pub def: bool,
    /// Parameters: the statement they belong to (its index in the items);
    /// 0 for everything else.
    pub scope: u32,
    /// Includes: the file loaded.
    pub target: Option<FileId>,
    /// A `#define`'s whole statement, a predecessor's production.
    pub stmt: Option<Span>,
}

/// Every occurrence of a model, sorted by file and position.
#[derive(Default)]
pub struct Index {
    pub occs: Vec<Occ>,
}

impl Index {
    /// Indexes `items` (from every file) and the loaded `includes`.
    pub fn build(
        items: &[(FileId, Item)],
        includes: &[(Span, FileId)],
        profile: &Profile,
    ) -> Index {
        let mut b = Builder {
            alphabet: Alphabet::new(),
            defines: HashSet::new(),
            cpfg_names: profile.cpfg_names,
            occs: Vec::new(),
        };
        b.alphabet_and_defines(items);
        for (n, (_, item)) in items.iter().enumerate() {
            b.item(n as u32 + 1, item);
        }
        for &(span, target) in includes {
            b.occs.push(Occ {
                span,
                kind: Kind::Include,
                name: String::new(),
                def: false,
                scope: 0,
                target: Some(target),
                stmt: None,
            });
        }
        let mut occs = b.occs;
        occs.sort_by_key(|o| (o.span.file, o.span.start, o.span.end));
        Index { occs }
    }

    /// The innermost occurrence at byte `offset` of `file` (a cursor just
    /// after a name still counts).
    pub fn at(&self, file: FileId, offset: u32) -> Option<&Occ> {
        self.occs
            .iter()
            .filter(|o| o.span.file == file && o.span.start <= offset && offset <= o.span.end)
            // On a character rather than just after a name; then innermost.
            .min_by_key(|o| (offset >= o.span.end, o.span.len()))
    }

    /// Every occurrence of the same name as `occ` (same parameter scope).
    pub fn references<'a>(&'a self, occ: &'a Occ) -> impl Iterator<Item = &'a Occ> + 'a {
        self.occs.iter().filter(move |o| same(o, occ))
    }

    /// The defining occurrences of `occ`'s name.
    pub fn definitions<'a>(&'a self, occ: &'a Occ) -> impl Iterator<Item = &'a Occ> + 'a {
        self.references(occ).filter(|o| o.def)
    }

    /// The defining occurrences of every name of `kind`, by name, each
    /// name once (first definition).
    pub fn defined(&self, kind: Kind) -> Vec<&Occ> {
        let mut seen = HashSet::new();
        self.occs
            .iter()
            .filter(|o| o.def && o.kind.class() == kind.class() && seen.insert((o.kind, &o.name)))
            .collect()
    }
}

fn same(a: &Occ, b: &Occ) -> bool {
    a.kind != Kind::Include
        && a.kind.class() == b.kind.class()
        && a.name == b.name
        && a.scope == b.scope
}

struct Builder {
    alphabet: Alphabet,
    defines: HashSet<String>,
    cpfg_names: bool,
    occs: Vec<Occ>,
}

impl Builder {
    /// The names the grammar defines, as resolve builds its alphabet, and
    /// every `#define` name (a use may come first).
    fn alphabet_and_defines(&mut self, items: &[(FileId, Item)]) {
        self.alphabet = crate::resolve::alphabet::grammar_alphabet(items, self.cpfg_names);
        for (_, item) in items {
            if let Item::Define(ds) = item {
                for d in ds {
                    self.defines.insert(d.name.name.clone());
                }
            }
        }
    }

    fn push(&mut self, span: Span, kind: Kind, name: &str, def: bool, scope: u32) {
        self.occs.push(Occ {
            span,
            kind,
            name: name.to_string(),
            def,
            scope,
            target: None,
            stmt: None,
        });
    }

    fn item(&mut self, scope: u32, item: &Item) {
        match item {
            Item::Define(ds) => {
                for d in ds {
                    let params: Vec<String> = d
                        .params
                        .iter()
                        .flatten()
                        .map(|p| {
                            self.push(p.span, Kind::Param, &p.name, true, scope);
                            p.name.clone()
                        })
                        .collect();
                    self.push(d.name.span, Kind::Define, &d.name.name, true, 0);
                    self.occs.last_mut().expect("pushed").stmt = Some(d.span);
                    for e in d.value.iter().chain(d.elems.iter().flat_map(|(es, _)| es)) {
                        self.expr(e, &params, scope);
                    }
                }
            }
            Item::Include(ast::Include::Components(cs)) => {
                for c in cs {
                    self.push(c.span, Kind::Component, &c.name, true, 0);
                }
            }
            Item::Include(_) | Item::OtherDirective { .. } => {}
            Item::Header(h) => self.header(scope, &h.kind),
            Item::Production(p) => {
                let mut params = Vec::new();
                for t in p.lctx.iter().chain(&p.pred).chain(&p.rctx) {
                    if let PatTok::Module(m) = t {
                        for a in m.args.iter().flatten() {
                            if let ExprKind::Name(n) = &a.kind {
                                self.push(a.span, Kind::Param, n, true, scope);
                                params.push(n.clone());
                            }
                        }
                    }
                }
                for t in &p.lctx {
                    self.pattern(t, false);
                }
                for t in &p.pred {
                    let first = self.occs.len();
                    self.pattern(t, true);
                    for o in &mut self.occs[first..] {
                        o.stmt = Some(p.span);
                    }
                }
                for t in &p.rctx {
                    self.pattern(t, false);
                }
                if let Some(Condition::Expr(e)) = &p.cond {
                    self.expr(e, &params, scope);
                }
                for b in p.pre.iter().chain(&p.post) {
                    self.stmts(&b.stmts, &params, scope);
                }
                for m in &p.succ {
                    self.module(m, false, &params, scope);
                }
                if let Some(e) = &p.prob {
                    self.expr(e, &params, scope);
                }
            }
        }
    }

    fn header(&mut self, scope: u32, h: &HeaderKind) {
        match h {
            HeaderKind::Axiom(ms) => {
                for m in ms {
                    self.module(m, false, &[], 0);
                }
            }
            HeaderKind::Ignore(ps) | HeaderKind::Consider(ps) => {
                for p in ps {
                    self.pattern(p, false);
                }
            }
            HeaderKind::DerivationLength(e)
            | HeaderKind::Seed(e)
            | HeaderKind::MaximumDepth(e)
            | HeaderKind::Angle(e)
            | HeaderKind::Step(e)
            | HeaderKind::Width(e)
            | HeaderKind::Colour(e, ..)
            | HeaderKind::Texture(e, ..) => self.expr(e, &[], 0),
            HeaderKind::Module(ds) => {
                for d in ds {
                    self.push(d.name.span, Kind::Module, &d.name.name, true, 0);
                    for p in &d.params {
                        self.push(p.span, Kind::Param, &p.name, true, scope);
                    }
                }
            }
            HeaderKind::Block(_, b) => self.stmts(&b.stmts, &[], 0),
            // An axiom line of over 1 MiB is not indexed: an occurrence a
            // module would take more memory than the model (issue 36), so
            // go-to, references and rename do not see its modules.
            HeaderKind::LongAxiom(_) => {}
            _ => {}
        }
    }

    fn pattern(&mut self, t: &PatTok, def: bool) {
        if let PatTok::Module(m) = t {
            self.names(m, def);
        }
    }

    fn module(&mut self, m: &ModuleTok, def: bool, params: &[String], scope: u32) {
        self.names(m, def);
        for a in m.args.iter().flatten() {
            self.expr(a, params, scope);
        }
    }

    /// The module names of one run, split as resolve splits it.
    fn names(&mut self, m: &ModuleTok, def: bool) {
        let base = m.name_span.start as usize;
        let file = m.name_span.file;
        let pieces: Vec<(String, usize, usize)> = if self.cpfg_names && m.kind == TokKind::Word {
            m.text
                .char_indices()
                .map(|(i, c)| (c.to_string(), i, i + c.len_utf8()))
                .collect()
        } else {
            self.alphabet
                .split(&m.text, m.kind)
                .into_iter()
                .map(|p| (p.name, p.start, p.end))
                .collect()
        };
        for (name, start, end) in pieces {
            let span = Span::new(file, base + start, base + end);
            if let Some(c) = name.strip_prefix('~') {
                let span = Span::new(file, base + start + 1, base + end);
                self.push(span, Kind::Component, c, false, 0);
            } else if name.starts_with('?') {
                self.push(span, Kind::Query, &name, false, 0);
            } else if lang::lookup(&name).is_some() {
                self.push(span, Kind::Turtle, &name, def, 0);
            } else {
                self.push(span, Kind::Module, &name, def, 0);
            }
        }
    }

    fn expr(&mut self, e: &Expr, params: &[String], scope: u32) {
        match &e.kind {
            ExprKind::Name(n) => {
                if params.contains(n) {
                    self.push(e.span, Kind::Param, n, false, scope);
                } else if self.defines.contains(n) {
                    self.push(e.span, Kind::Define, n, false, 0);
                }
            }
            ExprKind::Num(_) | ExprKind::Str(_) => {}
            ExprKind::Unary(_, a) => self.expr(a, params, scope),
            ExprKind::Binary(_, a, b) => {
                self.expr(a, params, scope);
                self.expr(b, params, scope);
            }
            ExprKind::Ternary(a, b, c) => {
                self.expr(a, params, scope);
                self.expr(b, params, scope);
                self.expr(c, params, scope);
            }
            ExprKind::Call(id, args) | ExprKind::Index(id, args) => {
                if self.defines.contains(&id.name) {
                    self.push(id.span, Kind::Define, &id.name, false, 0);
                }
                for a in args {
                    self.expr(a, params, scope);
                }
            }
        }
    }

    fn stmts(&mut self, stmts: &[CStmt], params: &[String], scope: u32) {
        for s in stmts {
            match s {
                CStmt::Assign { target, value, .. } => {
                    for e in target.index.iter().chain(std::iter::once(value)) {
                        self.expr(e, params, scope);
                    }
                }
                CStmt::Expr(e) => self.expr(e, params, scope),
                CStmt::If {
                    cond, then, els, ..
                } => {
                    self.expr(cond, params, scope);
                    self.stmts(then, params, scope);
                    self.stmts(els, params, scope);
                }
                CStmt::While { cond, body, .. } | CStmt::DoWhile { body, cond, .. } => {
                    self.expr(cond, params, scope);
                    self.stmts(body, params, scope);
                }
                CStmt::Array(ds) => {
                    for d in ds {
                        for e in d.dims.iter().chain(d.init.iter().flatten()) {
                            self.expr(e, params, scope);
                        }
                    }
                }
            }
        }
    }
}

/// The parameter names of every formal module of a predecessor, by module
/// name (for hovers): `A(x, y)` gives `("A", ["x", "y"])`.
pub fn formal_params(p: &ast::Production) -> Vec<(String, Vec<String>)> {
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    for t in &p.pred {
        if let PatTok::Module(m) = t {
            let names = m
                .args
                .iter()
                .flatten()
                .map(|a| match &a.kind {
                    ExprKind::Name(n) => n.clone(),
                    _ => a.to_string(),
                })
                .collect();
            out.push((m.text.clone(), names));
        }
    }
    out
}

/// Module names and the arities they are written with in predecessors and
/// `module` declarations (for completion snippets): name -> parameter names.
pub fn arities(items: &[(FileId, Item)]) -> HashMap<String, Vec<String>> {
    let mut out = HashMap::new();
    for (_, item) in items {
        match item {
            Item::Production(p) => {
                for (name, params) in formal_params(p) {
                    out.entry(name).or_insert(params);
                }
            }
            Item::Header(h) => {
                if let HeaderKind::Module(ds) = &h.kind {
                    for d in ds {
                        out.entry(d.name.name.clone())
                            .or_insert_with(|| d.params.iter().map(|p| p.name.clone()).collect());
                    }
                }
            }
            _ => {}
        }
    }
    out
}
