//! cpfg's C-like statement blocks: the text of one `{ ... }` block (as
//! captured by the statement grammar) in, an AST [`Block`] out.
//!
//! The statement grammar keeps newlines significant, but inside a block a
//! statement may span lines (`xl0 =\n  func(14, x);`). So the block is parsed
//! a second time, from `c_block_only`, after its comments and line breaks
//! are blanked to spaces byte for byte: every span still points at the
//! same bytes of the file.

use pest::iterators::Pair;
use pest::Parser;

use super::ast::*;
use super::error::PResult;
use super::lower::{next, Lower};
use super::{LsysParser, ParseError, Rule};

/// The block's text with comments and line breaks replaced by spaces, each
/// byte of them by one space (so offsets do not move; a multi-byte
/// character inside a comment becomes several spaces).
fn blank(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                out.push(b' ');
                i += 1;
            }
        } else if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
            let end = text[i + 2..].find("*/").map_or(b.len(), |k| i + 2 + k + 2);
            while i < end {
                out.push(if b[i] == b'\n' { b'\n' } else { b' ' });
                i += 1;
            }
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    // A backslash means nothing in a statement: cpfg's scanner passes over
    // one (left, e.g., by a `#define f(x) \\` whose body starts on the
    // next line).
    for c in out.iter_mut() {
        if *c == b'\n' || *c == b'\r' || *c == b'\\' {
            *c = b' ';
        }
    }
    // Only ASCII bytes were replaced, and whole characters at that (a
    // comment's multi-byte characters are all replaced), so this holds.
    String::from_utf8(out).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

impl Lower<'_> {
    /// Lower a `brace_block` pair: parse its text again as statements.
    pub fn block(&self, p: Pair<Rule>) -> PResult<Block> {
        let span = self.span(&p);
        let text = blank(p.as_str());
        let start = span.start as usize;
        let pairs = LsysParser::parse(Rule::c_block_only, &text)
            .map_err(|e| Box::new(ParseError::from_pest(self.file, self.file_id, start, &e)))?;
        let sub = Lower {
            file_id: self.file_id,
            base: start,
            file: self.file,
        };
        let only = pairs
            .into_iter()
            .next()
            .expect("c_block_only yields one pair");
        let block = next(&mut only.into_inner());
        Ok(Block {
            stmts: sub.stmts(block)?,
            span,
        })
    }

    /// The statements of a `c_block`, or the single statement of a body.
    fn stmts(&self, p: Pair<Rule>) -> PResult<Vec<CStmt>> {
        match p.as_rule() {
            Rule::c_block => p.into_inner().map(|s| self.stmt(s)).collect(),
            Rule::c_body => self.stmts(next(&mut p.into_inner())),
            _ => Ok(vec![self.stmt(p)?]),
        }
    }

    fn stmt(&self, p: Pair<Rule>) -> PResult<CStmt> {
        let span = self.span(&p);
        let rule = p.as_rule();
        let mut it = p.into_inner();
        Ok(match rule {
            Rule::c_assign => {
                let lv = next(&mut it);
                let lv_span = self.span(&lv);
                let mut parts = lv.into_inner();
                let name = self.ident(next(&mut parts));
                let index = parts
                    .map(|d| self.expr(next(&mut d.into_inner())))
                    .collect::<Result<_, _>>()?;
                let op = match next(&mut it).as_str() {
                    "+=" => AssignOp::Add,
                    "-=" => AssignOp::Sub,
                    "*=" => AssignOp::Mul,
                    "/=" => AssignOp::Div,
                    _ => AssignOp::Set,
                };
                let value = self.expr(next(&mut it))?;
                CStmt::Assign {
                    target: LValue {
                        name,
                        index,
                        span: lv_span,
                    },
                    op,
                    value,
                    span,
                }
            }
            Rule::c_expr_stmt => CStmt::Expr(self.expr(next(&mut it))?),
            // `;` alone: an `array` statement that declares nothing does
            // nothing too, and saves the tree a variant.
            Rule::c_empty => CStmt::Array(Vec::new()),
            Rule::c_if => {
                let _kw = next(&mut it);
                let cond = self.expr(next(&mut it))?;
                let then = self.stmts(next(&mut it))?;
                let els = match it.find(|q| q.as_rule() == Rule::c_body) {
                    Some(b) => self.stmts(b)?,
                    None => Vec::new(),
                };
                CStmt::If {
                    cond,
                    then,
                    els,
                    span,
                }
            }
            Rule::c_while => {
                let _kw = next(&mut it);
                let cond = self.expr(next(&mut it))?;
                let body = self.stmts(next(&mut it))?;
                CStmt::While { cond, body, span }
            }
            Rule::c_do => {
                let _kw = next(&mut it);
                let body = self.stmts(next(&mut it))?;
                let _kw = next(&mut it);
                let cond = self.expr(next(&mut it))?;
                CStmt::DoWhile { body, cond, span }
            }
            Rule::c_array => {
                let _kw = next(&mut it);
                CStmt::Array(it.map(|d| self.array_decl(d)).collect::<Result<_, _>>()?)
            }
            other => unreachable!("{other:?} is not a statement"),
        })
    }

    fn array_decl(&self, p: Pair<Rule>) -> PResult<ArrayDecl> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let name = self.ident(next(&mut it));
        let mut dims = Vec::new();
        let mut init = None;
        for q in it {
            match q.as_rule() {
                Rule::c_dim => dims.push(self.expr(next(&mut q.into_inner()))?),
                _ => {
                    let mut vals = Vec::new();
                    self.flatten_init(q, &mut vals)?;
                    init = Some(vals);
                }
            }
        }
        Ok(ArrayDecl {
            name,
            dims,
            init,
            span,
        })
    }

    fn flatten_init(&self, p: Pair<Rule>, out: &mut Vec<Expr>) -> PResult<()> {
        for q in p.into_inner() {
            if q.as_rule() == Rule::c_init {
                self.flatten_init(q, out)?;
            } else {
                out.push(self.expr(q)?);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::blank;

    #[test]
    fn blanking_keeps_offsets() {
        let t = "{ x = 1; // é\n /* a\n b */ y = 2; }";
        let b = blank(t);
        assert_eq!(b.len(), t.len());
        assert_eq!(b.find("y = 2"), t.find("y = 2"));
        assert!(!b.contains('\n'));
    }
}
