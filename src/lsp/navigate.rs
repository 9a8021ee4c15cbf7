//! Go to definition, find references, rename, document links and
//! document symbols. Input: an [`Analysis`] and the occurrence at the
//! cursor (from its [`super::index::Index`]); output: LSP locations and
//! edits in every file the model reads (the root, its includes, the
//! standard library's cached copies), sorted by file and position.

use std::collections::HashMap;

use lsp_types::{
    DocumentLink, DocumentSymbol, Location, Position, Range, SymbolKind, TextEdit, Url,
    WorkspaceEdit,
};

use super::analysis::{Analysis, ROOT};
use super::index::{Kind, Occ};
use super::position::LineIndex;
use crate::parse::ast::{HeaderKind, Item, PatTok};
use crate::resolve::alphabet::is_word_char;
use crate::source::{Origin, Span};

pub fn location(a: &Analysis, span: Span) -> Option<Location> {
    let uri = a.uri_of(span.file)?.clone();
    let ix = LineIndex::new(a.text(span.file));
    Some(Location::new(
        uri,
        ix.range(span.start as usize, span.end as usize),
    ))
}

pub fn definition(a: &Analysis, occ: &Occ) -> Vec<Location> {
    if occ.kind == Kind::Include {
        let Some(target) = occ.target else {
            return Vec::new();
        };
        return a
            .uri_of(target)
            .map(|u| Location::new(u.clone(), Range::default()))
            .into_iter()
            .collect();
    }
    let mut out: Vec<Location> = a
        .index
        .definitions(occ)
        .filter_map(|o| location(a, o.span))
        .collect();
    if occ.kind == Kind::Component {
        // The model (OBJ or grammar) the component places.
        if let Some(uri) = super::hover::component_source(a, &occ.name)
            .1
            .and_then(|p| Url::from_file_path(p).ok())
        {
            out.push(Location::new(uri, Range::default()));
        }
    }
    out
}

pub fn references(a: &Analysis, occ: &Occ, with_declarations: bool) -> Vec<Location> {
    a.index
        .references(occ)
        .filter(|o| with_declarations || !o.def)
        .filter_map(|o| location(a, o.span))
        .collect()
}

/// Whether `occ` can be renamed, and the range of its name.
pub fn can_rename(a: &Analysis, occ: &Occ) -> Result<(), String> {
    match occ.kind {
        Kind::Define | Kind::Module | Kind::Param => {}
        Kind::Turtle => return Err(format!("`{}` is a turtle command", occ.name)),
        _ => return Err("only modules, defines and parameters can be renamed".to_string()),
    }
    if let Some(o) = a.index.references(occ).find(|o| {
        !matches!(a.sources.get(o.span.file).origin, Origin::Disk(_)) && o.span.file != ROOT
    }) {
        return Err(format!(
            "`{}` is used in {}, which cannot be edited",
            occ.name,
            a.sources.get(o.span.file).name
        ));
    }
    Ok(())
}

pub fn rename(a: &Analysis, occ: &Occ, new_name: &str) -> Result<WorkspaceEdit, String> {
    can_rename(a, occ)?;
    let valid = !new_name.is_empty()
        && new_name.chars().all(is_word_char)
        && !new_name.starts_with(|c: char| c.is_ascii_digit());
    if !valid {
        return Err(format!(
            "`{new_name}` is not a name (letters, digits and `_`)"
        ));
    }
    if occ.kind != Kind::Param && crate::lang::lookup(new_name).is_some() {
        return Err(format!("`{new_name}` is a turtle command"));
    }
    if occ.kind == Kind::Module && a.profile.cpfg_names && new_name.chars().count() > 1 {
        return Err("module names of a cpfg model are one character".to_string());
    }
    let mut changes: HashMap<Url, Vec<TextEdit>> = HashMap::new();
    for o in a.index.references(occ) {
        if let Some(loc) = location(a, o.span) {
            changes
                .entry(loc.uri)
                .or_default()
                .push(TextEdit::new(loc.range, new_name.to_string()));
        }
    }
    Ok(WorkspaceEdit {
        changes: Some(changes),
        ..WorkspaceEdit::default()
    })
}

/// A link on each `#include` path of the root document.
pub fn links(a: &Analysis) -> Vec<DocumentLink> {
    let ix = LineIndex::new(a.text(ROOT));
    a.includes
        .iter()
        .filter(|(span, _)| span.file == ROOT)
        .filter_map(|&(span, target)| {
            Some(DocumentLink {
                range: ix.range(span.start as usize, span.end as usize),
                target: Some(a.uri_of(target)?.clone()),
                tooltip: Some(a.sources.get(target).name.clone()),
                data: None,
            })
        })
        .collect()
}

/// The outline of the root document: headers, defines and the productions
/// grouped by their first predecessor module.
#[allow(deprecated)] // `DocumentSymbol::deprecated` must still be written.
pub fn symbols(a: &Analysis) -> Vec<DocumentSymbol> {
    let ix = LineIndex::new(a.text(ROOT));
    let range = |s: Span| ix.range(s.start as usize, s.end as usize);
    let sym = |name: String, detail: Option<String>, kind, full: Span, sel: Span| DocumentSymbol {
        name,
        detail,
        kind,
        tags: None,
        deprecated: None,
        range: range(full),
        selection_range: range(sel),
        children: None,
    };
    let mut out: Vec<DocumentSymbol> = Vec::new();
    let mut groups: HashMap<String, usize> = HashMap::new();
    for (file, item) in &a.items {
        if *file != ROOT {
            continue;
        }
        match item {
            Item::Define(ds) => {
                for d in ds {
                    let value = d.value.as_ref().map(|v| v.to_string());
                    out.push(sym(
                        d.name.name.clone(),
                        value,
                        SymbolKind::CONSTANT,
                        d.span,
                        d.name.span,
                    ));
                }
            }
            Item::Header(h) => {
                let text = a.sources.slice(h.span).trim();
                let name = match &h.kind {
                    HeaderKind::Axiom(_) | HeaderKind::LongAxiom(_) => "axiom".to_string(),
                    _ => text.split(':').next().unwrap_or(text).trim().to_string(),
                };
                let detail = text.split_once(':').map(|(_, v)| v.trim().to_string());
                let detail = detail.filter(|d| !d.is_empty());
                out.push(sym(name, detail, SymbolKind::PROPERTY, h.span, h.keyword));
            }
            Item::Production(p) => {
                let head = p
                    .pred
                    .iter()
                    .find_map(|t| match t {
                        PatTok::Module(m) => Some(m.text.clone()),
                        _ => None,
                    })
                    .unwrap_or_default();
                let text = a.sources.slice(p.span).trim();
                let line = text.lines().next().unwrap_or(text).to_string();
                let child = sym(line, None, SymbolKind::METHOD, p.span, p.head_span);
                let i = *groups.entry(head.clone()).or_insert_with(|| {
                    out.push(sym(
                        head.clone(),
                        Some("productions".into()),
                        SymbolKind::FUNCTION,
                        p.span,
                        p.head_span,
                    ));
                    out.len() - 1
                });
                let g = &mut out[i];
                g.range.end = g.range.end.max(range(p.span).end);
                g.children.get_or_insert_with(Vec::new).push(child);
            }
            _ => {}
        }
    }
    out
}

/// The byte offset of `pos` in the root document.
pub fn offset(a: &Analysis, pos: Position) -> u32 {
    LineIndex::new(a.text(ROOT)).offset(pos) as u32
}
