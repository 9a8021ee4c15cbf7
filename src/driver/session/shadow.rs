//! Rules that can never apply: the main productions, in order -> for a
//! rule, an earlier one for the same predecessor that applies whenever it
//! would. Productions are tried in order and the first that matches
//! applies, so such a rule is dead; the REPL says so when one is typed
//! and `:rules` marks it. Only what can be decided from the text is
//! caught: no condition, an equal condition, a conjunction that contains
//! it, or a comparison of a parameter with a number that implies it
//! (`x > 3` implies `x > 0`).

use super::same::{expr_eq, is_catch_all, pred_eq, rctx_eq};
use crate::parse::ast::BinaryOp;
use crate::resolve::{Cond, Expr, ExprKind, Production};

/// The earlier production (index into `prods`) that always applies
/// before `prods[j]` can, if there is one.
pub(super) fn shadowed_by(prods: &[Production], j: usize) -> Option<usize> {
    (0..j).find(|&i| covers(&prods[i], &prods[j]))
}

/// Whether [`shadowed_by`] finds a rule that resolve does not already
/// warn about (resolve reports rules after a catch-all production).
pub(super) fn shadowed_beyond_resolve(prods: &[Production], j: usize) -> Option<usize> {
    shadowed_by(prods, j).filter(|&i| !is_catch_all(&prods[i]))
}

/// Whether `a`, earlier, applies wherever `b` would.
fn covers(a: &Production, b: &Production) -> bool {
    let ctx = (a.lctx.is_empty() || pred_eq(&a.lctx, &b.lctx))
        && (a.rctx.is_empty() || rctx_eq(&a.rctx, &b.rctx));
    let cond = match (&a.cond, &b.cond) {
        // `else` applies when nothing before it did: after it, nothing.
        (Cond::Always | Cond::Else(_), _) => true,
        (Cond::Expr(ca), Cond::Expr(cb)) => implies(cb, ca),
        _ => false,
    };
    pred_eq(&a.pred, &b.pred) && a.prob.is_none() && b.prob.is_none() && ctx && cond
}

/// Whether `b` true implies `a` true, as far as the text shows.
fn implies(b: &Expr, a: &Expr) -> bool {
    use ExprKind::*;
    if expr_eq(a, b) {
        return true;
    }
    match (&b.kind, &a.kind) {
        (Binary(BinaryOp::And, l, r), _) => implies(l, a) || implies(r, a),
        (_, Binary(BinaryOp::Or, l, r)) => implies(b, l) || implies(b, r),
        (Binary(ob, pb, cb), Binary(oa, pa, ca)) => {
            match (&pb.kind, &cb.kind, &pa.kind, &ca.kind) {
                (Param(x), Num(nb), Param(y), Num(na)) if x == y => {
                    bound_implies(*ob, *nb, *oa, *na)
                }
                _ => false,
            }
        }
        _ => false,
    }
}

/// `p ob nb` implies `p oa na`.
fn bound_implies(ob: BinaryOp, nb: f64, oa: BinaryOp, na: f64) -> bool {
    use BinaryOp::*;
    match (ob, oa) {
        (Gt, Gt) | (Gt, Ge) | (Ge, Ge) => nb >= na,
        (Ge, Gt) => nb > na,
        (Lt, Lt) | (Lt, Le) | (Le, Le) => nb <= na,
        (Le, Lt) => nb < na,
        (Eq, Gt) => nb > na,
        (Eq, Ge) => nb >= na,
        (Eq, Lt) => nb < na,
        (Eq, Le) => nb <= na,
        (Eq, Eq) => nb == na,
        (Eq, Ne) => nb != na,
        _ => false,
    }
}
