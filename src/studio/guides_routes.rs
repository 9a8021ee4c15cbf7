//! The guides page's part of the JSON API (docs/studio.md, "The guides
//! page"): a request under `/api/guides` -> the [`GuideSession`]'s answer.
//!
//! ```text
//! GET  /api/scenes              guided scenes in the folder (.toml with guides)
//! POST /api/guides/open         {"path", "new"?}: a scene of the folder, or a new one
//! POST /api/guides/edit         {"scene"}: the page's scene, run again
//! POST /api/guides/springs      {"scene", "vertex", "to", "held"}: a drag relaxed
//! POST /api/guides/save         {"path"?}: the scene written (a scene's file only)
//! GET  /api/guides/state        scene, drawing, regrown guides, timings, problem
//! GET  /api/guides/model.glb    the model (the drawing, guides and links as lines)
//! GET  /api/guides/scene.toml   the scene file's text, as a download
//! ```

use serde_json::{json, Value};
use tiny_http::Method;

use super::guides::{self, GuideSession};
use super::listing::files_ending;
use super::reply::{bytes, hdr, json_reply, text, Reply};
use super::{confine, lock, Shared};

/// A scene file read from the folder, at most.
const MAX_SCENE_FILE: u64 = 4 << 20;

pub fn route(method: &Method, path: &str, body: &[u8], sh: &Shared) -> Reply {
    let no_scene = || text(404, "no scene yet: open one (POST /api/guides/open)");
    let json_body = || serde_json::from_slice::<Value>(body).ok();
    match (method, path) {
        (Method::Get, "/api/scenes") => {
            let files: Vec<String> = files_ending(&sh.root, &[".toml"])
                .into_iter()
                .filter(|rel| is_scene(sh, rel))
                .collect();
            json_reply(200, json!({ "files": files }))
        }
        (Method::Post, "/api/guides/open") => {
            let Some(v) = json_body() else {
                return text(400, "say which scene: {\"path\": \"palm.toml\"}");
            };
            let Some(rel) = v["path"].as_str() else {
                return text(400, "say which scene: {\"path\": \"palm.toml\"}");
            };
            if !rel.ends_with(".toml") {
                return json_reply(
                    403,
                    json!({"error": format!("{rel}: a guided scene is a .toml file")}),
                );
            }
            let full = match confine(&sh.root, rel) {
                Ok(f) => f,
                Err(e) => return json_reply(403, json!({"error": e.to_string()})),
            };
            if std::fs::metadata(&full).is_ok_and(|m| m.len() > MAX_SCENE_FILE) {
                return json_reply(
                    403,
                    json!({"error": format!("{rel} is larger than {} MiB", MAX_SCENE_FILE >> 20)}),
                );
            }
            let new = v["new"].as_bool().unwrap_or(false);
            match GuideSession::open(&sh.root, rel, &full, new, sh.max_triangles) {
                Ok(s) => {
                    let state = s.state();
                    *lock(&sh.guides) = Some(s);
                    json_reply(200, state)
                }
                Err(problem) => json_reply(422, json!({ "problem": problem })),
            }
        }
        (Method::Post, "/api/guides/edit") => {
            let Some(v) = json_body() else {
                return text(400, "the body is not JSON");
            };
            let mut s = lock(&sh.guides);
            let Some(s) = s.as_mut() else {
                return no_scene();
            };
            match s.edit(&v["scene"]) {
                Ok(()) => json_reply(200, s.state()),
                Err(e) => json_reply(422, json!({"refused": e, "state": s.state()})),
            }
        }
        (Method::Post, "/api/guides/springs") => match json_body() {
            Some(v) => match guides::springs(&v) {
                Ok(r) => json_reply(200, r),
                Err(e) => json_reply(422, json!({ "refused": e })),
            },
            None => text(400, "the body is not JSON"),
        },
        (Method::Post, "/api/guides/save") => save(sh, json_body()),
        (Method::Get, "/api/guides/state") => match &*lock(&sh.guides) {
            Some(s) => json_reply(200, s.state()),
            None => no_scene(),
        },
        (Method::Get, "/api/guides/model.glb") => match &*lock(&sh.guides) {
            Some(s) => match &s.glb {
                Some(b) => bytes(b.clone(), "model/gltf-binary"),
                None => text(404, "the scene has not built (see the page's message)"),
            },
            None => no_scene(),
        },
        (Method::Get, "/api/guides/scene.toml") => match &*lock(&sh.guides) {
            Some(s) => {
                let stem = std::path::Path::new(&s.name)
                    .file_name()
                    .map_or("scene.toml".into(), |n| n.to_string_lossy().into_owned());
                bytes(s.text().into_bytes(), "text/plain; charset=utf-8").with_header(hdr(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{}\"", stem.replace('"', "_")),
                ))
            }
            None => no_scene(),
        },
        _ => text(404, "no such guides route (see docs/studio.md)"),
    }
}

/// Whether the folder's `rel` is a guided scene: a `.toml` with guides.
fn is_scene(sh: &Shared, rel: &str) -> bool {
    let Ok(full) = confine(&sh.root, rel) else {
        return false;
    };
    std::fs::metadata(&full).is_ok_and(|m| m.len() <= MAX_SCENE_FILE)
        && std::fs::read_to_string(&full).is_ok_and(|t| t.contains("[[guide]]"))
}

/// Writes the scene to `path` (default: where it was opened). The file
/// must be in the scene's folder (its grammars are named relative to it)
/// and be new or a guided scene: anything else is refused, not replaced.
fn save(sh: &Shared, body: Option<Value>) -> Reply {
    let guard = lock(&sh.guides);
    let Some(s) = guard.as_ref() else {
        return text(404, "no scene yet: open one (POST /api/guides/open)");
    };
    let rel = body
        .as_ref()
        .and_then(|v| v["path"].as_str())
        .unwrap_or(&s.name)
        .to_string();
    if !rel.ends_with(".toml") {
        return json_reply(
            403,
            json!({"error": format!("{rel}: a guided scene is saved as a .toml file")}),
        );
    }
    let full = match confine(&sh.root, &rel) {
        Ok(f) => f,
        Err(e) => return json_reply(403, json!({"error": e.to_string()})),
    };
    let same_folder = full
        .parent()
        .zip(s.folder().canonicalize().ok())
        .is_some_and(|(a, b)| a == b);
    if !same_folder {
        return json_reply(
            403,
            json!({"error": format!("{rel}: a scene is saved in its own folder, beside the grammars it names")}),
        );
    }
    if let Err(why) = GuideSession::may_replace(&full) {
        return json_reply(409, json!({"error": format!("{rel}: {why}")}));
    }
    let text = s.text();
    match crate::driver::write_file(&full, |w| w.write_all(text.as_bytes())) {
        Ok(()) => json_reply(200, json!({"saved": rel, "bytes": text.len()})),
        Err(e) => json_reply(500, json!({"error": format!("cannot write {rel}: {e}")})),
    }
}
