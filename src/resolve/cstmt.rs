//! cpfg's C-like statements: AST blocks (`Start: {...}`, `define: {array
//! ...}`, the blocks around a production's condition) in, resolved
//! [`Stmt`]s, variable slots and arrays out.
//!
//! Scoping follows cpfg. A name assigned in one of the L-system's blocks
//! (`Start:`, `StartEach:`, `EndEach:`, `End:`) or declared by `array` is
//! global: every production and block sees the same value, and it keeps
//! its value from step to step. A name first assigned in a production's
//! block belongs to that production (cpfg keeps it in the production's own
//! symbol table): it is a slot of its own, so two productions may use the
//! same local name independently. Assigning to a parameter gives the
//! production a local copy of it, initialised from the parameter, which
//! every later use in that production reads.

use std::collections::HashMap;
use std::sync::Arc;

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::{ArrayInfo, BinOp, Expr, ExprKind, Hooks, Stmt, Target, VarInfo};
use super::Resolver;
use crate::parse::ast::{self, AssignOp, CStmt, HeaderKind, Item};
use crate::source::Span;

/// Most elements an `array` may have (they live in the variables).
const MAX_ARRAY_ELEMENTS: usize = 1 << 24;

/// The variables of one L-system being resolved.
#[derive(Default)]
pub(crate) struct Vars {
    pub vars: Vec<VarInfo>,
    pub init: Vec<f64>,
    pub globals: HashMap<String, u32>,
    pub arrays: Vec<ArrayInfo>,
    pub array_ids: HashMap<String, u32>,
    pub hooks: Hooks,
    /// The view file's functions, taken at the first `func` call.
    pub functions: Option<Vec<crate::lang::spline::SplineFn>>,
}

impl Vars {
    fn slot(&mut self, name: &str, span: Span, value: f64) -> u32 {
        self.vars.push(VarInfo {
            name: name.to_string(),
            span,
        });
        self.init.push(value);
        (self.vars.len() - 1) as u32
    }
}

/// Every name a list of statements assigns (not array elements), in order.
fn assigned<'a>(stmts: &'a [CStmt], out: &mut Vec<&'a ast::Ident>) {
    for s in stmts {
        match s {
            CStmt::Assign { target, .. } if target.index.is_empty() => out.push(&target.name),
            CStmt::If { then, els, .. } => {
                assigned(then, out);
                assigned(els, out);
            }
            CStmt::While { body, .. } | CStmt::DoWhile { body, .. } => assigned(body, out),
            _ => {}
        }
    }
}

impl Resolver {
    /// Before the statements are resolved: declare every `array` (in any
    /// block) and make every name the L-system's blocks assign a global.
    pub(super) fn declare_globals(&mut self, items: &[(u32, Item)]) {
        for (order, (_, item)) in items.iter().enumerate() {
            let Item::Header(h) = item else { continue };
            let HeaderKind::Block(_, b) = &h.kind else {
                continue;
            };
            let scope = Scope {
                order,
                ..Scope::EMPTY
            };
            for s in &b.stmts {
                if let CStmt::Array(decls) = s {
                    for d in decls {
                        self.declare_array(d, &scope);
                    }
                }
            }
            let mut names = Vec::new();
            assigned(&b.stmts, &mut names);
            for n in names {
                if !self.vars.globals.contains_key(&n.name)
                    && !self.vars.array_ids.contains_key(&n.name)
                {
                    let slot = self.vars.slot(&n.name, n.span, 0.0);
                    self.vars.globals.insert(n.name.clone(), slot);
                }
            }
        }
    }

    fn declare_array(&mut self, d: &ast::ArrayDecl, scope: &Scope) {
        if self.vars.array_ids.contains_key(&d.name.name) {
            self.error(ResolveError::BadValue {
                what: format!("array `{}`", d.name.name),
                why: "it is declared twice".to_string(),
                src: self.sources.named_source(d.name.span),
                span: d.name.span.into(),
                help: Some("keep one `array` declaration per name".to_string()),
            });
            return;
        }
        let mut dims = Vec::new();
        for e in &d.dims {
            let n = self.const_count(e, scope, "array dimension", MAX_ARRAY_ELEMENTS as u64);
            dims.push(n.unwrap_or(1).max(1) as usize);
        }
        let len = dims
            .iter()
            .try_fold(1usize, |a, &b| a.checked_mul(b))
            .filter(|&l| l <= MAX_ARRAY_ELEMENTS);
        let Some(len) = len else {
            self.error(ResolveError::BadValue {
                what: format!("array `{}`", d.name.name),
                why: format!("it has more than {MAX_ARRAY_ELEMENTS} elements"),
                src: self.sources.named_source(d.span),
                span: d.span.into(),
                help: None,
            });
            return;
        };
        let mut values = vec![0.0; len];
        if let Some(init) = &d.init {
            if init.len() > len {
                self.error(ResolveError::BadValue {
                    what: format!("the initializer of array `{}`", d.name.name),
                    why: format!("it has {} values for {len} elements", init.len()),
                    src: self.sources.named_source(d.span),
                    span: d.span.into(),
                    help: Some(
                        "give at most one value per element, in row-major order".to_string(),
                    ),
                });
            }
            for (v, e) in values.iter_mut().zip(init) {
                *v = self.const_num(e, scope, "array value").unwrap_or(0.0);
            }
        }
        let base = self.vars.vars.len() as u32;
        for (k, v) in values.into_iter().enumerate() {
            let name = format!("{}[{k}]", d.name.name);
            self.vars.slot(&name, d.name.span, v);
        }
        self.vars
            .array_ids
            .insert(d.name.name.clone(), self.vars.arrays.len() as u32);
        self.vars.arrays.push(ArrayInfo {
            name: d.name.name.clone(),
            dims,
            base,
            span: d.name.span,
        });
    }

    /// `Start: {...}` and its kin: resolved into the hooks. (`define:`
    /// holds only `array` declarations, taken by [`Self::declare_globals`].)
    pub(super) fn hook_block(&mut self, kw: &str, b: &ast::Block, order: usize) {
        let scope = Scope {
            order,
            ..Scope::EMPTY
        };
        let stmts = self.stmts(&b.stmts, &scope);
        let hooks = &mut self.vars.hooks;
        let slot = match kw.to_ascii_lowercase().as_str() {
            "start" => &mut hooks.start,
            "starteach" => &mut hooks.start_each,
            "endeach" => &mut hooks.end_each,
            "end" => &mut hooks.end,
            _ => return,
        };
        slot.extend(stmts);
    }

    /// The local variables of a production with blocks, and the statements
    /// that copy the parameters it assigns into their locals.
    pub(super) fn production_locals(
        &mut self,
        p: &ast::Production,
        params: &[(String, u16)],
    ) -> (Vec<(String, u32)>, Vec<Stmt>) {
        let mut names = Vec::new();
        for b in p.pre.iter().chain(&p.post) {
            assigned(&b.stmts, &mut names);
        }
        let mut locals: Vec<(String, u32)> = Vec::new();
        let mut init = Vec::new();
        for n in names {
            if locals.iter().any(|(l, _)| *l == n.name)
                || self.vars.globals.contains_key(&n.name)
                || self.vars.array_ids.contains_key(&n.name)
            {
                continue;
            }
            let slot = self.vars.slot(&n.name, n.span, 0.0);
            if let Some((_, p)) = params.iter().find(|(q, _)| *q == n.name) {
                init.push(Stmt::Set {
                    target: Target::Var(slot, n.span),
                    value: Expr {
                        kind: ExprKind::Param(*p),
                        span: n.span,
                    },
                });
            }
            locals.push((n.name.clone(), slot));
        }
        (locals, init)
    }

    /// Resolve a list of statements.
    pub(super) fn stmts(&mut self, stmts: &[CStmt], scope: &Scope) -> Vec<Stmt> {
        let mut out = Vec::new();
        for s in stmts {
            match s {
                CStmt::Assign {
                    target, op, value, ..
                } => {
                    let Some(t) = self.target(target, scope) else {
                        continue;
                    };
                    let Some(v) = self.expr(value, scope) else {
                        continue;
                    };
                    let value = match op {
                        AssignOp::Set => v,
                        _ => {
                            let bin = match op {
                                AssignOp::Add => BinOp::Add,
                                AssignOp::Sub => BinOp::Sub,
                                AssignOp::Mul => BinOp::Mul,
                                _ => BinOp::Div,
                            };
                            let (kind, span) = match &t {
                                Target::Var(slot, span) => (ExprKind::Var(*slot), *span),
                                Target::Elem(a, idx, span) => {
                                    (ExprKind::Elem(*a, idx.clone()), *span)
                                }
                            };
                            let span = span.to(v.span);
                            Expr {
                                kind: ExprKind::Binary(
                                    bin,
                                    Arc::new(Expr { kind, span }),
                                    Arc::new(v),
                                ),
                                span,
                            }
                        }
                    };
                    out.push(Stmt::Set { target: t, value });
                }
                CStmt::Expr(e) => {
                    if let Some(e) = self.expr(e, scope) {
                        // A constant (`printf(...)`, whose output lsys
                        // does not print) does nothing.
                        if !matches!(e.kind, ExprKind::Num(_)) {
                            out.push(Stmt::Eval(e));
                        }
                    }
                }
                CStmt::If {
                    cond, then, els, ..
                } => {
                    let c = self.expr(cond, scope);
                    let t = self.stmts(then, scope);
                    let e = self.stmts(els, scope);
                    if let Some(c) = c {
                        out.push(Stmt::If(c, t, e));
                    }
                }
                CStmt::While { cond, body, .. } => {
                    let c = self.expr(cond, scope);
                    let b = self.stmts(body, scope);
                    if let Some(c) = c {
                        out.push(Stmt::While(c, b));
                    }
                }
                CStmt::DoWhile { body, cond, .. } => {
                    let b = self.stmts(body, scope);
                    if let Some(c) = self.expr(cond, scope) {
                        out.push(Stmt::DoWhile(b, c));
                    }
                }
                // Declared before resolution (`declare_globals`); one in a
                // production's block is an error there.
                CStmt::Array(decls) => {
                    if !scope.params.is_empty() || !scope.locals.is_empty() {
                        if let Some(d) = decls.first() {
                            self.error(ResolveError::Misplaced {
                                what: "an `array` declaration in a production".to_string(),
                                src: self.sources.named_source(d.span),
                                span: d.span.into(),
                                help:
                                    "declare arrays in the L-system's `define: { array ... }` block"
                                        .to_string(),
                            });
                        }
                    }
                }
            }
        }
        out
    }

    fn target(&mut self, lv: &ast::LValue, scope: &Scope) -> Option<Target> {
        let n = &lv.name.name;
        if lv.index.is_empty() {
            if let Some((_, slot)) = scope.locals.iter().find(|(l, _)| l == n) {
                return Some(Target::Var(*slot, lv.span));
            }
            if let Some(&slot) = self.vars.globals.get(n) {
                return Some(Target::Var(slot, lv.span));
            }
            // Every assigned name was given a slot beforehand; an array
            // name without an index is what is left.
            self.error(ResolveError::NotATable {
                what: format!("`{n}` is an array; assign to one of its elements"),
                src: self.sources.named_source(lv.span),
                span: lv.span.into(),
                help: format!("write `{n}[i] = ...`"),
            });
            return None;
        }
        let idx = self.elem_index(&lv.name, &lv.index, lv.span, scope)?;
        Some(Target::Elem(idx.0, idx.1, lv.span))
    }

    /// The array and resolved indices of `name[i][j]`, checked against the
    /// array's dimension count; `None` (reported) otherwise.
    pub(super) fn elem_index(
        &mut self,
        name: &ast::Ident,
        index: &[ast::Expr],
        span: Span,
        scope: &Scope,
    ) -> Option<(u32, Vec<Expr>)> {
        let Some(&id) = self.vars.array_ids.get(&name.name) else {
            self.error(ResolveError::NotATable {
                what: format!("there is no array `{}`", name.name),
                src: self.sources.named_source(name.span),
                span: name.span.into(),
                help: format!(
                    "declare it in the L-system's `define:` block: `define: {{ array {}[10]; }}`",
                    name.name
                ),
            });
            return None;
        };
        let dims = self.vars.arrays[id as usize].dims.len();
        if dims != index.len() {
            let shape: String = self.vars.arrays[id as usize]
                .dims
                .iter()
                .map(|d| format!("[{d}]"))
                .collect();
            self.error(ResolveError::NotATable {
                what: format!(
                    "`{}` is an array {shape}: it takes {dims} indices, not {}",
                    name.name,
                    index.len()
                ),
                src: self.sources.named_source(span),
                span: span.into(),
                help: format!(
                    "write one index per dimension, each in its own brackets: `{}{}`",
                    name.name,
                    ["[i]", "[j]", "[k]", "[l]"]
                        .iter()
                        .cycle()
                        .take(dims)
                        .copied()
                        .collect::<String>()
                ),
            });
            return None;
        }
        let idx: Vec<Option<Expr>> = index.iter().map(|e| self.expr(e, scope)).collect();
        Some((id, idx.into_iter().collect::<Option<_>>()?))
    }

    /// Moves the variables into the program.
    pub(super) fn take_vars(&mut self) -> Vars {
        std::mem::take(&mut self.vars)
    }
}

impl Resolver {
    /// A string module parameter (`@L(" %.f", c)`): cpfg keeps the string
    /// in a table and the module carries its number, from 1; so does lsys.
    pub(super) fn string_param(&mut self, s: &str, span: Span) -> Expr {
        let at = match self.strings.iter().position(|t| t == s) {
            Some(i) => i,
            None => {
                self.strings.push(s.to_string());
                self.strings.len() - 1
            }
        };
        Expr {
            kind: ExprKind::Num((at + 1) as f64),
            span,
        }
    }
}
