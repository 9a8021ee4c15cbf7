//! The shape-grammar part of `--stats` (docs/shapes.md): primitives drawn,
//! constraint rules applied, and where each attribute (`#define`) came
//! from: the file's default rule or the user's `-D`. Input: a built model
//! and its program; output: keys added to the stats JSON, only when the
//! model uses scopes (so other models' stats are unchanged).

use crate::build::Built;
use crate::resolve::Program;

pub(super) fn add(json: &mut serde_json::Value, built: &Built, program: &Program) {
    let d = &built.drawing;
    if d.primitives.is_empty() && d.constraints.is_empty() {
        return;
    }
    json["primitives"] = serde_json::json!(d.primitives);
    json["constraints"] = serde_json::json!(d.constraints);
    json["attributes"] = attributes(program);
}

/// Each `#define`: its value, `"from": "user"` when `-D` set it, else
/// `"default"` with the rule as written (a configure rule: a constant, or
/// a function of other attributes, recomputed when the user sets those).
pub(crate) fn attributes(program: &Program) -> serde_json::Value {
    let mut map = serde_json::Map::new();
    for def in &program.defines {
        // The span names the define; its rule is the rest of that line,
        // less a trailing `//` comment.
        let file = &program.sources.get(def.span.file).text;
        let rest = &file[(def.span.end as usize).min(file.len())..];
        let line = rest.lines().next().unwrap_or("");
        let rule = line.split("//").next().unwrap_or("").trim().to_string();
        let mut entry = serde_json::json!({
            "value": def.value,
            "from": if def.overridden { "user" } else { "default" },
        });
        if !def.overridden {
            entry["rule"] = serde_json::json!(rule);
        }
        map.insert(def.name.clone(), entry);
    }
    serde_json::Value::Object(map)
}
