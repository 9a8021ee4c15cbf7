//! The painting page's part of the JSON API (docs/studio.md, "The
//! painting page"): a request under `/api/paint` -> the
//! [`PaintSession`]'s answer.
//!
//! ```text
//! GET  /api/paintings          sessions (.lsys painted here), rules (.rules) and images of the folder
//! POST /api/paint/open         {"path", "rules"?}: a session, or a new one with those rules
//! POST /api/paint/paint        {"view", "rect", "component"}, or {"part", "view", "rect"}: placed and built
//! POST /api/paint/edit         {"session"}: the page's session (undo, delete, threshold, photos), built
//! POST /api/paint/save         {"path"?}: the session written (a new file or a session only)
//! GET  /api/paint/state        session, palette, reports, diagnostics, the file's text
//! GET  /api/paint/model.glb    the model
//! GET  /api/paint/session.lsys the session file's text, as a download
//! GET  /api/paint/photo?path=  an image of the folder, for a reference photo
//! ```

use serde_json::{json, Value};
use tiny_http::Method;

use super::listing::{files_ending, folder_file};
use super::painting::{is_session, PaintSession};
use super::reply::{bytes, hdr, json_reply, text, Reply};
use super::{confine, lock, Shared};

/// A session file read from the folder, at most.
const MAX_SESSION_FILE: u64 = 4 << 20;
/// A reference photo, at most.
const MAX_PHOTO: u64 = 32 << 20;
const PHOTO_ENDINGS: [&str; 4] = [".png", ".jpg", ".jpeg", ".webp"];

pub fn route(
    method: &Method,
    path: &str,
    query: &[(String, String)],
    body: &[u8],
    sh: &Shared,
) -> Reply {
    let no_session = || text(404, "no session yet: open one (POST /api/paint/open)");
    let json_body = || serde_json::from_slice::<Value>(body).ok();
    match (method, path) {
        (Method::Get, "/api/paintings") => {
            let sessions: Vec<String> = files_ending(&sh.root, &[".lsys"])
                .into_iter()
                .filter(|rel| {
                    folder_file(&sh.root, rel, &[".lsys"], MAX_SESSION_FILE)
                        .is_ok_and(|(_, b)| is_session(&String::from_utf8_lossy(&b)))
                })
                .collect();
            json_reply(
                200,
                json!({
                    "sessions": sessions,
                    "rules": files_ending(&sh.root, &[".rules"]),
                    "photos": files_ending(&sh.root, &PHOTO_ENDINGS),
                }),
            )
        }
        (Method::Post, "/api/paint/open") => {
            let Some(v) = json_body() else {
                return text(400, "say which session: {\"path\": \"villa.lsys\"}");
            };
            let Some(rel) = v["path"].as_str() else {
                return text(400, "say which session: {\"path\": \"villa.lsys\"}");
            };
            let new = v["rules"].as_str();
            let full = if let Some(rules) = new {
                if !rel.ends_with(".lsys") {
                    return json_reply(
                        403,
                        json!({"error": format!("{rel}: a session is a .lsys file")}),
                    );
                }
                let full = match confine(&sh.root, rel) {
                    Ok(f) => f,
                    Err(e) => return json_reply(403, json!({"error": e.to_string()})),
                };
                // The rules are included beside the session.
                let beside = full.parent().map(|d| d.join(rules));
                if !rules.ends_with(".rules") || !beside.is_some_and(|p| p.is_file()) {
                    return json_reply(
                        403,
                        json!({"error": format!("{rules}: the rules are a .rules file in the session's folder")}),
                    );
                }
                full
            } else {
                match folder_file(&sh.root, rel, &[".lsys"], MAX_SESSION_FILE) {
                    Ok((full, _)) => full,
                    Err((code, e)) => return json_reply(code, json!({"error": e})),
                }
            };
            match PaintSession::open(rel, &full, new, sh.max_triangles) {
                Ok(s) => {
                    let state = s.state();
                    *lock(&sh.painting) = Some(s);
                    json_reply(200, state)
                }
                Err(problem) => json_reply(422, json!({ "problem": problem })),
            }
        }
        (Method::Post, "/api/paint/paint") | (Method::Post, "/api/paint/edit") => {
            let Some(v) = json_body() else {
                return text(400, "the body is not JSON");
            };
            let mut s = lock(&sh.painting);
            let Some(s) = s.as_mut() else {
                return no_session();
            };
            let done = if path.ends_with("/paint") {
                s.paint(&v)
            } else {
                s.edit(&v["session"])
            };
            match done {
                Ok(()) => json_reply(200, s.state()),
                Err(e) => json_reply(422, json!({"refused": e, "state": s.state()})),
            }
        }
        (Method::Post, "/api/paint/save") => save(sh, json_body()),
        (Method::Get, "/api/paint/state") => match &*lock(&sh.painting) {
            Some(s) => json_reply(200, s.state()),
            None => no_session(),
        },
        (Method::Get, "/api/paint/model.glb") => match &*lock(&sh.painting) {
            Some(s) => match &s.glb {
                Some(b) => bytes(b.clone(), "model/gltf-binary"),
                None => text(
                    404,
                    "the session has not built (see the page's diagnostics)",
                ),
            },
            None => no_session(),
        },
        (Method::Get, "/api/paint/session.lsys") => match &*lock(&sh.painting) {
            Some(s) => {
                let stem = std::path::Path::new(&s.name)
                    .file_name()
                    .map_or("session.lsys".into(), |n| n.to_string_lossy().into_owned());
                bytes(s.text().into_bytes(), "text/plain; charset=utf-8").with_header(hdr(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{}\"", stem.replace('"', "_")),
                ))
            }
            None => no_session(),
        },
        (Method::Get, "/api/paint/photo") => {
            let rel = query
                .iter()
                .find(|(k, _)| k == "path")
                .map(|(_, v)| v.as_str());
            let Some(rel) = rel else {
                return text(400, "say which image: /api/paint/photo?path=villa.png");
            };
            match folder_file(&sh.root, rel, &PHOTO_ENDINGS, MAX_PHOTO) {
                Ok((_, b)) => {
                    let kind = match rel.rsplit('.').next() {
                        Some("png") => "image/png",
                        Some("webp") => "image/webp",
                        _ => "image/jpeg",
                    };
                    bytes(b, kind)
                }
                Err((code, e)) => text(code, &e),
            }
        }
        _ => text(404, "no such painting route (see docs/studio.md)"),
    }
}

/// Writes the session to `path` (default: where it was opened): a `.lsys`
/// file in the session's folder (its rules are included beside it) that
/// is new or a session this page wrote; anything else is refused.
fn save(sh: &Shared, body: Option<Value>) -> Reply {
    let guard = lock(&sh.painting);
    let Some(s) = guard.as_ref() else {
        return text(404, "no session yet: open one (POST /api/paint/open)");
    };
    let rel = body
        .as_ref()
        .and_then(|v| v["path"].as_str())
        .unwrap_or(&s.name)
        .to_string();
    if !rel.ends_with(".lsys") {
        return json_reply(
            403,
            json!({"error": format!("{rel}: a session is saved as a .lsys file")}),
        );
    }
    let full = match confine(&sh.root, &rel) {
        Ok(f) => f,
        Err(e) => return json_reply(403, json!({"error": e.to_string()})),
    };
    if full.parent().and_then(|p| p.canonicalize().ok()) != s.folder() {
        return json_reply(
            403,
            json!({"error": format!("{rel}: a session is saved in its own folder, beside its rules")}),
        );
    }
    if let Ok(old) = std::fs::read_to_string(&full) {
        if !is_session(&old) {
            return json_reply(
                409,
                json!({"error": format!("{rel} is not a painting session: it is not replaced (save under a new name)")}),
            );
        }
    } else if full.exists() {
        return json_reply(
            409,
            json!({"error": format!("{rel} cannot be read: it is not replaced")}),
        );
    }
    let text = s.text();
    match crate::driver::write_file(&full, |w| w.write_all(text.as_bytes())) {
        Ok(()) => json_reply(200, json!({"saved": rel, "bytes": text.len()})),
        Err(e) => json_reply(500, json!({"error": format!("cannot write {rel}: {e}")})),
    }
}
