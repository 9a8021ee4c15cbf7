//! Constant folding: a resolved expression -> the same expression with
//! every constant sub-expression computed. Arithmetic is IEEE f64, the same
//! operations the VM performs, so a folded value is exactly
//! what the VM would have computed (functions go through the VM's own
//! table, `lang::builtins::call`).

use super::error::ResolveError;
use super::ir::{BinOp, Expr, ExprKind, TableDef, UnOp};
use crate::source::SourceMap;

pub fn fold(e: Expr, sources: &SourceMap, tables: &[TableDef]) -> Result<Expr, Box<ResolveError>> {
    let span = e.span;
    let kind = match e.kind {
        ExprKind::Unary(op, a) => {
            let a = fold(*a, sources, tables)?;
            match a.kind {
                ExprKind::Num(v) => ExprKind::Num(apply_unary(op, v)),
                _ => ExprKind::Unary(op, Box::new(a)),
            }
        }
        ExprKind::Binary(op, a, b) => {
            let a = fold(*a, sources, tables)?;
            let b = fold(*b, sources, tables)?;
            match (op, &a.kind, &b.kind) {
                (BinOp::Div | BinOp::Rem, _, ExprKind::Num(z)) if *z == 0.0 => {
                    return Err(Box::new(ResolveError::DivisionByZero {
                        src: sources.named_source(b.span),
                        span: b.span.into(),
                    }))
                }
                (_, ExprKind::Num(x), ExprKind::Num(y)) => ExprKind::Num(apply_binary(op, *x, *y)),
                // A constant left side decides `&&` / `||` alone when it can.
                (BinOp::And, ExprKind::Num(x), _) if *x == 0.0 => ExprKind::Num(0.0),
                (BinOp::Or, ExprKind::Num(x), _) if *x != 0.0 => ExprKind::Num(1.0),
                _ => ExprKind::Binary(op, Box::new(a), Box::new(b)),
            }
        }
        ExprKind::Cond(c, a, b) => {
            let c = fold(*c, sources, tables)?;
            let a = fold(*a, sources, tables)?;
            let b = fold(*b, sources, tables)?;
            match c.kind {
                ExprKind::Num(v) => return Ok(if v != 0.0 { a } else { b }),
                _ => ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)),
            }
        }
        ExprKind::Call(f, args) => {
            let args = args
                .into_iter()
                .map(|a| fold(a, sources, tables))
                .collect::<Result<Vec<_>, _>>()?;
            let consts: Option<Vec<f64>> = args
                .iter()
                .map(|a| match a.kind {
                    ExprKind::Num(v) => Some(v),
                    _ => None,
                })
                .collect();
            match consts {
                // The VM's own function table, so a folded value is bit for bit
                // what the VM computes at run time.
                Some(vals) if f.is_pure() => ExprKind::Num(crate::lang::builtins::call(
                    f,
                    vals[0],
                    vals.get(1).copied().unwrap_or(0.0),
                )),
                _ => ExprKind::Call(f, args),
            }
        }
        ExprKind::Index(id, args) => {
            let args = args
                .into_iter()
                .map(|a| fold(a, sources, tables))
                .collect::<Result<Vec<_>, _>>()?;
            let t = &tables[id as usize];
            let consts: Option<Vec<f64>> = args
                .iter()
                .map(|a| match a.kind {
                    ExprKind::Num(v) => Some(v),
                    _ => None,
                })
                .collect();
            match consts {
                Some(idx) => match crate::lang::builtins::table_offset(t.bounds(), &idx) {
                    Ok(at) => ExprKind::Num(t.values[at]),
                    Err(k) => {
                        return Err(Box::new(ResolveError::TableIndex {
                            name: t.name.clone(),
                            value: idx[k],
                            lo: t.dims[k].0,
                            hi: t.dims[k].1,
                            dims: t.dims_text(),
                            src: sources.named_source(args[k].span),
                            span: args[k].span.into(),
                        }))
                    }
                },
                None => ExprKind::Index(id, args),
            }
        }
        k => k,
    };
    Ok(Expr { kind, span })
}

fn apply_unary(op: UnOp, v: f64) -> f64 {
    match op {
        UnOp::Neg => -v,
        UnOp::Not => bool_f(v == 0.0),
    }
}

/// The arithmetic of the language. Division by zero is the caller's to
/// detect (it is an error, not infinity).
fn apply_binary(op: BinOp, x: f64, y: f64) -> f64 {
    match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => x / y,
        BinOp::Rem => x % y,
        BinOp::Pow => x.powf(y),
        BinOp::Lt => bool_f(x < y),
        BinOp::Le => bool_f(x <= y),
        BinOp::Gt => bool_f(x > y),
        BinOp::Ge => bool_f(x >= y),
        BinOp::Eq => bool_f(x == y),
        BinOp::Ne => bool_f(x != y),
        BinOp::And => bool_f(x != 0.0 && y != 0.0),
        BinOp::Or => bool_f(x != 0.0 || y != 0.0),
    }
}

fn bool_f(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}
