//! The Pailou front-end: a style (`4-3-7`, ridge or pillar type, in
//! `style.rs`) or a component graph (TOML, read into a document by
//! `document.rs` and checked by `graph.rs`) -> a [`Layout`] -> the standard
//! library's Pailou grammar with its layout tables filled in, ready to
//! compile (or to print for an expert to continue by hand); and a layout's
//! canonical graph back out (`emit.rs`, written by `document.rs`).
//! `kinds.rs` names the component kinds, `structure/` checks a built
//! Pailou's parts against the relation matrix.
pub mod document;
mod emit;
pub mod graph;
pub mod kinds;
pub mod ranges;
pub mod structure;
pub mod style;

pub use document::GraphDocument;
pub use style::{layout, parse_style, Entrance, Layout, PailouType, Roof, StyleError};

use crate::load::Input;

const BEGIN: &str = "// <layout>";
const END: &str = "// </layout>";

/// The standard library's Pailou grammar with `layout`'s tables in place
/// of its default ones.
pub fn source(layout: &Layout, title: &str) -> String {
    let std = crate::stdlib::get("pailou").expect("the standard library has pailou.lsys");
    let start = std.find(BEGIN).expect("pailou.lsys marks its layout");
    let end = std.find(END).expect("pailou.lsys marks its layout's end");
    // Keep the marker lines so that the output can be generated again.
    let begin_line_end = start + std[start..].find('\n').map_or(0, |n| n + 1);
    format!(
        "{}{BEGIN} {title}, written by `lsys pailou`\n{}{}",
        &std[..start],
        layout.defines(),
        &std[end..]
    )
    .replacen(&std[start..begin_line_end], "", 0)
}

/// The grammar for a layout, as an input to compile, named `name`.
pub fn input(layout: &Layout, kind: PailouType, title: &str, name: &str) -> Input {
    let _ = kind; // the type is in the layout (dec[i,j,11] and the roofs)
    Input::Text {
        name: name.to_string(),
        text: source(layout, title),
    }
}

/// The layout of a style.
pub fn style_layout(style: &str, kind: PailouType) -> Result<Layout, StyleError> {
    let (np, ne, nr) = parse_style(style)?;
    layout(np, ne, nr, kind)
}

/// The Pailou's Toukung levels `NTL` and those of its Toukungs (`TM.NTL`,
/// `TS.NTL`) agree: the grammar sizes the Toukung rows from `NTL`, so
/// `-D NTL=7` also reaches the components, and `-D TM.NTL=7` alone sets
/// the Pailou's `NTL` too (the side Toukungs follow unless given).
pub fn toukung_levels(defines: &mut Vec<(String, String)>) {
    let last = |d: &[(String, String)], n: &str| {
        d.iter().rev().find(|(k, _)| k == n).map(|(_, v)| v.clone())
    };
    let ntl = last(defines, "NTL").or_else(|| last(defines, "TM.NTL"));
    if let Some(v) = ntl {
        for name in ["NTL", "TM.NTL", "TS.NTL"] {
            if last(defines, name).is_none() {
                defines.push((name.to_string(), v.clone()));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The library's own tables are the generator's 4-3-7 ridge type, so
    /// `std:pailou` and `lsys pailou --style 4-3-7` build the same Pailou.
    #[test]
    fn std_default_is_the_4_3_7_ridge_style() {
        let l = layout(4, 3, 7, PailouType::Ridge).unwrap();
        let std = crate::stdlib::get("pailou").unwrap();
        let start = std.find(BEGIN).unwrap();
        let block = &std[start..std.find(END).unwrap()];
        let block = &block[block.find('\n').unwrap() + 1..];
        assert_eq!(block, l.defines());
    }
}
