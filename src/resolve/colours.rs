//! Colour indices no palette entry has: the resolved [`Program`] in, one
//! warning per index out, for `;(i)`, `,(i)` and `'(i)` with a constant
//! `i` below 0 (read as 0) or past every entry (it wraps around the 16
//! defaults, `src/mesh/palette.rs`): an ABOP or cpfg index such as
//! `;(300)` silently gives another colour (issue 35).

use std::collections::HashSet;

use super::error::ResolveError;
use super::ir::{ExprKind, Program, SuccModule};

/// The number of default palette entries (`mesh::palette::DEFAULT`).
const DEFAULTS: usize = 16;

pub(super) fn out_of_palette(program: &Program) -> Vec<ResolveError> {
    let symbols = &program.symbols;
    let setters: Vec<u32> = [";", ",", "'"]
        .iter()
        .filter_map(|n| symbols.get(n))
        .collect();
    if setters.is_empty() {
        return Vec::new();
    }
    let entries = program
        .turtle
        .palette
        .iter()
        .map(|(i, _)| i + 1)
        .max()
        .unwrap_or(0)
        .max(DEFAULTS);
    let modules = program.axiom.iter().chain(
        program
            .productions
            .iter()
            .chain(&program.decomposition)
            .chain(&program.homomorphism)
            .flat_map(|p| p.succ.iter()),
    );
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for m in modules.filter(|m| setters.contains(&m.sym)) {
        let Some(i) = constant_index(m) else { continue };
        if (0.0..entries as f64).contains(&i) || !seen.insert(i.to_bits()) {
            continue;
        }
        let (what, help) = if i < 0.0 {
            (
                "below 0: it is read as 0".to_string(),
                "colour indices count from 0".to_string(),
            )
        } else {
            (
                format!(
                    "past the palette's {entries} entries: it wraps around to the default {}",
                    (i as u64) % DEFAULTS as u64
                ),
                format!("lsys has 16 default colours (0-15); give this index a colour of its own with a header `colour {i}: #rrggbb`, or use an index the palette has"),
            )
        };
        out.push(ResolveError::ColourIndex {
            index: i,
            what,
            help,
            src: program.sources.named_source(m.span),
            span: m.span.into(),
        });
    }
    out
}

/// The first parameter of a colour command, when it is a constant.
fn constant_index(m: &SuccModule) -> Option<f64> {
    match m.args.first()?.kind {
        ExprKind::Num(v) => Some(v),
        _ => None,
    }
}
