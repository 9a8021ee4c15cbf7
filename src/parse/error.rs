//! Syntax errors (`lsys::parse::*`): pest's failures turned into sentences
//! that name what was expected in the language's own words.

use miette::{Diagnostic, NamedSource, SourceSpan};
use pest::error::{Error as PestError, ErrorVariant, InputLocation};
use thiserror::Error;

use super::help::{
    arrow_typo, closes, empty_entry, found_at, line_of, structural_help, typographic_help,
    without_empty_entries, ARROW_HELP, MISSING_ARROW_HELP,
};
use super::Rule;
use crate::source::{FileId, SourceFile, Span};

/// Errors are boxed on the way up: they are rare and large (each carries
/// its source for rendering), results are common and should stay small.
pub(crate) type PResult<T> = Result<T, Box<ParseError>>;

#[derive(Debug, Error, Diagnostic)]
pub enum ParseError {
    #[error("syntax error: {message}")]
    #[diagnostic(code(lsys::parse::syntax))]
    Syntax {
        message: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("{label}")]
        span: SourceSpan,
        label: String,
        #[help]
        help: Option<String>,
        offset: usize,
    },

    #[error("comment is never closed")]
    #[diagnostic(
        code(lsys::parse::unclosed_comment),
        help("close the comment with `*/`; everything after `/*` was read as comment")
    )]
    UnclosedComment {
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this `/*` has no matching `*/`")]
        span: SourceSpan,
        offset: usize,
    },

    #[error("bad number `{text}`: {why}")]
    #[diagnostic(
        code(lsys::parse::number),
        help("write numbers as digits with an optional fraction and exponent, e.g. `2.5e-3`")
    )]
    BadNumber {
        text: String,
        why: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this number")]
        span: SourceSpan,
        offset: usize,
    },

    #[error("{what} is more than {limit} (the limit set by `{option}`)")]
    #[diagnostic(
        code(lsys::parse::too_deep),
        help("lsys refuses such input rather than risk running out of stack; split the expression with #defines or a production with fewer levels, or raise the limit with `{option}` (see docs/limits.md)")
    )]
    TooDeep {
        what: String,
        limit: usize,
        option: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("here")]
        span: SourceSpan,
        offset: usize,
    },

    #[error("`//` starts a comment: the rest of this line is ignored")]
    #[diagnostic(
        code(lsys::parse::comment_in_successor),
        severity(Warning),
        help("if `//` means two rolls (ABOP writes `/////` for five), write them apart, `/ /`, or with an angle, `/(5*22.5)`; to silence this, put a space before the comment")
    )]
    SlashComment {
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("a comment begins here, right after a module")]
        span: SourceSpan,
        offset: usize,
    },

    #[error("`{typed}:` is not a header; it would be read as a production")]
    #[diagnostic(
        code(lsys::parse::misspelt_header),
        help("did you mean `{header}:`? (if this is a production, write it with an arrow: `{typed} --> ...`)")
    )]
    MisspeltHeader {
        typed: String,
        header: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("not a header keyword")]
        span: SourceSpan,
        offset: usize,
    },

    #[error("bad table dimension")]
    #[diagnostic(
        code(lsys::parse::table_dimension),
        help("write each dimension as `lo..hi` with lo <= hi (e.g. `1..3`) or as a count `n` meaning 0..n-1; a dimension has at most 1 000 000 indices")
    )]
    BadTableDim {
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this dimension")]
        span: SourceSpan,
        offset: usize,
    },
}

impl ParseError {
    /// No help, or only "a production needs an arrow", which a more
    /// specific diagnosis may replace.
    pub(crate) fn has_only_generic_help(&self) -> bool {
        match self {
            ParseError::Syntax { help: None, .. } => true,
            ParseError::Syntax { help: Some(h), .. } => h == MISSING_ARROW_HELP,
            _ => false,
        }
    }

    /// An unindented line of modules right after a successor: not a
    /// statement, and not part of the successor either.
    pub(crate) fn lost_indent(file: &SourceFile, span: Span) -> ParseError {
        ParseError::Syntax {
            message: "a line of modules that is not part of any statement".to_string(),
            src: file.named_source(),
            span: span.into(),
            label: "not indented, so it does not continue the successor above".to_string(),
            help: Some("indent it to continue the successor above (a successor goes on over indented lines); to make it a production, give it a predecessor and an arrow: `A --> ...`".to_string()),
            offset: span.start as usize,
        }
    }

    /// Byte offset of the error in its file.
    pub fn offset(&self) -> usize {
        match self {
            ParseError::Syntax { offset, .. }
            | ParseError::UnclosedComment { offset, .. }
            | ParseError::BadNumber { offset, .. }
            | ParseError::BadTableDim { offset, .. }
            | ParseError::TooDeep { offset, .. }
            | ParseError::MisspeltHeader { offset, .. }
            | ParseError::SlashComment { offset, .. } => *offset,
        }
    }

    pub(crate) fn unclosed_comment(file: &SourceFile, span: Span) -> ParseError {
        ParseError::UnclosedComment {
            src: file.named_source(),
            span: span.into(),
            offset: span.start as usize,
        }
    }

    pub(crate) fn bad_table_dim(file: &SourceFile, span: Span) -> ParseError {
        ParseError::BadTableDim {
            src: file.named_source(),
            span: span.into(),
            offset: span.start as usize,
        }
    }

    pub(crate) fn bad_number(file: &SourceFile, span: Span, why: &str) -> ParseError {
        ParseError::BadNumber {
            text: file.text[span.start as usize..span.end as usize].to_string(),
            why: why.to_string(),
            src: file.named_source(),
            span: span.into(),
            offset: span.start as usize,
        }
    }

    /// Text left on a line after a complete statement.
    pub(crate) fn trailing(
        file: &SourceFile,
        file_id: FileId,
        at: usize,
        in_define: bool,
    ) -> ParseError {
        // A typographic character later on the line (`F(x—1)`) is the
        // likelier cause than the token the statement stopped at.
        let line_end = file.text[at..]
            .find('\n')
            .map_or(file.text.len(), |i| at + i);
        let at = file.text[at..line_end]
            .char_indices()
            .map(|(i, _)| at + i)
            .find(|&i| typographic_help(&file.text, i).is_some())
            .unwrap_or(at);
        let found = found_at(&file.text, at);
        let (len, help) = typographic_help(&file.text, at)
            .map(|(len, h)| (len, Some(h)))
            .unwrap_or_else(|| {
                let rest = &file.text[at..];
                let digit_before = file.text[..at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_ascii_digit());
                let line_start = file.text[..at].rfind('\n').map_or(0, |i| i + 1);
                let stmt = file.text[line_start..line_end].trim();
                let h = match rest.chars().next() {
                    // `A --> B \` + `B --> C`: C's line join made one
                    // statement of two lines.
                    _ if joined_at(&file.text, line_start).is_some() => {
                        let line = joined_at(&file.text, line_start).unwrap_or(0);
                        Some(format!(
                            "line {line} ends with `\\`, which joins this line onto it (as in C and cpfg), so this line was read as more of that statement; if the `\\` is the roll-left command, put a space or a comment after it, otherwise remove it"
                        ))
                    }
                    // `#include shared.lsys`: read as component names up
                    // to the `.`.
                    _ if stmt.starts_with("#include") && !stmt.contains(['"', '<']) => {
                        let path = stmt["#include".len()..].trim();
                        Some(format!(
                            "a file to include is written in quotes: `#include \"{path}\"` (`#include A, B` without quotes declares components)"
                        ))
                    }
                    // `0,5`: a decimal comma, as many locales write it.
                    Some(',')
                        if digit_before
                            && rest[1..].starts_with(|c: char| c.is_ascii_digit()) =>
                    {
                        Some("a decimal number is written with a point: `0.5`, not `0,5`".to_string())
                    }
                    Some('°') => Some(
                        "angles are in degrees already: write the number without `°` (e.g. `angle: 25.7`)"
                            .to_string(),
                    ),
                    // `#define N 5;`, `Axiom: F;` written C-style.
                    Some(';') if rest[1..].trim_start_matches([' ', '\t', '\r']).starts_with('\n')
                        || rest[1..].trim().is_empty() =>
                    {
                        Some("a statement ends at the end of its line: remove the `;`".to_string())
                    }
                    _ if in_define => Some(
                        "the value of a #define must be an expression; cpfg's textual macros (module strings, statements) are not supported yet"
                            .to_string(),
                    ),
                    Some('(') if !closes(&file.text[at..]) => Some(
                        "this `(` is never closed: end the parameter list with `)`".to_string(),
                    ),
                    Some('(') if empty_entry(&file.text[at..]) => Some(format!(
                        "a parameter list has no empty entries: remove the extra `,` (write `{}`)",
                        without_empty_entries(&file.text, at)
                    )),
                    Some('(') => Some(
                        "a parameter list must follow its module name directly: write `F(1)`, not `F (1)`"
                            .to_string(),
                    ),
                    _ => Some(
                        "one statement per line: start the next statement on a new line, or remove this text"
                            .to_string(),
                    ),
                };
                (found.1, h)
            });
        let span = Span::new(file_id, at, at + len);
        ParseError::Syntax {
            message: format!("unexpected {} after the end of the statement", found.0),
            src: file.named_source(),
            span: span.into(),
            label: "the statement ended before this".to_string(),
            help,
            offset: at,
        }
    }

    pub(crate) fn from_pest(
        file: &SourceFile,
        file_id: FileId,
        base: usize,
        e: &PestError<Rule>,
    ) -> ParseError {
        let at = base
            + match e.location {
                InputLocation::Pos(p) => p,
                InputLocation::Span((s, _)) => s,
            };
        let mut expected: Vec<&str> = match &e.variant {
            ErrorVariant::ParsingError { positives, .. } => {
                positives.iter().filter_map(|r| describe(*r)).collect()
            }
            ErrorVariant::CustomError { .. } => Vec::new(),
        };
        // Prefix operators, names and numbers together are "an expression".
        if expected.contains(&"a number") {
            expected.retain(|e| !matches!(*e, "`!`" | "`+`" | "`-`" | "a name" | "a number"));
            expected.push("an expression");
        }
        expected.sort_unstable();
        expected.dedup();
        let (found, len) = found_at(&file.text, at);
        // `A(x) : x < 3 => F`: the list of operators the condition could
        // go on with is noise; the arrow is what was meant.
        if file.text[at..].starts_with("=>") && expected.contains(&"`-->`") {
            return ParseError::Syntax {
                message: "expected `-->`, found `=>`".to_string(),
                src: file.named_source(),
                span: Span::new(file_id, at, at + 2).into(),
                label: "not an arrow".to_string(),
                help: Some(ARROW_HELP.to_string()),
                offset: at,
            };
        }
        let message = match expected.as_slice() {
            [] => format!("unexpected {found}"),
            [one] => format!("expected {one}, found {found}"),
            many => {
                let (last, rest) = many.split_last().expect("non-empty");
                format!("expected {} or {last}, found {found}", rest.join(", "))
            }
        };
        let line = line_of(&file.text, at);
        let col = at - file.text[..at].rfind('\n').map_or(0, |i| i + 1);
        // A mistyped arrow is what the caret should point at, not the end
        // of the line where the parser gave up.
        if let (Some((c, l, h)), true) = (arrow_typo(line), expected.contains(&"`-->`")) {
            let from = at - col + c;
            return ParseError::Syntax {
                message: format!("expected `-->`, found `{}`", &line[c..c + l]),
                src: file.named_source(),
                span: Span::new(file_id, from, from + l).into(),
                label: "not an arrow".to_string(),
                help: Some(h.to_string()),
                offset: from,
            };
        }
        let (len, help) = match typographic_help(&file.text, at) {
            Some((l, h)) => (l, Some(h)),
            None => (len, structural_help(line, col, &expected)),
        };
        ParseError::Syntax {
            message,
            src: file.named_source(),
            span: Span::new(file_id, at, at + len).into(),
            label: "here".to_string(),
            help,
            offset: at,
        }
    }
}

/// The language's name for a grammar rule in "expected ..." messages, or
/// `None` for rules that never appear there. The match is exhaustive on
/// purpose: a new rule does not compile until it has a human name.
fn describe(rule: Rule) -> Option<&'static str> {
    use Rule::*;
    Some(match rule {
        EOI => "the end of the file",
        word | sym | pattern_sym | module | pattern_module => "a module",
        ident | define_head | directive_name => "a name",
        arrow => "`-->`",
        number => "a number",
        expr | expr_only => "an expression",
        args | call_args | macro_params => "a parameter list `(...)`",
        index_args => "an index `[...]`",
        ternary => "`?`",
        call | index => "a function call",
        statement => "a statement",
        define | include | other_directive => "a directive",
        define_item => "a define `NAME value`",
        table_dims | table_dim | table_int => "table dimensions `[lo..hi, ...]`",
        table_values | table_value => "table values `{...}`",
        define_value => "a value",
        include_path => "a quoted file name",
        include_std => "a library name in `<...>`",
        include_list => "component names",
        path_text | std_name | rest_of_line => "text",
        lsystem_h | lsystem_kw | dlength_h | dlength_kw | axiom_h | axiom_kw | ignore_h
        | ignore_kw | consider_h | consider_kw | seed_h | seed_kw | maxdepth_h | maxdepth_kw
        | endlsystem_h | ring_h | homomorphism_h | homomorphism_kw | decomposition_h
        | decomposition_kw | module_h | module_kw | block_h | block_kw | angle_h | angle_kw
        | step_h | step_kw | width_h | width_kw | dialect_h | dialect_kw | colour_h | colour_kw
        | texture_h | texture_kw | environment_h | environment_kw => "a header statement",
        dialect_name => "a dialect name (`paper` or `cpfg`)",
        hex_colour => "a colour `#rrggbb`",
        module_decl => "a module declaration",
        brace_block | stmt_block => "a `{ ... }` block",
        production | head | lctx | pred | rctx => "a production",
        open_br => "`[`",
        close_br => "`]`",
        arrow_form | paper_form => "`-->`",
        condition | paper_cond | paper_cmp | paper_arith => "a condition",
        cond_else => "`else`",
        cond_always => "`*`",
        probability => "a probability",
        successor => "a successor",
        neg | sub => "`-`",
        pos | add => "`+`",
        // Never worth suggesting.
        stray_backslash => return None,
        not => "`!`",
        mul => "`*`",
        div => "`/`",
        rem => "`%`",
        pow => "`^`",
        le => "`<=`",
        ge => "`>=`",
        eq => "`==`",
        ne => "`!=`",
        lt => "`<`",
        gt => "`>`",
        and => "`&&`",
        or => "`||`",
        arith_op | rel_op | logic_op | infix_op | prefix_op => "an operator",
        primary | paper_primary => "an expression",
        at_sym | query_sym | tilde_sym | punct | pattern_punct | context_item => "a module",
        stmt_start | directive | header => "a statement",
        NL => "the end of the line",
        string_lit => "a string `\"...\"`",
        call_arg => "an argument",
        c_block_only | c_block | c_body => "a `{ ... }` block",
        c_stmt | c_expr_stmt | c_empty => "a statement",
        c_if | c_kw_if => "`if`",
        c_kw_else => "`else`",
        c_while | c_kw_while => "`while`",
        c_do | c_kw_do => "`do`",
        c_array | c_kw_array | c_array_def => "an array declaration",
        c_dim => "an index `[...]`",
        c_init | c_init_item => "array values `{...}`",
        c_assign | c_lvalue => "an assignment",
        c_assign_op => "`=`",
        WHITESPACE | comment | block_comment | line_comment | block_rest | line_rest
        | plain_char | cont | blank_line | indent | may_start | line_has_arrow | lctx_marker
        | nl_indent | keyword | word_char | statement_fast | exact | op_stop => return None,
    })
}

/// When the line starting at `line_start` is joined onto the line above
/// by a `\\` right before the line break: that line's number (from 1).
fn joined_at(text: &str, line_start: usize) -> Option<usize> {
    let above = text[..line_start].strip_suffix('\n')?;
    let above = above.strip_suffix('\r').unwrap_or(above);
    above
        .ends_with('\\')
        .then(|| above.matches('\n').count() + 1)
}
