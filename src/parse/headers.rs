//! Misspelt header keywords: source text in, errors out. `derivation
//! lenght: 5` is a valid arrowless production (module string `derivation
//! lenght`, successor `5`), so the grammar alone would silently derive 0
//! steps; a line `WORDS:` whose words are one or two edits from a header
//! keyword is reported instead, naming the header.

use super::error::ParseError;
use crate::source::{FileId, SourceFile, Span};

/// Header keywords as the user should write them (before the colon).
pub const HEADERS: &[&str] = &[
    "derivation length",
    "axiom",
    "ignore",
    "consider",
    "seed",
    "maximum depth",
    "lsystem",
    "homomorphism",
    "decomposition",
    "module",
    "angle",
    "step",
    "width",
    "dialect",
    "environment",
    "colour",
    "color",
];

/// Shorter words are left alone: a module named `stem` or `sed` is as
/// likely as a misspelt `step` or `seed`.
const MIN_LETTERS: usize = 5;

pub(super) fn misspelt_headers(file: &SourceFile, file_id: FileId) -> Vec<ParseError> {
    let text = file.text.as_str();
    let mut out = Vec::new();
    let mut in_block = false;
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let line_start = start;
        start += line.len();
        let was_in_block = in_block;
        in_block = block_state(line, in_block);
        if was_in_block {
            continue;
        }
        let code = line.trim_start();
        let indent = line.len() - code.len();
        let words_len = code
            .find(|c: char| !(c.is_ascii_alphabetic() || c == ' ' || c == '\t'))
            .unwrap_or(code.len());
        if !code[words_len..].starts_with(':')
            || ["-->", "->", "→"].iter().any(|a| line.contains(a))
        {
            continue;
        }
        let typed = code[..words_len].trim_end();
        let words: Vec<&str> = typed.split_whitespace().collect();
        let letters: usize = words.iter().map(|w| w.len()).sum();
        if words.is_empty() || words.len() > 2 || letters < MIN_LETTERS {
            continue;
        }
        let key = words.join(" ").to_ascii_lowercase();
        if HEADERS.contains(&key.as_str()) {
            continue;
        }
        let best = HEADERS
            .iter()
            .map(|h| (strsim::damerau_levenshtein(&key, h), *h))
            .min();
        if let Some((d, header)) = best {
            if d > 0 && d <= 2 {
                let at = line_start + indent;
                out.push(ParseError::MisspeltHeader {
                    typed: typed.to_string(),
                    header: header.to_string(),
                    src: file.named_source(),
                    span: Span::new(file_id, at, at + typed.len()).into(),
                    offset: at,
                });
            }
        }
    }
    out
}

/// Whether a `/* ... */` comment is open at the end of `line`.
fn block_state(line: &str, mut open: bool) -> bool {
    let mut rest = line;
    loop {
        if open {
            match rest.find("*/") {
                Some(i) => {
                    rest = &rest[i + 2..];
                    open = false;
                }
                None => return true,
            }
        } else {
            let line_comment = rest.find("//");
            match rest.find("/*") {
                Some(i) if line_comment.map_or(true, |c| i < c) => {
                    rest = &rest[i + 2..];
                    open = true;
                }
                _ => return false,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::Origin;

    fn found(text: &str) -> Vec<String> {
        let f = SourceFile::new("t", Origin::Memory, text);
        misspelt_headers(&f, 0)
            .iter()
            .map(|e| match e {
                ParseError::MisspeltHeader { typed, header, .. } => format!("{typed}={header}"),
                _ => unreachable!(),
            })
            .collect()
    }

    #[test]
    fn misspelt_headers_are_named_and_others_left_alone() {
        assert_eq!(
            found("derivation lenght: 5\n"),
            ["derivation lenght=derivation length"]
        );
        assert_eq!(found("  Axoim: F\n"), ["Axoim=axiom"]);
        // Headers, productions, short names and comments are not reported.
        assert!(found("Axiom: F\nderivation length: 2\nA : x > 1 --> B\nstem: F\n").is_empty());
        assert!(found("/* axoim: F\n derivation lenght: 5 */\n// axoim: F\n").is_empty());
        assert!(found("branch: F\n").is_empty());
    }
}
