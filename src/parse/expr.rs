//! Expressions: the flat operator/operand pairs of an `expr` (or of the
//! paper's arrowless condition) -> an [`Expr`] tree, by precedence
//! climbing with C's precedences and `^` as right-associative power.

use std::sync::LazyLock;

use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};

use super::ast::*;
use super::error::{PResult, ParseError};
use super::lower::Lower;
use super::Rule;

static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::or, Assoc::Left))
        .op(Op::infix(Rule::and, Assoc::Left))
        .op(Op::infix(Rule::eq, Assoc::Left) | Op::infix(Rule::ne, Assoc::Left))
        .op(Op::infix(Rule::lt, Assoc::Left)
            | Op::infix(Rule::le, Assoc::Left)
            | Op::infix(Rule::gt, Assoc::Left)
            | Op::infix(Rule::ge, Assoc::Left))
        .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
        .op(Op::infix(Rule::mul, Assoc::Left)
            | Op::infix(Rule::div, Assoc::Left)
            | Op::infix(Rule::rem, Assoc::Left))
        .op(Op::prefix(Rule::neg)
            | Op::prefix(Rule::pos)
            | Op::prefix(Rule::not)
            | Op::prefix(Rule::stray_backslash))
        .op(Op::infix(Rule::pow, Assoc::Right))
});

impl Lower<'_> {
    /// Lowers an `expr` pair.
    pub fn expr(&self, e: Pair<Rule>) -> PResult<Expr> {
        let mut inner = e.into_inner();
        // A lone operand, as most arguments are: no list of parts.
        if inner.len() == 1 {
            return self.primary(super::lower::next(&mut inner));
        }
        let mut parts: Vec<Pair<Rule>> = inner.collect();
        let ternary = match parts.last() {
            Some(p) if p.as_rule() == Rule::ternary => parts.pop(),
            _ => None,
        };
        let cond = self.climb(parts)?;
        match ternary {
            None => Ok(cond),
            Some(t) => {
                let tspan = self.span(&t);
                let mut arms = t.into_inner();
                let a = self.expr(super::lower::next(&mut arms))?;
                let b = self.expr(super::lower::next(&mut arms))?;
                Ok(Expr {
                    span: cond.span.to(tspan),
                    kind: ExprKind::Ternary(Box::new(cond), Box::new(a), Box::new(b)),
                })
            }
        }
    }

    /// Lowers the paper's arrowless condition (`i == 1 and j == 1`).
    pub fn paper_cond(&self, c: Pair<Rule>) -> PResult<Expr> {
        let mut flat = Vec::new();
        for part in c.into_inner() {
            match part.as_rule() {
                Rule::paper_cmp => {
                    for side in part.into_inner() {
                        match side.as_rule() {
                            Rule::paper_arith => flat.extend(side.into_inner()),
                            _ => flat.push(side),
                        }
                    }
                }
                _ => flat.push(part),
            }
        }
        self.climb(flat)
    }

    fn climb(&self, mut parts: Vec<Pair<Rule>>) -> PResult<Expr> {
        // A lone operand (a ternary's condition) is what the Pratt parser
        // would make of it, without its set-up.
        if parts.len() == 1 {
            return self.primary(parts.pop().expect("one part"));
        }
        PRATT
            .map_primary(|p| self.primary(p))
            .map_prefix(|op, rhs| {
                let rhs = rhs?;
                let o = match op.as_rule() {
                    Rule::neg => UnaryOp::Neg,
                    Rule::pos | Rule::stray_backslash => UnaryOp::Pos,
                    _ => UnaryOp::Not,
                };
                Ok(Expr {
                    span: self.span(&op).to(rhs.span),
                    kind: ExprKind::Unary(o, Box::new(rhs)),
                })
            })
            .map_infix(|lhs, op, rhs| {
                let (lhs, rhs) = (lhs?, rhs?);
                let o = match op.as_rule() {
                    Rule::add => BinaryOp::Add,
                    Rule::sub => BinaryOp::Sub,
                    Rule::mul => BinaryOp::Mul,
                    Rule::div => BinaryOp::Div,
                    Rule::rem => BinaryOp::Rem,
                    Rule::pow => BinaryOp::Pow,
                    Rule::lt => BinaryOp::Lt,
                    Rule::le => BinaryOp::Le,
                    Rule::gt => BinaryOp::Gt,
                    Rule::ge => BinaryOp::Ge,
                    Rule::eq => BinaryOp::Eq,
                    Rule::ne => BinaryOp::Ne,
                    Rule::and => BinaryOp::And,
                    Rule::or => BinaryOp::Or,
                    other => unreachable!("{other:?} is not an infix operator"),
                };
                Ok(Expr {
                    span: lhs.span.to(rhs.span),
                    kind: ExprKind::Binary(o, Box::new(lhs), Box::new(rhs)),
                })
            })
            .parse(parts.into_iter())
    }

    /// An argument of a call or a module: an expression or a string.
    pub fn arg(&self, a: Pair<Rule>) -> PResult<Expr> {
        if a.as_rule() == Rule::string_lit {
            Ok(Expr {
                span: self.span(&a),
                kind: ExprKind::Str(a.as_str().to_string()),
            })
        } else {
            self.expr(a)
        }
    }

    pub(super) fn primary(&self, p: Pair<Rule>) -> PResult<Expr> {
        let span = self.span(&p);
        let kind = match p.as_rule() {
            Rule::number => {
                let v: f64 = p.as_str().parse().map_err(|_| {
                    Box::new(ParseError::bad_number(
                        self.file,
                        span,
                        "it is not a valid number",
                    ))
                })?;
                if !v.is_finite() {
                    return Err(Box::new(ParseError::bad_number(
                        self.file,
                        span,
                        "it is too large for a 64-bit float",
                    )));
                }
                ExprKind::Num(v)
            }
            Rule::ident => ExprKind::Name(p.as_str().to_string()),
            Rule::call => {
                let mut it = p.into_inner();
                let name = self.ident(super::lower::next(&mut it));
                let args = super::lower::next(&mut it)
                    .into_inner()
                    .map(|a| self.arg(a))
                    .collect::<Result<_, _>>()?;
                ExprKind::Call(name, args)
            }
            Rule::index => {
                let mut it = p.into_inner();
                let name = self.ident(super::lower::next(&mut it));
                let mut args = Vec::new();
                for group in it {
                    for a in group.into_inner() {
                        args.push(self.expr(a)?);
                    }
                }
                ExprKind::Index(name, args)
            }
            Rule::expr => return self.expr(p),
            other => unreachable!("{other:?} is not a primary"),
        };
        Ok(Expr { kind, span })
    }
}
