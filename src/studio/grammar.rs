//! Grammar mode (live preview): a `.lsys` file in the opened folder ->
//! compiled with the page's `-D` overrides, built at the page's step ->
//! the model and its diagnostics. The root file's `#define`s become the
//! page's sliders. A failed build keeps the last good model.
//!
//! With a [`Watcher`] (the server's; see `watch` in studio/mod.rs), every
//! build gives it the files to watch: before it reads them, the root file
//! and the files the last build read, so that a save during the build (or
//! right after opening) is the watcher's next change; after, the files
//! this build read.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use serde_json::{json, Value};

use super::model::{self, Model};
use crate::driver::Watcher;

/// A `#define` of the root file, as the page shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct Define {
    pub name: String,
    pub value: String,
    /// The value as a number (a number or `a/b`), for a slider.
    pub number: Option<f64>,
    /// A slider's range, for a number.
    pub range: Option<(f64, f64)>,
    pub integer: bool,
}

pub struct GrammarSession {
    /// The opened folder.
    pub folder: PathBuf,
    /// The files the last build read (root, includes, view and function
    /// files), which the watcher watches.
    pub sources: Vec<PathBuf>,
    /// Told the files to watch on every build (`None`: no watching).
    watcher: Option<Arc<Watcher>>,
    /// The root file, absolute.
    pub path: PathBuf,
    /// The same, relative to the opened folder (for the page).
    pub file: String,
    pub defines: Vec<Define>,
    pub overrides: BTreeMap<String, String>,
    /// The step shown (`None`: the grammar's derivation length).
    pub step: Option<u32>,
    pub length: u32,
    pub model: Option<Model>,
    pub diagnostics: Vec<Value>,
    /// Whether `model` is from the current text (false: the last good one).
    pub current: bool,
    /// The triangle budget of its models.
    pub max_triangles: usize,
}

impl GrammarSession {
    pub fn open(folder: PathBuf, path: PathBuf, file: String) -> GrammarSession {
        GrammarSession::open_watched(folder, path, file, None, model::DEFAULT_MAX_TRIANGLES)
    }

    /// [`GrammarSession::open`], telling `watcher` the files to watch on
    /// every build, starting with the first.
    /// Models have at most `max_triangles` triangles.
    pub fn open_watched(
        folder: PathBuf,
        path: PathBuf,
        file: String,
        watcher: Option<Arc<Watcher>>,
        max_triangles: usize,
    ) -> GrammarSession {
        let mut s = GrammarSession {
            max_triangles,
            folder,
            sources: Vec::new(),
            watcher,
            path,
            file,
            defines: Vec::new(),
            overrides: BTreeMap::new(),
            step: None,
            length: 0,
            model: None,
            diagnostics: Vec::new(),
            current: false,
        };
        s.rebuild();
        s
    }

    /// Compiles and builds again (after a save, or a change on the page).
    pub fn rebuild(&mut self) {
        // Watched before they are read: a save from here on is a change.
        self.watch();
        if let Ok(text) = std::fs::read_to_string(&self.path) {
            self.defines = defines_of(&text);
        }
        let defines: Vec<(String, String)> = self
            .overrides
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        let name = self.path.to_string_lossy().into_owned();
        let input = crate::driver::Input::Path(self.path.clone());
        let job = model::job(input, &name, &defines, self.step, false, self.max_triangles);
        let (built, sources) = model::build_reading(&job);
        // None read (the root file is unreadable): the last build's, as
        // a fix may come in any of them.
        if !sources.is_empty() {
            self.sources = sources;
        }
        self.watch();
        match built {
            Ok((m, g)) => {
                self.length = g.derivation_length();
                self.model = Some(m);
                self.diagnostics = model::diagnostics_json(g.warnings());
                self.current = true;
            }
            Err(d) => {
                self.diagnostics = model::diagnostics_json(&d);
                self.current = false;
            }
        }
        self.relative_paths();
    }

    /// Tells the watcher the root file and the last build's sources
    /// (where they cannot be watched, saves are not seen: nothing to tell
    /// the page).
    fn watch(&self) {
        if let Some(w) = &self.watcher {
            let mut files = self.sources.clone();
            files.push(self.path.clone());
            let _ = w.watch_files(&files);
        }
    }

    /// Diagnostics name files relative to the opened folder, as the page
    /// lists them (the compiler was given the absolute path).
    fn relative_paths(&mut self) {
        let full = self.path.to_string_lossy();
        let Some(folder) = full.strip_suffix(self.file.as_str()) else {
            return;
        };
        if folder.is_empty() {
            return;
        }
        for d in &mut self.diagnostics {
            for key in ["file", "rendered"] {
                if let Some(text) = d[key].as_str() {
                    d[key] = Value::String(text.replace(folder, ""));
                }
            }
        }
    }

    /// Takes the page's overrides and step, and rebuilds.
    pub fn set(&mut self, v: &Value) {
        if let Some(d) = v["defines"].as_object() {
            self.overrides = d
                .iter()
                .filter_map(|(k, v)| match v {
                    Value::Number(n) => Some((k.clone(), n.to_string())),
                    Value::String(s) if !s.trim().is_empty() => Some((k.clone(), s.clone())),
                    _ => None,
                })
                .collect();
        }
        match &v["step"] {
            Value::Number(n) => self.step = n.as_u64().map(|s| s.min(100_000) as u32),
            Value::Null if v.get("step").is_some() => self.step = None,
            _ => {}
        }
        self.rebuild();
    }

    pub fn state(&self) -> Value {
        let defines: Vec<Value> = self
            .defines
            .iter()
            .map(|d| {
                json!({
                    "name": d.name,
                    "value": d.value,
                    "number": d.number,
                    "override": self.overrides.get(&d.name),
                    "range": d.range.map(|(a, b)| [a, b]),
                    "integer": d.integer,
                })
            })
            .collect();
        json!({
            "mode": "grammar",
            "file": self.file,
            "defines": defines,
            "step": self.step.unwrap_or(self.length),
            "length": self.length,
            "diagnostics": self.diagnostics,
            "current": self.current,
            "parts": self.model.as_ref().map_or(0, |m| m.parts),
            "triangles": self.model.as_ref().map_or(0, |m| m.triangles),
        })
    }
}

/// The `#define NAME VALUE` lines of a grammar's text, lists included
/// (`#define αPW 7/61, αEW 10/12`; function-like macros and tables left
/// out): a number (or a fraction of two) gets a slider from 0 to twice it
/// (around it when negative; 0..1 for 0).
pub fn defines_of(text: &str) -> Vec<Define> {
    let mut out: Vec<Define> = Vec::new();
    for line in text.lines() {
        let Some(rest) = line.trim_start().strip_prefix("#define") else {
            continue;
        };
        let rest = without_comments(rest);
        for item in top_level_items(&rest) {
            let item = item.trim();
            let name: String = item
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
                .collect();
            let after = &item[name.len()..];
            if name.is_empty() || after.starts_with(['(', '[']) {
                continue;
            }
            let value = after.trim().to_string();
            out.retain(|d| d.name != name);
            out.push(slider(name, value));
        }
    }
    out
}

/// A line's text without its `//` comment and `/* */` comments (an
/// unclosed `/*` comments out the rest).
fn without_comments(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    loop {
        let line_comment = rest.find("//");
        let block = rest.find("/*");
        match (line_comment, block) {
            (Some(l), b) if b.map_or(true, |b| l < b) => {
                out.push_str(&rest[..l]);
                return out;
            }
            (_, Some(b)) => {
                out.push_str(&rest[..b]);
                out.push(' ');
                match rest[b + 2..].find("*/") {
                    Some(e) => rest = &rest[b + 2 + e + 2..],
                    None => return out,
                }
            }
            _ => {
                out.push_str(rest);
                return out;
            }
        }
    }
}

/// `text` cut at the commas outside brackets (the items of a list define).
fn top_level_items(text: &str) -> Vec<&str> {
    let (mut items, mut depth, mut start) = (Vec::new(), 0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&text[start..]);
    items
}

/// A define's text as a number when it is one or a fraction of two
/// (`7/61`); `1/0` is infinite.
pub(super) fn number_or_fraction(s: &str) -> Option<f64> {
    match s.split_once('/') {
        Some((a, b)) => Some(a.trim().parse::<f64>().ok()? / b.trim().parse::<f64>().ok()?),
        None => s.trim().parse().ok(),
    }
}

/// A define as the page shows it: a slider for a number or `a/b`.
fn slider(name: String, value: String) -> Define {
    let number = number_or_fraction(&value).filter(|v| v.is_finite());
    let integer = number.is_some() && !value.contains(['.', 'e', 'E', '/']);
    let range = number.map(|v| match v {
        v if v > 0.0 => (
            0.0,
            if integer {
                (2.0 * v).max(v + 5.0)
            } else {
                2.0 * v
            },
        ),
        v if v < 0.0 => (2.0 * v, -2.0 * v),
        _ => (0.0, if integer { 10.0 } else { 1.0 }),
    });
    Define {
        name,
        value,
        number,
        range,
        integer,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defines_become_sliders() {
        let d = defines_of(
            "#define N 4\n#define angle 22.5 // degrees\n#define F(x) x\n#define NAME foo\n#define W 3 /* wide */\n",
        );
        let shown: Vec<String> = d
            .iter()
            .map(|d| format!("{} {} {:?} {}", d.name, d.value, d.range, d.integer))
            .collect();
        assert_eq!(
            shown,
            [
                "N 4 Some((0.0, 9.0)) true",
                "angle 22.5 Some((0.0, 45.0)) false",
                "NAME foo None false",
                "W 3 Some((0.0, 8.0)) true"
            ]
        );
    }

    /// A list define gives one slider per item (the Pailou's ratios); a
    /// table or a call in a value does not cut it.
    #[test]
    fn list_defines_give_one_slider_each() {
        let d = defines_of(
            "#define αPW 7/61, αEW 10/12, αUp 1/2 // ratios\n#define NTL 5, κT max(1, 2)\n#define exists[1..2, 1..2] {\n",
        );
        let shown: Vec<String> = d
            .iter()
            .map(|d| format!("{} {} {:?}", d.name, d.value, d.range.map(|r| r.1)))
            .collect();
        assert_eq!(
            shown,
            [
                "αPW 7/61 Some(0.22950819672131148)",
                "αEW 10/12 Some(1.6666666666666667)",
                "αUp 1/2 Some(1.0)",
                "NTL 5 Some(10.0)",
                "κT max(1, 2) None"
            ]
        );
    }
}
