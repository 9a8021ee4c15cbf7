//! Constant folding: a resolved expression -> the same expression with
//! every constant sub-expression computed. Arithmetic is IEEE f64, the same
//! operations the VM performs, so a folded value is exactly
//! what the VM would have computed (functions go through the VM's own
//! table, `lang::builtins::call`).

use std::sync::Arc;

use super::error::ResolveError;
use super::ir::{BinOp, Expr, ExprKind, TableDef, UnOp};
use crate::source::SourceMap;

/// `e` folded: the same tree where nothing in it is constant.
pub fn fold(e: Expr, sources: &SourceMap, tables: &[TableDef]) -> Result<Expr, Box<ResolveError>> {
    Ok(folded(&e, sources, tables)?.unwrap_or(e))
}

/// `e` with its constant parts computed, or `None` when there are none.
/// A sub-tree that folding leaves alone is kept, not copied: a define's
/// expansion, folded once and shared by its uses (`resolve::expr`), is
/// walked again at each use but allocates nothing.
pub(super) fn folded(
    e: &Expr,
    sources: &SourceMap,
    tables: &[TableDef],
) -> Result<Option<Expr>, Box<ResolveError>> {
    let span = e.span;
    let kind = match &e.kind {
        ExprKind::Unary(op, a) => {
            let fa = child(a, sources, tables)?;
            match &fa.as_ref().unwrap_or(a).kind {
                ExprKind::Num(v) => ExprKind::Num(apply_unary(*op, *v)),
                _ if fa.is_none() => return Ok(None),
                _ => ExprKind::Unary(*op, kept(fa, a)),
            }
        }
        ExprKind::Binary(op, a, b) => {
            let (fa, fb) = (child(a, sources, tables)?, child(b, sources, tables)?);
            let (ra, rb) = (fa.as_ref().unwrap_or(a), fb.as_ref().unwrap_or(b));
            match (op, &ra.kind, &rb.kind) {
                (BinOp::Div | BinOp::Rem, _, ExprKind::Num(z)) if *z == 0.0 => {
                    return Err(Box::new(ResolveError::DivisionByZero {
                        src: sources.named_source(rb.span),
                        span: rb.span.into(),
                    }))
                }
                (_, ExprKind::Num(x), ExprKind::Num(y)) => ExprKind::Num(apply_binary(*op, *x, *y)),
                // A constant left side decides `&&` / `||` alone when it can.
                (BinOp::And, ExprKind::Num(x), _) if *x == 0.0 => ExprKind::Num(0.0),
                (BinOp::Or, ExprKind::Num(x), _) if *x != 0.0 => ExprKind::Num(1.0),
                _ if fa.is_none() && fb.is_none() => return Ok(None),
                _ => ExprKind::Binary(*op, kept(fa, a), kept(fb, b)),
            }
        }
        ExprKind::Cond(c, a, b) => {
            let fc = child(c, sources, tables)?;
            let (fa, fb) = (child(a, sources, tables)?, child(b, sources, tables)?);
            match fc.as_ref().unwrap_or(c).kind {
                ExprKind::Num(v) => {
                    let (f, r) = if v != 0.0 { (fa, a) } else { (fb, b) };
                    return Ok(Some(f.map_or_else(|| Expr::clone(r), Arc::unwrap_or_clone)));
                }
                _ if fc.is_none() && fa.is_none() && fb.is_none() => return Ok(None),
                _ => ExprKind::Cond(kept(fc, c), kept(fa, a), kept(fb, b)),
            }
        }
        ExprKind::Call(f, args) => {
            let (new, consts) = list(args, sources, tables)?;
            match consts {
                // The VM's own function table, so a folded value is bit for bit
                // what the VM computes at run time.
                Some(vals) if f.is_pure() => ExprKind::Num(crate::lang::builtins::call(
                    *f,
                    vals[0],
                    vals.get(1).copied().unwrap_or(0.0),
                )),
                _ => match new {
                    Some(args) => ExprKind::Call(*f, args),
                    None => return Ok(None),
                },
            }
        }
        ExprKind::Index(id, args) => {
            let (new, consts) = list(args, sources, tables)?;
            let args = new.as_deref().unwrap_or(args);
            let t = &tables[*id as usize];
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
                None => match new {
                    Some(args) => ExprKind::Index(*id, args),
                    None => return Ok(None),
                },
            }
        }
        _ => return Ok(None),
    };
    Ok(Some(Expr { kind, span }))
}

/// A sub-tree folded, or `None` when folding leaves it as it is.
fn child(
    a: &Arc<Expr>,
    sources: &SourceMap,
    tables: &[TableDef],
) -> Result<Option<Arc<Expr>>, Box<ResolveError>> {
    Ok(folded(a, sources, tables)?.map(Arc::new))
}

/// The folded sub-tree, or the one that was there.
fn kept(folded: Option<Arc<Expr>>, was: &Arc<Expr>) -> Arc<Expr> {
    folded.unwrap_or_else(|| Arc::clone(was))
}

/// A list of arguments folded (`None`: none changed), and their values
/// when all are constants.
type Folded = (Option<Vec<Expr>>, Option<Vec<f64>>);

fn list(
    args: &[Expr],
    sources: &SourceMap,
    tables: &[TableDef],
) -> Result<Folded, Box<ResolveError>> {
    let mut new: Option<Vec<Expr>> = None;
    for (i, a) in args.iter().enumerate() {
        if let Some(f) = folded(a, sources, tables)? {
            new.get_or_insert_with(|| args[..i].to_vec()).push(f);
        } else if let Some(n) = &mut new {
            n.push(a.clone());
        }
    }
    let consts = new
        .as_deref()
        .unwrap_or(args)
        .iter()
        .map(|a| match a.kind {
            ExprKind::Num(v) => Some(v),
            _ => None,
        })
        .collect();
    Ok((new, consts))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::builtins::Func;
    use crate::source::{Origin, SourceFile, Span};

    fn sources() -> (SourceMap, Span) {
        let mut map = SourceMap::new();
        let file = map.add(SourceFile::new("t.lsys", Origin::Memory, "p / 0 + 2 * 3"));
        (map, Span::new(file, 0, 1))
    }

    fn e(kind: ExprKind, span: Span) -> Expr {
        Expr { kind, span }
    }

    fn bin(op: BinOp, a: Expr, b: Expr, span: Span) -> Expr {
        e(ExprKind::Binary(op, Arc::new(a), Arc::new(b)), span)
    }

    fn num(v: f64, span: Span) -> Expr {
        e(ExprKind::Num(v), span)
    }

    fn param(slot: u16, span: Span) -> Expr {
        e(ExprKind::Param(slot), span)
    }

    fn child_of(x: &Expr, right: bool) -> &Arc<Expr> {
        match &x.kind {
            ExprKind::Binary(_, a, b) => [a, b][right as usize],
            k => panic!("not a binary node: {k:?}"),
        }
    }

    #[test]
    fn a_tree_with_nothing_to_fold_is_kept_not_copied() {
        let (map, s) = sources();
        let shared = Arc::new(bin(BinOp::Mul, param(1, s), num(2.0, s), s));
        let whole = e(
            ExprKind::Binary(BinOp::Add, Arc::new(param(0, s)), shared.clone()),
            s,
        );
        assert_eq!(folded(&whole, &map, &[]).unwrap(), None);
        let out = fold(whole, &map, &[]).unwrap();
        assert!(Arc::ptr_eq(child_of(&out, true), &shared));
    }

    #[test]
    fn a_constant_part_is_computed_and_the_rest_kept() {
        let (map, s) = sources();
        let left = Arc::new(param(0, s));
        let right = bin(BinOp::Mul, num(2.0, s), num(3.0, s), s);
        let whole = e(
            ExprKind::Binary(BinOp::Add, left.clone(), Arc::new(right)),
            s,
        );
        let out = fold(whole, &map, &[]).unwrap();
        assert!(Arc::ptr_eq(child_of(&out, false), &left));
        assert_eq!(child_of(&out, true).kind, ExprKind::Num(6.0));
    }

    #[test]
    fn a_constant_condition_picks_its_branch_folded() {
        let (map, s) = sources();
        let then = bin(BinOp::Sub, num(5.0, s), num(1.0, s), s);
        let cond = e(
            ExprKind::Cond(Arc::new(num(1.0, s)), Arc::new(then), Arc::new(param(0, s))),
            s,
        );
        assert_eq!(fold(cond, &map, &[]).unwrap().kind, ExprKind::Num(4.0));
    }

    #[test]
    fn a_division_by_zero_is_found_in_a_tree_otherwise_left_alone() {
        let (map, s) = sources();
        let div = bin(BinOp::Div, param(0, s), num(0.0, s), s);
        let err = fold(div, &map, &[]).unwrap_err();
        assert!(
            matches!(*err, ResolveError::DivisionByZero { .. }),
            "{err:?}"
        );
    }

    #[test]
    fn arguments_fold_and_a_pure_call_of_constants_is_computed() {
        let (map, s) = sources();
        let call = e(
            ExprKind::Call(
                Func::Max,
                vec![bin(BinOp::Add, num(1.0, s), num(2.0, s), s), num(2.5, s)],
            ),
            s,
        );
        assert_eq!(fold(call, &map, &[]).unwrap().kind, ExprKind::Num(3.0));
        let kept = e(ExprKind::Call(Func::Max, vec![param(0, s)]), s);
        assert_eq!(folded(&kept, &map, &[]).unwrap(), None);
    }
}
