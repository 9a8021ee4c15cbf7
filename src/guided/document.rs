//! A scene as the studio's guides page edits it: the scene file's own
//! tables (guides, links, seeds by name, not yet checked) as JSON from the
//! page, or read from a scene's TOML text, in; the TOML text `scene.rs`
//! reads (and `lsys build` runs) out.
//!
//! The text written is the file format of docs/guided.md, key for key, so
//! a saved scene reads back to the same document. Comments of the file
//! that was opened are not kept: the text starts with a comment saying so.

use serde::{Deserialize, Serialize};

/// What a page may send, at most: more is refused before it is read.
pub const MAX_GUIDES: usize = 500;
pub const MAX_POINTS: usize = 200;
pub const MAX_LINKS: usize = 2_000;
pub const MAX_SEEDS: usize = 500;
/// The studio derives at most this many steps (`lsys build` has no
/// such limit: a scene of more steps builds from the command line).
pub const MAX_STEPS: u32 = 1_000;

/// Coordinates and angles are written to this many decimals: a dragged
/// vertex does not write 17 digits.
const DECIMALS: f64 = 1e4;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDoc {
    pub steps: u32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    #[serde(default)]
    pub guide: Vec<GuideDoc>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub link: Vec<LinkDoc>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub seeds: Vec<SeedDoc>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuideDoc {
    pub name: String,
    pub grammar: String,
    pub points: Vec<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<i64>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkDoc {
    pub from: String,
    pub from_edge: usize,
    pub to: String,
    pub to_edge: usize,
    #[serde(default)]
    pub tokens: u32,
    pub continuity: String,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub heading: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<i64>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeedDoc {
    pub guide: String,
    pub position: [f64; 2],
    pub heading: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grammar: Option<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parameters: Vec<f64>,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn round(x: f64) -> f64 {
    let r = (x * DECIMALS).round() / DECIMALS;
    // No "-0.0" in the file.
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

impl SceneDoc {
    /// The document of a scene file's text (`scene::read` says what is
    /// wrong with a text this refuses; this only reads its tables).
    pub fn from_toml(text: &str) -> Result<SceneDoc, String> {
        toml::from_str(text).map_err(|e| e.message().to_string())
    }

    /// A page's document, refused whole when it is not one or is larger
    /// than the studio takes.
    pub fn from_json(v: &serde_json::Value) -> Result<SceneDoc, String> {
        let d: SceneDoc = serde_json::from_value(v.clone()).map_err(|e| {
            format!("the scene is not a guided scene's tables (docs/guided.md): {e}")
        })?;
        let too_many = |what: &str, n: usize| format!("{what}: at most {n} in the studio");
        if d.guide.len() > MAX_GUIDES {
            return Err(too_many("guides", MAX_GUIDES));
        }
        if d.guide.iter().any(|g| g.points.len() > MAX_POINTS) {
            return Err(too_many("points of a guide", MAX_POINTS));
        }
        if d.link.len() > MAX_LINKS {
            return Err(too_many("links", MAX_LINKS));
        }
        if d.seeds.len() > MAX_SEEDS {
            return Err(too_many("seeds", MAX_SEEDS));
        }
        if d.steps > MAX_STEPS {
            return Err(format!(
                "steps: at most {MAX_STEPS} in the studio (`lsys build` derives more)"
            ));
        }
        Ok(d)
    }

    /// The scene file's text, with coordinates and angles rounded to four
    /// decimals.
    pub fn to_toml(&self) -> String {
        let mut d = self.clone();
        for g in &mut d.guide {
            for p in &mut g.points {
                *p = [round(p[0]), round(p[1])];
            }
        }
        for l in &mut d.link {
            l.heading = round(l.heading);
        }
        for s in &mut d.seeds {
            s.position = [round(s.position[0]), round(s.position[1])];
            s.heading = round(s.heading);
        }
        // Every value is a plain number, string or array: serialising
        // cannot fail.
        let body = toml::to_string(&d).unwrap_or_default();
        format!("# A guided scene (docs/guided.md), written by the studio's guides page.\n{body}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_file_reads_writes_and_reads_back_the_same() {
        let text = std::fs::read_to_string("examples/guided/links.toml").unwrap();
        let d = SceneDoc::from_toml(&text).unwrap();
        assert_eq!(d.guide.len(), 3);
        assert_eq!(d.link[1].continuity, "C0");
        let written = d.to_toml();
        assert_eq!(SceneDoc::from_toml(&written).unwrap(), d);
        // What the file means is unchanged: the checked scenes are equal
        // but for the spans.
        let a = crate::guided::scene::read("a", &text).unwrap();
        let b = crate::guided::scene::read("b", &written).unwrap();
        assert_eq!(a.links, b.links);
        assert_eq!(a.seeds.len(), b.seeds.len());
        for (x, y) in a.guides.iter().zip(&b.guides) {
            assert_eq!((&x.name, &x.points, x.id), (&y.name, &y.points, y.id));
        }
    }

    #[test]
    fn a_dragged_point_is_written_to_four_decimals_and_pages_are_bounded() {
        let v = serde_json::json!({
            "steps": 3,
            "guide": [{"name": "g", "grammar": "x.lsys",
                       "points": [[0.123456789, -0.00001], [1, 0], [1, 1]]}],
        });
        let d = SceneDoc::from_json(&v).unwrap();
        let t = d.to_toml();
        assert!(t.contains("[0.1235, 0.0]"), "{t}");
        let mut big = v.clone();
        big["steps"] = serde_json::json!(MAX_STEPS + 1);
        assert!(SceneDoc::from_json(&big).unwrap_err().contains("steps"));
        let bad = serde_json::json!({"steps": 1, "guides": []});
        assert!(SceneDoc::from_json(&bad).is_err());
    }
}
