//! Output text of one file. Input: tokens (each knowing its output line)
//! and whole lines for kept directives. Output: the text, one line per
//! physical line of the original.

use super::token::{Kind, Token};

pub(crate) struct Render {
    lines: Vec<String>,
}

impl Render {
    pub fn new(line_count: usize) -> Render {
        Render {
            lines: vec![String::new(); line_count.max(1)],
        }
    }

    fn line_mut(&mut self, line: usize) -> &mut String {
        let last = self.lines.len() - 1;
        &mut self.lines[line.min(last)]
    }

    pub fn set_line(&mut self, line: usize, text: String) {
        *self.line_mut(line) = text;
    }

    pub fn emit(&mut self, toks: &[Token]) {
        for t in toks {
            if t.kind == Kind::Placemarker {
                continue;
            }
            let out = self.line_mut(t.line);
            if t.has_space() {
                out.push_str(&t.ws);
            } else if t.pad {
                // Tokens that meet at a macro boundary must not merge into
                // another token (`-` and an expanded `-1` stay `- -1`).
                if let (Some(a), Some(b)) = (out.chars().last(), t.text.chars().next()) {
                    if would_paste(a, b) {
                        out.push(' ');
                    }
                }
            }
            out.push_str(&t.text);
        }
    }

    pub fn finish(self) -> String {
        self.lines.join("\n")
    }
}

/// Whether a token ending in `a` followed by one starting with `b` would
/// be read as a different token (or a comment).
fn would_paste(a: char, b: char) -> bool {
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '.';
    if word(a) && word(b) {
        return true;
    }
    matches!(
        (a, b),
        ('+', '+' | '=')
            | ('-', '-' | '=' | '>')
            | ('<', '<' | '=' | ':' | '%')
            | ('>', '>' | '=')
            | ('=' | '!' | '*' | '%' | '^', '=')
            | ('&', '&' | '=')
            | ('|', '|' | '=')
            | ('/', '/' | '*' | '=')
            | ('#', '#')
            | (':', ':' | '>')
            | ('%', '>' | ':')
    )
}
