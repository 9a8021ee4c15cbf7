//! One item of a batch: a JSON object (a manifest line, or a dict handed
//! over by the Python package) and the folder relative grammar paths start
//! from -> an [`Item`] (id, grammar, defines, seed, steps, format), or an
//! [`ItemError`] saying which key is wrong and why.

use std::path::Path;

use miette::Diagnostic;
use serde_json::Value;
use thiserror::Error;

use crate::export::output::Format;

/// One model to build: what `lsys build GRAMMAR -D ... --seed S -n N -o
/// ID.FORMAT` would build.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// Names the output file (`ID.FORMAT`) and the item's line in the
    /// index; unique in a manifest, safe as a file name.
    pub id: String,
    /// Anything `lsys build` takes: a grammar file, `std:NAME`, a Pailou
    /// component graph or a guided scene (`.toml`). A relative path has
    /// already been joined to the manifest's folder.
    pub grammar: String,
    /// `-D NAME=VALUE`s, namespaced names (`TM.NTL`) as `-D` takes them.
    pub defines: Vec<(String, String)>,
    /// `--seed`.
    pub seed: Option<u64>,
    /// `-n`.
    pub steps: Option<u32>,
    pub format: Format,
}

/// The keys an item may have.
pub const KEYS: [&str; 6] = ["id", "grammar", "defines", "seed", "steps", "format"];

/// Longest id: a file name is at most 255 bytes on the usual file
/// systems, and `.gltf` takes five of them.
pub const MAX_ID: usize = 250;

/// What is wrong with one item's fields.
#[derive(Clone, Debug, Error, Diagnostic, PartialEq, Eq)]
pub enum ItemError {
    #[error("an item is a JSON object, not {found}")]
    #[diagnostic(
        code(lsys::batch::not_an_object),
        help(r#"write one object per line: {{"id": "a", "grammar": "plant.lsys"}}"#)
    )]
    NotAnObject { found: &'static str },

    #[error("unknown key `{key}`")]
    #[diagnostic(code(lsys::batch::unknown_key), help("{help}"))]
    UnknownKey { key: String, help: String },

    #[error("the item has no `{key}`")]
    #[diagnostic(
        code(lsys::batch::missing_key),
        help("every item needs an \"id\" (its output file's name) and a \"grammar\"")
    )]
    MissingKey { key: &'static str },

    #[error("`{key}` must be {expected}, not {found}")]
    #[diagnostic(code(lsys::batch::wrong_type))]
    WrongType {
        key: String,
        expected: &'static str,
        found: String,
    },

    #[error("the id `{id}` cannot name a file: {why}")]
    #[diagnostic(
        code(lsys::batch::unsafe_id),
        help("an id names the output file ID.FORMAT in the output folder: letters, digits, `-`, `_` and inner dots are safe")
    )]
    UnsafeId { id: String, why: &'static str },

    #[error("unknown format `{format}`")]
    #[diagnostic(
        code(lsys::batch::unknown_format),
        help("the formats are glb (the default), gltf, obj (with an .mtl beside it) and png")
    )]
    UnknownFormat { format: String },
}

impl ItemError {
    /// The key the mistake is in, so that a manifest line can point at it
    /// (`defines.NAME` for one define; `None`: the whole item).
    pub fn key(&self) -> Option<&str> {
        match self {
            ItemError::NotAnObject { .. } | ItemError::MissingKey { .. } => None,
            ItemError::UnknownKey { key, .. } | ItemError::WrongType { key, .. } => Some(key),
            ItemError::UnsafeId { .. } => Some("id"),
            ItemError::UnknownFormat { .. } => Some("format"),
        }
    }
}

/// The item `value` states; a relative grammar path is joined to
/// `base_dir` (the manifest's folder).
pub fn item_from_json(value: &Value, base_dir: &Path) -> Result<Item, ItemError> {
    let Value::Object(map) = value else {
        return Err(ItemError::NotAnObject { found: kind(value) });
    };
    if let Some(key) = map.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(unknown_key(key));
    }
    let id = string(map.get("id"), "id")?.ok_or(ItemError::MissingKey { key: "id" })?;
    check_id(&id)?;
    let grammar = string(map.get("grammar"), "grammar")?
        .filter(|g| !g.is_empty())
        .ok_or(ItemError::MissingKey { key: "grammar" })?;
    let format = match string(map.get("format"), "format")? {
        None => Format::Glb,
        Some(f) => format_named(&f).ok_or(ItemError::UnknownFormat { format: f })?,
    };
    Ok(Item {
        id,
        grammar: resolve_grammar(&grammar, base_dir),
        defines: defines(map.get("defines"))?,
        // `--seed`'s range (0 to 4294967295).
        seed: whole(map.get("seed"), "seed", u32::MAX as u64)?,
        steps: whole(map.get("steps"), "steps", u32::MAX as u64)?.map(|n| n as u32),
        format,
    })
}

/// A grammar as `lsys build` takes it: `std:NAME` as it is, a relative
/// path from `base_dir`.
fn resolve_grammar(grammar: &str, base_dir: &Path) -> String {
    if grammar.starts_with("std:") || Path::new(grammar).is_absolute() {
        return grammar.to_string();
    }
    base_dir.join(grammar).to_string_lossy().into_owned()
}

/// The format an extension names (`glb`, `GLB`, `obj`, ...), as an output
/// file's extension would name it.
fn format_named(ext: &str) -> Option<Format> {
    if ext.is_empty() || ext.contains(['.', '/', '\\']) {
        return None;
    }
    Format::of(Path::new(&format!("model.{ext}")))
}

/// The extension an item's output file gets.
pub fn extension(format: Format) -> &'static str {
    match format {
        Format::Glb => "glb",
        Format::Gltf => "gltf",
        Format::Obj => "obj",
        Format::Png => "png",
    }
}

impl Item {
    /// The output file's name: `ID.FORMAT`.
    pub fn output_name(&self) -> String {
        format!("{}.{}", self.id, extension(self.format))
    }
}

/// Refuses an id that would not stay a plain file in the output folder:
/// empty, a path (`/`, `\`, `..`), hidden or special (a leading `.`, as
/// `.` and `..` are and the atomic writer's temporary files are), with a
/// control character (NUL ends a C string), or too long for a file name.
pub fn check_id(id: &str) -> Result<(), ItemError> {
    let why = if id.is_empty() {
        "it is empty"
    } else if id.contains(['/', '\\']) {
        "it has a path separator (`/` or `\\`)"
    } else if id.contains("..") {
        "it has `..`"
    } else if id.starts_with('.') {
        "it starts with `.` (a hidden file)"
    } else if id.chars().any(char::is_control) {
        "it has a control character"
    } else if id.len() > MAX_ID {
        "it is longer than 250 bytes"
    } else {
        return Ok(());
    };
    Err(ItemError::UnsafeId {
        id: id.to_string(),
        why,
    })
}

fn unknown_key(key: &str) -> ItemError {
    let near = KEYS
        .iter()
        .map(|k| (strsim::damerau_levenshtein(key, k), *k))
        .filter(|(d, _)| *d <= 2)
        .min();
    let keys = KEYS.map(|k| format!("\"{k}\"")).join(", ");
    let help = match near {
        Some((_, k)) => format!("did you mean \"{k}\"? The keys are {keys}"),
        None => format!("the keys are {keys}"),
    };
    ItemError::UnknownKey {
        key: key.to_string(),
        help,
    }
}

/// What a JSON value is, for messages.
fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn wrong(key: &str, expected: &'static str, v: &Value) -> ItemError {
    ItemError::WrongType {
        key: key.to_string(),
        expected,
        found: kind(v).to_string(),
    }
}

/// An optional string (`null` is absent).
fn string(v: Option<&Value>, key: &str) -> Result<Option<String>, ItemError> {
    match v {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(other) => Err(wrong(key, "a string", other)),
    }
}

/// An optional whole number from 0 to `max` (`null` is absent).
fn whole(v: Option<&Value>, key: &str, max: u64) -> Result<Option<u64>, ItemError> {
    match v {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(n)) => match n.as_u64() {
            Some(n) if n <= max => Ok(Some(n)),
            _ => Err(ItemError::WrongType {
                key: key.to_string(),
                expected: "a whole number from 0 to 4294967295",
                found: n.to_string(),
            }),
        },
        Some(other) => Err(wrong(key, "a whole number", other)),
    }
}

/// `{"NAME": VALUE, ...}` as `-D NAME=VALUE`s: a number as JSON writes it,
/// a string as it is (an expression, as `-D` takes one).
fn defines(v: Option<&Value>) -> Result<Vec<(String, String)>, ItemError> {
    let map = match v {
        None | Some(Value::Null) => return Ok(Vec::new()),
        Some(Value::Object(m)) => m,
        Some(other) => return Err(wrong("defines", "an object of NAME: VALUE", other)),
    };
    let mut out = Vec::with_capacity(map.len());
    for (name, value) in map {
        // `-D` trims both sides and refuses an empty one: the same here.
        let key = format!("defines.{name}");
        let value = match value {
            Value::Number(n) => n.to_string(),
            Value::String(s) if !s.trim().is_empty() => s.trim().to_string(),
            Value::String(_) => {
                return Err(ItemError::WrongType {
                    key,
                    expected: "a number or an expression",
                    found: "an empty string".into(),
                })
            }
            other => return Err(wrong(&key, "a number or a string", other)),
        };
        if name.trim().is_empty() {
            return Err(ItemError::WrongType {
                key: "defines".into(),
                expected: "an object whose names are not empty",
                found: "an empty name".into(),
            });
        }
        out.push((name.trim().to_string(), value));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn an_item_reads_with_defaults_and_a_path_from_the_manifests_folder() {
        let v = json!({"id": "a", "grammar": "g/plant.lsys",
                       "defines": {"N": 3, "TM.NTL": "2*2", "X": 0.5}, "seed": 7});
        let item = item_from_json(&v, Path::new("jobs")).unwrap();
        assert_eq!(
            item.grammar,
            Path::new("jobs/g/plant.lsys").to_string_lossy()
        );
        assert_eq!(
            item.defines,
            [("N", "3"), ("TM.NTL", "2*2"), ("X", "0.5")]
                .map(|(a, b)| (a.to_string(), b.to_string()))
        );
        assert_eq!(
            (item.seed, item.steps, item.format),
            (Some(7), None, Format::Glb)
        );
        assert_eq!(item.output_name(), "a.glb");
        let std = json!({"id": "t", "grammar": "std:toukung_middle", "format": "OBJ"});
        let item = item_from_json(&std, Path::new("jobs")).unwrap();
        assert_eq!(
            (item.grammar.as_str(), item.format),
            ("std:toukung_middle", Format::Obj)
        );
        assert_eq!(item.output_name(), "t.obj");
    }

    #[test]
    fn mistakes_name_their_key() {
        let e = |v: Value| item_from_json(&v, Path::new("")).unwrap_err();
        let err = e(json!({"id": "a", "grammar": "g", "sead": 1}));
        assert_eq!(err.key(), Some("sead"));
        assert!(err
            .help()
            .unwrap()
            .to_string()
            .starts_with("did you mean \"seed\"?"));
        assert_eq!(
            e(json!({"grammar": "g"})),
            ItemError::MissingKey { key: "id" }
        );
        assert_eq!(
            e(json!({"id": "a"})),
            ItemError::MissingKey { key: "grammar" }
        );
        assert_eq!(
            e(json!({"id": "a", "grammar": "g", "seed": -1})).key(),
            Some("seed")
        );
        assert_eq!(
            e(json!({"id": "a", "grammar": "g", "steps": 1.5})).key(),
            Some("steps")
        );
        assert_eq!(
            e(json!({"id": "a", "grammar": "g", "defines": {"N": true}})).key(),
            Some("defines.N")
        );
        assert_eq!(
            e(json!({"id": "a", "grammar": "g", "format": "stl"})).key(),
            Some("format")
        );
        assert_eq!(e(json!([1])), ItemError::NotAnObject { found: "an array" });
    }

    #[test]
    fn ids_that_would_leave_the_folder_are_refused() {
        for bad in ["", "a/b", "a\\b", "..", "a..b", ".hidden", "a\0b", "a\nb"] {
            assert!(check_id(bad).is_err(), "{bad:?}");
        }
        assert!(check_id(&"x".repeat(MAX_ID + 1)).is_err());
        for good in ["a", "plant-3_seed.7", "Ü", "x".repeat(MAX_ID).as_str()] {
            assert!(check_id(good).is_ok(), "{good:?}");
        }
    }
}
