//! The drawing page's part of the JSON API (docs/studio.md, "The drawing
//! page"): a request under `/api/drawing` -> the [`DrawingSession`]'s
//! answer.
//!
//! ```text
//! GET  /api/drawings              drawings in the folder (.png, .svg)
//! POST /api/drawing/open          {"path"}: a drawing of the folder
//! POST /api/drawing/upload?name=  the body is the drawing (PNG or SVG)
//! POST /api/drawing/edit          {"strokes", "corrections", "gap"}
//! GET  /api/drawing/state         tree, regions, grammar, counts, problem
//! GET  /api/drawing/image.png     the drawing as read (the tree's pixels)
//! GET  /api/drawing/model.glb     the hall the grammar builds
//! GET  /api/drawing/grammar.lsys  the grammar, as a download
//! ```

use serde_json::{json, Value};
use tiny_http::Method;

use super::drawing::DrawingSession;
use super::listing::files_ending;
use super::reply::{bytes, hdr, json_reply, text, Reply};
use super::{confine, lock, Shared};

/// Drawings listed and opened.
const DRAWING_ENDINGS: [&str; 2] = [".png", ".svg"];
/// A drawing file read from the folder, at most (uploads are bounded by
/// the request body's limit).
const MAX_DRAWING_FILE: u64 = 64 << 20;

pub fn route(
    method: &Method,
    path: &str,
    query: &[(String, String)],
    body: &[u8],
    sh: &Shared,
) -> Reply {
    let q = |k: &str| query.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    let no_drawing = || {
        text(
            404,
            "no drawing yet: open one (POST /api/drawing/open) or upload one",
        )
    };
    match (method, path) {
        (Method::Get, "/api/drawings") => json_reply(
            200,
            json!({"files": files_ending(&sh.root, &DRAWING_ENDINGS)}),
        ),
        (Method::Post, "/api/drawing/open") => {
            let rel = serde_json::from_slice::<Value>(body)
                .ok()
                .and_then(|v| v["path"].as_str().map(str::to_string));
            let Some(rel) = rel else {
                return text(400, "say which drawing: {\"path\": \"front.png\"}");
            };
            if !DRAWING_ENDINGS.iter().any(|e| rel.ends_with(e)) {
                return json_reply(
                    403,
                    json!({"error": format!("{rel}: a drawing is a .png or .svg file")}),
                );
            }
            let full = match confine(&sh.root, &rel) {
                Ok(f) => f,
                Err(e) => return json_reply(403, json!({"error": e.to_string()})),
            };
            let read = std::fs::metadata(&full)
                .map_err(|e| e.to_string())
                .and_then(|m| {
                    if m.len() > MAX_DRAWING_FILE {
                        Err(format!(
                            "{} MiB; the studio reads drawings of at most {} MiB",
                            m.len() >> 20,
                            MAX_DRAWING_FILE >> 20
                        ))
                    } else {
                        std::fs::read(&full).map_err(|e| e.to_string())
                    }
                });
            match read {
                Ok(b) => open(sh, &rel, &b),
                Err(e) => json_reply(403, json!({"error": format!("cannot read {rel}: {e}")})),
            }
        }
        (Method::Post, "/api/drawing/upload") => {
            let name = q("name").unwrap_or("upload.png");
            // Only a name: the upload is never written anywhere.
            let name = name.rsplit(['/', '\\']).next().unwrap_or(name);
            open(sh, name, body)
        }
        (Method::Post, "/api/drawing/edit") => {
            let Ok(v) = serde_json::from_slice::<Value>(body) else {
                return text(400, "the body is not JSON");
            };
            let mut d = lock(&sh.drawing);
            let Some(d) = d.as_mut() else {
                return no_drawing();
            };
            match d.edit(&v) {
                Ok(()) => json_reply(200, d.state()),
                Err(e) => json_reply(422, json!({"refused": e, "state": d.state()})),
            }
        }
        (Method::Get, "/api/drawing/state") => match &*lock(&sh.drawing) {
            Some(d) => json_reply(200, d.state()),
            None => no_drawing(),
        },
        (Method::Get, "/api/drawing/image.png") => match &*lock(&sh.drawing) {
            Some(d) => bytes(d.png.clone(), "image/png"),
            None => no_drawing(),
        },
        (Method::Get, "/api/drawing/model.glb") => match &*lock(&sh.drawing) {
            Some(d) => match &d.model {
                Some(m) => bytes(m.glb.clone(), "model/gltf-binary"),
                None => text(
                    404,
                    "the drawing's grammar has not built (see the page's message)",
                ),
            },
            None => no_drawing(),
        },
        (Method::Get, "/api/drawing/grammar.lsys") => match &*lock(&sh.drawing) {
            Some(d) => match d.grammar() {
                Some(g) => {
                    let stem = std::path::Path::new(&d.name)
                        .file_stem()
                        .map_or("drawing".into(), |s| s.to_string_lossy().into_owned());
                    let stem: String = stem
                        .chars()
                        .map(|c| {
                            if c.is_ascii_alphanumeric() || "-_".contains(c) {
                                c
                            } else {
                                '_'
                            }
                        })
                        .collect();
                    bytes(g.as_bytes().to_vec(), "text/plain; charset=utf-8").with_header(hdr(
                        "Content-Disposition",
                        &format!("attachment; filename=\"{stem}.lsys\""),
                    ))
                }
                None => text(
                    404,
                    "the drawing has not been read (see the page's message)",
                ),
            },
            None => no_drawing(),
        },
        _ => text(404, "no such drawing route (see docs/studio.md)"),
    }
}

/// Reads a drawing as the session's; a drawing that cannot be read
/// leaves the one before it open.
fn open(sh: &Shared, name: &str, bytes: &[u8]) -> Reply {
    match DrawingSession::open(name, bytes, sh.max_triangles) {
        Ok(d) => {
            let state = d.state();
            *lock(&sh.drawing) = Some(d);
            json_reply(200, state)
        }
        Err(problem) => json_reply(422, json!({"problem": problem})),
    }
}
