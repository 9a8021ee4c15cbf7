//! Expressions: AST expressions -> IR expressions. Names bind, innermost
//! first, to a function-like define's arguments, the production's
//! parameters, then `#define`s, whose values are inlined at the use site
//! (C macro semantics: `#define h sqrt(p*q)` sees the `p` and `q` of the
//! production that uses `h`).

use std::collections::HashMap;
use std::sync::Arc;

use miette::Report;

use super::error::ResolveError;
use super::ir::{Expr, ExprKind, Func, RandFn, UnOp};
use super::Resolver;
use crate::parse::ast;

/// What names mean where an expression stands.
pub(super) struct Scope<'a> {
    /// Parameter names of the production, with their binding slots.
    pub params: &'a [(String, u16)],
    /// The production's own variables (cpfg statement blocks), with their
    /// slots; they shadow parameters of the same name.
    pub locals: &'a [(String, u32)],
    /// Position in the flattened statement list, for "used before its
    /// #define".
    pub order: usize,
}

impl Scope<'_> {
    pub const EMPTY: Scope<'static> = Scope {
        params: &[],
        locals: &[],
        order: usize::MAX,
    };
}

/// Expansions of defines without arguments already made: a define's
/// expansion depends only on the names in scope where it is used (the
/// production's parameters and variables, and cpfg's globals and arrays,
/// counted here), so within a production each define is resolved once
/// however often it is used (a Pailou's defines use each other thousands
/// of times). Only expansions that succeeded without a diagnostic are
/// kept; a failing one runs again and reports again, as before.
#[derive(Default)]
pub(crate) struct Expansions {
    made: HashMap<String, Vec<Made>>,
}

/// One expansion and the scope it was made in.
struct Made {
    params: Vec<(String, u16)>,
    locals: Vec<(String, u32)>,
    declared: (usize, usize),
    expr: Expr,
}

/// Expansion state: defines being expanded (for cycles) and the arguments
/// of the function-like define being expanded.
#[derive(Default, Clone)]
pub(super) struct Expansion {
    stack: Option<std::rc::Rc<Frame>>,
    args: HashMap<String, Expr>,
}

/// One define being expanded, and the one whose expansion named it. A
/// list shared between levels, not a `Vec` copied at each: a chain of
/// 10,000 defines each naming the previous one held 50 million names
/// (2 GB) in copies of the stack (issue 36).
struct Frame {
    name: String,
    outer: Option<std::rc::Rc<Frame>>,
}

impl Expansion {
    fn frames(&self) -> impl Iterator<Item = &Frame> {
        std::iter::successors(self.stack.as_deref(), |f| f.outer.as_deref())
    }
}

impl Resolver {
    /// Resolves and folds an expression; `None` when an error was recorded.
    pub(super) fn expr(&mut self, e: &ast::Expr, scope: &Scope) -> Option<Expr> {
        let r = self.expr_in(e, scope, &Expansion::default())?;
        match super::fold::fold(r, &self.sources, &self.tables) {
            Ok(f) => Some(f),
            Err(err) => {
                self.errors.push(Report::new(*err));
                None
            }
        }
    }

    pub(super) fn expr_in(
        &mut self,
        e: &ast::Expr,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Expr> {
        let span = e.span;
        let kind = match &e.kind {
            ast::ExprKind::Num(v) => ExprKind::Num(*v),
            ast::ExprKind::Name(n) => return self.name(n, span, scope, exp),
            ast::ExprKind::Unary(op, a) => {
                let a = self.expr_in(a, scope, exp)?;
                match op {
                    ast::UnaryOp::Pos => return Some(a),
                    ast::UnaryOp::Neg => ExprKind::Unary(UnOp::Neg, Arc::new(a)),
                    ast::UnaryOp::Not => ExprKind::Unary(UnOp::Not, Arc::new(a)),
                }
            }
            ast::ExprKind::Binary(op, a, b) => {
                let a = self.expr_in(a, scope, exp);
                let b = self.expr_in(b, scope, exp);
                ExprKind::Binary(*op, Arc::new(a?), Arc::new(b?))
            }
            ast::ExprKind::Ternary(c, a, b) => {
                let c = self.expr_in(c, scope, exp);
                let a = self.expr_in(a, scope, exp);
                let b = self.expr_in(b, scope, exp);
                ExprKind::Cond(Arc::new(c?), Arc::new(a?), Arc::new(b?))
            }
            ast::ExprKind::Call(name, args) => return self.call(name, args, span, scope, exp),
            ast::ExprKind::Index(name, args) => {
                if self.vars.array_ids.contains_key(&name.name) {
                    let (id, idx) = self.elem_index(name, args, span, scope)?;
                    ExprKind::Elem(id, idx)
                } else {
                    return self.index(name, args, span, scope, exp);
                }
            }
            ast::ExprKind::Str(_) => {
                self.error(ResolveError::Unsupported {
                    what: "a string here".to_string(),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: "strings are arguments of cpfg's `printf` only".to_string(),
                });
                return None;
            }
        };
        Some(Expr { kind, span })
    }

    /// `NAME[i, j, ...]`: an element of a table.
    fn index(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Expr],
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Expr> {
        let n = &name.name;
        let Some(&id) = self.table_ids.get(n) else {
            let (what, help) = match self.defines.get(n) {
                // Its #define failed and was reported; say nothing more.
                Some(d) if d.dims.is_some() => return None,
                Some(_) => (
                    format!("`{n}` is not a table, so it cannot be indexed"),
                    format!("`{n}` is a plain #define; declare a table with dimensions instead, e.g. `#define {n}[1..3] {{a, b, c}}`"),
                ),
                None => (
                    format!("there is no table or array `{n}`"),
                    format!("declare it above its first use, e.g. `#define {n}[1..3] {{a, b, c}}`, or in cpfg's `define: {{ array {n}[3]; }}`"),
                ),
            };
            self.error(ResolveError::NotATable {
                what,
                src: self.sources.named_source(span),
                span: span.into(),
                help,
            });
            return None;
        };
        if let Some(def) = self.defines.get(n) {
            if exp.stack.is_none() && scope.order < def.order {
                let def_span = def.span;
                self.error(ResolveError::DefineAfterUse {
                    name: n.clone(),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    def: (def_span.file == span.file).then(|| def_span.into()),
                    help: format!("move `#define {n}[...]` above its first use"),
                });
                return None;
            }
        }
        let ndims = self.tables[id as usize].dims.len();
        if args.len() != ndims {
            let t = &self.tables[id as usize];
            let dims = t.dims_text();
            self.error(ResolveError::TableUse {
                name: n.clone(),
                dims: dims.clone(),
                problem: format!("it takes {ndims} indices, found {}", args.len()),
                src: self.sources.named_source(span),
                span: span.into(),
                help: format!("write one index per dimension of {dims}"),
            });
            return None;
        }
        let mut out = Vec::new();
        let mut ok = true;
        for a in args {
            match self.expr_in(a, scope, exp) {
                Some(e) => out.push(e),
                None => ok = false,
            }
        }
        ok.then_some(Expr {
            kind: ExprKind::Index(id, out),
            span,
        })
    }

    fn name(
        &mut self,
        n: &str,
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Expr> {
        if let Some(arg) = exp.args.get(n) {
            return Some(arg.clone());
        }
        if let Some((_, slot)) = scope.locals.iter().find(|(p, _)| p == n) {
            return Some(Expr {
                kind: ExprKind::Var(*slot),
                span,
            });
        }
        if let Some((_, slot)) = scope.params.iter().find(|(p, _)| p == n) {
            return Some(Expr {
                kind: ExprKind::Param(*slot),
                span,
            });
        }
        if let Some(&slot) = self.vars.globals.get(n) {
            return Some(Expr {
                kind: ExprKind::Var(slot),
                span,
            });
        }
        if self.vars.array_ids.contains_key(n) {
            self.error(ResolveError::TableUse {
                name: n.to_string(),
                dims: String::new(),
                problem: "it is an array and needs an index".to_string(),
                src: self.sources.named_source(span),
                span: span.into(),
                help: format!("read one element, e.g. `{n}[i]`"),
            });
            return None;
        }
        if let Some(def) = self.defines.get(n).cloned() {
            if def.dims.is_some() {
                let dims = self
                    .tables
                    .iter()
                    .find(|t| t.name == n)
                    .map_or(String::new(), |t| t.dims_text());
                self.error(ResolveError::TableUse {
                    name: n.to_string(),
                    dims,
                    problem: "it needs an index".to_string(),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: format!("read one element, e.g. `{n}[i, j]`"),
                });
                return None;
            }
            if def.params.is_some() {
                self.error(ResolveError::CallArity {
                    name: n.to_string(),
                    expected: def.params.as_ref().map_or(0, Vec::len),
                    found: 0,
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: Some(format!(
                        "`{n}` is a function-like #define; call it with its arguments: `{n}(...)`"
                    )),
                });
                return None;
            }
            return self.expand(&def, span, scope, exp, HashMap::new());
        }
        if !self.failed_includes.is_empty() {
            // Probably defined by the include that failed: one error for
            // all such names (see `report_missing_names`).
            if !self.missing_names.iter().any(|(m, _)| m == n) {
                self.missing_names.push((n.to_string(), span));
            }
            return None;
        }
        if self.evaluating_for_display {
            return None;
        }
        let mut candidates: Vec<String> = scope.params.iter().map(|(p, _)| p.clone()).collect();
        candidates.extend(self.defines.keys().cloned());
        let mut help = match suggest(n, candidates.iter().map(String::as_str)) {
            Some(s) => format!("did you mean `{s}`?"),
            None => String::new(),
        };
        if scope.params.is_empty() {
            help.push_str(if help.is_empty() { "" } else { " " });
            help.push_str(
                "names here are #defines; define it with `#define NAME value` above its first use",
            );
        } else {
            let ps: Vec<&str> = scope.params.iter().map(|(p, _)| p.as_str()).collect();
            help.push_str(if help.is_empty() { "" } else { " " });
            help.push_str(&format!(
                "names here are the production's parameters ({}) and #defines",
                ps.join(", ")
            ));
        }
        self.error(ResolveError::UnknownName {
            name: n.to_string(),
            src: self.sources.named_source(span),
            span: span.into(),
            help,
        });
        None
    }

    fn expand(
        &mut self,
        def: &super::DefineEntry,
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
        args: HashMap<String, Expr>,
    ) -> Option<Expr> {
        let name = &def.name;
        if exp.stack.is_none() && scope.order < def.order {
            self.error(ResolveError::DefineAfterUse {
                name: name.clone(),
                src: self.sources.named_source(span),
                span: span.into(),
                def: (def.span.file == span.file).then(|| def.span.into()),
                help: format!(
                    "move `#define {name}` above its first use, as the C preprocessor requires"
                ),
            });
            return None;
        }
        if exp.frames().any(|f| &f.name == name) {
            let mut chain: Vec<String> = exp.frames().map(|f| f.name.clone()).collect();
            chain.reverse();
            chain.push(name.clone());
            self.error(ResolveError::DefineCycle {
                name: name.clone(),
                chain: chain.join(" -> "),
                src: self.sources.named_source(span),
                span: span.into(),
            });
            return None;
        }
        let Some(value) = &def.value else {
            self.error(ResolveError::DefineWithoutValue {
                name: name.clone(),
                src: self.sources.named_source(span),
                span: span.into(),
                help: format!(
                    "`#define {name}` declares a parameter without a value; give it one in the file (`#define {name} 5`) or for this run (`-D {name}=5`)"
                ),
            });
            return None;
        };
        // Without arguments the expansion is the same wherever the same
        // names are in scope (the stack only finds cycles, and a define
        // that expanded once has none).
        let reusable = args.is_empty();
        let declared = (self.vars.globals.len(), self.vars.array_ids.len());
        if reusable {
            let made = self.expansions.made.get(name).and_then(|m| {
                m.iter().find(|m| {
                    m.declared == declared && m.params == scope.params && m.locals == scope.locals
                })
            });
            if let Some(m) = made {
                return Some(m.expr.clone());
            }
        }
        let inner = Expansion {
            stack: Some(std::rc::Rc::new(Frame {
                name: name.clone(),
                outer: exp.stack.clone(),
            })),
            args,
        };
        let reported = (
            self.errors.len(),
            self.warnings.len(),
            self.missing_names.len(),
        );
        let expr = self.expr_in(value, scope, &inner)?;
        let quiet = reported
            == (
                self.errors.len(),
                self.warnings.len(),
                self.missing_names.len(),
            );
        if reusable && quiet {
            // Folded once, here, so that the uses share one folded tree:
            // the statement's own fold then walks it without copying it
            // (see `fold::folded`). A fold that fails keeps the tree as it
            // was, and the statement's fold reports the error where it
            // always did. An expansion that is not kept has one use, and
            // the statement's fold is its only one.
            let expr = match super::fold::folded(&expr, &self.sources, &self.tables) {
                Ok(Some(folded)) => folded,
                Ok(None) | Err(_) => expr,
            };
            self.expansions
                .made
                .entry(name.clone())
                .or_default()
                .push(Made {
                    params: scope.params.to_vec(),
                    locals: scope.locals.to_vec(),
                    declared,
                    expr: expr.clone(),
                });
            return Some(expr);
        }
        Some(expr)
    }

    fn call(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Expr],
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Expr> {
        // cpfg's functions with effects outside the string: printing and
        // writing files (lsys prints the derived string, not the model's
        // messages or files), and `stop`, `display`, `play`, which control
        // cpfg's animation window, not the derivation. The call does
        // nothing and yields 0 (docs/cpfg.md lists them).
        if matches!(
            name.name.as_str(),
            "printf" | "fprintf" | "fflush" | "fopen" | "fclose" | "stop" | "display" | "play"
        ) {
            return Some(Expr {
                kind: ExprKind::Num(0.0),
                span,
            });
        }
        if let Some(e) = self.curve_call(name, args, span, scope, exp) {
            return e;
        }
        if name.name == "func" && !self.defines.contains_key("func") {
            return self.spline_call(name, args, span, scope, exp);
        }
        let resolved: Vec<Option<Expr>> =
            args.iter().map(|a| self.expr_in(a, scope, exp)).collect();
        let resolved: Vec<Expr> = resolved.into_iter().collect::<Option<_>>()?;
        if let Some(def) = self.defines.get(&name.name).cloned() {
            let Some(params) = def.params.clone() else {
                self.error(ResolveError::Unsupported {
                    what: format!("calling `{}`, which is a #define with no parameters,", name.name),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: format!("use it without parentheses (`{}`), or give the #define parameters: `#define {}(x) ...`", name.name, name.name),
                });
                return None;
            };
            if params.len() != resolved.len() {
                self.error(ResolveError::CallArity {
                    name: name.name.clone(),
                    expected: params.len(),
                    found: resolved.len(),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: Some(format!(
                        "`{}({})` is defined at {}",
                        name.name,
                        params.join(","),
                        self.sources.location(def.span)
                    )),
                });
                return None;
            }
            let map = params.into_iter().zip(resolved).collect();
            return self.expand(&def, span, scope, exp, map);
        }
        if let Some(e) = self.random_call(name, &resolved, span) {
            return e;
        }
        let Some(f) = Func::from_name(&name.name) else {
            let mut known: Vec<String> = Func::ALL.iter().map(|f| f.name().to_string()).collect();
            known.extend(
                self.defines
                    .iter()
                    .filter(|(_, d)| d.params.is_some())
                    .map(|(k, _)| k.clone()),
            );
            let mut help = suggest(&name.name, known.iter().map(String::as_str))
                .map(|s| format!("did you mean `{s}`? "))
                .unwrap_or_default();
            help.push_str(&format!(
                "the built-in functions are {}",
                Func::ALL.map(|f| f.name()).join(", ")
            ));
            self.error(ResolveError::UnknownFunction {
                name: name.name.clone(),
                src: self.sources.named_source(name.span),
                span: name.span.into(),
                help,
            });
            return None;
        };
        if f.arity() != resolved.len() {
            self.error(ResolveError::CallArity {
                name: name.name.clone(),
                expected: f.arity(),
                found: resolved.len(),
                src: self.sources.named_source(span),
                span: span.into(),
                help: None,
            });
            return None;
        }
        Some(Expr {
            kind: ExprKind::Call(f, resolved),
            span,
        })
    }
}

/// The closest known name, if one is close enough to be a typo.
pub(super) fn suggest<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    known
        .map(|k| (strsim::damerau_levenshtein(name, k), k))
        .filter(|(d, k)| *d <= 2 && *d < name.chars().count().max(2) && *k != name)
        .min_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(b.1)))
        .map(|(_, k)| k)
}

impl Resolver {
    /// cpfg's generator calls that are not plain functions: `nran(mean,
    /// sd)` and `srand(seed)`. `None` when `name` is neither.
    fn random_call(
        &mut self,
        name: &ast::Ident,
        args: &[Expr],
        span: crate::source::Span,
    ) -> Option<Option<Expr>> {
        let (want, rand) = match name.name.as_str() {
            "nran" => (2, RandFn::Nran),
            "bran" => (2, RandFn::Bran),
            "biran" => (2, RandFn::Biran),
            "srand" => (1, RandFn::Nran),
            _ => return None,
        };
        if !self.call_arity(name, args.len(), want, span, None) {
            return Some(None);
        }
        let mut a = args.iter().cloned().map(Arc::new);
        let first = a.next().expect("checked count");
        let kind = match a.next() {
            Some(second) => ExprKind::Random(rand, first, second),
            None => ExprKind::Srand(first),
        };
        Some(Some(Expr { kind, span }))
    }
}

impl Resolver {
    /// Whether a call of `name` has the `want` arguments it needs; reports
    /// it when not.
    pub(super) fn call_arity(
        &mut self,
        name: &ast::Ident,
        found: usize,
        want: usize,
        span: crate::source::Span,
        help: Option<String>,
    ) -> bool {
        if found != want {
            self.error(ResolveError::CallArity {
                name: name.name.clone(),
                expected: want,
                found,
                src: self.sources.named_source(span),
                span: span.into(),
                help,
            });
        }
        found == want
    }
}
