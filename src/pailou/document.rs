//! The component graph as a document, the one reader and writer of the
//! graph format (TOML, docs/pailou.md). Input: a graph file's text; output:
//! a [`GraphDocument`] (type, centre, components, attachments, defines and
//! icon positions, in file order) with the [`Spans`] of its parts in the
//! text. Edits (add, remove, duplicate an entrance set, defines) change the
//! document, and [`GraphDocument::write`] turns it into graph text again.
//!
//! [`crate::pailou::graph::read`] checks a parsed document against the
//! relation matrix and points its diagnostics at the spans;
//! [`crate::pailou::graph::emit`] writes a layout's canonical document; the
//! studio's Pailou mode edits one. Icon positions ride along as `# @pos`
//! comments, which the graph reader ignores.
//!
//! Edits never check legality themselves: the studio reads every edited
//! text with [`crate::pailou::graph::read`] and refuses an edit whose graph
//! does not read, so the studio and the CLI share one set of rules and one
//! set of diagnostics.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;

use serde::Deserialize;
use toml::Spanned;

/// A graph as a document (order kept, so a saved file reads like the one
/// that was opened).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GraphDocument {
    /// `type`: "ridge" (also when the file does not say) or "pillar"; the
    /// graph reader refuses any other.
    pub kind: String,
    pub centre: String,
    /// (id, kind) in file order.
    pub components: Vec<(String, String)>,
    /// (id, what it attaches to) in file order.
    pub attach: Vec<(String, Vec<String>)>,
    /// (name, value as TOML), ordered by name.
    pub defines: Vec<(String, toml::Value)>,
    /// Icon positions the user dragged (others are laid out).
    pub positions: BTreeMap<String, (f64, f64)>,
}

/// Where the parts of a parsed document are in its text (byte ranges),
/// for the graph reader's diagnostics.
#[derive(Clone, Debug, Default)]
pub struct Spans {
    /// `type`'s value, if the file gives one.
    pub kind: Option<Range<usize>>,
    /// `centre`'s value.
    pub centre: Range<usize>,
    /// Each component's kind, by id.
    pub components: BTreeMap<String, Range<usize>>,
    /// Each attachment's list and each id in it, by the attaching id.
    pub attach: BTreeMap<String, (Range<usize>, Vec<Range<usize>>)>,
}

impl Spans {
    /// Where `id`'s kind is (empty when the text has no such component).
    pub fn component(&self, id: &str) -> Range<usize> {
        self.components.get(id).cloned().unwrap_or_default()
    }

    /// Where `id`'s attachment list is, and each id in it.
    pub fn attachment(&self, id: &str) -> (Range<usize>, &[Range<usize>]) {
        self.attach.get(id).map_or((0..0, &[][..]), |(list, ids)| {
            (list.clone(), ids.as_slice())
        })
    }
}

/// The file's shape, as TOML deserializes it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GraphFile {
    #[serde(rename = "type")]
    kind: Option<Spanned<String>>,
    centre: Spanned<String>,
    components: BTreeMap<String, Spanned<String>>,
    #[serde(default)]
    attach: BTreeMap<String, Spanned<Vec<Spanned<String>>>>,
    /// Overrides of the Pailou grammar's #defines, e.g. `"ω" = 10`.
    #[serde(default)]
    defines: BTreeMap<String, toml::Value>,
}

/// Id prefixes, as `lsys pailou --emit-graph` names components.
fn prefix(kind: &str) -> &'static str {
    match kind {
        "pillar" => "P",
        "suspended_pillar" => "S",
        "lintel" => "L",
        "pillar_base" => "B",
        "flower_board" => "FB",
        "queti" => "Q",
        "yundan" => "Y",
        "inscribed_board" => "IB",
        "middle_toukung" => "TM",
        "side_toukung" => "TS",
        "clipped_roof" => "RC",
        "eaves_roof" => "RE",
        _ => "X",
    }
}

/// The heading of a graph the studio saves.
const SAVED_BY_STUDIO: &str = "A Pailou component graph (docs/pailou.md), saved by `lsys studio`.";

impl GraphDocument {
    /// Parses a graph's text: `Err` (with the place, where TOML knows it)
    /// when it is not TOML of the graph's shape. Nothing is checked
    /// against the relation matrix or the layout (that is
    /// [`crate::pailou::graph::read`]'s).
    pub fn parse_spanned(text: &str) -> Result<(GraphDocument, Spans), toml::de::Error> {
        let file: GraphFile = toml::from_str(text)?;
        let mut spans = Spans {
            kind: file.kind.as_ref().map(Spanned::span),
            centre: file.centre.span(),
            ..Default::default()
        };
        let mut components: Vec<(Range<usize>, String, String)> = Vec::new();
        for (id, kind) in file.components {
            spans.components.insert(id.clone(), kind.span());
            components.push((kind.span(), id, kind.into_inner()));
        }
        let mut attach: Vec<(Range<usize>, String, Vec<String>)> = Vec::new();
        for (id, on) in file.attach {
            let span = on.span();
            let (ids, id_spans): (Vec<String>, Vec<Range<usize>>) = on
                .into_inner()
                .into_iter()
                .map(|t| {
                    let span = t.span();
                    (t.into_inner(), span)
                })
                .unzip();
            spans.attach.insert(id.clone(), (span.clone(), id_spans));
            attach.push((span, id, ids));
        }
        // TOML's tables are sorted by key; the file's order is the spans'.
        components.sort_by_key(|(span, _, _)| span.start);
        attach.sort_by_key(|(span, _, _)| span.start);
        let mut positions = BTreeMap::new();
        for line in text.lines() {
            let mut w = line.split_whitespace();
            if let (Some("#"), Some("@pos"), Some(id), Some(x), Some(y)) =
                (w.next(), w.next(), w.next(), w.next(), w.next())
            {
                if let (Ok(x), Ok(y)) = (x.parse(), y.parse()) {
                    positions.insert(id.to_string(), (x, y));
                }
            }
        }
        let doc = GraphDocument {
            kind: file
                .kind
                .map_or_else(|| "ridge".to_string(), Spanned::into_inner),
            centre: file.centre.into_inner(),
            components: components.into_iter().map(|(_, id, k)| (id, k)).collect(),
            attach: attach.into_iter().map(|(_, id, on)| (id, on)).collect(),
            defines: file.defines.into_iter().collect(),
            positions,
        };
        Ok((doc, spans))
    }

    /// Parses a graph's text ([`GraphDocument::parse_spanned`] without the
    /// places): `Err` with TOML's message.
    pub fn parse(text: &str) -> Result<GraphDocument, String> {
        GraphDocument::parse_spanned(text)
            .map(|(doc, _)| doc)
            .map_err(|e| e.message().to_string())
    }

    /// The graph's text, under a `# heading` comment: what `lsys pailou`
    /// reads (and `--emit-graph` prints).
    pub fn write(&self, heading: &str) -> String {
        let mut s = String::new();
        for line in heading.lines() {
            s += &format!("# {line}\n");
        }
        s += &format!(
            "type = {}\ncentre = {}\n\n[components]\n",
            quote(&self.kind),
            quote(&self.centre)
        );
        for (id, kind) in &self.components {
            s += &format!("{} = {}\n", key(id), quote(kind));
        }
        s += "\n[attach]\n";
        for (id, on) in &self.attach {
            let on: Vec<String> = on.iter().map(|t| quote(t)).collect();
            s += &format!("{} = [{}]\n", key(id), on.join(", "));
        }
        if !self.defines.is_empty() {
            s += "\n[defines]\n";
            for (k, v) in &self.defines {
                s += &format!("{} = {v}\n", key(k));
            }
        }
        if !self.positions.is_empty() {
            s += "\n# lsys studio: where the icons were dragged\n";
            for (id, (x, y)) in &self.positions {
                s += &format!("# @pos {id} {x:.0} {y:.0}\n");
            }
        }
        s
    }

    /// The graph's text as the studio saves it.
    pub fn to_toml(&self) -> String {
        self.write(SAVED_BY_STUDIO)
    }

    pub fn kind_of(&self, id: &str) -> Option<&str> {
        self.components
            .iter()
            .find(|(i, _)| i == id)
            .map(|(_, k)| k.as_str())
    }

    /// What `id` attaches to.
    pub fn on(&self, id: &str) -> &[String] {
        self.attach
            .iter()
            .find(|(i, _)| i == id)
            .map_or(&[], |(_, v)| v.as_slice())
    }

    /// What attaches to `id`, in file order.
    pub fn under(&self, id: &str) -> Vec<String> {
        self.attach
            .iter()
            .filter(|(_, on)| on.iter().any(|t| t == id))
            .map(|(i, _)| i.clone())
            .collect()
    }

    /// The mirror partner of a component of one half: `X…R` <-> `X…L`
    /// (the naming of emitted graphs and of the studio's own ids).
    pub fn mirror(&self, id: &str) -> Option<String> {
        let other = match id.as_bytes().last()? {
            b'R' => format!("{}L", &id[..id.len() - 1]),
            b'L' => format!("{}R", &id[..id.len() - 1]),
            _ => return None,
        };
        self.kind_of(&other).is_some().then_some(other)
    }

    /// A fresh id for `kind`, with `suffix` ("R", "L" or "").
    fn fresh(&self, kind: &str, taken: &BTreeSet<String>) -> String {
        let p = prefix(kind);
        (1..)
            .map(|n| format!("{p}n{n}"))
            .find(|id| {
                ["", "R", "L", "a", "b"].iter().all(|s| {
                    let full = format!("{id}{s}");
                    self.kind_of(&full).is_none() && !taken.contains(&full)
                })
            })
            .expect("an unbounded range finds a free id")
    }

    fn push(&mut self, id: &str, kind: &str, on: Vec<String>) {
        self.components.push((id.to_string(), kind.to_string()));
        self.attach.push((id.to_string(), on));
    }

    /// Adds a `kind` attached to `to` (and the same to `to`'s mirror
    /// partner). A lintel on a ground pillar comes with the pillar at its
    /// other end (an entrance beside); a suspended pillar comes as a pair
    /// (the feet of an entrance above); a lintel on a suspended pillar
    /// rests on it and its partner. Returns the new ids.
    pub fn add(&mut self, to: &str, kind: &str) -> Result<Vec<String>, String> {
        if self.kind_of(to).is_none() {
            return Err(format!("there is no component `{to}`"));
        }
        let base = self.fresh(kind, &BTreeSet::new());
        let pillar_base = self.fresh("pillar", &BTreeSet::from([base.clone()]));
        let mut sides = vec![(to.to_string(), String::new())];
        if let Some(m) = self.mirror(to) {
            let s = |id: &str| id[id.len() - 1..].to_string();
            sides = vec![(to.to_string(), s(to)), (m.clone(), s(&m))];
        }
        let mut added = Vec::new();
        for (target, side) in sides {
            let id = format!("{base}{side}");
            match (kind, self.kind_of(&target).unwrap_or("")) {
                ("lintel", "pillar") => {
                    let outer = format!("{pillar_base}{side}");
                    self.components.push((outer.clone(), "pillar".into()));
                    self.push(&id, kind, vec![target.clone(), outer.clone()]);
                    added.push(outer);
                }
                ("lintel", "suspended_pillar") => {
                    let host = self.on(&target).to_vec();
                    let partner = self
                        .components
                        .iter()
                        .filter(|(i, k)| k == "suspended_pillar" && *i != target)
                        .map(|(i, _)| i.clone())
                        .find(|i| {
                            self.on(i) == host.as_slice()
                                && !self
                                    .under(i)
                                    .iter()
                                    .any(|u| self.kind_of(u) == Some("lintel"))
                        });
                    let mut on = vec![target.clone()];
                    on.extend(partner);
                    self.push(&id, kind, on);
                }
                ("suspended_pillar", _) => {
                    for half in ["a", "b"] {
                        let s = format!("{base}{half}{side}");
                        self.push(&s, kind, vec![target.clone()]);
                        added.push(s);
                    }
                    continue;
                }
                _ => self.push(&id, kind, vec![target.clone()]),
            }
            added.push(id);
        }
        Ok(added)
    }

    /// Removes `id`, its mirror partner and everything resting on them.
    pub fn remove(&mut self, id: &str) -> Result<Vec<String>, String> {
        if self.kind_of(id).is_none() {
            return Err(format!("there is no component `{id}`"));
        }
        let mut gone: BTreeSet<String> = BTreeSet::from([id.to_string()]);
        gone.extend(self.mirror(id));
        loop {
            let more: Vec<String> = self
                .attach
                .iter()
                .filter(|(i, on)| !gone.contains(i) && on.iter().any(|t| gone.contains(t)))
                .map(|(i, _)| i.clone())
                .collect();
            if more.is_empty() {
                break;
            }
            gone.extend(more);
        }
        self.components.retain(|(i, _)| !gone.contains(i));
        self.attach.retain(|(i, _)| !gone.contains(i));
        self.positions.retain(|i, _| !gone.contains(i));
        Ok(gone.into_iter().collect())
    }

    /// Upward group duplication: an entrance above the one whose lintel is
    /// `lintel` (a pair of suspended pillars on it and a lintel on them,
    /// as the palette adds them), carrying a copy of everything the lintel
    /// carries but its pillars (Toukungs with their roofs, boards, Quetis
    /// with their Yundans, roofs); on both halves when the lintel has a
    /// mirror twin. Returns the new ids.
    pub fn duplicate_upward(&mut self, lintel: &str) -> Result<Vec<String>, String> {
        if self.kind_of(lintel) != Some("lintel") {
            return Err(format!(
                "`{lintel}` is not a lintel: pick the lintel of the entrance to copy upward"
            ));
        }
        let has_above = self.under(lintel).iter().any(|u| {
            self.kind_of(u) == Some("suspended_pillar")
                && self
                    .under(u)
                    .iter()
                    .any(|v| self.kind_of(v) == Some("lintel"))
        });
        if has_above {
            return Err(format!(
                "`{lintel}` already carries an entrance above: copy that one upward instead"
            ));
        }
        let side = |g: &GraphDocument, id: &str| -> String {
            match g.mirror(id) {
                Some(_) => id[id.len() - 1..].to_string(),
                None => String::new(),
            }
        };
        let same_side = |g: &GraphDocument, ids: &[String], as_of: &str| -> Option<String> {
            let s = side(g, as_of);
            ids.iter().find(|i| side(g, i) == s).cloned()
        };
        let decorations: Vec<String> = self
            .under(lintel)
            .into_iter()
            .filter(|u| {
                !matches!(
                    self.kind_of(u),
                    Some("suspended_pillar" | "pillar" | "lintel")
                )
            })
            .collect();
        let mut added = self.add(lintel, "suspended_pillar")?;
        let first = same_side(self, &added, lintel).ok_or("no suspended pillar was added")?;
        let lintels = self.add(&first, "lintel")?;
        added.extend(lintels.iter().cloned());
        let top = same_side(self, &lintels, lintel).ok_or("no lintel was added")?;
        let mut queue: Vec<(String, String)> =
            decorations.into_iter().map(|d| (d, top.clone())).collect();
        while let Some((source, parent)) = queue.pop() {
            let kind = self.kind_of(&source).unwrap_or("").to_string();
            let made = self.add(&parent, &kind)?;
            let copy = same_side(self, &made, &parent).ok_or("a copy was not added")?;
            added.extend(made);
            queue.extend(self.under(&source).into_iter().map(|u| (u, copy.clone())));
        }
        Ok(added)
    }

    /// Group duplication (the paper's entrance sets): a copy of the
    /// entrance whose lintel is `lintel`, with everything on the lintel
    /// and on its outer pillar, added outside the outermost entrance on
    /// each side. Returns the new ids.
    pub fn duplicate_entrance(&mut self, lintel: &str) -> Result<Vec<String>, String> {
        if self.kind_of(lintel) != Some("lintel")
            || self
                .on(lintel)
                .iter()
                .any(|p| self.kind_of(p) != Some("pillar"))
        {
            return Err(format!(
                "`{lintel}` is not the lintel of a ground entrance: pick one to duplicate"
            ));
        }
        let outer_of = |g: &GraphDocument, l: &str, inner: Option<&str>| {
            g.on(l).iter().find(|p| Some(p.as_str()) != inner).cloned()
        };
        // The lintel's outer pillar: for the centre, either (the halves
        // copy alike); else the one farther from the centre along a chain.
        let chains = self.chains();
        let source_outer = chains
            .iter()
            .flat_map(|c| c.iter())
            .find(|(l, _)| l == lintel)
            .map(|(_, p)| p.clone())
            .or_else(|| outer_of(self, lintel, None))
            .ok_or("the lintel rests on no pillar")?;
        let mut added = Vec::new();
        let mut taken = BTreeSet::new();
        let base_l = self.fresh("lintel", &taken);
        taken.insert(base_l.clone());
        let base_p = self.fresh("pillar", &taken);
        taken.insert(base_p.clone());
        // One base id per copied component, shared by both sides, so that
        // the copies are mirror partners (`…R` / `…L`).
        let mut bases: BTreeMap<String, String> = BTreeMap::new();
        for (chain, side) in chains.iter().zip(["R", "L"]) {
            let Some((_, outermost)) = chain.last().cloned() else {
                continue;
            };
            let new_l = format!("{base_l}{side}");
            let new_p = format!("{base_p}{side}");
            self.components.push((new_p.clone(), "pillar".into()));
            self.push(&new_l, "lintel", vec![outermost.clone(), new_p.clone()]);
            added.extend([new_p.clone(), new_l.clone()]);
            let mut map = BTreeMap::from([
                (lintel.to_string(), new_l.clone()),
                (source_outer.clone(), new_p.clone()),
            ]);
            let mut queue = vec![lintel.to_string(), source_outer.clone()];
            while let Some(x) = queue.pop() {
                for u in self.under(&x) {
                    if map.contains_key(&u)
                        || self.kind_of(&u) == Some("lintel") && x == source_outer
                    {
                        continue; // another entrance's lintel on the shared pillar
                    }
                    let kind = self.kind_of(&u).unwrap_or("").to_string();
                    let base = match bases.get(&u) {
                        Some(b) => b.clone(),
                        None => {
                            let b = self.fresh(&kind, &taken);
                            taken.insert(b.clone());
                            bases.insert(u.clone(), b.clone());
                            b
                        }
                    };
                    let id = format!("{base}{side}");
                    map.insert(u.clone(), id.clone());
                    self.components.push((id.clone(), kind));
                    self.attach.push((id.clone(), Vec::new()));
                    added.push(id);
                    queue.push(u);
                }
            }
            // Attachments copied after all ids exist.
            let copies: Vec<(String, Vec<String>)> = map
                .iter()
                .filter(|(old, _)| *old != lintel && **old != source_outer)
                .map(|(old, new)| {
                    let on = self
                        .on(old)
                        .iter()
                        .filter_map(|t| map.get(t).cloned())
                        .collect();
                    (new.clone(), on)
                })
                .collect();
            for (new, on) in copies {
                if let Some(a) = self.attach.iter_mut().find(|(i, _)| *i == new) {
                    a.1 = on;
                }
            }
        }
        Ok(added)
    }

    /// Each half's chain of (lintel, outer pillar) from the centre
    /// outward, as the graph reader walks it: right (the centre's pillar
    /// ending in R, or its first) then left.
    pub fn chains(&self) -> Vec<Vec<(String, String)>> {
        let mut pillars: Vec<String> = self
            .on(&self.centre)
            .iter()
            .filter(|p| self.kind_of(p) == Some("pillar"))
            .cloned()
            .collect();
        pillars.sort_by_key(|p| !p.ends_with('R'));
        pillars
            .into_iter()
            .map(|first| {
                let mut chain = vec![(self.centre.clone(), first.clone())];
                let mut seen = BTreeSet::from([self.centre.clone()]);
                let mut pillar = first;
                while let Some(next) = self.under(&pillar).into_iter().find(|l| {
                    self.kind_of(l) == Some("lintel")
                        && !seen.contains(l)
                        && self.on(l).iter().all(|p| self.kind_of(p) == Some("pillar"))
                }) {
                    seen.insert(next.clone());
                    let Some(outer) = self.on(&next).iter().find(|p| **p != pillar).cloned() else {
                        break;
                    };
                    chain.push((next, outer.clone()));
                    pillar = outer;
                }
                chain
            })
            .collect()
    }

    /// Sets (or with `None` removes) a define of `[defines]`.
    pub fn set_define(&mut self, name: &str, value: Option<toml::Value>) {
        match value {
            None => self.defines.retain(|(k, _)| k != name),
            Some(v) => match self.defines.iter_mut().find(|(k, _)| k == name) {
                Some(d) => d.1 = v,
                None => self.defines.push((name.to_string(), v)),
            },
        }
    }
}

/// A TOML basic string.
fn quote(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A TOML key: bare when it can be.
fn key(s: &str) -> String {
    if !s.is_empty()
        && s.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
    {
        s.to_string()
    } else {
        quote(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pailou::graph::{read, RELATIONS};
    use crate::pailou::{emit, layout, parse_style, PailouType};

    /// `--emit-graph`'s text is its document's, written by the one writer,
    /// and parses back to the same document.
    #[test]
    fn emitted_graphs_are_documents_written() {
        for style in ["2-1-1", "4-3-7", "6-5-15", "8-7-7"] {
            for kind in [PailouType::Ridge, PailouType::Pillar] {
                let (np, ne, nr) = parse_style(style).unwrap();
                let l = layout(np, ne, nr, kind).unwrap();
                let doc = emit::document(&l, kind);
                let text = emit::emit(&l, kind, style);
                let heading = format!("{style}: a Pailou as a component graph (docs/pailou.md).");
                assert_eq!(doc.write(&heading), text);
                assert_eq!(GraphDocument::parse(&text).unwrap(), doc, "{text}");
            }
        }
    }

    /// The document keeps the file's order (not TOML's sorted keys), and
    /// its spans point at the text of each part.
    #[test]
    fn order_and_spans_are_the_files() {
        let text = "centre = \"L11\"\n[attach]\nL11 = [\"P1R\", \"P1L\"]\nB = [\"P1R\"]\n[components]\nP1R = \"pillar\"\nL11 = \"lintel\"\nB = \"pillar_base\"\nP1L = \"pillar\"\n[defines]\n\"ω\" = 10\n# @pos B 3 -4\n";
        let (doc, spans) = GraphDocument::parse_spanned(text).unwrap();
        let ids: Vec<&str> = doc.components.iter().map(|(i, _)| i.as_str()).collect();
        assert_eq!(ids, ["P1R", "L11", "B", "P1L"]);
        let ids: Vec<&str> = doc.attach.iter().map(|(i, _)| i.as_str()).collect();
        assert_eq!(ids, ["L11", "B"]);
        assert_eq!(doc.kind, "ridge");
        assert_eq!(spans.kind, None);
        assert_eq!(doc.positions["B"], (3.0, -4.0));
        assert_eq!(&text[spans.centre.clone()], "\"L11\"");
        assert_eq!(&text[spans.component("B")], "\"pillar_base\"");
        let (list, ids) = spans.attachment("L11");
        assert_eq!(&text[list], "[\"P1R\", \"P1L\"]");
        assert_eq!(&text[ids[1].clone()], "\"P1L\"");
        // Written and parsed again: the same document.
        let again = doc.to_toml();
        assert_eq!(GraphDocument::parse(&again).unwrap(), doc, "{again}");
        assert!(GraphDocument::parse("centre = 1").is_err());
    }

    /// Upward duplication: the entrance above carries the same kinds as
    /// the one it copies, on both halves; a lintel with an entrance above,
    /// or no lintel, is refused.
    #[test]
    fn duplicating_upward_copies_the_set_above() {
        let style = |s: &str| {
            let (np, ne, nr) = parse_style(s).unwrap();
            emit::document(
                &layout(np, ne, nr, PailouType::Ridge).unwrap(),
                PailouType::Ridge,
            )
        };
        let mut doc = style("4-3-3");
        let kinds_on = |d: &GraphDocument, l: &str| {
            let mut k: Vec<String> = d
                .under(l)
                .iter()
                .filter_map(|u| d.kind_of(u).map(str::to_string))
                .filter(|k| k != "suspended_pillar")
                .collect();
            k.sort();
            k
        };
        let below = kinds_on(&doc, "L21R");
        let added = doc.duplicate_upward("L21R").unwrap();
        let g = read("g.toml", &doc.to_toml(), RELATIONS).unwrap();
        assert!(
            g.layout.chart().starts_with("level 2  [G22^]      [G22^]"),
            "{}",
            g.layout.chart()
        );
        let tops: Vec<&String> = added
            .iter()
            .filter(|a| doc.kind_of(a) == Some("lintel"))
            .collect();
        assert_eq!(tops.len(), 2, "{added:?}");
        for t in tops {
            assert_eq!(kinds_on(&doc, t), below, "{t}");
        }
        let e = doc.duplicate_upward("L21R").unwrap_err();
        assert!(e.contains("already carries an entrance above"), "{e}");
        assert!(doc.duplicate_upward("P1R").is_err());
    }

    /// Edits keep the two halves alike: an entrance added beside on one
    /// pillar comes on its mirror too, and goes with it.
    #[test]
    fn edits_mirror_and_read() {
        let mut doc = GraphDocument::parse(
            "centre = \"L11\"\n[components]\nP1R = \"pillar\"\nL11 = \"lintel\"\nP1L = \"pillar\"\n[attach]\nL11 = [\"P1L\", \"P1R\"]\n",
        )
        .unwrap();
        let added = doc.add("P1R", "lintel").unwrap();
        assert_eq!(added, ["Pn1R", "Ln1R", "Pn1L", "Ln1L"]);
        doc.add("L11", "flower_board").unwrap();
        let g = read("g.toml", &doc.to_toml(), RELATIONS).unwrap();
        assert!(g.layout.chart().starts_with("level 1  [G21 ][G11 ][G21 ]"));
        assert_eq!(doc.chains()[0].len(), 2);
        let gone = doc.remove("Ln1L").unwrap();
        assert_eq!(gone, ["Ln1L", "Ln1R"]);
        doc.set_define("ω", Some(toml::Value::Integer(10)));
        let g = read("g.toml", &doc.to_toml(), RELATIONS).unwrap();
        assert_eq!(g.defines, [("ω".to_string(), "10".to_string())]);
    }
}
