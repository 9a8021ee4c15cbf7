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
    kind("pillar_cap", Some("MBP"), false),
    kind("flower_board", Some("MFB"), true),
    kind("queti", Some("MQ"), true),
    kind("yundan", Some("MY"), true),
    kind("inscribed_board", Some("MIB"), true),
    kind("middle_toukung", Some("TM"), true),
    kind("side_toukung", Some("TS"), true),
    kind("clipped_roof", Some("RC"), true),
    kind("eaves_roof", Some("RE"), true),
];

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
    KINDS.iter().filter_map(|k| Some((k.symbol?, k.name)))
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
