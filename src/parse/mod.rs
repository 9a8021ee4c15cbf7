//! Parse: the text of one source file -> [`ast::File`] plus every syntax
//! error in it.
//!
//! The pest grammar (`grammar/lsys.pest`) is run one statement at a time.
//! When a statement fails, the error is recorded and parsing resumes at the
//! next line that starts a statement, so one run reports all the file's
//! syntax errors instead of stopping at the first.

pub mod ast;
mod error;
mod expr;
mod lower;

use pest::Parser;
use pest_derive::Parser;

pub use error::ParseError;

use crate::source::{FileId, SourceFile, Span};

#[derive(Parser)]
#[grammar = "../grammar/lsys.pest"]
pub(crate) struct LsysParser;

/// Parses one file. Always returns a tree (of the statements that parsed)
/// together with the errors of those that did not.
pub fn parse(file_id: FileId, file: &SourceFile) -> (ast::File, Vec<ParseError>) {
    let text = file.text.as_str();
    let mut items = Vec::new();
    let mut errors = Vec::new();
    let mut pos = 0;
    loop {
        pos = match skip_blank(text, pos) {
            Ok(p) => p,
            Err(start) => {
                errors.push(ParseError::unclosed_comment(
                    file,
                    Span::new(file_id, start, start + 2),
                ));
                break;
            }
        };
        if pos >= text.len() {
            break;
        }
        let rest = &text[pos..];
        match LsysParser::parse(Rule::statement, rest) {
            Ok(mut pairs) => {
                let pair = pairs.next().expect("statement rule yields one pair");
                let end = pos + pair.as_span().end();
                let is_define =
                    pair.clone().into_inner().next().map(|p| p.as_rule()) == Some(Rule::define);
                let lower = lower::Lower {
                    file_id,
                    base: pos,
                    file,
                };
                match lower.statement(pair) {
                    Ok(item) => items.push(item),
                    Err(e) => errors.push(*e),
                }
                let after = skip_inline(text, end);
                if after < text.len() && text.as_bytes()[after] != b'\n' {
                    errors.push(ParseError::trailing(file, file_id, after, is_define));
                    pos = next_statement(text, after);
                } else {
                    pos = after;
                }
            }
            Err(e) => {
                let err = ParseError::from_pest(file, file_id, pos, &e);
                let at = err.offset();
                errors.push(err);
                pos = next_statement(text, at.max(pos));
            }
        }
    }
    (ast::File { items }, errors)
}

/// Parses the value of a `-D NAME=VALUE` override or a REPL expression.
pub fn parse_expr(file_id: FileId, file: &SourceFile) -> Result<ast::Expr, Box<ParseError>> {
    let text = file.text.as_str();
    match LsysParser::parse(Rule::expr_only, text) {
        Ok(mut pairs) => {
            let only = pairs.next().expect("expr_only yields one pair");
            let e = only
                .into_inner()
                .next()
                .expect("expr_only contains an expr");
            lower::Lower {
                file_id,
                base: 0,
                file,
            }
            .expr(e)
        }
        Err(e) => Err(Box::new(ParseError::from_pest(file, file_id, 0, &e))),
    }
}

/// A `-D` value: an expression (`Err` side of the result's `Ok`) or the
/// flattened elements of a braced table list (`Ok`).
pub fn parse_define_value(
    file_id: FileId,
    file: &SourceFile,
) -> Result<Result<Vec<ast::Expr>, ast::Expr>, Box<ParseError>> {
    match LsysParser::parse(Rule::define_value, file.text.as_str()) {
        Ok(mut pairs) => {
            let v = pairs
                .next()
                .and_then(|p| p.into_inner().next())
                .expect("define_value holds a value");
            let lower = lower::Lower {
                file_id,
                base: 0,
                file,
            };
            if v.as_rule() == Rule::table_values {
                let mut out = Vec::new();
                lower.table_values(v, &mut out)?;
                Ok(Ok(out))
            } else {
                Ok(Err(lower.expr(v)?))
            }
        }
        Err(e) => Err(Box::new(ParseError::from_pest(file, file_id, 0, &e))),
    }
}

/// Skips white space, newlines and comments. `Err(start)` for a block
/// comment that is never closed.
fn skip_blank(text: &str, mut pos: usize) -> Result<usize, usize> {
    loop {
        pos = skip_inline(text, pos);
        let rest = &text[pos..];
        if rest.starts_with('\n') {
            pos += 1;
        } else if rest.starts_with('\u{FEFF}') {
            pos += '\u{FEFF}'.len_utf8();
        } else if rest.starts_with("/*") {
            // skip_inline stops at a block comment only when it is unclosed.
            return Err(pos);
        } else {
            return Ok(pos);
        }
    }
}

/// Skips spaces, tabs and comments on the current line.
fn skip_inline(text: &str, mut pos: usize) -> usize {
    let b = text.as_bytes();
    loop {
        while pos < b.len() && matches!(b[pos], b' ' | b'\t' | b'\r') {
            pos += 1;
        }
        if text[pos..].starts_with("//") {
            pos = text[pos..].find('\n').map_or(text.len(), |i| pos + i);
        } else if text[pos..].starts_with("/*") {
            match text[pos + 2..].find("*/") {
                Some(i) => pos = pos + 2 + i + 2,
                None => return pos,
            }
        } else {
            return pos;
        }
    }
}

/// After an error at `at`: the start of the next unindented line. Indented
/// lines continue the broken statement and would only repeat its error.
fn next_statement(text: &str, at: usize) -> usize {
    let mut pos = text[at..].find('\n').map_or(text.len(), |i| at + i + 1);
    while pos < text.len() && matches!(text.as_bytes()[pos], b' ' | b'\t') {
        pos = text[pos..].find('\n').map_or(text.len(), |i| pos + i + 1);
    }
    pos
}
