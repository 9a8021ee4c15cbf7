//! Completion and semantic tokens. Input: an [`Analysis`] and a cursor
//! (completion) or nothing (tokens); output: completion items — modules
//! with their arity as snippets, turtle commands, defines, header
//! keywords, include paths and standard library names — and the root
//! document's semantic tokens (module vs turtle command vs query vs
//! parameter vs component vs define vs include path).

use lsp_types::{
    CompletionItem, CompletionItemKind, InsertTextFormat, SemanticToken, SemanticTokenModifier,
    SemanticTokenType, SemanticTokensLegend,
};

use super::analysis::{Analysis, ROOT};
use super::index::{arities, Kind};
use super::position::LineIndex;
use crate::stdlib;

/// Header keywords and directives offered at the start of a line.
const KEYWORDS: &[(&str, &str)] = &[
    ("axiom: ", "the starting string"),
    ("derivation length: ", "steps to derive by default"),
    ("ignore: ", "modules context matching skips"),
    ("consider: ", "the only modules context matching looks at"),
    ("seed: ", "seed of the random generator"),
    ("angle: ", "the default turning angle in degrees"),
    ("step: ", "the default step length"),
    ("width: ", "the initial line width"),
    ("dialect: ", "paper or cpfg"),
    (
        "maximum depth: ",
        "recursion limit of decomposition and homomorphism",
    ),
    ("lsystem: ", "the L-system's number (cpfg)"),
    ("module ", "declare modules and their parameters"),
    ("homomorphism", "productions for the turtle's string only"),
    (
        "decomposition",
        "productions applied recursively after each step",
    ),
    ("endlsystem", "end of the L-system (cpfg)"),
    ("#define ", "a named constant, table or function"),
    (
        "#include ",
        "a file, a standard library grammar or components",
    ),
];

fn item(label: String, kind: CompletionItemKind, detail: String, sort: &str) -> CompletionItem {
    CompletionItem {
        sort_text: Some(format!("{sort}{label}")),
        label,
        kind: Some(kind),
        detail: Some(detail),
        ..CompletionItem::default()
    }
}

/// Completions at byte `offset` of the root document.
/// `trigger`: the character typed that asked for completion, if any (`<`
/// and `"` ask only on an `#include` line; elsewhere `<` is a command).
pub fn completions(a: &Analysis, offset: usize, trigger: Option<&str>) -> Vec<CompletionItem> {
    let text = a.text(ROOT);
    let offset = offset.min(text.len());
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let before = &text[line_start..offset];
    let trimmed = before.trim_start();
    if let Some(rest) = trimmed.strip_prefix("#include") {
        return includes(a, rest);
    }
    if matches!(trigger, Some("<" | "\"")) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let at_line_start = trimmed
        .chars()
        .all(|c| c.is_alphanumeric() || c == '#' || c == ' ');
    if at_line_start && !trimmed.contains(' ') {
        for (kw, doc) in KEYWORDS {
            out.push(item(
                kw.trim_end().to_string(),
                CompletionItemKind::KEYWORD,
                doc.to_string(),
                "3",
            ));
            out.last_mut().expect("pushed").insert_text = Some(kw.to_string());
        }
    }
    let params = arities(&a.items);
    for o in a.index.defined(Kind::Module) {
        if o.kind != Kind::Module {
            continue;
        }
        let ps = params.get(&o.name).cloned().unwrap_or_default();
        let mut it = item(
            o.name.clone(),
            CompletionItemKind::CLASS,
            if ps.is_empty() {
                "module".into()
            } else {
                format!("module {}({})", o.name, ps.join(", "))
            },
            "0",
        );
        if !ps.is_empty() {
            let args: Vec<String> = ps
                .iter()
                .enumerate()
                .map(|(i, p)| format!("${{{}:{p}}}", i + 1))
                .collect();
            it.insert_text = Some(format!("{}({})", o.name, args.join(",")));
            it.insert_text_format = Some(InsertTextFormat::SNIPPET);
        }
        out.push(it);
    }
    for o in a.index.defined(Kind::Define) {
        let value = o
            .stmt
            .map(|s| format!("#define {}", a.sources.slice(s).trim()))
            .unwrap_or_default();
        out.push(item(
            o.name.clone(),
            CompletionItemKind::CONSTANT,
            value,
            "1",
        ));
    }
    for c in crate::lang::commands::all() {
        let mut it = item(
            c.symbol.to_string(),
            CompletionItemKind::FUNCTION,
            c.doc.to_string(),
            "2",
        );
        if c.min_args > 0 {
            it.insert_text = Some(format!("{}(${{1}})", c.symbol));
            it.insert_text_format = Some(InsertTextFormat::SNIPPET);
        }
        out.push(it);
    }
    for o in a.index.defined(Kind::Component) {
        out.push(item(
            format!("~{}", o.name),
            CompletionItemKind::MODULE,
            "component".into(),
            "2",
        ));
    }
    out
}

/// After `#include`: files beside the document, `<std>` names, components.
fn includes(a: &Analysis, rest: &str) -> Vec<CompletionItem> {
    let rest = rest.trim_start();
    let mut out = Vec::new();
    let quoted = rest.starts_with('"');
    let angled = rest.starts_with('<');
    if !quoted {
        for name in stdlib::names() {
            let (label, insert) = if angled {
                (name.to_string(), name.to_string())
            } else {
                (format!("<{name}>"), format!("<{name}>"))
            };
            let mut it = item(
                label,
                CompletionItemKind::MODULE,
                format!("standard library grammar std:{name}"),
                "0",
            );
            it.insert_text = Some(insert);
            out.push(it);
        }
    }
    if !angled {
        let dir = a
            .uri
            .to_file_path()
            .ok()
            .and_then(|p| p.parent().map(|d| d.to_path_buf()));
        let mut files: Vec<String> = dir
            .and_then(|d| std::fs::read_dir(d).ok())
            .into_iter()
            .flatten()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.ends_with(".lsys"))
            .filter(|n| Some(n.as_str()) != a.uri.path_segments().and_then(|mut s| s.next_back()))
            .collect();
        files.sort();
        for f in files {
            let insert = if quoted {
                f.clone()
            } else {
                format!("\"{f}\"")
            };
            let mut it = item(
                format!("\"{f}\""),
                CompletionItemKind::FILE,
                "a grammar beside this one".into(),
                "1",
            );
            it.insert_text = Some(insert);
            out.push(it);
        }
    }
    if !quoted && !angled {
        for (name, _) in stdlib::COMPONENTS {
            out.push(item(
                name.to_string(),
                CompletionItemKind::MODULE,
                "built-in component".into(),
                "2",
            ));
        }
    }
    out
}

/// The semantic token types, in legend order.
const TYPES: &[(Kind, SemanticTokenType)] = &[
    (Kind::Module, SemanticTokenType::TYPE),
    (Kind::Turtle, SemanticTokenType::FUNCTION),
    (Kind::Query, SemanticTokenType::EVENT),
    (Kind::Component, SemanticTokenType::CLASS),
    (Kind::Define, SemanticTokenType::MACRO),
    (Kind::Param, SemanticTokenType::PARAMETER),
    (Kind::Include, SemanticTokenType::STRING),
];

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: TYPES.iter().map(|(_, t)| t.clone()).collect(),
        token_modifiers: vec![SemanticTokenModifier::DECLARATION],
    }
}

/// The root document's tokens, delta-encoded in UTF-16 positions.
pub fn semantic_tokens(a: &Analysis) -> Vec<SemanticToken> {
    let ix = LineIndex::new(a.text(ROOT));
    let doc_ix = LineIndex::new(&a.doc);
    let mut out = Vec::new();
    let (mut line, mut col, mut last_end) = (0u32, 0u32, 0u32);
    for o in a.index.occs.iter().filter(|o| o.span.file == ROOT) {
        if o.span.start < last_end || o.span.is_empty() {
            continue;
        }
        let start = ix.position(o.span.start as usize);
        let end = ix.position(o.span.end as usize);
        if end.line != start.line {
            continue;
        }
        // A cpfg model's root is the preprocessor's output: keep only the
        // tokens that are where the document has them.
        let at = doc_ix.offset(start);
        if a.doc.get(at..at + o.span.len()) != Some(a.sources.slice(o.span)) {
            continue;
        }
        let ty = TYPES
            .iter()
            .position(|(k, _)| *k == o.kind)
            .expect("every kind has a type");
        out.push(SemanticToken {
            delta_line: start.line - line,
            delta_start: if start.line == line {
                start.character - col
            } else {
                start.character
            },
            length: end.character - start.character,
            token_type: ty as u32,
            token_modifiers_bitset: u32::from(o.def),
        });
        (line, col, last_end) = (start.line, start.character, o.span.end);
    }
    out
}
