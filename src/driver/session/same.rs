//! Comparing productions: whether two rules have the same predecessor,
//! contexts, condition or expressions, spans aside. Input: resolved
//! productions; output: yes or no. Used by the edits (a typed rule that
//! replaces one) and by the shadowing check.

use crate::resolve::{Cond, Expr, ExprKind, PatItem, PatModule, Production};

/// A production with no context, no probability and no condition (or
/// `else`): once it is reached, nothing after it for the same predecessor
/// applies.
pub(super) fn is_catch_all(p: &Production) -> bool {
    p.lctx.is_empty()
        && p.rctx.is_empty()
        && p.prob.is_none()
        && matches!(p.cond, Cond::Always | Cond::Else(_))
}

pub(super) fn pred_eq(a: &[PatModule], b: &[PatModule]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.sym == y.sym && x.arity == y.arity)
}

/// Whether typing `new` replaces `old`: same predecessor, contexts and
/// condition; with probabilities, also the same successor.
pub(super) fn same_rule(old: &Production, new: &Production) -> bool {
    let rctx_eq = rctx_eq(&old.rctx, &new.rctx);
    let cond_eq = match (&old.cond, &new.cond) {
        (Cond::Always, Cond::Always) | (Cond::Else(_), Cond::Else(_)) => true,
        (Cond::Expr(a), Cond::Expr(b)) => expr_eq(a, b),
        _ => false,
    };
    let prob_eq = match (&old.prob, &new.prob) {
        (None, None) => true,
        (Some(_), Some(_)) => {
            old.succ.len() == new.succ.len()
                && old.succ.iter().zip(&new.succ).all(|(a, b)| {
                    a.sym == b.sym
                        && a.args.len() == b.args.len()
                        && a.args.iter().zip(&b.args).all(|(x, y)| expr_eq(x, y))
                })
        }
        _ => false,
    };
    pred_eq(&old.lctx, &new.lctx) && pred_eq(&old.pred, &new.pred) && rctx_eq && cond_eq && prob_eq
}

/// Equal right contexts (modules and brackets).
pub(super) fn rctx_eq(a: &[PatItem], b: &[PatItem]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| match (x, y) {
            (PatItem::Module(a), PatItem::Module(b)) => a.sym == b.sym && a.arity == b.arity,
            (PatItem::Open(_), PatItem::Open(_)) | (PatItem::Close(_), PatItem::Close(_)) => true,
            _ => false,
        })
}

/// Structural equality of expressions, spans aside (parameters compare by
/// slot, so `A(x) : x > 1` and `A(y) : y > 1` are the same condition).
pub(super) fn expr_eq(a: &Expr, b: &Expr) -> bool {
    use ExprKind::*;
    match (&a.kind, &b.kind) {
        (Num(x), Num(y)) => x == y || (x.is_nan() && y.is_nan()),
        (Param(x), Param(y)) => x == y,
        (Unary(o, x), Unary(p, y)) => o == p && expr_eq(x, y),
        (Binary(o, x1, x2), Binary(p, y1, y2)) => o == p && expr_eq(x1, y1) && expr_eq(x2, y2),
        (Cond(x1, x2, x3), Cond(y1, y2, y3)) => {
            expr_eq(x1, y1) && expr_eq(x2, y2) && expr_eq(x3, y3)
        }
        (Call(f, xs), Call(g, ys)) => {
            f == g && xs.len() == ys.len() && xs.iter().zip(ys).all(|(x, y)| expr_eq(x, y))
        }
        _ => false,
    }
}
