//! `#if` expressions. Input: the tokens after `#if`/`#elif`. Output: first
//! `defined X` replaced by 1 or 0 (before macro expansion, as C requires),
//! then, after the caller has expanded macros, the integer value of the
//! expression (i64 arithmetic that wraps instead of overflowing), or why it
//! has none.

use std::ops::Range;
use std::rc::Rc;

use super::macros::Macros;
use super::token::{Kind, Token};

/// Why an expression has no value.
#[derive(Debug)]
pub(crate) struct ExprError {
    pub span: Range<usize>,
    pub message: String,
    pub help: Option<String>,
}

fn err(span: Range<usize>, message: impl Into<String>) -> ExprError {
    ExprError {
        span,
        message: message.into(),
        help: None,
    }
}

/// Replaces `defined X` and `defined ( X )` by `1`/`0`.
pub(crate) fn replace_defined(toks: &[Token], macros: &Macros) -> Result<Vec<Token>, ExprError> {
    let mut out = Vec::with_capacity(toks.len());
    let mut i = 0;
    while i < toks.len() {
        let t = &toks[i];
        if !(t.is_ident() && &*t.text == "defined") {
            out.push(t.clone());
            i += 1;
            continue;
        }
        let (name, end) = match toks.get(i + 1) {
            Some(n) if n.is_ident() => (n, i + 2),
            Some(p) if p.is_punct("(") => match (toks.get(i + 2), toks.get(i + 3)) {
                (Some(n), Some(r)) if n.is_ident() && r.is_punct(")") => (n, i + 4),
                _ => {
                    return Err(err(
                        t.span.start..toks.get(i + 2).unwrap_or(p).span.end,
                        "`defined(` must be followed by a macro name and `)`",
                    ))
                }
            },
            _ => {
                return Err(err(
                    t.span.clone(),
                    "`defined` must be followed by a macro name",
                ))
            }
        };
        let yes = macros.contains_key(&name.text) || matches!(&*name.text, "__LINE__" | "__FILE__");
        out.push(Token {
            kind: Kind::Number,
            text: Rc::from(if yes { "1" } else { "0" }),
            span: t.span.start..name.span.end.max(t.span.start),
            ..t.clone()
        });
        i = end;
    }
    Ok(out)
}

/// How deeply parentheses and unary operators may nest (C requires 63;
/// more would risk the stack of a 2 MiB thread in debug builds).
const MAX_NESTING: usize = 64;

/// Evaluates a macro-expanded `#if` expression; `whole` is the span of the
/// directive, for errors at its end.
pub(crate) fn eval(toks: &[Token], whole: Range<usize>) -> Result<i64, ExprError> {
    if toks.is_empty() {
        return Err(err(whole, "#if with no expression"));
    }
    let mut p = Parser {
        toks,
        pos: 0,
        nesting: 0,
        end: whole.end..whole.end,
    };
    let v = p.comma(true)?;
    if let Some(t) = p.toks.get(p.pos) {
        return Err(err(
            t.span.clone(),
            format!("unexpected `{}` in #if expression", t.text),
        ));
    }
    Ok(v)
}

struct Parser<'a> {
    toks: &'a [Token],
    pos: usize,
    nesting: usize,
    end: Range<usize>,
}

/// Binary operators from loosest to tightest binding (below `?:`).
const LEVELS: &[&[&str]] = &[
    &["||"],
    &["&&"],
    &["|"],
    &["^"],
    &["&"],
    &["==", "!="],
    &["<", ">", "<=", ">="],
    &["<<", ">>"],
    &["+", "-"],
    &["*", "/", "%"],
];

impl Parser<'_> {
    fn peek_punct(&self, p: &str) -> bool {
        self.toks.get(self.pos).is_some_and(|t| t.is_punct(p))
    }

    fn span_here(&self) -> Range<usize> {
        self.toks
            .get(self.pos)
            .map_or(self.end.clone(), |t| t.span.clone())
    }

    fn comma(&mut self, ev: bool) -> Result<i64, ExprError> {
        let mut v = self.cond(ev)?;
        while self.peek_punct(",") {
            self.pos += 1;
            v = self.cond(ev)?;
        }
        Ok(v)
    }

    fn cond(&mut self, ev: bool) -> Result<i64, ExprError> {
        let c = self.binary(0, ev)?;
        if !self.peek_punct("?") {
            return Ok(c);
        }
        self.pos += 1;
        self.enter()?;
        let a = self.comma(ev && c != 0)?;
        if !self.peek_punct(":") {
            return Err(err(
                self.span_here(),
                "expected `:` in `?:` in #if expression",
            ));
        }
        self.pos += 1;
        let b = self.cond(ev && c == 0)?;
        self.nesting -= 1;
        Ok(if c != 0 { a } else { b })
    }

    fn enter(&mut self) -> Result<(), ExprError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(err(self.span_here(), "#if expression nested too deeply"));
        }
        Ok(())
    }

    fn binary(&mut self, level: usize, ev: bool) -> Result<i64, ExprError> {
        let Some(ops) = LEVELS.get(level) else {
            return self.unary(ev);
        };
        let mut l = self.binary(level + 1, ev)?;
        loop {
            let Some(op) = self
                .toks
                .get(self.pos)
                .filter(|t| t.kind == Kind::Punct && ops.contains(&&*t.text))
            else {
                return Ok(l);
            };
            let op_span = op.span.clone();
            let op: &str = &op.text.clone();
            self.pos += 1;
            // The right side of `&&`/`||` is parsed but only evaluated when needed.
            let ev_r = match op {
                "&&" => ev && l != 0,
                "||" => ev && l == 0,
                _ => ev,
            };
            let r = self.binary(level + 1, ev_r)?;
            l = match op {
                "||" => i64::from(l != 0 || r != 0),
                "&&" => i64::from(l != 0 && r != 0),
                "|" => l | r,
                "^" => l ^ r,
                "&" => l & r,
                "==" => i64::from(l == r),
                "!=" => i64::from(l != r),
                "<" => i64::from(l < r),
                ">" => i64::from(l > r),
                "<=" => i64::from(l <= r),
                ">=" => i64::from(l >= r),
                "<<" => shift(l, r),
                ">>" => shift(l, r.wrapping_neg()),
                "+" => l.wrapping_add(r),
                "-" => l.wrapping_sub(r),
                "*" => l.wrapping_mul(r),
                _ => {
                    if r == 0 {
                        if ev {
                            return Err(err(op_span, "division by zero in #if expression"));
                        }
                        0
                    } else if op == "/" {
                        l.wrapping_div(r)
                    } else {
                        l.wrapping_rem(r)
                    }
                }
            };
        }
    }

    fn unary(&mut self, ev: bool) -> Result<i64, ExprError> {
        let Some(t) = self.toks.get(self.pos) else {
            return Err(err(self.end.clone(), "#if expression ends too early"));
        };
        if t.kind == Kind::Punct && matches!(&*t.text, "!" | "~" | "-" | "+") {
            let op = t.text.clone();
            self.pos += 1;
            self.enter()?;
            let v = self.unary(ev)?;
            self.nesting -= 1;
            return Ok(match &*op {
                "!" => i64::from(v == 0),
                "~" => !v,
                "-" => v.wrapping_neg(),
                _ => v,
            });
        }
        self.pos += 1;
        match t.kind {
            Kind::Number => number(t),
            // Identifiers left after expansion count as 0.
            Kind::Ident => Ok(0),
            Kind::Punct if t.is_punct("(") => {
                self.enter()?;
                let v = self.comma(ev)?;
                if !self.peek_punct(")") {
                    return Err(err(self.span_here(), "expected `)` in #if expression"));
                }
                self.pos += 1;
                self.nesting -= 1;
                Ok(v)
            }
            _ => Err(err(
                t.span.clone(),
                format!("unexpected `{}` in #if expression", t.text),
            )),
        }
    }
}

/// `l << r` for any `r` (negative shifts right); shifting everything out gives 0 or -1.
fn shift(l: i64, r: i64) -> i64 {
    if r >= 0 {
        if r >= 64 {
            0
        } else {
            l.wrapping_shl(r as u32)
        }
    } else {
        let r = r.unsigned_abs();
        if r >= 64 {
            if l < 0 {
                -1
            } else {
                0
            }
        } else {
            l >> r
        }
    }
}

fn number(t: &Token) -> Result<i64, ExprError> {
    let s = t.text.trim_end_matches(['u', 'U', 'l', 'L']);
    let (digits, radix) = if let Some(h) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        (h, 16)
    } else if s.len() > 1 && s.starts_with('0') {
        (&s[1..], 8)
    } else {
        (s, 10)
    };
    let float = radix != 16 && s.contains(['.', 'e', 'E']);
    if float {
        return Err(ExprError {
            span: t.span.clone(),
            message: format!("`{}` is not an integer; #if only evaluates integer constants", t.text),
            help: Some("#if cannot compare fractions: define an integer flag for the condition (e.g. `#define BIG 1`), or use #ifdef".into()),
        });
    }
    match u64::from_str_radix(digits, radix) {
        Ok(v) => Ok(v as i64),
        Err(e) => Err(err(
            t.span.clone(),
            if matches!(e.kind(), std::num::IntErrorKind::PosOverflow) {
                format!("integer constant `{}` is too large for #if", t.text)
            } else {
                format!("`{}` is not a valid integer constant", t.text)
            },
        )),
    }
}
