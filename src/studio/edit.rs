//! The editor's component graph: a graph file's text -> components,
//! attachments, defines and icon positions that the studio's clicks edit
//! -> graph text again (the same format `lsys pailou GRAPH` reads; icon
//! positions ride along as `# @pos` comments, which the reader ignores).
//!
//! Edits never check legality themselves: the session reads every edited
//! text with [`crate::pailou::graph::read`] and refuses an edit whose graph
//! does not read, so the studio and the CLI share one set of rules and one
//! set of diagnostics.

use std::collections::{BTreeMap, BTreeSet};

/// A graph as the editor holds it (order kept, so a saved file reads like
/// the one that was opened).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EditGraph {
    pub kind: String,
    pub centre: String,
    /// (id, kind) in file order.
    pub components: Vec<(String, String)>,
    /// (id, what it attaches to) in file order.
    pub attach: Vec<(String, Vec<String>)>,
    /// (name, value as TOML) in file order.
    pub defines: Vec<(String, toml::Value)>,
    /// Icon positions the user dragged (others are laid out).
    pub positions: BTreeMap<String, (f64, f64)>,
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

impl EditGraph {
    /// Reads a graph's text leniently (no relation matrix, no layout):
    /// `Err` only when it is not TOML of the graph's shape.
    pub fn parse(text: &str) -> Result<EditGraph, String> {
        let table: toml::Table = toml::from_str(text).map_err(|e| e.message().to_string())?;
        let string = |v: &toml::Value| v.as_str().map(str::to_string);
        let mut g = EditGraph {
            kind: table
                .get("type")
                .and_then(string)
                .unwrap_or_else(|| "ridge".into()),
            centre: table.get("centre").and_then(string).unwrap_or_default(),
            ..Default::default()
        };
        if let Some(c) = table.get("components").and_then(|v| v.as_table()) {
            for (id, kind) in c {
                g.components
                    .push((id.clone(), string(kind).unwrap_or_default()));
            }
        }
        if let Some(a) = table.get("attach").and_then(|v| v.as_table()) {
            for (id, on) in a {
                let on = on
                    .as_array()
                    .map(|v| v.iter().filter_map(string).collect())
                    .unwrap_or_default();
                g.attach.push((id.clone(), on));
            }
        }
        if let Some(d) = table.get("defines").and_then(|v| v.as_table()) {
            g.defines = d.iter().map(|(k, v)| (k.clone(), v.clone())).collect();
        }
        // toml's tables are sorted; take the file's order back from the text.
        let at = |id: &str| {
            text.find(&format!("\n{id} ="))
                .or_else(|| text.find(&format!("\n\"{id}\" =")))
                .unwrap_or(usize::MAX)
        };
        g.components.sort_by_key(|(id, _)| at(id));
        for line in text.lines() {
            let mut w = line.split_whitespace();
            if let (Some("#"), Some("@pos"), Some(id), Some(x), Some(y)) =
                (w.next(), w.next(), w.next(), w.next(), w.next())
            {
                if let (Ok(x), Ok(y)) = (x.parse(), y.parse()) {
                    g.positions.insert(id.to_string(), (x, y));
                }
            }
        }
        let attach_at = |id: &str| {
            let a = text.find("[attach]").unwrap_or(0);
            text[a..]
                .find(&format!("\n{id} ="))
                .map_or(usize::MAX, |n| n + a)
        };
        g.attach.sort_by_key(|(id, _)| attach_at(id));
        Ok(g)
    }

    /// The graph as a file `lsys pailou` reads.
    pub fn to_toml(&self) -> String {
        let mut s =
            String::from("# A Pailou component graph (docs/pailou.md), saved by `lsys studio`.\n");
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
        let outer_of = |g: &EditGraph, l: &str, inner: Option<&str>| {
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
