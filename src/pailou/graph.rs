//! Component graphs checked. Input: a graph file's text, a TOML file of
//! components and attachments (the paper's iconized graph, Sec. 4.1–4.2),
//! and a relation matrix; output: a [`Graph`], the layout chart as a
//! [`Layout`] with the graph's type, defines and the components the layout
//! has no place for, or a diagnostic pointing into the text. The text is
//! parsed into a [`GraphDocument`] (`document.rs`, the format's one reader
//! and writer), every attachment checked against the matrix, and the
//! document walked for the layout. The reverse, the canonical graph of a
//! style, is [`emit`] (in `emit.rs`).
//!
//! ```toml
//! type = "ridge"            # or "pillar"
//! centre = "L11"            # the central entrance's lintel
//! [components]              # id = kind
//! L11 = "lintel"
//! P1R = "pillar"
//! [attach]                  # id = [what it attaches to]
//! L11 = ["P1R", "P1L"]      # a lintel on two pillars: an entrance
//! [defines]                 # optional: the grammar's #defines
//! "ω" = 10
//! ```

use std::collections::{BTreeMap, BTreeSet};

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

use super::document::GraphDocument;
pub use super::emit::emit;
use super::style::*;

/// The library's relation matrix (`grammar/std/relations.toml`).
pub const RELATIONS: &str = include_str!("../../grammar/std/relations.toml");

#[derive(Debug, Error, Diagnostic)]
pub enum GraphError {
    #[error("{file} is not a component graph: {message}")]
    #[diagnostic(
        code(lsys::pailou::syntax),
        help("a graph has `type`, `centre`, a [components] table (id = kind) and an [attach] table (id = [ids]); see docs/pailou.md")
    )]
    Syntax {
        file: String,
        message: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("here")]
        span: Option<SourceSpan>,
    },

    #[error("{message}")]
    #[diagnostic(code(lsys::pailou::graph))]
    Graph {
        message: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("{label}")]
        span: SourceSpan,
        label: String,
        #[help]
        help: String,
    },
}

/// A graph read and checked: the layout it describes and its type.
#[derive(Debug)]
pub struct Graph {
    pub layout: Layout,
    pub kind: PailouType,
    /// `[defines]`: (name, value) as `-D` would give them.
    pub defines: Vec<(String, String)>,
    /// Components the layout has no place for, one sentence each.
    pub unplaced: Vec<String>,
    /// Each entrance's lintel (both halves; the centre's once) and its
    /// entrance (i, j), from 1: what the studio's entrance fields name.
    pub lintels: Vec<(String, usize, usize)>,
    /// Every placed component's entrance (i, j), sorted by id: whose
    /// per-entrance sizes (`pw[i,j]`, `tk[i,j]`, ...) it takes.
    pub entrance_of: Vec<(String, usize, usize)>,
}

struct Reader<'a> {
    src: NamedSource<crate::source::SourceText>,
    kinds: BTreeMap<&'a str, &'a str>,
    /// id -> what it attaches to.
    on: BTreeMap<&'a str, Vec<&'a str>>,
    /// id -> what attaches to it.
    under: BTreeMap<&'a str, Vec<&'a str>>,
    /// Components the layout has taken a decoration or entrance from.
    used: std::cell::RefCell<BTreeSet<String>>,
}

impl Reader<'_> {
    fn err(
        &self,
        span: std::ops::Range<usize>,
        message: String,
        label: &str,
        help: String,
    ) -> Box<GraphError> {
        Box::new(GraphError::Graph {
            message,
            src: self.src.clone(),
            span: span.into(),
            label: label.to_string(),
            help,
        })
    }

    fn kind(&self, id: &str) -> &str {
        self.kinds.get(id).copied().unwrap_or("")
    }

    /// What of `kind` attaches to `id` (each marked as used).
    fn attached(&self, id: &str, kind: &str) -> Vec<&str> {
        let found: Vec<&str> = self
            .under
            .get(id)
            .map(|v| v.iter().copied().filter(|x| self.kind(x) == kind).collect())
            .unwrap_or_default();
        let mut used = self.used.borrow_mut();
        used.extend(found.iter().map(|x| x.to_string()));
        found
    }

    /// The pillars (or suspended pillars) a lintel rests on.
    fn supports(&self, lintel: &str) -> Vec<&str> {
        self.on
            .get(lintel)
            .map(|v| {
                v.iter()
                    .copied()
                    .filter(|x| matches!(self.kind(x), "pillar" | "suspended_pillar"))
                    .collect()
            })
            .unwrap_or_default()
    }
}

/// Reads a graph file (`name` for messages) against a relation matrix.
pub fn read(name: &str, text: &str, relations: &str) -> Result<Graph, Box<GraphError>> {
    let src = NamedSource::new(name, crate::source::SourceText::from(text.to_string()));
    let (doc, spans) = GraphDocument::parse_spanned(text).map_err(|e| {
        Box::new(GraphError::Syntax {
            file: name.to_string(),
            message: e.message().to_string(),
            src: src.clone(),
            span: e.span().map(Into::into),
        })
    })?;
    let matrix: BTreeMap<String, Vec<String>> = toml::from_str(relations).map_err(|e| {
        Box::new(GraphError::Syntax {
            file: "the relation matrix".to_string(),
            message: e.message().to_string(),
            src: NamedSource::new(
                "relations.toml",
                crate::source::SourceText::from(relations.to_string()),
            ),
            span: e.span().map(Into::into),
        })
    })?;
    let mut r = Reader {
        src: src.clone(),
        kinds: BTreeMap::new(),
        on: BTreeMap::new(),
        under: BTreeMap::new(),
        used: Default::default(),
    };
    // Checked in the order of the ids, so that the first problem reported
    // does not depend on where the file lists it.
    let mut components: Vec<&(String, String)> = doc.components.iter().collect();
    components.sort();
    for (id, kind) in components {
        if !super::kinds::is_graph_kind(kind) {
            return Err(r.err(
                spans.component(id),
                format!("`{id}` has the unknown kind `{kind}`"),
                "this kind",
                format!(
                    "the kinds are: {}",
                    super::kinds::graph_kinds().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        r.kinds.insert(id, kind);
    }
    let mut attach: Vec<&(String, Vec<String>)> = doc.attach.iter().collect();
    attach.sort_by(|a, b| a.0.cmp(&b.0));
    for (id, targets) in attach {
        let (list, target_spans) = spans.attachment(id);
        let Some(&kind) = r.kinds.get(id.as_str()) else {
            return Err(r.err(
                list,
                format!("`{id}` attaches to something but is not in [components]"),
                "its attachments",
                format!("declare it: `{id} = \"lintel\"` (or another kind) under [components]"),
            ));
        };
        for (i, t) in targets.iter().enumerate() {
            let span = target_spans.get(i).cloned().unwrap_or_default();
            let Some(&tkind) = r.kinds.get(t.as_str()) else {
                return Err(r.err(
                    span,
                    format!("`{id}` attaches to `{t}`, which is not in [components]"),
                    "unknown component",
                    "declare it under [components], or correct the name".to_string(),
                ));
            };
            let legal = matrix
                .get(tkind)
                .is_some_and(|v| v.iter().any(|k| k == kind));
            if !legal {
                let accepts = matrix.get(tkind).map(|v| v.join(", ")).unwrap_or_default();
                return Err(r.err(
                    span,
                    format!("`{id}` ({kind}) cannot attach to `{t}` ({tkind})"),
                    "this attachment",
                    format!(
                        "by the relation matrix a {tkind} accepts: {}",
                        if accepts.is_empty() {
                            "nothing"
                        } else {
                            &accepts
                        }
                    ),
                ));
            }
            r.on.entry(id).or_default().push(t);
            r.under.entry(t).or_default().push(id);
        }
    }
    let kind = match doc.kind.as_str() {
        "ridge" => PailouType::Ridge,
        "pillar" => PailouType::Pillar,
        other => {
            return Err(r.err(
                spans.kind.clone().unwrap_or_default(),
                format!("`{other}` is not a Pailou type"),
                "this type",
                "write `type = \"ridge\"` or `type = \"pillar\"`".to_string(),
            ));
        }
    };
    let centre = doc.centre.as_str();
    if r.kind(centre) != "lintel" {
        return Err(r.err(
            spans.centre.clone(),
            format!("the centre `{centre}` is not a lintel"),
            "the centre",
            "name the central entrance's lintel".to_string(),
        ));
    }
    let pillars = r.supports(centre);
    if pillars.len() != 2 || pillars.iter().any(|p| r.kind(p) != "pillar") {
        return Err(r.err(
            spans.centre.clone(),
            format!(
                "the central lintel `{centre}` must rest on two ground pillars; it rests on {}",
                pillars.len()
            ),
            "the centre",
            format!("attach it to its pillars: `{centre} = [\"P1R\", \"P1L\"]` under [attach]"),
        ));
    }
    // Walk each half outward along the ground: an extra lintel on a pillar
    // adds an entrance beside (Sec. 4.2).
    let mut halves = Vec::new();
    for &first in &pillars {
        let mut chain = vec![(centre, first)];
        let mut seen: BTreeSet<&str> = BTreeSet::from([centre]);
        let mut pillar = first;
        while let Some(next) = r
            .attached(pillar, "lintel")
            .into_iter()
            .find(|l| !seen.contains(l) && r.supports(l).iter().all(|p| r.kind(p) == "pillar"))
        {
            seen.insert(next);
            let Some(outer) = r.supports(next).into_iter().find(|&p| p != pillar) else {
                break;
            };
            chain.push((next, outer));
            pillar = outer;
        }
        halves.push(chain);
    }
    if halves[0].len() != halves[1].len() {
        return Err(r.err(
            spans.centre.clone(),
            format!(
                "the Pailou is not symmetric: {} entrances on one side of `{centre}`, {} on the other",
                halves[0].len(),
                halves[1].len()
            ),
            "the centre",
            "the Pailou grammar mirrors one half; give both halves the same entrances".to_string(),
        ));
    }
    if halves[0].len() > MAX_HALF {
        return Err(r.err(
            spans.centre.clone(),
            format!(
                "{} entrances per half: at most {MAX_HALF} are supported",
                halves[0].len()
            ),
            "the centre",
            String::new(),
        ));
    }
    let mut lintels: Vec<(String, usize, usize)> = Vec::new();
    let layouts: Vec<Layout> = halves
        .iter()
        .map(|h| half_layout(&r, h, kind, &mut lintels))
        .collect();
    lintels.sort_by(|a, b| (a.1, a.2, &a.0).cmp(&(b.1, b.2, &b.0)));
    lintels.dedup();
    let entrance_of = entrances_of(&r, &halves, &lintels);
    if layouts[0] != layouts[1] {
        return Err(r.err(
            spans.centre.clone(),
            "the Pailou is not symmetric: the two halves carry different decorations".to_string(),
            "the centre",
            "the Pailou grammar mirrors one half; decorate both halves alike".to_string(),
        ));
    }
    r.used.borrow_mut().insert(centre.to_string());
    for half in &halves {
        for &(lintel, pillar) in half {
            r.used.borrow_mut().insert(lintel.to_string());
            r.used.borrow_mut().insert(pillar.to_string());
        }
    }
    // A row of middle Toukungs is drawn under its entrance's roof (the
    // grammar's `Row` needs the roof's span): one on a lintel without a
    // roof would be neither drawn nor told (issue 34).
    let roofless: Vec<String> = r
        .kinds
        .iter()
        .filter(|(_, kind)| **kind == "middle_toukung")
        .filter_map(|(id, _)| {
            let roofed = |x: &str| {
                ["eaves_roof", "clipped_roof"]
                    .iter()
                    .any(|k| !r.attached(x, k).is_empty())
            };
            let lintels = r.on.get(id)?;
            if roofed(id) || lintels.iter().any(|l| roofed(l)) {
                return None;
            }
            Some(format!(
                "`{id}` (middle_toukung) on {} is not drawn: a row of middle Toukungs stands under its entrance's roof; attach an eaves_roof or a clipped_roof to it",
                lintels.join(", ")
            ))
        })
        .collect();
    let unplaced = {
        let used = r.used.borrow();
        let mut out: Vec<String> = r
            .kinds
            .iter()
            .filter(|(id, _)| !used.contains(**id))
            .map(|(id, kind)| {
                let on = r.on.get(id).map(|v| v.join(", ")).unwrap_or_default();
                if on.is_empty() {
                    format!("`{id}` ({kind}) attaches to nothing and is not placed")
                } else {
                    format!("`{id}` ({kind}) on {on} is not placed: the layout has no place for it (docs/pailou.md, \"The layout\")")
                }
            })
            .collect();
        out.extend(roofless);
        out
    };
    let defines = doc
        .defines
        .iter()
        .map(|(k, v)| (k.clone(), v.to_string().trim_matches('"').to_string()))
        .collect();
    Ok(Graph {
        layout: layouts.into_iter().next().expect("two halves"),
        kind,
        defines,
        unplaced,
        lintels,
        entrance_of,
    })
}

/// One half's layout from its chain of (lintel, outer pillar) on the ground.
fn half_layout(
    r: &Reader,
    chain: &[(&str, &str)],
    kind: PailouType,
    lintels: &mut Vec<(String, usize, usize)>,
) -> Layout {
    let mut l = Layout {
        exists: [[false; MAX_LEVELS + 1]; MAX_HALF + 1],
        dec: [[[false; KINDS]; MAX_LEVELS + 1]; MAX_HALF + 1],
    };
    for (i, &(lintel, outer)) in chain.iter().enumerate() {
        let mut current = lintel;
        for j in 0..MAX_LEVELS {
            l.exists[i][j] = true;
            lintels.push((current.to_string(), i + 1, j + 1));
            let d = &mut l.dec[i][j];
            decorate(r, current, d);
            if j == 0 {
                // A Queti may be fixed to a pillar (the matrix allows it):
                // it decorates the entrance whose outer pillar it is on.
                let on_pillar = r.attached(outer, "queti");
                if !on_pillar.is_empty() {
                    d[QUETI] = true;
                    d[YUNDAN] |= on_pillar
                        .iter()
                        .map(|q| r.attached(q, "yundan").len())
                        .sum::<usize>()
                        > 0;
                }
                d[PILLAR_BASE] = !r.attached(outer, "pillar_base").is_empty();
                d[PILLAR_TYPE] = kind == PailouType::Pillar;
                d[PILLAR_ROOF] = !r.attached(outer, "clipped_roof").is_empty();
            }
            // An extra pillar on a lintel adds an entrance above.
            let standing = r.attached(current, "suspended_pillar");
            let above = r
                .attached(standing.first().copied().unwrap_or(""), "lintel")
                .into_iter()
                .find(|u| r.supports(u).len() == 2);
            // every one looked at, so that each roof counts as placed
            let roofs: usize = standing
                .iter()
                .map(|s| r.attached(s, "clipped_roof").len())
                .sum();
            d[SIDE_CLIPPED_ROOFS] = roofs > 0;
            match above {
                Some(u) => current = u,
                None => break,
            }
        }
    }
    l
}

/// Every component's entrance (i, j): a lintel's own; a ground pillar's,
/// the entrance it is the outer pillar of (the grammar draws an entrance's
/// outer pillars; its inner one is its inner neighbour's outer one); a
/// suspended pillar's, the entrance above it that it holds up; anything
/// else, the entrance of what it attaches to, except a clipped roof on a
/// suspended pillar, which is a side roof of the entrance under it
/// (decoration 8). Components attached to nothing placed have none.
fn entrances_of(
    r: &Reader,
    halves: &[Vec<(&str, &str)>],
    lintels: &[(String, usize, usize)],
) -> Vec<(String, usize, usize)> {
    let mut at: BTreeMap<&str, (usize, usize)> = lintels
        .iter()
        .map(|(id, i, j)| (id.as_str(), (*i, *j)))
        .collect();
    for half in halves {
        for (k, &(_, pillar)) in half.iter().enumerate() {
            at.insert(pillar, (k + 1, 1));
        }
    }
    for (id, kind) in &r.kinds {
        if *kind == "suspended_pillar" {
            let held = r.under.get(id).into_iter().flatten();
            if let Some(e) = held.filter_map(|l| at.get(l).copied()).min() {
                at.insert(id, e);
            }
        }
    }
    // Outward along the attachments, one step per pass: a chain is at
    // most as long as there are components.
    for _ in 0..r.kinds.len() {
        let mut found = Vec::new();
        for (id, kind) in &r.kinds {
            if at.contains_key(id) {
                continue;
            }
            let hosts = r.on.get(id).into_iter().flatten();
            let host = hosts
                .filter_map(|h| at.get(h).map(|e| (*e, r.kind(h))))
                .min();
            if let Some(((i, j), host_kind)) = host {
                let under = *kind == "clipped_roof" && host_kind == "suspended_pillar";
                found.push((*id, (i, if under { j.saturating_sub(1).max(1) } else { j })));
            }
        }
        if found.is_empty() {
            break;
        }
        at.extend(found);
    }
    at.into_iter()
        .map(|(id, (i, j))| (id.to_string(), i, j))
        .collect()
}

fn decorate(r: &Reader, lintel: &str, d: &mut [bool; KINDS]) {
    let has = |k: &str| !r.attached(lintel, k).is_empty();
    let toukungs = r.attached(lintel, "middle_toukung");
    // every one looked at (no short cut), so that each counts as placed
    let on_toukungs = |k: &str| {
        toukungs
            .iter()
            .map(|t| r.attached(t, k).len())
            .sum::<usize>()
            > 0
    };
    d[MIDDLE_TOUKUNGS] = !toukungs.is_empty();
    d[SIDE_TOUKUNGS] = has("side_toukung");
    d[EAVES_ROOF] = has("eaves_roof") | on_toukungs("eaves_roof");
    d[CLIPPED_ROOF] = has("clipped_roof") | on_toukungs("clipped_roof");
    let quetis = r.attached(lintel, "queti");
    d[QUETI] = !quetis.is_empty();
    d[YUNDAN] = quetis
        .iter()
        .map(|q| r.attached(q, "yundan").len())
        .sum::<usize>()
        > 0;
    d[FLOWER_BOARD] = has("flower_board");
    d[INSCRIBED_BOARD] = has("inscribed_board");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every style's canonical graph reads back to the same layout.
    #[test]
    fn emitted_graphs_read_back() {
        for style in [
            "2-1-1", "2-1-2", "2-1-3", "2-1-4", "4-3-3", "4-3-4", "4-3-7", "6-5-11", "6-5-15",
            "8-7-7",
        ] {
            for kind in [PailouType::Ridge, PailouType::Pillar] {
                let (np, ne, nr) = parse_style(style).unwrap();
                let l = layout(np, ne, nr, kind).unwrap();
                let text = emit(&l, kind, style);
                let g = read("g.toml", &text, RELATIONS)
                    .unwrap_or_else(|e| panic!("{style}: {e:?}\n{text}"));
                assert_eq!(g.layout, l, "{style} {kind:?}\n{text}");
                assert_eq!(g.kind, kind);
            }
        }
    }

    #[test]
    fn illegal_attachment_points_at_it() {
        let text = "centre = \"L11\"\n[components]\nL11 = \"lintel\"\nP1R = \"pillar\"\nP1L = \"pillar\"\nIB = \"inscribed_board\"\n[attach]\nL11 = [\"P1R\", \"P1L\"]\nIB = [\"P1R\"]\n";
        let e = read("g.toml", text, RELATIONS).unwrap_err();
        let GraphError::Graph { message, span, .. } = &*e else {
            panic!("{e:?}")
        };
        assert!(
            message.contains("(inscribed_board) cannot attach to `P1R` (pillar)"),
            "{message}"
        );
        assert_eq!(&text[span.offset()..span.offset() + span.len()], "\"P1R\"");
    }
}
