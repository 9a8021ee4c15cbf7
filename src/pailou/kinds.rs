//! The Pailou's one vocabulary: every kind of component, the name graph
//! files and the relation matrix give it, the grammar symbol that draws
//! it, and whether a graph may name it. The graph reader, the structural
//! check and the studio's palette all read this table.

/// One kind of Pailou component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Kind {
    /// As graph files and `grammar/std/relations.toml` name it.
    pub name: &'static str,
    /// The module of `grammar/std/pailou.lsys` that draws it, if one
    /// draws only it (suspended pillars are drawn as `MP`, like pillars).
    pub symbol: Option<&'static str>,
    /// Whether a component graph may name it (a pillar cap comes with its
    /// pillar).
    pub in_graphs: bool,
}

const fn kind(name: &'static str, symbol: Option<&'static str>, in_graphs: bool) -> Kind {
    Kind {
        name,
        symbol,
        in_graphs,
    }
}

/// Every kind, in the order graph files list them.
pub const KINDS: &[Kind] = &[
    kind("pillar", Some("MP"), true),
    kind("suspended_pillar", None, true),
    kind("lintel", Some("ML"), true),
    kind("pillar_base", Some("MPB"), true),
    kind("pillar_cap", Some("MPC"), false),
    kind("flower_board", Some("MFB"), true),
    kind("queti", Some("MQ"), true),
    kind("yundan", Some("MY"), true),
    kind("inscribed_board", Some("MIB"), true),
    kind("middle_toukung", Some("TM"), true),
    kind("side_toukung", Some("TS"), true),
    kind("clipped_roof", Some("RC"), true),
    kind("eaves_roof", Some("RE"), true),
    // Issue 37, defect 8: parts that come with their hosts (a graph names
    // the host): booklet pillars with the flower board, capital stones
    // with the pillar bases, Chuihuas with the pillars of an entrance
    // above, ornaments and stone animals with the roofs.
    kind("booklet_pillar", Some("MBP"), false),
    kind("capital_stone", Some("MCS"), false),
    kind("chuihua", Some("MCH"), false),
    kind("ridge_ornament", Some("MRO"), false),
    kind("stone_animal", Some("MSA"), false),
];

/// Symbols that draw a kind another symbol draws too: the paper's three
/// lintels (C1-C3) are one kind to the relation matrix, `ML` the big
/// lintel, `MLS` the small one under the flower board, `MLO` the single
/// lintel of an entrance above.
const ALSO: &[(&str, &str)] = &[("MLS", "lintel"), ("MLO", "lintel")];

/// The kinds a graph may name.
pub fn graph_kinds() -> impl Iterator<Item = &'static str> {
    KINDS.iter().filter(|k| k.in_graphs).map(|k| k.name)
}

/// Whether a graph may name `kind`.
pub fn is_graph_kind(kind: &str) -> bool {
    graph_kinds().any(|k| k == kind)
}

/// Each drawing symbol with the kind it draws.
pub fn symbols() -> impl Iterator<Item = (&'static str, &'static str)> {
    KINDS
        .iter()
        .filter_map(|k| Some((k.symbol?, k.name)))
        .chain(ALSO.iter().copied())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grammar components the library places (`~TM`, `~TS`) are
    /// kinds of this table, and every symbol draws in the Pailou grammar.
    #[test]
    fn the_vocabulary_agrees_with_the_library() {
        let pailou = crate::stdlib::get("pailou").expect("pailou.lsys");
        for (symbol, _) in crate::stdlib::GRAMMAR_COMPONENTS {
            assert!(
                symbols().any(|(s, _)| s == *symbol),
                "{symbol} is not a Pailou kind"
            );
        }
        for (symbol, name) in symbols() {
            assert!(
                pailou.contains(&format!("{symbol}(")) || pailou.contains(&format!("~{symbol}")),
                "{symbol} ({name}) is not in pailou.lsys"
            );
        }
        let relations: std::collections::BTreeMap<String, Vec<String>> =
            toml::from_str(super::super::graph::RELATIONS).expect("relations read");
        for (support, parts) in &relations {
            for k in std::iter::once(support).chain(parts) {
                assert!(
                    KINDS.iter().any(|x| x.name == k),
                    "relations.toml names `{k}`, not a kind"
                );
            }
        }
    }
}
