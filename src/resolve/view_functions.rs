//! cpfg's view-file functions: a call of `func(id, x)` (a function of the
//! view file's `function:` lines), of `curveX(id, s)`, `curveY`, `curveZ`
//! (a coordinate of the view file's curve `id` at arc length `s`) or
//! `curveGAL(id)` (its length) in, an expression out. The curve number must
//! be a constant, as in every cpfg model; a coordinate becomes a call of a
//! function the VM evaluates like `func` (appended after the view file's
//! functions), the length a number.

use std::sync::Arc;

use super::error::ResolveError;
use super::expr::{Expansion, Scope};
use super::ir::{Expr, ExprKind};
use super::Resolver;
use crate::lang::spline::SplineFn;
use crate::parse::ast;

impl Resolver {
    /// cpfg's `func(id, x)`: `id` is a function's number in the view file
    /// (from 1) or its name; the functions are read from the view file the
    /// first time.
    pub(super) fn spline_call(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Expr],
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Expr> {
        let help = "`func(id, x)`: function `id` of the view file at `x` in [0, 1]";
        if !self.call_arity(name, args.len(), 2, span, Some(help.to_string())) {
            return None;
        }
        let functions = self.view_function_names(span)?;
        let by_name = match &args[0].kind {
            ast::ExprKind::Name(n) => functions.iter().position(|f| f == n),
            _ => None,
        };
        let index = match by_name {
            Some(i) => i,
            None => {
                let id = self.expr_in(&args[0], scope, exp)?;
                let id = super::fold::fold(id, &self.sources, &self.tables).ok()?;
                match id.kind {
                    ExprKind::Num(v)
                        if v >= 1.0 && v.fract() == 0.0 && (v as usize) <= functions.len() =>
                    {
                        v as usize - 1
                    }
                    _ => {
                        let names: Vec<String> = functions
                            .iter()
                            .enumerate()
                            .map(|(i, f)| format!("{} = {f}", i + 1))
                            .collect();
                        self.error(ResolveError::BadValue {
                            what: "the function of `func`".to_string(),
                            why: "it is not the number or name of a function of the view file"
                                .to_string(),
                            src: self.sources.named_source(args[0].span),
                            span: args[0].span.into(),
                            help: Some(if names.is_empty() {
                                "the view file has no `function:` lines".to_string()
                            } else {
                                format!("the view file's functions are {}", names.join(", "))
                            }),
                        });
                        return None;
                    }
                }
            }
        };
        let x = self.expr_in(&args[1], scope, exp)?;
        Some(Expr {
            kind: ExprKind::Spline(index as u32, Arc::new(x)),
            span,
        })
    }

    /// The functions the VM evaluates start with the view file's (read
    /// while loading), once, so that `func`'s numbers are theirs.
    fn seed_functions(&mut self) {
        if self.vars.functions.is_none() {
            if let crate::load::ViewFunctions::Read(fs) = &self.view_functions {
                self.vars.functions = Some(fs.clone());
            }
        }
    }

    /// The names of the view file's functions, in `func` order; `None`
    /// after reporting why there are none.
    fn view_function_names(&mut self, span: crate::source::Span) -> Option<Vec<String>> {
        use crate::load::ViewFunctions;
        self.seed_functions();
        match &mut self.view_functions {
            ViewFunctions::Read(fs) => Some(fs.iter().map(|f| f.name.clone()).collect()),
            ViewFunctions::NoViewFile => {
                self.error(ResolveError::Unsupported {
                    what: "`func` without a view file".to_string(),
                    src: self.sources.named_source(span),
                    span: span.into(),
                    help: "cpfg's `func(id, x)` reads the functions named on the `function:` lines of the model's view file; put the `.v` file beside the model (named in `specifications`, or the model's name with `.v`)".to_string(),
                });
                None
            }
            // Reported once, at the first `func` call; they point into the
            // view file and the function files.
            ViewFunctions::Failed(errors) => {
                let errors = std::mem::take(errors);
                self.errors.extend(errors);
                None
            }
        }
    }

    /// The call resolved, when `name` is one of the curve functions (and
    /// not a `#define`); `Some(None)` after reporting an error.
    pub(super) fn curve_call(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Expr],
        span: crate::source::Span,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<Option<Expr>> {
        let axis = match name.name.as_str() {
            "curveX" => Some(0),
            "curveY" => Some(1),
            "curveZ" => Some(2),
            "curveGAL" => None,
            _ => return None,
        };
        if self.defines.contains_key(&name.name) {
            return None;
        }
        let want = if axis.is_some() { 2 } else { 1 };
        let help = "`curveX(id, s)`: curve `id` of the view file's `curve:` lines at arc length `s` in [0, 1]; `curveGAL(id)`: its length";
        if !self.call_arity(name, args.len(), want, span, Some(help.to_string())) {
            return Some(None);
        }
        let Some(curve) = self.curve(&args[0], scope, exp) else {
            return Some(None);
        };
        let Some(axis) = axis else {
            return Some(Some(Expr {
                kind: ExprKind::Num(curve.length),
                span,
            }));
        };
        let s = self.expr_in(&args[1], scope, exp)?;
        // After the view file's functions, so that `func`'s numbers stay.
        self.seed_functions();
        let functions = self.vars.functions.get_or_insert_with(Vec::new);
        // One function per curve and axis, however many calls name it.
        let fname = format!("{}:{}", name.name, curve.name);
        let index = match functions.iter().position(|f| f.name == fname) {
            Some(i) => i as u32,
            None => {
                functions.push(SplineFn {
                    name: fname,
                    points: Vec::new(),
                    table: Vec::new(),
                    contour: Some((Box::new(curve), axis)),
                });
                functions.len() as u32 - 1
            }
        };
        Some(Some(Expr {
            kind: ExprKind::Spline(index, Arc::new(s)),
            span,
        }))
    }

    /// The curve a constant `id` names (from 1), or `None` after saying
    /// why not.
    fn curve(
        &mut self,
        id: &ast::Expr,
        scope: &Scope,
        exp: &Expansion,
    ) -> Option<crate::lang::curve::Curve> {
        let e = self.expr_in(id, scope, exp)?;
        let e = super::fold::fold(e, &self.sources, &self.tables).ok()?;
        let n = match e.kind {
            ExprKind::Num(v) if v >= 1.0 && v.fract() == 0.0 => v as usize,
            _ => 0,
        };
        let why = match self.view_curves.get(n.wrapping_sub(1)) {
            Some(Ok(c)) => return Some(c.clone()),
            Some(Err(why)) => why.clone(),
            None if self.view_curves.is_empty() => {
                "the model's view file has no `curve:` lines".to_string()
            }
            None => format!(
                "not a constant from 1 to {} (the view file's `curve:` lines)",
                self.view_curves.len()
            ),
        };
        self.error(ResolveError::BadValue {
            what: "the curve".to_string(),
            why,
            src: self.sources.named_source(id.span),
            span: id.span.into(),
            help: Some(
                "cpfg numbers the curves of the view file's `curve: FILE.con` lines from 1"
                    .to_string(),
            ),
        });
        None
    }
}
