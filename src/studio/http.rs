//! The studio's HTTP side: a request -> the safety checks -> a route of
//! the JSON API, the page, or an event stream. Every handler runs under
//! `catch_unwind`: a bug answers 500 and the server stays up.

use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering::SeqCst};
use std::sync::Arc;
use std::time::Duration;

use serde_json::{json, Value};
use tiny_http::{Method, Request, Server};

use super::listing::files_ending;
use super::reply::{bytes, hdr, json_reply, text, Reply};
use super::safety::{self, confine, host_ok, origin_ok};
use super::{lock, open_file, Session, Shared};

/// Requests handled at once (each on a thread of its own); more wait
/// for an answer 503.
const MAX_BUSY: usize = 64;
/// Event streams open at once. A stream lasts as long as its page, so
/// they are counted apart from [`MAX_BUSY`]: 63 open tabs used to take
/// every request's place and answer everything else 503.
const MAX_STREAMS: usize = 16;

/// Accepts requests until the server is unblocked; one thread each.
pub fn serve(server: &Server, shared: &Arc<Shared>) {
    let busy = Arc::new(AtomicUsize::new(0));
    let streams = Arc::new(AtomicUsize::new(0));
    while let Ok(req) = server.recv() {
        if *lock(&shared.stopped) {
            return;
        }
        let stream = *req.method() == Method::Get && split_url(req.url()).0 == "/api/events";
        let (count, limit, refusal) = if stream {
            (
                &streams,
                MAX_STREAMS,
                "too many open event streams (pages of this studio): close some tabs",
            )
        } else {
            (&busy, MAX_BUSY, "busy: too many requests at once")
        };
        if count.load(SeqCst) >= limit {
            let _ = req.respond(text(503, refusal));
            continue;
        }
        count.fetch_add(1, SeqCst);
        let (sh, c) = (shared.clone(), count.clone());
        let spawned = std::thread::Builder::new()
            .stack_size(crate::driver::WORKER_STACK)
            .spawn(move || {
                handle(req, &sh);
                c.fetch_sub(1, SeqCst);
            });
        if spawned.is_err() {
            count.fetch_sub(1, SeqCst);
        }
    }
}

fn header<'r>(req: &'r Request, name: &str) -> Option<&'r str> {
    req.headers()
        .iter()
        .find(|h| h.field.as_str().as_str().eq_ignore_ascii_case(name))
        .map(|h| h.value.as_str())
}

fn handle(mut req: Request, shared: &Shared) {
    if !host_ok(header(&req, "Host"), &shared.hosts) {
        let _ = req.respond(text(
            403,
            "forbidden: this server answers only to its own address (Host)",
        ));
        return;
    }
    if !origin_ok(header(&req, "Origin"), &shared.hosts) {
        let _ = req.respond(text(
            403,
            "forbidden: requests from other sites are refused (Origin)",
        ));
        return;
    }
    let (path, query) = split_url(req.url());
    if *req.method() == Method::Get && path == "/api/events" {
        events(req, shared);
        return;
    }
    let body = if *req.method() == Method::Post {
        match safety::read_body(req.body_length(), req.as_reader()) {
            Some(b) => b,
            None => {
                let _ = req.respond(text(413, "the request body is larger than 1 MiB"));
                return;
            }
        }
    } else {
        Vec::new()
    };
    let method = req.method().clone();
    let reply = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        route(&method, &path, &query, &body, shared)
    }))
    .unwrap_or_else(|_| {
        text(
            500,
            "internal error in lsys studio (a bug: please report it); the last good model is kept",
        )
    });
    let _ = req.respond(reply);
}

fn split_url(url: &str) -> (String, Vec<(String, String)>) {
    let (path, q) = url.split_once('?').unwrap_or((url, ""));
    let query = q
        .split('&')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (decode(k), decode(v)))
        .collect();
    (decode(path), query)
}

/// Percent-decoding (`+` is a space in queries, harmless in paths here).
fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'%' if i + 2 < b.len() => {
                let hex = std::str::from_utf8(&b[i + 1..i + 3]).unwrap_or("");
                match u8::from_str_radix(hex, 16) {
                    Ok(v) => {
                        out.push(v);
                        i += 3;
                        continue;
                    }
                    Err(_) => out.push(b'%'),
                }
            }
            b'+' => out.push(b' '),
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn route(
    method: &Method,
    path: &str,
    query: &[(String, String)],
    body: &[u8],
    sh: &Shared,
) -> Reply {
    let q = |k: &str| query.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    let json_body = || serde_json::from_slice::<Value>(body).ok();
    match (method, path) {
        (Method::Get, "/") | (Method::Get, "/index.html") => page(sh, "index.html"),
        (Method::Get, "/drawing") | (Method::Get, "/drawing.html") => page(sh, "drawing.html"),
        (Method::Get, "/guides") | (Method::Get, "/guides.html") => page(sh, "guides.html"),
        (Method::Get, "/paint") | (Method::Get, "/paint.html") => page(sh, "paint.html"),
        (Method::Get, p) if p.starts_with("/assets/") => asset(sh, &p[1..]),
        (Method::Get, "/api/state") => json_reply(200, state(sh)),
        (Method::Get, "/api/model.glb") => match model_bytes(sh) {
            Some(b) => bytes(b, "model/gltf-binary"),
            None => text(404, "no model yet: the opened file has not built"),
        },
        (Method::Get, "/api/palette") => {
            let s = lock(&sh.session);
            match &*s {
                Session::Pailou(p) => {
                    let id = q("id").unwrap_or(&p.active);
                    json_reply(
                        200,
                        json!({"id": id, "kind": p.graph.kind_of(id), "kinds": super::pailou::palette(&p.graph, id)}),
                    )
                }
                Session::Grammar(_) => text(409, "the palette is Pailou mode's; open a graph"),
            }
        }
        (Method::Get, "/api/files") => json_reply(200, json!({"files": files(sh)})),
        (Method::Get, "/api/export") => export(sh, q("format").unwrap_or("glb")),
        (Method::Post, "/api/edit") => {
            let Some(edit) = json_body() else {
                return text(400, "the body is not JSON");
            };
            let result = match &mut *lock(&sh.session) {
                Session::Pailou(p) => p.apply(&edit),
                Session::Grammar(_) => Err(
                    json!({"message": "edits are Pailou mode's; open a graph", "rendered": "edits are Pailou mode's; open a graph"}),
                ),
            };
            let moved = matches!(edit["op"].as_str(), Some("move" | "select"));
            if result.is_ok() && !moved {
                sh.bump();
            }
            match result {
                Ok(()) => json_reply(200, json!({"ok": true, "state": state(sh)})),
                Err(e) => json_reply(422, json!({"ok": false, "refused": e, "state": state(sh)})),
            }
        }
        (Method::Post, "/api/grammar") => {
            let Some(v) = json_body() else {
                return text(400, "the body is not JSON");
            };
            match &mut *lock(&sh.session) {
                Session::Grammar(g) => g.set(&v),
                Session::Pailou(_) => return text(409, "open a grammar (.lsys) first"),
            }
            sh.bump();
            json_reply(200, state(sh))
        }
        (Method::Post, "/api/open") => {
            let rel = json_body().and_then(|v| v["path"].as_str().map(str::to_string));
            let Some(rel) = rel else {
                return text(400, "say which file: {\"path\": \"name.toml\"}");
            };
            // Under the session's lock: the watcher thread cannot rebuild
            // the old grammar (and tell the watcher its files) meanwhile.
            let mut session = lock(&sh.session);
            match open_file(&sh.root, &rel, sh.watcher.as_ref(), sh.max_triangles) {
                Ok(s) => {
                    *session = s;
                    drop(session);
                    sh.bump();
                    json_reply(200, state(sh))
                }
                Err(e) => json_reply(403, json!({"error": e})),
            }
        }
        (Method::Post, "/api/save") => save(sh, json_body()),
        (_, p) if p.starts_with("/api/drawing") => {
            super::drawing_routes::route(method, p, query, body, sh)
        }
        (_, p) if p.starts_with("/api/paint") => {
            super::painting_routes::route(method, p, query, body, sh)
        }
        (_, p) if p.starts_with("/api/guides") || p == "/api/scenes" => {
            super::guides_routes::route(method, p, body, sh)
        }
        _ => text(404, "no such page or API route (see docs/studio.md)"),
    }
}

fn state(sh: &Shared) -> Value {
    let mut v = match &*lock(&sh.session) {
        Session::Pailou(p) => p.state(),
        Session::Grammar(g) => g.state(),
    };
    v["version"] = json!(*lock(&sh.version));
    v["folder"] = json!(sh.root.display().to_string());
    v
}

fn model_bytes(sh: &Shared) -> Option<Vec<u8>> {
    match &*lock(&sh.session) {
        Session::Pailou(p) => p.model.as_ref().map(|m| m.glb.clone()),
        Session::Grammar(g) => g.model.as_ref().map(|m| m.glb.clone()),
    }
}

/// Saves the graph (Pailou mode) as `path` inside the folder.
fn save(sh: &Shared, body: Option<Value>) -> Reply {
    let Some(rel) = body.as_ref().and_then(|v| v["path"].as_str()) else {
        return text(400, "say where: {\"path\": \"name.toml\"}");
    };
    if !rel.ends_with(".toml") {
        return json_reply(403, json!({"error": "a graph is saved as a .toml file"}));
    }
    let full = match confine(&sh.root, rel) {
        Ok(f) => f,
        Err(e) => return json_reply(403, json!({"error": e.to_string()})),
    };
    let replace = body.as_ref().is_some_and(|v| v["replace"] == json!(true));
    let mut s = lock(&sh.session);
    let Session::Pailou(p) = &mut *s else {
        return text(409, "only a Pailou graph is saved from the studio");
    };
    if let Err(refusal) = may_replace(&full, rel, p.file.as_deref(), replace) {
        return json_reply(409, refusal);
    }
    let text_out = p.graph.to_toml();
    match crate::driver::write_file::<std::io::Error>(&full, |w| w.write_all(text_out.as_bytes())) {
        Ok(_) => {
            p.file = Some(rel.to_string());
            json_reply(200, json!({"saved": rel, "bytes": text_out.len()}))
        }
        Err(e) => json_reply(500, json!({"error": format!("cannot write {rel}: {e}")})),
    }
}

/// Whether saving over `full` (`rel` in the folder) is allowed: a new
/// file, or the graph this session opened or saved; another graph only
/// when the page asked the user (`replace`); a file that is not a Pailou
/// graph (`Cargo.toml`, a guided scene) never.
fn may_replace(full: &Path, rel: &str, own: Option<&str>, replace: bool) -> Result<(), Value> {
    let Ok(existing) = std::fs::read_to_string(full) else {
        return if full.exists() {
            Err(
                json!({"error": format!("{rel} exists and is not a text file: the studio does not replace it; save under another name")}),
            )
        } else {
            Ok(())
        };
    };
    if own == Some(rel) {
        return Ok(());
    }
    let is_graph = matches!(
        crate::driver::toml_file(Path::new(rel), &existing),
        Ok(crate::driver::TomlFile::PailouGraph)
    );
    if !is_graph {
        return Err(
            json!({"error": format!("{rel} exists and is not a Pailou graph: the studio never replaces it; save under another name")}),
        );
    }
    if replace {
        return Ok(());
    }
    Err(json!({"error": format!("{rel} is another graph; replace it?"), "exists": true}))
}

/// A download of the model (.glb, .obj, .png) or the emitted grammar
/// (.lsys) or graph (.toml).
fn export(sh: &Shared, format: &str) -> Reply {
    let s = lock(&sh.session);
    let (model, lsys, toml) = match &*s {
        Session::Pailou(p) => (
            p.model.as_ref(),
            Some(p.lsys.clone()),
            Some(p.graph.to_toml()),
        ),
        // The grammar as it is on disk (the page's define values are
        // not written into it).
        Session::Grammar(g) => (
            g.model.as_ref(),
            std::fs::read_to_string(&g.path).ok(),
            None,
        ),
    };
    let file = |ext: &str| format!("attachment; filename=\"studio.{ext}\"");
    match format {
        "lsys" | "toml" => match if format == "lsys" { lsys } else { toml } {
            Some(t) => bytes(t.into_bytes(), "text/plain; charset=utf-8")
                .with_header(hdr("Content-Disposition", &file(format))),
            None => text(409, "a grammar opened in the studio has no component graph: export .lsys, .glb, .obj or .png"),
        },
        "glb" | "obj" | "png" => {
            let Some(m) = model else {
                return text(404, "no model yet");
            };
            // The GLB is the one the page already shows; OBJ and PNG are
            // encoded in memory (the download has no room for an `.mtl`).
            let encoded = match format {
                "glb" => Ok(m.glb.clone()),
                "obj" => Ok(m.scene.to_obj("studio.mtl")),
                _ => m.scene.to_png(1024, 768).map_err(|e| e.to_string()),
            };
            match encoded {
                Ok(b) => {
                    let mime = match format {
                        "png" => "image/png",
                        "obj" => "text/plain",
                        _ => "model/gltf-binary",
                    };
                    bytes(b, mime).with_header(hdr("Content-Disposition", &file(format)))
                }
                Err(e) => text(500, &format!("cannot export: {e}")),
            }
        }
        _ => text(400, "export formats: glb, obj, png, lsys, toml"),
    }
}

/// Graphs and grammars in the opened folder and its subfolders (paths
/// relative to it, `/`-separated), to open.
fn files(sh: &Shared) -> Vec<String> {
    files_ending(&sh.root, &[".toml", ".lsys", ".l"])
}

/// Server-sent events: `update` with the version whenever the model
/// changes (an edit, a save of a watched file), a comment every 15 s.
fn events(req: Request, sh: &Shared) {
    let mut w = req.into_writer();
    let head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
    if w.write_all(head.as_bytes())
        .and_then(|_| w.flush())
        .is_err()
    {
        return;
    }
    let mut seen = 0;
    loop {
        let version = {
            let v = lock(&sh.version);
            let (v, _) = sh
                .changed
                .wait_timeout_while(v, Duration::from_secs(15), |v| {
                    *v == seen && !*lock(&sh.stopped)
                })
                .unwrap_or_else(|e| e.into_inner());
            *v
        };
        if *lock(&sh.stopped) {
            return;
        }
        let msg = if version != seen {
            seen = version;
            format!("event: update\ndata: {version}\n\n")
        } else {
            ": still here\n\n".to_string()
        };
        if w.write_all(msg.as_bytes()).and_then(|_| w.flush()).is_err() {
            return;
        }
    }
}

/// The front end built into the binary (`build.rs`; empty when
/// `web/studio/dist` was not built before it).
mod embedded {
    include!(concat!(env!("OUT_DIR"), "/studio_page.rs"));
}

/// A file of the embedded front end.
fn embedded_file(rel: &str) -> Option<&'static [u8]> {
    embedded::PAGE
        .iter()
        .find(|(p, _)| *p == rel)
        .map(|(_, b)| *b)
}

/// Whether the binary carries its front end.
pub fn has_embedded_page() -> bool {
    embedded_file("index.html").is_some()
}

/// One of the front end's pages (`index.html`, `drawing.html`).
fn page(sh: &Shared, name: &str) -> Reply {
    if let Some(dir) = &sh.assets {
        if let Ok(b) = std::fs::read(dir.join(name)) {
            return bytes(b, "text/html; charset=utf-8");
        }
    } else if let Some(b) = embedded_file(name) {
        return bytes(b.to_vec(), "text/html; charset=utf-8");
    }
    bytes(
        FALLBACK_PAGE.as_bytes().to_vec(),
        "text/html; charset=utf-8",
    )
}

fn asset(sh: &Shared, rel: &str) -> Reply {
    let found = match &sh.assets {
        Some(dir) => match confine(dir, rel) {
            Ok(full) => std::fs::read(full).ok(),
            Err(_) => return text(403, "not an asset"),
        },
        None => match embedded_file(rel) {
            Some(b) => Some(b.to_vec()),
            None if !has_embedded_page() => {
                return text(404, "the front end is not built (docs/studio.md)")
            }
            None => None,
        },
    };
    match found {
        Some(b) => {
            let mime = match rel.rsplit_once('.').map(|(_, e)| e) {
                Some("js") => "text/javascript",
                Some("css") => "text/css",
                Some("svg") => "image/svg+xml",
                Some("png") => "image/png",
                _ => "application/octet-stream",
            };
            bytes(b, mime)
        }
        None => text(404, "no such asset"),
    }
}

/// The page served when the front end has not been built.
const FALLBACK_PAGE: &str = "<!doctype html><html><head><meta charset=\"utf-8\"><title>lsys studio</title></head><body style=\"font-family:sans-serif;max-width:40em;margin:3em auto\"><h1>lsys studio</h1><p>The server is running, but its front end (three.js, from npm) has not been built. Build it once with</p><pre>cd web/studio &amp;&amp; npm ci &amp;&amp; npm run build</pre><p>then restart <code>lsys studio</code> (or pass <code>--assets web/studio/dist</code>). See docs/studio.md. The JSON API works without it: <a href=\"/api/state\">/api/state</a>.</p></body></html>";
