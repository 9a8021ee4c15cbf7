//! The manifest: a JSON Lines file, one item per line -> the items in
//! order, or every mistake in it, each pointing at its line and column
//! (a line that is not JSON, a key that is wrong, an id used twice), so
//! that a manifest is fixed in one go and nothing is built from a
//! manifest with a mistake.

use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

use miette::{NamedSource, SourceSpan};

use super::error::BatchError;
use super::item::{item_from_json, Item, ItemError};
use super::mistake::{ManifestError, Mistake};

/// A manifest's mistakes told one by one; the rest are counted.
pub const MISTAKES_TOLD: usize = 20;

/// The items of the manifest at `path` (its text `text`), each with its
/// line (from 1); relative grammar paths start from the manifest's folder.
pub fn read(path: &Path, text: String) -> Result<Vec<(usize, Item)>, BatchError> {
    let base = path.parent().unwrap_or(Path::new(""));
    let text = Arc::new(text);
    let src = NamedSource::new(
        path.display().to_string(),
        crate::source::SourceText::from(text.clone()),
    );
    let mut items = Vec::new();
    let mut mistakes = Vec::new();
    // Where each id was first used: its line and span.
    let mut seen: HashMap<String, (usize, SourceSpan)> = HashMap::new();
    let mut start = 0;
    for (n, raw) in text.split_inclusive('\n').enumerate() {
        let mut line_start = start;
        start += raw.len();
        let mut line = raw.trim_end_matches(['\n', '\r']);
        // A byte order mark, as some Windows editors write one, is no JSON.
        if n == 0 {
            if let Some(rest) = line.strip_prefix('\u{feff}') {
                line_start += line.len() - rest.len();
                line = rest;
            }
        }
        if line.trim().is_empty() {
            continue;
        }
        let mistake = |at: Range<usize>, kind: Mistake| ManifestError {
            src: src.clone(),
            span: (line_start + at.start..line_start + at.end).into(),
            line: n + 1,
            kind,
        };
        let value: serde_json::Value = match serde_json::from_str(line) {
            Ok(v) => v,
            Err(e) => {
                // serde_json counts columns from 1 within the one line.
                let at = (e.column().max(1) - 1).min(line.len());
                let at = floor_char(line, at);
                let end = ceil_char(line, at + 1);
                mistakes.push(mistake(at..end, Mistake::Json(json_message(&e))));
                continue;
            }
        };
        match item_from_json(&value, base) {
            Ok(item) => {
                let id_at = value_span(line, "id").unwrap_or(0..line.len());
                let span: SourceSpan = (line_start + id_at.start..line_start + id_at.end).into();
                match seen.get(&item.id) {
                    Some(&(first, first_span)) => mistakes.push(mistake(
                        id_at,
                        Mistake::Duplicate {
                            id: item.id.clone(),
                            first,
                            first_span,
                        },
                    )),
                    None => {
                        seen.insert(item.id.clone(), (n + 1, span));
                        items.push((n + 1, item));
                    }
                }
            }
            Err(e) => {
                let at = match e.key() {
                    Some(k) if matches!(e, ItemError::UnknownKey { .. }) => key_span(line, k),
                    Some(k) => match k.split_once('.') {
                        // One define: its value inside `defines`.
                        Some(("defines", name)) => key_span(line, "defines").and_then(|d| {
                            let v = value_span(&line[d.end..], name)?;
                            Some(d.end + v.start..d.end + v.end)
                        }),
                        _ => value_span(line, k),
                    },
                    None => None,
                };
                let at = at.unwrap_or_else(|| trimmed(line));
                mistakes.push(mistake(at, Mistake::Item(e)));
            }
        }
    }
    if mistakes.is_empty() {
        return Ok(items);
    }
    let count = mistakes.len();
    mistakes.truncate(MISTAKES_TOLD);
    Err(BatchError::Manifest {
        file: path.display().to_string(),
        count,
        mistakes,
    })
}

/// serde_json's message without its ` at line 1 column 7` (the
/// diagnostic shows the place in the manifest instead).
fn json_message(e: &serde_json::Error) -> String {
    let m = e.to_string();
    match m.rfind(" at line ") {
        Some(i) => m[..i].to_string(),
        None => m,
    }
}

/// The line without its surrounding blanks.
fn trimmed(line: &str) -> Range<usize> {
    let start = line.len() - line.trim_start().len();
    start..line.trim_end().len().max(start)
}

/// Where `"key"` is written as a key (followed by `:`) in `line`. Found
/// in the text, not in the parsed value: good enough to point at, and a
/// key spelt with escapes is pointed at as the whole line instead.
fn key_span(line: &str, key: &str) -> Option<Range<usize>> {
    let quoted = format!("\"{key}\"");
    let mut from = 0;
    while let Some(i) = line[from..].find(&quoted) {
        let at = from + i;
        let after = &line[at + quoted.len()..];
        if after.trim_start().starts_with(':') {
            return Some(at..at + quoted.len());
        }
        from = at + 1;
    }
    None
}

/// Where the value of `key` is written in `line`: a string to its
/// closing quote, anything else to the next `,` or `}` (an object or
/// array: its key).
fn value_span(line: &str, key: &str) -> Option<Range<usize>> {
    let k = key_span(line, key)?;
    let colon = k.end + line[k.end..].find(':')?;
    let rest = &line[colon + 1..];
    let start = colon + 1 + (rest.len() - rest.trim_start().len());
    let bytes = line.as_bytes();
    match bytes.get(start)? {
        b'"' => {
            let mut i = start + 1;
            while i < bytes.len() {
                match bytes[i] {
                    b'\\' => i += 2,
                    b'"' => return Some(start..i + 1),
                    _ => i += 1,
                }
            }
            Some(start..line.len())
        }
        b'{' | b'[' => Some(k),
        _ => {
            let end = line[start..]
                .find([',', '}'])
                .map_or(line.len(), |e| start + e);
            Some(start..line[..end].trim_end().len().max(start + 1))
        }
    }
}

fn floor_char(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn ceil_char(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while i < s.len() && !s.is_char_boundary(i) {
        i += 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_values_are_found_in_the_line() {
        let line = r#"{"id": "a\"b", "seed": 12 , "defines": {"id": 1}}"#;
        assert_eq!(&line[key_span(line, "seed").unwrap()], "\"seed\"");
        assert_eq!(&line[value_span(line, "id").unwrap()], r#""a\"b""#);
        assert_eq!(&line[value_span(line, "seed").unwrap()], "12");
        assert_eq!(&line[value_span(line, "defines").unwrap()], "\"defines\"");
        assert_eq!(key_span(line, "steps"), None);
    }

    #[test]
    fn items_keep_their_lines_and_blank_lines_are_skipped() {
        // A byte order mark and Windows line ends are no mistake.
        let text = "\u{feff}{\"id\":\"a\",\"grammar\":\"g.lsys\"}\r\n\n  \n{\"id\":\"b\",\"grammar\":\"std:x\"}\n";
        let items = read(Path::new("m/list.jsonl"), text.into()).unwrap();
        let lines: Vec<_> = items.iter().map(|(l, i)| (*l, i.id.as_str())).collect();
        assert_eq!(lines, [(1, "a"), (4, "b")]);
        assert_eq!(items[0].1.grammar, Path::new("m/g.lsys").to_string_lossy());
    }
}
