//! Constant folding: a resolved expression -> the same expression with
//! every constant sub-expression computed. Shared with the VM's semantics
//! through [`apply_binary`] and [`apply_func`], so a folded value is exactly
//! what the VM would have computed.

use super::error::ResolveError;
use super::ir::{BinOp, Expr, ExprKind, Func, UnOp};
use crate::source::SourceMap;

pub fn fold(e: Expr, sources: &SourceMap) -> Result<Expr, Box<ResolveError>> {
    let span = e.span;
    let kind = match e.kind {
        ExprKind::Unary(op, a) => {
            let a = fold(*a, sources)?;
            match a.kind {
                ExprKind::Num(v) => ExprKind::Num(apply_unary(op, v)),
                _ => ExprKind::Unary(op, Box::new(a)),
            }
        }
        ExprKind::Binary(op, a, b) => {
            let a = fold(*a, sources)?;
            let b = fold(*b, sources)?;
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
            let c = fold(*c, sources)?;
            let a = fold(*a, sources)?;
            let b = fold(*b, sources)?;
            match c.kind {
                ExprKind::Num(v) => return Ok(if v != 0.0 { a } else { b }),
                _ => ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)),
            }
        }
        ExprKind::Call(f, args) => {
            let args = args
                .into_iter()
                .map(|a| fold(a, sources))
                .collect::<Result<Vec<_>, _>>()?;
            let consts: Option<Vec<f64>> = args
                .iter()
                .map(|a| match a.kind {
                    ExprKind::Num(v) => Some(v),
                    _ => None,
                })
                .collect();
            match consts {
                Some(vals) if f.is_pure() => ExprKind::Num(apply_func(f, &vals, 0.0)),
                _ => ExprKind::Call(f, args),
            }
        }
        k => k,
    };
    Ok(Expr { kind, span })
}

pub fn apply_unary(op: UnOp, v: f64) -> f64 {
    match op {
        UnOp::Neg => -v,
        UnOp::Not => bool_f(v == 0.0),
    }
}

/// The arithmetic of the language. Division by zero is the caller's to
/// detect (it is an error, not infinity).
pub fn apply_binary(op: BinOp, x: f64, y: f64) -> f64 {
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

/// Built-in functions; trigonometry in degrees as in cpfg. `uniform` is a
/// draw in [0,1) used by `ran`.
pub fn apply_func(f: Func, a: &[f64], uniform: f64) -> f64 {
    let deg = std::f64::consts::PI / 180.0;
    match f {
        Func::Sin => (a[0] * deg).sin(),
        Func::Cos => (a[0] * deg).cos(),
        Func::Tan => (a[0] * deg).tan(),
        Func::Asin => a[0].asin() / deg,
        Func::Acos => a[0].acos() / deg,
        Func::Atan => a[0].atan() / deg,
        Func::Atan2 => a[0].atan2(a[1]) / deg,
        Func::Sqrt => a[0].sqrt(),
        Func::Exp => a[0].exp(),
        Func::Log => a[0].ln(),
        Func::Floor => a[0].floor(),
        Func::Ceil => a[0].ceil(),
        Func::Trunc => a[0].trunc(),
        Func::Abs => a[0].abs(),
        Func::Sign => {
            if a[0] > 0.0 {
                1.0
            } else if a[0] < 0.0 {
                -1.0
            } else {
                0.0
            }
        }
        Func::Min => a[0].min(a[1]),
        Func::Max => a[0].max(a[1]),
        Func::Ran => a[0] * uniform,
    }
}

fn bool_f(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}
