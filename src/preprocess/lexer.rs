//! Lexing of one file. Input: the original text. Output: logical lines of
//! preprocessing tokens (backslash-newlines spliced away, comments turned
//! into whitespace, CRLF accepted), each token knowing its byte span in the
//! original text and the output line it belongs on, plus the number of
//! physical lines (which the output must keep).

use std::ops::Range;
use std::rc::Rc;

use super::error::{ErrorKind, PreprocessError};
use super::token::{Kind, Token};

pub(crate) struct Lexed {
    /// Logical lines (split at newlines outside comments), empty ones left out.
    pub lines: Vec<Vec<Token>>,
    /// Physical lines of the text: `text.split('\n').count()`.
    pub line_count: usize,
}

/// Multi-character punctuators worth keeping whole: `##` and `...` for
/// macros, the rest for `#if` expressions.
const PUNCT3: &[&str] = &["..."];
const PUNCT2: &[&str] = &["##", "||", "&&", "==", "!=", "<=", ">=", "<<", ">>"];

/// The text with backslash-newlines removed: each char with its byte offset.
struct Spliced {
    chars: Vec<(char, usize)>,
    end: usize,
}

fn splice(text: &str) -> Spliced {
    let bytes: Vec<(usize, char)> = text.char_indices().collect();
    let mut chars = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let (off, c) = bytes[i];
        if c == '\\' {
            // GNU cpp also accepts blanks between the backslash and the newline.
            let mut j = i + 1;
            while j < bytes.len() && matches!(bytes[j].1, ' ' | '\t' | '\r') {
                j += 1;
            }
            if j < bytes.len() && bytes[j].1 == '\n' {
                i = j + 1;
                continue;
            }
        }
        chars.push((c, off));
        i += 1;
    }
    Spliced {
        chars,
        end: text.len(),
    }
}

/// Maps byte offsets to output lines: the first physical line of the
/// backslash-continued group the offset is in.
struct Lines {
    starts: Vec<usize>,
    group: Vec<usize>,
}

impl Lines {
    fn new(text: &str) -> Lines {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        let mut group = Vec::with_capacity(starts.len());
        for (i, &s) in starts.iter().enumerate() {
            // Mirrors `splice`: a backslash, blanks, newline joins the lines.
            let continued = i > 0 && {
                let prev = text
                    .get(starts[i - 1]..s - 1)
                    .unwrap_or("")
                    .trim_end_matches([' ', '\t', '\r']);
                prev.ends_with('\\')
            };
            let g = if continued { group[i - 1] } else { i };
            group.push(g);
        }
        Lines { starts, group }
    }

    fn line_of(&self, off: usize) -> usize {
        let i = self.starts.partition_point(|&s| s <= off).saturating_sub(1);
        self.group.get(i).copied().unwrap_or(0)
    }
}

pub(crate) fn lex(text: &str, file: usize, errors: &mut Vec<PreprocessError>) -> Lexed {
    let sp = splice(text);
    let lines_map = Lines::new(text);
    let cs = &sp.chars;
    let at = |i: usize| cs.get(i).map(|c| c.0);
    let off = |i: usize| cs.get(i).map_or(sp.end, |c| c.1);
    // End offset of the char at i.
    let end_of = |i: usize| cs.get(i).map_or(sp.end, |c| c.1 + c.0.len_utf8());

    let mut lines: Vec<Vec<Token>> = Vec::new();
    let mut cur: Vec<Token> = Vec::new();
    let mut ws = String::new();
    let mut i = 0;
    while i < cs.len() {
        let c = cs[i].0;
        let start = i;
        match c {
            '\n' => {
                if !cur.is_empty() {
                    lines.push(std::mem::take(&mut cur));
                }
                ws.clear();
                i += 1;
                continue;
            }
            ' ' | '\t' | '\r' | '\x0b' | '\x0c' => {
                ws.push(c);
                i += 1;
                continue;
            }
            '/' if at(i + 1) == Some('*') => {
                let mut j = i + 2;
                loop {
                    match at(j) {
                        None => {
                            errors.push(
                                PreprocessError::new(
                                    ErrorKind::UnterminatedComment,
                                    file,
                                    off(i)..end_of(i + 1),
                                    "unterminated comment: `/*` without `*/`".into(),
                                )
                                .help("close the comment with `*/`"),
                            );
                            break;
                        }
                        Some('*') if at(j + 1) == Some('/') => {
                            j += 2;
                            break;
                        }
                        _ => j += 1,
                    }
                }
                ws.push(' ');
                i = j;
                continue;
            }
            '/' if at(i + 1) == Some('/') => {
                while at(i).is_some_and(|c| c != '\n') {
                    i += 1;
                }
                continue;
            }
            _ => {}
        }
        let kind;
        if c.is_ascii_alphabetic() || c == '_' {
            while at(i).is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
                i += 1;
            }
            kind = Kind::Ident;
        } else if c.is_ascii_digit() || (c == '.' && at(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            i += 1;
            while let Some(d) = at(i) {
                if matches!(d, 'e' | 'E' | 'p' | 'P') && matches!(at(i + 1), Some('+' | '-')) {
                    i += 2;
                } else if d.is_ascii_alphanumeric() || d == '_' || d == '.' {
                    i += 1;
                } else {
                    break;
                }
            }
            kind = Kind::Number;
        } else if c == '"' {
            let mut j = i + 1;
            let mut closed = false;
            while let Some(d) = at(j) {
                match d {
                    '\\' if at(j + 1).is_some_and(|e| e != '\n') => j += 2,
                    '"' => {
                        closed = true;
                        j += 1;
                        break;
                    }
                    '\n' => break,
                    _ => j += 1,
                }
            }
            if closed {
                i = j;
                kind = Kind::Str;
            } else {
                // Like cpp, a lone quote is just a character.
                i += 1;
                kind = Kind::Punct;
            }
        } else {
            let rest: String = cs[i..cs.len().min(i + 3)].iter().map(|c| c.0).collect();
            let n = if PUNCT3.iter().any(|p| rest.starts_with(p)) {
                3
            } else if PUNCT2.iter().any(|p| rest.starts_with(p)) {
                2
            } else {
                1
            };
            i += n;
            kind = Kind::Punct;
        }
        let text: String = cs[start..i].iter().map(|c| c.0).collect();
        let span = off(start)..end_of(i - 1);
        let tok = Token {
            kind,
            text: Rc::from(text),
            ws: Rc::from(std::mem::take(&mut ws)),
            line: lines_map.line_of(span.start),
            span,
            bol: cur.is_empty(),
            hide: None,
            pad: false,
        };
        cur.push(tok);
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    Lexed {
        lines,
        line_count: lines_map.starts.len(),
    }
}

/// Lexes a piece of text that is not part of a file (a pasted token, a
/// `-D` value); spans and lines are all `span`/`line`.
pub(crate) fn lex_fragment(text: &str, span: Range<usize>, line: usize) -> Vec<Token> {
    let mut sink = Vec::new();
    let lexed = lex(text, 0, &mut sink);
    let mut out: Vec<Token> = lexed.lines.into_iter().flatten().collect();
    for (k, t) in out.iter_mut().enumerate() {
        t.span = span.clone();
        t.line = line;
        t.bol = false;
        if k == 0 {
            t.ws = Rc::from("");
        }
    }
    out
}
