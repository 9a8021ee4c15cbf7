//! Pailou mode (the paper's iconized editor, Sec. 4): a component graph
//! -> edits from the page (add from the palette, remove, duplicate an
//! entrance set, parameters, type, style) -> each edited graph read by the
//! CLI's graph reader, built, and checked; an edit whose graph does not
//! read or build is refused with the diagnostic and the last good graph
//! and model stay.

use std::collections::BTreeMap;

use serde_json::{json, Value};

use super::model::{self, Model};
use crate::driver::{
    is_graph_kind, Entrance, GraphDocument, Pailou, PailouError, PailouType, Roof,
};
use crate::Grammar;

pub struct PailouSession {
    /// The triangle budget of its models.
    pub max_triangles: usize,
    /// The graph file (relative to the opened folder), if one was opened.
    pub file: Option<String>,
    pub graph: GraphDocument,
    pub model: Option<Model>,
    /// Why the opened graph or the last edit was refused.
    pub error: Option<Value>,
    pub unplaced: Vec<String>,
    pub chart: String,
    /// The chart's entrances, as the page draws them (Fig. 9a).
    pub entrances: Vec<Value>,
    /// Each entrance's lintel: `{id: [i, j]}` (the entrance fields).
    pub lintels: Value,
    /// Every placed component's entrance: `{id: [i, j]}` (the fields of
    /// the active component's sizes).
    pub entrance_of: Value,
    /// The emitted grammar of the last good graph.
    pub lsys: String,
    /// The build's defines (the graph's, with the Toukung levels passed on).
    defines: Vec<(String, String)>,
    pub active: String,
}

/// The default entrance: a lintel on two pillars (the paper's Fig. 6
/// starts from it).
pub const DEFAULT_ENTRANCE: &str = "type = \"ridge\"\ncentre = \"L11\"\n\n[components]\nP1R = \"pillar\"\nL11 = \"lintel\"\nP1L = \"pillar\"\n\n[attach]\nL11 = [\"P1L\", \"P1R\"]\n";

impl PailouSession {
    /// Opens a graph's text, named `name` in diagnostics; `file` is where
    /// it is saved back.
    /// Models have at most `max_triangles` triangles.
    pub fn open(
        name: &str,
        text: &str,
        file: Option<String>,
        max_triangles: usize,
    ) -> PailouSession {
        let mut s = PailouSession {
            max_triangles,
            file,
            graph: GraphDocument::parse(text).unwrap_or_default(),
            model: None,
            error: None,
            unplaced: Vec::new(),
            chart: String::new(),
            entrances: Vec::new(),
            lintels: json!({}),
            entrance_of: json!({}),
            lsys: String::new(),
            defines: Vec::new(),
            active: String::new(),
        };
        s.active = s.graph.centre.clone();
        if let Err(e) = s.rebuild_from(name, text) {
            s.error = Some(e);
        }
        s
    }

    /// Reads and builds `text`; on success it becomes the current graph.
    fn rebuild_from(&mut self, name: &str, text: &str) -> Result<(), Value> {
        let built = self.build(name, text)?;
        self.commit(built);
        Ok(())
    }

    /// Reads and builds `text`, leaving the session as it is.
    fn build(&self, name: &str, text: &str) -> Result<Built, Value> {
        let p = Pailou::graph(name, text, None)
            .map_err(|e| match e {
                PailouError::Graph(e) => model::one_json(e.as_ref()),
                e => json!({"severity": "error", "message": e.to_string(), "rendered": e.to_string()}),
            })?
            .named("pailou-graph.lsys");
        let job = model::for_page(p.job(Grammar::options()), self.max_triangles);
        let defines = job.options.defines().to_vec();
        let (model, _) = model::build(&job).map_err(|d| first_diagnostic(&d))?;
        Ok(Built {
            model,
            unplaced: p.unplaced().to_vec(),
            chart: p.chart(),
            entrances: p.entrances().iter().map(entrance_json).collect(),
            lintels: entrance_map(p.lintels()),
            entrance_of: entrance_map(p.entrance_of()),
            lsys: p.grammar_text(),
            defines,
        })
    }

    fn commit(&mut self, b: Built) {
        self.model = Some(b.model);
        self.unplaced = b.unplaced;
        self.chart = b.chart;
        self.entrances = b.entrances;
        self.lintels = b.lintels;
        self.entrance_of = b.entrance_of;
        self.lsys = b.lsys;
        self.defines = b.defines;
        self.error = None;
    }

    /// The structural problems of the current model.
    fn problems(&self) -> &[Value] {
        self.model.as_ref().map_or(&[], |m| m.problems.as_slice())
    }

    /// Applies one edit from the page. `Err` carries the diagnostic of a
    /// refused edit (the graph and model are unchanged).
    pub fn apply(&mut self, edit: &Value) -> Result<(), Value> {
        let op = edit["op"].as_str().unwrap_or("");
        let id = edit["id"].as_str().unwrap_or("").to_string();
        let mut g = self.graph.clone();
        // The added part becomes active once its graph is taken.
        let mut active = None;
        let refuse = |m: String| json!({"severity": "error", "message": m, "rendered": m, "code": "lsys::studio::edit"});
        match op {
            "select" => {
                if g.kind_of(&id).is_none() {
                    return Err(refuse(format!("there is no component `{id}`")));
                }
                self.active = id;
                return Ok(());
            }
            "move" => {
                let (Some(x), Some(y)) = (edit["x"].as_f64(), edit["y"].as_f64()) else {
                    return Err(refuse("a move needs x and y".into()));
                };
                if g.kind_of(&id).is_some() {
                    self.graph.positions.insert(id, (x, y));
                }
                return Ok(());
            }
            "add" => {
                let kind = edit["kind"].as_str().unwrap_or("");
                let allowed = palette(&g, &id);
                if !allowed.iter().any(|k| k == kind) {
                    // Made anyway, so that the refusal is the graph
                    // reader's own diagnostic, as `lsys pailou` gives it.
                    g.components.push(("NEW".into(), kind.into()));
                    g.attach.push(("NEW".into(), vec![id.clone()]));
                } else {
                    let added = g.add(&id, kind).map_err(refuse)?;
                    active = added.last().cloned();
                }
            }
            "remove" => {
                g.remove(&id).map_err(refuse)?;
            }
            "duplicate" => {
                g.duplicate_entrance(&id).map_err(refuse)?;
            }
            "duplicate_up" => {
                g.duplicate_upward(&id).map_err(refuse)?;
            }
            "define" => {
                let name = edit["name"].as_str().unwrap_or("");
                if name.is_empty() {
                    return Err(refuse("a define needs a name".into()));
                }
                let number = match &edit["value"] {
                    Value::Number(n) => n.as_f64(),
                    Value::String(s) => super::grammar::number_or_fraction(s),
                    _ => None,
                };
                if let Some(v) = number {
                    crate::driver::check_pailou_define(name, v).map_err(refuse)?;
                }
                let value = match &edit["value"] {
                    Value::Null => None,
                    Value::Number(n) if n.is_i64() => {
                        Some(toml::Value::Integer(n.as_i64().unwrap_or(0)))
                    }
                    Value::Number(n) => Some(toml::Value::Float(n.as_f64().unwrap_or(0.0))),
                    Value::String(s) => Some(toml::Value::String(s.clone())),
                    _ => return Err(refuse("a define's value is a number or text".into())),
                };
                g.set_define(name, value);
            }
            "type" => g.kind = edit["value"].as_str().unwrap_or("ridge").to_string(),
            "style" => {
                let style = edit["style"].as_str().unwrap_or("");
                let kind = match edit["type"].as_str().unwrap_or(&g.kind) {
                    "pillar" => PailouType::Pillar,
                    _ => PailouType::Ridge,
                };
                let pailou = Pailou::style(style, kind).map_err(|e| match e {
                    PailouError::Style { error, .. } => {
                        refuse(format!("the style {style}: {error}"))
                    }
                    e => refuse(e.to_string()),
                })?;
                let defines = std::mem::take(&mut g.defines);
                g = GraphDocument::parse(&pailou.graph_toml()).map_err(refuse)?;
                g.defines = defines;
            }
            _ => return Err(refuse(format!("unknown edit `{op}`"))),
        }
        let text = g.to_toml();
        let name = self.file.clone().unwrap_or_else(|| "graph.toml".into());
        let built = self.build(&name, &text)?;
        // A placement that would collide is refused (the paper's editor
        // only offers legal placements): an added part or a duplicated
        // entrance whose model has structural problems the last one did
        // not. Parameters, types and styles may still make some: those are
        // listed and drawn red, as the user asked for them.
        if matches!(op, "add" | "duplicate" | "duplicate_up") {
            let new: Vec<&Value> = built
                .model
                .problems
                .iter()
                .filter(|p| !self.problems().contains(p))
                .collect();
            if !new.is_empty() {
                return Err(collision(op, edit, &id, &new));
            }
        }
        self.commit(built);
        if let Some(a) = active {
            self.active = a;
        }
        if g.kind_of(&self.active).is_none() {
            self.active = g.centre.clone();
        }
        self.graph = g;
        Ok(())
    }

    /// The state the page draws.
    pub fn state(&self) -> Value {
        let pos = positions(&self.graph);
        let components: Vec<Value> = self
            .graph
            .components
            .iter()
            .map(|(id, kind)| {
                let (x, y) = pos.get(id).copied().unwrap_or((0.0, 0.0));
                json!({"id": id, "kind": kind, "on": self.graph.on(id), "x": x, "y": y})
            })
            .collect();
        let defines: BTreeMap<&str, &toml::Value> = self
            .graph
            .defines
            .iter()
            .map(|(k, v)| (k.as_str(), v))
            .collect();
        json!({
            "mode": "pailou",
            "file": self.file,
            "type": self.graph.kind,
            "centre": self.graph.centre,
            "active": self.active,
            "palette": palette(&self.graph, &self.active),
            "components": components,
            "defines": serde_json::to_value(defines).unwrap_or_default(),
            "build_defines": self.defines,
            "chart": self.chart,
            "entrances": self.entrances,
            "lintels": self.lintels,
            "entrance_of": self.entrance_of,
            "matrix": matrix(),
            "unplaced": self.unplaced,
            "error": self.error,
            "problems": self.model.as_ref().map(|m| m.problems.clone()).unwrap_or_default(),
            "parts": self.model.as_ref().map_or(0, |m| m.parts),
            "triangles": self.model.as_ref().map_or(0, |m| m.triangles),
            // The box around the model, [min, max] (model units, y up).
            "bounds": self.model.as_ref().and_then(|m| m.scene.bounds()).map(|(lo, hi)| [lo, hi]),
            "toml": self.graph.to_toml(),
        })
    }
}

/// `{id: [i, j]}` of (id, i, j).
fn entrance_map(of: &[(String, usize, usize)]) -> Value {
    of.iter()
        .map(|(id, i, j)| (id.clone(), json!([i, j])))
        .collect::<serde_json::Map<_, _>>()
        .into()
}

fn first_diagnostic(d: &crate::Diagnostics) -> Value {
    model::diagnostics_json(d)
        .into_iter()
        .next()
        .unwrap_or_else(|| json!({"message": d.to_string(), "rendered": d.to_string()}))
}

/// The kinds the relation matrix lets attach to `id` (graph kinds only).
pub fn palette(g: &GraphDocument, id: &str) -> Vec<String> {
    let kind = g.kind_of(id).unwrap_or("");
    crate::driver::library_rules()
        .accepts
        .get(kind)
        .map(|v| v.iter().filter(|k| is_graph_kind(k)).cloned().collect())
        .unwrap_or_default()
}

/// What a build gives the session.
struct Built {
    model: Model,
    unplaced: Vec<String>,
    chart: String,
    entrances: Vec<Value>,
    lintels: Value,
    entrance_of: Value,
    lsys: String,
    defines: Vec<(String, String)>,
}

/// The refusal of an edit whose model collides: the first problems, the
/// parts they name, and the component the page marks (`at`).
fn collision(op: &str, edit: &Value, id: &str, new: &[&Value]) -> Value {
    let what = match op {
        "add" => format!(
            "a {} on {id}",
            edit["kind"].as_str().unwrap_or("part").replace('_', " ")
        ),
        "duplicate_up" => format!("the copy of {id}'s entrance above it"),
        _ => format!("the copy of {id}'s entrance"),
    };
    let shown: Vec<String> = new
        .iter()
        .take(3)
        .filter_map(|p| p["message"].as_str().map(str::to_string))
        .collect();
    let more = new.len().saturating_sub(shown.len());
    let mut message = format!("refused: {what} would collide: {}", shown.join("; "));
    if more > 0 {
        message += &format!(" (and {more} more)");
    }
    let parts: Vec<Value> = new
        .iter()
        .flat_map(|p| p["parts"].as_array().cloned().unwrap_or_default())
        .collect();
    json!({
        "severity": "error",
        "code": "lsys::studio::collision",
        "message": message,
        "rendered": format!("{message}\nhelp: the graph is unchanged; attach the part elsewhere or remove what is in its place first"),
        "at": id,
        "parts": parts,
    })
}

fn entrance_json(e: &Entrance) -> Value {
    let roof = match e.roof {
        Roof::Eaves => "eaves",
        Roof::Clipped => "clipped",
        Roof::None => "none",
    };
    json!({
        "name": format!("G{}{}", e.i, e.j), "i": e.i, "j": e.j, "side": e.side, "roof": roof,
        "side_clipped": e.side_clipped, "pillar_roof": e.pillar_roof, "toukungs": e.toukungs,
        "flower_board": e.flower_board, "inscribed_board": e.inscribed_board,
    })
}

/// The relation matrix (paper, Sec. 4.1, Figs. 5C and 8) over the kinds a
/// graph may name: `{"kinds": [...], "accepts": {kind: [kinds that may
/// attach to it]}}`, the rows and columns in the paper's order (roofs,
/// Toukungs, lintel, pillars, Queti, flower board, Yundan) with ours after.
fn matrix() -> Value {
    static MATRIX: std::sync::OnceLock<Value> = std::sync::OnceLock::new();
    MATRIX.get_or_init(library_matrix).clone()
}

fn library_matrix() -> Value {
    const ORDER: [&str; 12] = [
        "clipped_roof",
        "eaves_roof",
        "middle_toukung",
        "side_toukung",
        "lintel",
        "pillar",
        "queti",
        "flower_board",
        "yundan",
        "inscribed_board",
        "suspended_pillar",
        "pillar_base",
    ];
    debug_assert!(ORDER.iter().all(|k| is_graph_kind(k)));
    let rules = crate::driver::library_rules();
    let accepts: serde_json::Map<String, Value> = ORDER
        .iter()
        .map(|k| {
            let row: Vec<&str> = rules
                .accepts
                .get(*k)
                .map(|v| {
                    v.iter()
                        .map(String::as_str)
                        .filter(|a| ORDER.contains(a))
                        .collect()
                })
                .unwrap_or_default();
            (k.to_string(), json!(row))
        })
        .collect();
    json!({"kinds": ORDER, "accepts": accepts})
}

/// Where each icon is drawn: dragged ones where they were left; ground
/// pillars in a row by their entrance; everything else above (resting on)
/// or below (hanging from) what it attaches to, siblings side by side.
fn positions(g: &GraphDocument) -> BTreeMap<String, (f64, f64)> {
    const GROUND: f64 = 460.0;
    let mut at: BTreeMap<String, (f64, f64)> = BTreeMap::new();
    for (chain, sign) in g.chains().iter().zip([1.0, -1.0]) {
        for (k, (_, pillar)) in chain.iter().enumerate() {
            at.insert(pillar.clone(), (sign * (110.0 + 220.0 * k as f64), GROUND));
        }
    }
    let hangs = |k: &str| {
        matches!(
            k,
            "queti" | "yundan" | "flower_board" | "inscribed_board" | "pillar_base"
        )
    };
    loop {
        // Ready: every target placed. Grouped by (targets, direction).
        let mut groups: BTreeMap<(Vec<String>, bool), Vec<String>> = BTreeMap::new();
        for (id, kind) in &g.components {
            if at.contains_key(id) {
                continue;
            }
            let on = g.on(id);
            if !on.is_empty() && on.iter().all(|t| at.contains_key(t)) {
                groups
                    .entry((on.to_vec(), hangs(kind)))
                    .or_default()
                    .push(id.clone());
            }
        }
        if groups.is_empty() {
            break;
        }
        for ((on, down), ids) in groups {
            let xs: Vec<f64> = on.iter().map(|t| at[t].0).collect();
            let ys = on.iter().map(|t| at[t].1);
            let x = xs.iter().sum::<f64>() / xs.len() as f64;
            let y = if down {
                ys.fold(f64::MIN, f64::max) + 70.0
            } else {
                ys.fold(f64::MAX, f64::min) - 90.0
            };
            let n = ids.len() as f64;
            for (i, id) in ids.into_iter().enumerate() {
                at.insert(id, (x + (i as f64 - (n - 1.0) / 2.0) * 62.0, y));
            }
        }
    }
    // Attached to nothing (or to a cycle): a row at the bottom.
    let mut x = -300.0;
    for (id, _) in &g.components {
        at.entry(id.clone()).or_insert_with(|| {
            x += 70.0;
            (x, GROUND + 200.0)
        });
    }
    for (id, p) in &g.positions {
        if at.contains_key(id) {
            at.insert(id.clone(), *p);
        }
    }
    at
}
