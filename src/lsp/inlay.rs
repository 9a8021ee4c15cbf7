//! Inlay hints. Input: an [`Analysis`] and a line range of the root
//! document; output: the evaluated value after each `#define` whose value
//! is an expression (`#define W N*2` shows `= 6`, with `-D` overrides
//! applied), and parameter names before the arguments of a module written
//! in a successor or the axiom (`A(x+1)` shows `x: x+1` when `A`'s
//! productions name the parameter `x`; not repeated when the argument is
//! that name).

use std::collections::HashMap;

use lsp_types::{InlayHint, InlayHintKind, InlayHintLabel};

use super::analysis::{Analysis, ROOT};
use super::index::{arities, Kind};
use super::position::LineIndex;
use crate::parse::ast::{ExprKind, HeaderKind, Item, ModuleTok};

pub fn hints(a: &Analysis, first_line: u32, last_line: u32) -> Vec<InlayHint> {
    let ix = LineIndex::new(a.text(ROOT));
    let params = arities(&a.items);
    let mut out = Vec::new();
    let hint = |offset: u32, label: String, kind, left: bool| InlayHint {
        position: ix.position(offset as usize),
        label: InlayHintLabel::String(label),
        kind: Some(kind),
        text_edits: None,
        tooltip: None,
        padding_left: Some(left),
        padding_right: Some(!left),
        data: None,
    };
    // Looked up once, not searched per module or define: searching made
    // hints quadratic (a 16k-line grammar took 27 s).
    let modules: HashMap<u32, &str> = a
        .index
        .occs
        .iter()
        .filter(|o| o.span.file == ROOT && o.kind == Kind::Module)
        .map(|o| (o.span.end, o.name.as_str()))
        .collect();
    let mut values: HashMap<&str, Option<f64>> = HashMap::new();
    for i in a.program().map_or(&[][..], |p| &p.defines) {
        values.entry(i.name.as_str()).or_insert(i.value);
    }
    let calls = |m: &ModuleTok, out: &mut Vec<InlayHint>| {
        let Some(args) = &m.args else { return };
        let name = modules.get(&m.name_span.end);
        let Some(ps) = name.and_then(|o| params.get(*o)) else {
            return;
        };
        if ps.len() != args.len() {
            return;
        }
        for (p, arg) in ps.iter().zip(args) {
            if matches!(&arg.kind, ExprKind::Name(n) if n == p) {
                continue;
            }
            out.push(hint(
                arg.span.start,
                format!("{p}:"),
                InlayHintKind::PARAMETER,
                false,
            ));
        }
    };
    for (file, item) in &a.items {
        if *file != ROOT {
            continue;
        }
        match item {
            Item::Define(ds) => {
                for d in ds {
                    let Some(v) = &d.value else { continue };
                    if matches!(v.kind, ExprKind::Num(_)) || d.params.is_some() {
                        continue;
                    }
                    if let Some(value) = values.get(d.name.name.as_str()).copied().flatten() {
                        out.push(hint(
                            d.span.end,
                            format!("= {value}"),
                            InlayHintKind::TYPE,
                            true,
                        ));
                    }
                }
            }
            Item::Production(p) => {
                for m in &p.succ {
                    calls(m, &mut out);
                }
            }
            Item::Header(h) => {
                if let HeaderKind::Axiom(ms) = &h.kind {
                    for m in ms {
                        calls(m, &mut out);
                    }
                }
            }
            _ => {}
        }
    }
    out.retain(|h| (first_line..=last_line).contains(&h.position.line));
    out.sort_by_key(|h| (h.position.line, h.position.character));
    out
}
