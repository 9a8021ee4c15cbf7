//! A job's figures: a finished [`Done`] -> the `--stats` JSON (modules,
//! instances, vertices, triangles, bounds, output, time per stage, and for
//! shape grammars the primitives, constraints and attributes) and the
//! one-line summary `lsys watch` prints.

use std::path::PathBuf;
use std::time::Duration;

use super::run::Done;
use crate::build::Built;
use crate::resolve::Program;

/// The file written as the figures name it (empty when none was).
pub(super) fn shown(output: &Option<PathBuf>) -> String {
    output
        .as_ref()
        .map_or(String::new(), |p| p.display().to_string())
}

/// Milliseconds with three decimals.
pub fn ms(d: Duration) -> f64 {
    (d.as_secs_f64() * 1e6).round() / 1e3
}

impl Done {
    /// The `--stats` figures (`lsys build --stats` prints them as one line
    /// of JSON).
    pub fn stats(&self) -> serde_json::Value {
        let built = &self.scene.built;
        let s = &built.scene;
        // f32 coordinates printed through f64 would show binary noise
        // (84.05000305175781); print the shortest decimal that reads back.
        let short = |v: glam::Vec3| {
            v.to_array()
                .map(|x| x.to_string().parse::<f64>().unwrap_or(f64::NAN))
        };
        let bounds = s
            .bounds()
            .map(|(lo, hi)| serde_json::json!([short(lo), short(hi)]));
        let t = &built.timings;
        let path = shown(&self.output);
        let mut json = serde_json::json!({
            "modules": built.modules,
            "instances": s.instance_counts(),
            "vertices": s.vertex_count(),
            "triangles": s.triangle_count(),
            "bounds": bounds,
            "output": {"path": path, "bytes": self.written},
            "timings_ms": {
                "parse": ms(self.parse),
                "derive": ms(t.derive),
                "interpret": ms(t.interpret),
                "mesh": ms(t.mesh),
                "write": ms(self.write),
            },
        });
        add_shapes(&mut json, built, &self.grammar.comp.program);
        json
    }

    /// One line for `watch`: what was written and how big the model is.
    pub fn summary(&self) -> String {
        let path = shown(&self.output);
        format!(
            "wrote {path}: {} modules, {} triangles, {} bytes in {} ms",
            self.scene.built.modules,
            self.scene.built.scene.triangle_count(),
            self.written,
            self.took.as_millis()
        )
    }
}

/// The shape-grammar part of the figures (docs/shapes.md): primitives
/// drawn, constraint rules applied, and where each attribute (`#define`)
/// came from; only when the model uses scopes (so other models' figures
/// are unchanged).
fn add_shapes(json: &mut serde_json::Value, built: &Built, program: &Program) {
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
fn attributes(program: &Program) -> serde_json::Value {
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
