//! Editing a grammar as text: the root file's text and an edit (a
//! production to insert, a span to replace or remove, a new axiom) in, the
//! edited text and where the edited statement starts out. The REPL keeps
//! its grammar as source text and recompiles it after every edit, so the
//! compiler decides what the edit means, and what `:rules` shows is what
//! the file would say.

use std::ops::Range;

use crate::parse::ast::{HeaderKind, Item};
use crate::source::{Origin, SourceFile};

/// The root file's statements (errors are ignored: the text compiled).
fn items(text: &str) -> Vec<Item> {
    let file = SourceFile::new("<edit>", Origin::Memory, text);
    crate::parse::parse(0, &file).0.items
}

/// The start of the line holding byte `pos`.
pub fn line_start(text: &str, pos: usize) -> usize {
    text[..pos.min(text.len())].rfind('\n').map_or(0, |i| i + 1)
}

/// Just past the end of the line holding byte `pos` (after its newline).
pub fn after_line(text: &str, pos: usize) -> usize {
    let pos = pos.min(text.len());
    text[pos..].find('\n').map_or(text.len(), |i| pos + i + 1)
}

/// Where a new production of the main table goes: after the last one in
/// the file, else before the first `homomorphism`, `decomposition` or
/// `endlsystem` line, else at the end.
pub fn default_insertion(text: &str) -> usize {
    let mut in_main = true;
    let mut last_main = None;
    let mut first_section = None;
    for item in items(text) {
        match item {
            Item::Production(p) if in_main => last_main = Some(p.span.end as usize),
            Item::Header(h) => match h.kind {
                HeaderKind::Homomorphism | HeaderKind::Decomposition | HeaderKind::Endlsystem => {
                    in_main = false;
                    first_section.get_or_insert(h.span.start as usize);
                }
                _ => {}
            },
            _ => {}
        }
    }
    match (last_main, first_section) {
        (Some(end), _) => after_line(text, end),
        (None, Some(start)) => line_start(text, start),
        (None, None) => text.len(),
    }
}

/// `statement` inserted as a line of its own at line start `at`; returns
/// the text and where the statement starts.
pub fn insert_at(text: &str, at: usize, statement: &str) -> (String, usize) {
    let mut out = String::with_capacity(text.len() + statement.len() + 2);
    out.push_str(&text[..at]);
    if !out.is_empty() && !out.ends_with('\n') {
        out.push('\n');
    }
    let start = out.len();
    out.push_str(statement);
    out.push('\n');
    out.push_str(&text[at..]);
    (out, start)
}

/// `span` replaced by `statement`; returns the text and where the
/// statement starts.
pub fn replace(text: &str, span: Range<usize>, statement: &str) -> (String, usize) {
    let mut out = String::with_capacity(text.len() + statement.len());
    out.push_str(&text[..span.start]);
    out.push_str(statement);
    out.push_str(&text[span.end..]);
    (out, span.start)
}

/// `overrides` (`NAME`, value) written over the values of the root file's
/// plain `#define NAME value` lines; returns the text and the overrides
/// it has no such line for (defined in an included file, by `-D` only,
/// or function-like or a table).
pub fn set_defines(text: &str, overrides: &[(String, String)]) -> (String, Vec<(String, String)>) {
    let mut spans: Vec<(Range<usize>, &str)> = Vec::new();
    let mut missing = Vec::new();
    let items = items(text);
    for (name, value) in overrides {
        let found = items.iter().find_map(|item| match item {
            Item::Define(ds) => ds
                .iter()
                .find_map(|d| match (&d.value, &d.params, &d.dims) {
                    (Some(v), None, None) if d.name.name == *name => {
                        Some(v.span.start as usize..v.span.end as usize)
                    }
                    _ => None,
                }),
            _ => None,
        });
        match found {
            Some(span) => spans.push((span, value)),
            None => missing.push((name.clone(), value.clone())),
        }
    }
    // From the end, so that earlier spans stay where they are.
    spans.sort_by_key(|(s, _)| std::cmp::Reverse(s.start));
    let mut out = text.to_string();
    for (span, value) in spans {
        out.replace_range(span, value);
    }
    (out, missing)
}

/// The lines that `span` covers removed.
pub fn remove_lines(text: &str, span: Range<usize>) -> String {
    let start = line_start(text, span.start);
    let end = after_line(text, span.end);
    format!("{}{}", &text[..start], &text[end..])
}

/// The axiom set to `modules`: the file's `Axiom:` line rewritten (keeping
/// its keyword), or a new `Axiom:` line before the first production.
pub fn set_axiom(text: &str, modules: &str) -> (String, usize) {
    let items = items(text);
    for item in &items {
        if let Item::Header(h) = item {
            if let HeaderKind::Axiom(_) | HeaderKind::LongAxiom(_) = h.kind {
                let kw_end = h.keyword.end as usize;
                let colon = text[kw_end..].find(':').map_or(kw_end, |i| kw_end + i + 1);
                let keep = &text[h.span.start as usize..colon];
                return replace(
                    text,
                    h.span.start as usize..h.span.end as usize,
                    &format!("{keep} {modules}"),
                );
            }
        }
    }
    let before = items.iter().find_map(|item| match item {
        Item::Production(p) => Some(p.span.start as usize),
        Item::Header(h)
            if matches!(
                h.kind,
                HeaderKind::Homomorphism | HeaderKind::Decomposition | HeaderKind::Endlsystem
            ) =>
        {
            Some(h.span.start as usize)
        }
        _ => None,
    });
    let at = before.map_or(text.len(), |s| line_start(text, s));
    insert_at(text, at, &format!("Axiom: {modules}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const KOCH: &str =
        "derivation length: 3\nAxiom: F // start\nF --> F+F-F // rule\n\nhomomorphism\nF --> G\n";

    #[test]
    fn new_productions_go_after_the_last_main_one() {
        let at = default_insertion(KOCH);
        let (t, start) = insert_at(KOCH, at, "G --> GG");
        assert_eq!(
            t,
            "derivation length: 3\nAxiom: F // start\nF --> F+F-F // rule\nG --> GG\n\nhomomorphism\nF --> G\n"
        );
        assert_eq!(&t[start..start + 8], "G --> GG");
    }

    #[test]
    fn without_productions_before_the_first_section() {
        let text = "Axiom: F\nhomomorphism\nF --> G";
        let (t, _) = insert_at(text, default_insertion(text), "F --> FF");
        assert_eq!(t, "Axiom: F\nF --> FF\nhomomorphism\nF --> G");
        let (t, _) = insert_at("Axiom: F", default_insertion("Axiom: F"), "F --> FF");
        assert_eq!(t, "Axiom: F\nF --> FF\n");
    }

    #[test]
    fn axiom_is_rewritten_in_place_or_added() {
        let (t, _) = set_axiom(KOCH, "F - F");
        assert!(t.contains("\nAxiom: F - F // start\n"), "{t}");
        let (t, _) = set_axiom("Ω : A\nA : B\n", "A A");
        assert_eq!(t, "Ω : A A\nA : B\n");
        let (t, _) = set_axiom("#define N 2\nA --> B\n", "A");
        assert_eq!(t, "#define N 2\nAxiom: A\nA --> B\n");
        let (t, _) = set_axiom("", "A");
        assert_eq!(t, "Axiom: A\n");
    }

    #[test]
    fn removal_takes_whole_lines() {
        let span = KOCH.find("F -->").unwrap()..KOCH.find(" // rule").unwrap();
        assert_eq!(
            remove_lines(KOCH, span),
            "derivation length: 3\nAxiom: F // start\n\nhomomorphism\nF --> G\n"
        );
    }
}
