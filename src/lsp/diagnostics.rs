//! Compiler diagnostics -> LSP diagnostics and their quick fixes. Input:
//! an [`Analysis`] (the compiler's errors and warnings, miette reports
//! with byte spans); output: `Diagnostic`s for the root document, with
//! the code (`lsys::resolve::arity`), the first label as the range, the
//! other labels as related information, the help appended to the message,
//! and unreachable productions tagged unnecessary.
//!
//! A diagnostic inside an included file is shown at the root's `#include`
//! line that leads to it, with its real place as related information.
//! Where the help names the fix (`did you mean \`X\`?`, a typographic
//! character's ASCII form, an unquoted include), the fix rides along in
//! the diagnostic's `data` and [`code_actions`] offers it.

use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Diagnostic, DiagnosticRelatedInformation,
    DiagnosticSeverity, DiagnosticTag, Location, NumberOrString, Range, TextEdit, Url,
    WorkspaceEdit,
};
use miette::Severity;
use serde::{Deserialize, Serialize};

use super::analysis::{Analysis, ROOT};
use std::collections::HashMap;

use super::position::{LineIndex, Lines};
use crate::source::FileId;

/// A fix carried in a diagnostic's `data`.
#[derive(Serialize, Deserialize)]
struct Fix {
    title: String,
    range: Range,
    text: String,
}

/// Every diagnostic of the root document, errors first as the compiler
/// reports them.
pub fn diagnostics(a: &Analysis) -> Vec<Diagnostic> {
    let reports: Vec<&dyn miette::Diagnostic> = match &a.result {
        Ok(c) => c.warnings.iter().map(|r| r.as_ref() as _).collect(),
        Err(d) => d.iter().map(|d| d as _).collect(),
    };
    // Each source text is measured once, not once per diagnostic: that
    // made 20,000 errors in a 340 kB file take longer than the server's
    // analysis budget.
    let mut texts: Texts = HashMap::new();
    for d in &reports {
        let Some(src) = d.source_code() else { continue };
        let Some(name) = source_name(src) else {
            continue;
        };
        if texts.contains_key(&name) {
            continue;
        }
        if let Ok(whole) = src.read_span(&(0, 0).into(), 0, usize::MAX) {
            let text = String::from_utf8_lossy(whole.data()).into_owned();
            texts.insert(name, LineIndex::owned(text));
        }
    }
    let root = if a.sources.files().is_empty() {
        ""
    } else {
        a.text(ROOT)
    };
    let ixs = Indexes {
        texts,
        root: LineIndex::new(root),
        doc: LineIndex::new(&a.doc),
    };
    reports.into_iter().map(|d| convert(a, &ixs, d)).collect()
}

/// Source texts by name (`None`: a source without a name), measured.
type Texts = HashMap<Option<String>, Lines>;

struct Indexes<'a> {
    texts: Texts,
    root: LineIndex<'a>,
    doc: LineIndex<'a>,
}

/// The name of a diagnostic's source (`Some(None)` when it has none),
/// read without going through the whole text.
fn source_name(src: &dyn miette::SourceCode) -> Option<Option<String>> {
    let first = src.read_span(&(0, 0).into(), 0, 0).ok()?;
    Some(first.name().map(str::to_string))
}

/// Where a label points: the file (by the name of the diagnostic's
/// source) and the range, measured in the diagnostic's own source text
/// (for a cpfg model that is the file as written, before the
/// preprocessor).
fn label_place(
    a: &Analysis,
    ixs: &Indexes,
    d: &dyn miette::Diagnostic,
    l: &miette::LabeledSpan,
) -> Option<(FileId, Range)> {
    let name = source_name(d.source_code()?)?;
    let file = match &name {
        Some(name) => a.file_named(name)?,
        None => ROOT,
    };
    let ix = ixs.texts.get(&name)?.index();
    Some((file, ix.range(l.offset(), l.offset() + l.len())))
}

fn location(a: &Analysis, file: FileId, range: Range) -> Option<Location> {
    Some(Location::new(a.uri_of(file)?.clone(), range))
}

fn convert(a: &Analysis, ixs: &Indexes, d: &dyn miette::Diagnostic) -> Diagnostic {
    let labels: Vec<miette::LabeledSpan> = d.labels().map(|l| l.collect()).unwrap_or_default();
    let places: Vec<_> = labels.iter().map(|l| label_place(a, ixs, d, l)).collect();
    let root_ix = &ixs.root;
    let mut message = d.to_string();
    let mut related = Vec::new();
    let mut range = Range::default();
    match places.first().copied().flatten() {
        Some((ROOT, r)) => range = r,
        Some((file, r)) => {
            if let Some(inc) = a.root_include(file) {
                range = root_ix.range(inc.start as usize, inc.end as usize);
            }
            message = format!("in {}: {message}", a.sources.get(file).name);
            if let Some(loc) = location(a, file, r) {
                related.push(DiagnosticRelatedInformation {
                    location: loc,
                    message: labels[0].label().unwrap_or("here").to_string(),
                });
            }
        }
        None => {}
    }
    for (l, place) in labels.iter().zip(&places).skip(1) {
        if let Some(loc) = place.and_then(|(f, r)| location(a, f, r)) {
            related.push(DiagnosticRelatedInformation {
                location: loc,
                message: l.label().unwrap_or("here").to_string(),
            });
        }
    }
    let help = d.help().map(|h| h.to_string());
    if let Some(h) = &help {
        message.push_str("\nhelp: ");
        message.push_str(h);
    }
    let code = d.code().map(|c| c.to_string());
    let tags = (code.as_deref() == Some("lsys::resolve::unreachable"))
        .then(|| vec![DiagnosticTag::UNNECESSARY]);
    let on_root = matches!(places.first(), Some(Some((ROOT, ..))));
    let fix = help
        .as_deref()
        .filter(|_| on_root)
        .and_then(|h| fix(&a.doc, &ixs.doc, range, h));
    Diagnostic {
        range,
        severity: Some(match d.severity() {
            None | Some(Severity::Error) => DiagnosticSeverity::ERROR,
            Some(Severity::Warning) => DiagnosticSeverity::WARNING,
            Some(Severity::Advice) => DiagnosticSeverity::HINT,
        }),
        code: code.map(NumberOrString::String),
        source: Some("lsys".to_string()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        tags,
        data: fix.map(|f| serde_json::to_value(f).expect("a fix serialises")),
        ..Diagnostic::default()
    }
}

/// The text between the first pair of backticks after `marker` in `help`.
fn quoted_after<'h>(help: &'h str, marker: &str) -> Option<&'h str> {
    let rest = &help[help.find(marker)? + marker.len()..];
    let start = rest.find('`')? + 1;
    let len = rest[start..].find('`')?;
    Some(&rest[start..start + len])
}

/// The fix a help text names, if it names one.
fn fix(text: &str, ix: &LineIndex, range: Range, help: &str) -> Option<Fix> {
    let (s, e) = (ix.offset(range.start), ix.offset(range.end));
    let written = text.get(s..e)?;
    if let Some(name) = quoted_after(help, "did you mean") {
        // `~MPX` -> `~MP`: keep whichever `~` the range already has.
        let name = if written.starts_with('~') {
            name.to_string()
        } else {
            name.trim_start_matches('~').to_string()
        };
        if name.ends_with(':') || name.is_empty() {
            return None;
        }
        return Some(Fix {
            title: format!("Replace `{written}` with `{name}`"),
            range,
            text: name,
        });
    }
    if help.contains("is a typographic character") {
        let ascii = quoted_after(help, "write the ASCII")?;
        return Some(Fix {
            title: format!("Replace `{written}` with `{ascii}`"),
            range,
            text: ascii.to_string(),
        });
    }
    if let Some(line) = quoted_after(help, "a file to include is written in quotes:") {
        // Replace the whole `#include ...` statement of that line.
        let line_start = text[..s].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[s..].find('\n').map_or(text.len(), |i| s + i);
        let stmt = &text[line_start..line_end];
        let from = line_start + stmt.find("#include")?;
        let to = line_start + stmt.trim_end().len();
        return Some(Fix {
            title: format!("Write `{line}`"),
            range: ix.range(from, to),
            text: line.to_string(),
        });
    }
    None
}

/// The quick fixes of the diagnostics the client sends back (each carries
/// its fix in `data`).
pub fn code_actions(uri: &Url, diagnostics: &[Diagnostic]) -> Vec<CodeActionOrCommand> {
    diagnostics
        .iter()
        .filter_map(|d| {
            let fix: Fix = serde_json::from_value(d.data.clone()?).ok()?;
            let edit = TextEdit::new(fix.range, fix.text);
            Some(CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title,
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![d.clone()]),
                edit: Some(WorkspaceEdit {
                    changes: Some([(uri.clone(), vec![edit])].into_iter().collect()),
                    ..WorkspaceEdit::default()
                }),
                is_preferred: Some(true),
                ..CodeAction::default()
            }))
        })
        .collect()
}
