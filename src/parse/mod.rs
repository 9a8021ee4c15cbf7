//! Parse: the text of one source file -> [`ast::File`] plus every syntax
//! error in it.
//!
//! The pest grammar (`grammar/lsys.pest`) is run one statement at a time.
//! When a statement fails, the error is recorded and parsing resumes at the
//! next line that starts a statement, so one run reports all the file's
//! syntax errors instead of stopping at the first.

pub mod ast;
mod block;
mod error;
mod expr;
mod headers;
mod help;
mod long_axiom;
mod lower;
mod print;
pub mod stored;

use pest::iterators::Pairs;
use pest::Parser;
use pest_derive::Parser;

pub use error::ParseError;
pub use headers::HEADERS;
pub use long_axiom::axiom_piece;

use crate::source::{FileId, SourceFile, Span};

#[derive(Parser)]
#[grammar = "../grammar/lsys.pest"]
pub(crate) struct LsysParser;

/// Deepest nesting of `(` and `{` a file may have (`--max-nesting`).
pub const MAX_NESTING: usize = 256;
/// Most operators one expression (a parenthesised argument list or a
/// `#define` line) may have (`--max-operators`).
pub const MAX_OPERATORS: usize = 2000;
/// The options above may raise their limits this far and no further: the
/// CLI's 256 MiB stack holds this much recursion with room to spare.
pub const MAX_NESTING_CEILING: usize = 4096;
pub const MAX_OPERATORS_CEILING: usize = 100_000;

/// How deep and how long input the parser accepts (see `too_deep`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Deepest nesting of `(` and `{` (`--max-nesting`).
    pub max_nesting: usize,
    /// Most operators in one expression (`--max-operators`).
    pub max_operators: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_nesting: MAX_NESTING,
            max_operators: MAX_OPERATORS,
        }
    }
}

/// Finds input deep enough to exhaust the stack of the recursive parts of
/// the compiler (the PEG, the Pratt parser, resolve and folding), before
/// any of them runs: nesting of `(` and `{` deeper than [`MAX_NESTING`],
/// or an expression with more than [`MAX_OPERATORS`] operators.
fn too_deep(file: &SourceFile, file_id: FileId, limits: Limits) -> Option<ParseError> {
    let max_nesting = limits.max_nesting.min(MAX_NESTING_CEILING);
    let max_operators = limits.max_operators.min(MAX_OPERATORS_CEILING);
    let text = file.text.as_str();
    let b = text.as_bytes();
    let (mut depth, mut ops, mut in_define) = (0usize, 0usize, false);
    let mut line_start = true;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let err = |what: &str, limit: usize, option: &str| {
            Some(ParseError::TooDeep {
                what: what.to_string(),
                limit,
                option: option.to_string(),
                src: file.named_source(),
                span: Span::new(file_id, i, i + 1).into(),
                offset: i,
            })
        };
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        if c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i + 1 < b.len() && !(b[i] == b'*' && b[i + 1] == b'/') {
                i += 1;
            }
            i += 2;
            continue;
        }
        if line_start && !c.is_ascii_whitespace() {
            in_define = text[i..].starts_with("#define");
            line_start = false;
        }
        match c {
            b'\n' => {
                line_start = true;
                if depth == 0 {
                    ops = 0;
                    in_define = false;
                }
            }
            b'(' | b'{' => {
                depth += 1;
                if depth > max_nesting {
                    return err(
                        "nesting of parentheses and braces",
                        max_nesting,
                        "--max-nesting",
                    );
                }
            }
            b')' | b'}' => {
                depth = depth.saturating_sub(1);
                if depth == 0 && !in_define {
                    ops = 0;
                }
            }
            b'+' | b'-' | b'*' | b'/' | b'^' | b'%' | b'<' | b'>' | b'=' | b'!' | b'&' | b'|'
            | b'?'
                if depth > 0 || in_define =>
            {
                ops += 1;
                if ops > max_operators {
                    return err(
                        "the number of operators in one expression",
                        max_operators,
                        "--max-operators",
                    );
                }
            }
            _ => {}
        }
        i += 1;
    }
    None
}

/// `//` glued to a module on a production or axiom line (`F/////[`):
/// ABOP's run of rolls, silently cut off as a comment. Warnings.
fn slash_comments(file: &SourceFile, file_id: FileId) -> Vec<ParseError> {
    let text = file.text.as_str();
    let mut out = Vec::new();
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let code = line.trim_start();
        let is_rule = ["-->", "->", "→", "⟶"].iter().any(|a| line.contains(a))
            || code.starts_with("Axiom:")
            || code.starts_with("axiom:");
        if is_rule && !code.starts_with("//") && !code.starts_with('#') {
            if let Some(at) = line.find("//") {
                let before = line[..at].chars().next_back();
                let in_block = line[..at].contains("/*");
                if before.is_some_and(|c| !c.is_whitespace()) && !in_block {
                    let i = start + at;
                    out.push(ParseError::SlashComment {
                        src: file.named_source(),
                        span: Span::new(file_id, i, i + 2).into(),
                        offset: i,
                    });
                }
            }
        }
        start += line.len();
    }
    out
}

/// Parses one file. Always returns a tree (of the statements that parsed)
/// together with its errors and warnings (see [`crate::diag::is_error`]).
pub fn parse(file_id: FileId, file: &SourceFile) -> (ast::File, Vec<ParseError>) {
    parse_limited(file_id, file, Limits::default())
}

/// [`parse`] with the nesting and expression limits of `limits`.
pub fn parse_limited(
    file_id: FileId,
    file: &SourceFile,
    limits: Limits,
) -> (ast::File, Vec<ParseError>) {
    if let Some(e) = too_deep(file, file_id, limits) {
        return (
            ast::File {
                items: Vec::new(),
                broken: Vec::new(),
            },
            vec![e],
        );
    }
    // The standard library's files were parsed when the crate was built
    // (see `stored`): what a text shares with one is read, not parsed. A
    // library file itself parsed with no error or warning (build.rs stops
    // the build otherwise). Limits still apply, above.
    let reuse = match stored::reuse(file_id, &file.text) {
        Some(stored::Shared::Whole(items)) => {
            let tree = ast::File {
                items,
                broken: Vec::new(),
            };
            return (tree, Vec::new());
        }
        Some(stored::Shared::Parts(parts)) => Some(parts),
        None => None,
    };
    let (file_ast, mut errors, _) = parse_statements(file_id, file, reuse);
    errors.extend(slash_comments(file, file_id));
    errors.extend(headers::misspelt_headers(file, file_id));
    (file_ast, errors)
}

/// A standard library file's tree to store (`build.rs`), or the file's
/// errors and warnings: a library file must have none.
pub fn tree_to_store(file: &SourceFile) -> Result<stored::Stored, Vec<ParseError>> {
    let (tree, mut errors, bounds) = parse_statements(0, file, None);
    errors.extend(slash_comments(file, 0));
    errors.extend(headers::misspelt_headers(file, 0));
    if errors.is_empty() && tree.broken.is_empty() && bounds.len() == tree.items.len() {
        Ok(stored::Stored { tree, bounds })
    } else {
        Err(errors)
    }
}

/// The statements of `file`, its errors, and where each statement that
/// gave an item starts and ends (those parsed here: the statements `reuse`
/// has are taken from it, see `stored`).
fn parse_statements(
    file_id: FileId,
    file: &SourceFile,
    reuse: Option<stored::Reuse>,
) -> (ast::File, Vec<ParseError>, Vec<(u32, u32)>) {
    // As in C, everything after an unclosed `/*` is comment: the
    // statements are read up to it (else `A --> B /* note` would give the
    // modules `/ *` and errors that are consequences of the one mistake).
    let unclosed = unclosed_comment_at(&file.text);
    let text = &file.text[..unclosed.unwrap_or(file.text.len())];
    let mut items = Vec::new();
    let mut errors = Vec::new();
    let mut broken = Vec::new();
    let mut bounds = Vec::new();
    let mut pos = 0;
    let mut reuse = reuse;
    if let Some(r) = reuse.as_mut() {
        items = std::mem::take(&mut r.first);
        pos = r.resume;
    }
    loop {
        pos = match skip_blank(text, pos) {
            Ok(p) => p,
            // Reported below, with any unclosed `/*` after code.
            Err(_) => break,
        };
        if pos >= text.len() {
            break;
        }
        if let Some(last) = reuse.as_mut().and_then(|r| r.last_from(pos)) {
            items.extend(last);
            break;
        }
        if let Some((item, end)) = long_axiom::parse(file_id, file, pos)
            .filter(|&(_, end)| unclosed.map_or(true, |at| end <= at))
        {
            let after = skip_inline(text, end);
            if after >= text.len() || text.as_bytes()[after] == b'\n' {
                items.push(item);
                bounds.push((pos as u32, end as u32));
                pos = after;
                continue;
            }
        }
        let rest = &text[pos..];
        match parse_statement(rest) {
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
                    Ok(item) => {
                        items.push(item);
                        bounds.push((pos as u32, end as u32));
                    }
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
                let mut err = ParseError::from_pest(file, file_id, pos, &e);
                // Unless something more specific was found (`C => F` is
                // modules too, but a mistyped arrow).
                if err.has_only_generic_help() {
                    if let Some(end) = lost_indent(text, pos, items.last()) {
                        err = ParseError::lost_indent(file, Span::new(file_id, pos, end));
                    }
                }
                let at = err.offset();
                let line_end = text[pos..].find('\n').map_or(text.len(), |i| pos + i);
                broken.push(Span::new(file_id, pos, line_end));
                errors.push(err);
                pos = next_statement(text, at.max(pos));
            }
        }
    }
    if let Some(at) = unclosed {
        errors.push(ParseError::unclosed_comment(
            file,
            Span::new(file_id, at, at + 2),
        ));
    }
    (ast::File { items, broken }, errors, bounds)
}

/// Where the first `/*` without a matching `*/` begins, outside line
/// comments and double-quoted text, as the C preprocessor reads it.
fn unclosed_comment_at(text: &str) -> Option<usize> {
    let b = text.as_bytes();
    let mut i = 0;
    while i + 1 < b.len() {
        match (b[i], b[i + 1]) {
            (b'/', b'/') => i = text[i..].find('\n').map_or(b.len(), |k| i + k),
            (b'/', b'*') => match text[i + 2..].find("*/") {
                Some(k) => i += 2 + k + 2,
                None => return Some(i),
            },
            (b'"', _) => {
                let rest = &b[i + 1..];
                let end = rest.iter().position(|&c| c == b'"' || c == b'\n');
                i += 1 + end.map_or(rest.len(), |k| k + 1);
            }
            _ => i += 1,
        }
    }
    None
}

/// Parses the statement at the start of `rest`: first by `statement_fast`,
/// which skips alternatives that cannot match (see the grammar); when that
/// fails, again by `statement`, which tries them all so that the error
/// names everything that was expected. (`statement_fast` skips white space
/// before the statement: a `\` line join, the only white space left at
/// the start of `rest`, is parsed by `statement` alone.)
fn parse_statement(rest: &str) -> Result<Pairs<'_, Rule>, pest::error::Error<Rule>> {
    if !rest.starts_with('\\') {
        if let Ok(pairs) = LsysParser::parse(Rule::statement_fast, rest) {
            return Ok(pairs);
        }
    }
    LsysParser::parse(Rule::statement, rest)
}

/// Whether the unindented line at `pos`, which failed as a statement, is
/// a run of modules right after a production: a continuation line of its
/// successor that lost its indentation. The end of the modules when it
/// is. (After an axiom, which seldom spans lines, such a line is more
/// likely a production without its arrow.)
fn lost_indent(text: &str, pos: usize, last: Option<&ast::Item>) -> Option<usize> {
    let last_end = match last {
        Some(ast::Item::Production(p)) => p.span.end as usize,
        _ => return None,
    };
    // Only blank lines and comments in between.
    if last_end > pos || skip_blank(text, last_end) != Ok(pos) {
        return None;
    }
    let line_end = text[pos..].find('\n').map_or(text.len(), |i| pos + i);
    let line = &text[pos..line_end];
    let modules = LsysParser::parse(Rule::successor, line).ok()?.next()?;
    let end = modules.as_span().end();
    (end > 0 && end == skip_inline(line, end)).then_some(pos + line.trim_end().len())
}

/// Parses the value of a `-D NAME=VALUE` override or a REPL expression.
pub fn parse_expr(file_id: FileId, file: &SourceFile) -> Result<ast::Expr, Box<ParseError>> {
    if let Some(e) = too_deep(file, file_id, Limits::default()) {
        return Err(Box::new(e));
    }
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

/// What a `-D NAME=VALUE` value is.
pub enum DefineValue {
    /// One expression.
    Expr(ast::Expr),
    /// The flattened elements of a braced table list.
    Table(Vec<ast::Expr>),
}

/// Parses a `-D` value.
pub fn parse_define_value(
    file_id: FileId,
    file: &SourceFile,
) -> Result<DefineValue, Box<ParseError>> {
    if let Some(e) = too_deep(file, file_id, Limits::default()) {
        return Err(Box::new(e));
    }
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
                Ok(DefineValue::Table(out))
            } else {
                Ok(DefineValue::Expr(lower.expr(v)?))
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

#[cfg(test)]
mod tests;
