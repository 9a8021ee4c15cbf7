//! The help line of a syntax error: the text around where pest stopped
//! in, a sentence that says what to write instead out (typographic
//! characters copied from a PDF, `=>` and `=` for `-->` and `==`, a header
//! without its colon, the textbooks' `n = 5`, an unclosed `(`).

/// Whether the parameter list that starts `rest` has an empty entry
/// (`(x,)`, `(,x)`, `(x,,y)`).
pub(super) fn empty_entry(rest: &str) -> bool {
    let list: String = rest
        .chars()
        .take_while(|&c| c != '\n' && c != ')')
        .filter(|c| !c.is_whitespace())
        .collect();
    let list = format!("{list})");
    list.contains(",)") || list.contains("(,") || list.contains(",,")
}

/// The module whose parameter list starts at `at` (closed on its line),
/// written without the list's empty entries: `C(x,)` -> `C(x)`.
pub(super) fn without_empty_entries(text: &str, at: usize) -> String {
    let name_start = text[..at]
        .rfind(|c: char| c.is_whitespace() || matches!(c, '>' | '[' | ']' | ')'))
        .map_or(0, |i| {
            i + text[i..].chars().next().map_or(1, char::len_utf8)
        });
    let inner = &text[at + 1..];
    let inner = &inner[..inner.find(')').unwrap_or(inner.len())];
    let entries: Vec<&str> = inner
        .split(',')
        .map(str::trim)
        .filter(|e| !e.is_empty())
        .collect();
    format!("{}({})", &text[name_start..at], entries.join(", "))
}

/// Whether the `(` that starts `rest` is closed on its line.
pub(super) fn closes(rest: &str) -> bool {
    let mut depth = 0;
    for c in rest.chars().take_while(|&c| c != '\n') {
        match c {
            '(' => depth += 1,
            ')' if depth == 1 => return true,
            ')' => depth -= 1,
            _ => {}
        }
    }
    false
}

/// How to name what stands at `at`, and its length in bytes.
pub(super) fn found_at(text: &str, at: usize) -> (String, usize) {
    match text[at..].chars().next() {
        None => ("the end of the file".to_string(), 0),
        Some('\n') => ("the end of the line".to_string(), 0),
        Some(c) => (format!("`{c}`"), c.len_utf8()),
    }
}

pub(super) fn line_of(text: &str, at: usize) -> &str {
    let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    &text[start..end]
}

/// Characters that arrive by copying from a PDF, with their ASCII forms.
pub(super) fn typographic_help(text: &str, at: usize) -> Option<(usize, String)> {
    let c = text[at..].chars().next()?;
    if c == '\u{FFFD}' {
        // What lsys reads in place of bytes that are not UTF-8.
        return Some((
            c.len_utf8(),
            "this byte is not UTF-8 (the file is probably in Latin-1 or another old encoding): save the file as UTF-8, or write the name in ASCII".to_string(),
        ));
    }
    let ascii = match c {
        '—' | '–' | '‐' | '‑' => "-",
        '×' | '·' | '∗' => "*",
        '÷' | '∕' => "/",
        '‘' | '’' | '′' => "'",
        '“' | '”' => "\"",
        '⇒' | '⟹' | '↦' => "-->",
        '≤' => "<=",
        '≥' => ">=",
        '≠' => "!=",
        '\u{A0}' | '\u{2009}' | '\u{202F}' => " ",
        _ => return None,
    };
    Some((
        c.len_utf8(),
        format!(
            "`{c}` (U+{:04X}) is a typographic character, probably copied from a PDF; write the ASCII `{ascii}` instead",
            c as u32
        ),
    ))
}

/// A mistyped arrow on a line that did not parse: where it is in the
/// line, how long, and the help. `=>`, and an arrow broken by spaces
/// (`- >`, `-- >`, `- ->`).
pub(super) fn arrow_typo(line: &str) -> Option<(usize, usize, &'static str)> {
    if let Some(at) = line.find("=>") {
        return Some((at, 2, ARROW_HELP));
    }
    let b = line.as_bytes();
    // Each run of dashes and spaces once: linear in the line.
    let mut start = 0;
    while start < b.len() {
        if b[start] != b'-' {
            start += 1;
            continue;
        }
        let mut i = start;
        while i < b.len() && (b[i] == b'-' || b[i] == b' ') {
            i += 1;
        }
        if i < b.len() && b[i] == b'>' && line[start..i].contains("- ") {
            return Some((
                start,
                i + 1 - start,
                "the arrow of a production is written without spaces: `-->` (or `->`)",
            ));
        }
        start = i.max(start + 1);
    }
    None
}

pub(super) fn structural_help(line: &str, col: usize, expected: &[&str]) -> Option<String> {
    let before = line.get(..col.min(line.len())).unwrap_or(line);
    let code = line.trim_start();
    if line.contains("=>") {
        return Some(ARROW_HELP.to_string());
    }
    if let Some(kw) = HEADERS.iter().find(|k| {
        // `get`: the line may hold non-ASCII text where the keyword would end.
        code.len() > k.len()
            && code
                .get(..k.len())
                .is_some_and(|c| c.eq_ignore_ascii_case(k))
            && !code[k.len()..].starts_with(|c: char| c.is_alphanumeric() || c == '_')
            && !code[k.len()..].trim_start().starts_with(':')
    }) {
        let typed = &code[..kw.len()];
        return Some(format!(
            "a header needs a colon after its keyword: `{typed}: ...`"
        ));
    }
    if code.starts_with(':') {
        return Some(
            "a probability or condition belongs on the production's own line, after the successor: `F --> F[+F]F : 0.5`".to_string(),
        );
    }
    if let Some(help) = assignment_help(code) {
        return Some(help);
    }
    if single_equals(line) {
        return Some(
            "`=` is not a comparison: write `==` (e.g. `A(x) : x == 1 --> B`)".to_string(),
        );
    }
    if before.matches('(').count() > before.matches(')').count() {
        return Some(
            "a `(` before this point is not closed: close the parameter list with `)`".to_string(),
        );
    }
    let has_arrow = ["-->", "->", "→"].iter().any(|a| line.contains(a));
    if expected.contains(&"`-->`") && !has_arrow && !line.contains(':') {
        return Some(MISSING_ARROW_HELP.to_string());
    }
    if expected.iter().any(|e| e.contains("`)`")) {
        return Some(
            "a parameter list is closed by `)`; parameters are separated by `,`".to_string(),
        );
    }
    if expected.contains(&"an expression") {
        return Some(
            "an expression is numbers, names and operators such as `x*2+1`, `sqrt(p*q)`, `x < 5 && y > 1`"
                .to_string(),
        );
    }
    None
}

pub(super) const MISSING_ARROW_HELP: &str =
    "a production needs an arrow between predecessor and successor: `A(x) --> B(x+1)`";

pub(super) const ARROW_HELP: &str = "the arrow of a production is `-->` (or `->`, `→`), not `=>`";

/// Header keywords, for "a header needs a colon".
const HEADERS: &[&str] = &[
    "axiom",
    "derivation length",
    "lsystem",
    "ignore",
    "consider",
    "seed",
    "angle",
    "step",
    "width",
    "dialect",
    "environment",
    "maximum depth",
];

/// What to write instead of a line `NAME = VALUE`: the textbooks' `n = 5`
/// and `δ = 25.7` are headers here, and any other name a `#define`.
fn assignment_help(code: &str) -> Option<String> {
    let (name, value) = code.split_once('=')?;
    let (name, value) = (name.trim(), value.trim());
    let is_name = name.chars().next().is_some_and(char::is_alphabetic)
        && name.chars().all(|c| c.is_alphanumeric() || c == '_');
    if !is_name || value.is_empty() || value.starts_with('=') {
        return None;
    }
    Some(match name {
        "n" | "N" | "iterations" | "steps" | "generations" => {
            format!("the number of derivation steps is a header: `derivation length: {value}`")
        }
        "delta" | "δ" => format!("the turning angle is a header: `angle: {value}`"),
        _ => format!("a constant is defined with `#define {name} {value}`"),
    })
}

/// A lone `=` (not `==`, `<=`, `>=`, `!=`) before the line's arrow.
fn single_equals(line: &str) -> bool {
    let head = ["-->", "->", "→"]
        .iter()
        .filter_map(|a| line.find(a))
        .min()
        .map_or(line, |i| &line[..i]);
    let b = head.as_bytes();
    (0..b.len()).any(|i| {
        b[i] == b'='
            && b.get(i + 1) != Some(&b'=')
            && !(i > 0 && matches!(b[i - 1], b'=' | b'<' | b'>' | b'!'))
    })
}
