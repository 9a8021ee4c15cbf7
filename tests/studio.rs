//! `lsys studio`'s server without a browser: the JSON API (edits, palette,
//! save and reopen, grammar mode) and its safety rules (paths confined to
//! the folder, Host/Origin checks, body limit, bad input never crashes).
#![cfg(feature = "studio")]

mod common;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;

use lsys::internals::studio::{start, Config, Handle};
use serde_json::{json, Value};

fn studio(path: &Path) -> Handle {
    studio_with(path, None)
}

fn studio_with(path: &Path, max_triangles: Option<usize>) -> Handle {
    start(Config {
        path: Some(path.to_path_buf()),
        bind: "127.0.0.1".parse().unwrap(),
        port: 0,
        assets: Some(path.join("no-assets")),
        max_triangles,
    })
    .expect("the studio starts")
}

/// One request (HTTP/1.1, closed after); returns (status, body).
fn request(
    h: &Handle,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(h.addr).unwrap();
    let host = format!("127.0.0.1:{}", h.addr.port());
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    if !headers.iter().any(|(k, _)| *k == "Host") {
        head += &format!("Host: {host}\r\n");
    }
    for (k, v) in headers {
        head += &format!("{k}: {v}\r\n");
    }
    head += "\r\n";
    s.write_all(head.as_bytes()).unwrap();
    let _ = s.write_all(body);
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let split = out
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a response head");
    let status = std::str::from_utf8(&out[9..12]).unwrap().parse().unwrap();
    let head = String::from_utf8_lossy(&out[..split]).to_ascii_lowercase();
    let body = &out[split + 4..];
    if !head.contains("transfer-encoding: chunked") {
        return (status, body.to_vec());
    }
    // Chunked (tiny_http sends large bodies so): size line, data, CRLF.
    let (mut plain, mut rest) = (Vec::new(), body);
    while let Some(eol) = rest.windows(2).position(|w| w == b"\r\n") {
        let size =
            usize::from_str_radix(std::str::from_utf8(&rest[..eol]).unwrap().trim(), 16).unwrap();
        if size == 0 {
            break;
        }
        plain.extend_from_slice(&rest[eol + 2..eol + 2 + size]);
        rest = &rest[eol + 4 + size..];
    }
    (status, plain)
}

fn get(h: &Handle, path: &str) -> (u16, Value) {
    let (s, b) = request(h, "GET", path, &[], b"");
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

/// An edit and the state it made (a refusal's answer as it is).
fn edit_state(h: &Handle, v: Value) -> (u16, Value) {
    let (code, r) = post(h, "/api/edit", v);
    let state = r.get("state").cloned().unwrap_or(r);
    (code, state)
}

/// Setting each `name` to its `value` is refused with a message saying
/// `says`.
fn defines_are_refused(h: &Handle, cases: &[(&str, f64, &str)]) {
    for &(name, value, says) in cases {
        let edit = json!({"op": "define", "name": name, "value": value});
        let (code, r) = post(h, "/api/edit", edit);
        assert_eq!(code, 422, "{name}: {r}");
        let m = r["refused"]["message"].as_str().unwrap();
        assert!(m.contains(says), "{name}: {m}");
    }
}

fn post(h: &Handle, path: &str, v: Value) -> (u16, Value) {
    let (s, b) = request(
        h,
        "POST",
        path,
        &[("Content-Type", "application/json")],
        v.to_string().as_bytes(),
    );
    (
        s,
        serde_json::from_slice(&b).unwrap_or_else(|_| json!(String::from_utf8_lossy(&b))),
    )
}

#[test]
fn clicks_build_a_2_1_1_pailou_and_save_it() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let (_, s) = get(&h, "/api/state");
    assert_eq!(s["mode"], "pailou");
    assert_eq!(s["active"], "L11");
    let parts0 = s["parts"].as_u64().unwrap();
    let (_, p) = get(&h, "/api/palette?id=L11");
    assert_eq!(
        p["kinds"],
        json!([
            "middle_toukung",
            "side_toukung",
            "flower_board",
            "queti",
            "suspended_pillar",
            "inscribed_board",
            "eaves_roof",
            "clipped_roof"
        ])
    );
    let (code, r) = post(
        &h,
        "/api/edit",
        json!({"op": "add", "id": "L11", "kind": "flower_board"}),
    );
    assert_eq!(code, 200, "{r}");
    assert!(r["state"]["parts"].as_u64().unwrap() > parts0);
    for (id, kind) in [
        ("L11", "middle_toukung"),
        ("TMn1", "eaves_roof"),
        ("L11", "side_toukung"),
        ("L11", "queti"),
        ("Qn1", "yundan"),
        ("L11", "inscribed_board"),
        ("P1R", "pillar_base"),
    ] {
        let (code, r) = post(
            &h,
            "/api/edit",
            json!({"op": "add", "id": id, "kind": kind}),
        );
        assert_eq!(code, 200, "{id} + {kind}: {r}");
    }
    let (_, s) = get(&h, "/api/state");
    assert_eq!(s["problems"], json!([]));
    assert_eq!(s["unplaced"], json!([]));
    insta::assert_snapshot!("studio_2_1_1_graph", s["toml"].as_str().unwrap());
    insta::assert_snapshot!("studio_2_1_1_chart", s["chart"].as_str().unwrap());
    // What the page's coloured chart draws: the one entrance, G11, its
    // eaves roof and Toukungs, the same as the text chart.
    assert_eq!(s["entrances"].as_array().unwrap().len(), 1);
    let g = &s["entrances"][0];
    assert_eq!(
        (
            g["name"].as_str(),
            g["side"].as_i64(),
            g["roof"].as_str(),
            g["toukungs"].as_bool()
        ),
        (Some("G11"), Some(0), Some("eaves"), Some(true))
    );
    // The relation matrix over every graph kind, its rows the library's.
    let kinds: std::collections::BTreeSet<&str> = s["matrix"]["kinds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_str().unwrap())
        .collect();
    assert_eq!(
        kinds,
        lsys::internals::pailou::kinds::graph_kinds().collect()
    );
    let lintel = &s["matrix"]["accepts"]["lintel"];
    assert!(lintel.as_array().unwrap().contains(&json!("flower_board")));
    assert!(!s["matrix"]["accepts"]["pillar"]
        .as_array()
        .unwrap()
        .contains(&json!("inscribed_board")));
    // The saved graph is one `lsys pailou` reads, and it reopens alike.
    let (code, r) = post(&h, "/api/save", json!({"path": "fig6.toml"}));
    assert_eq!(code, 200, "{r}");
    let out = common::lsys_ok(dir.path(), &["pailou", "fig6.toml", "--chart"]);
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        s["chart"].as_str().unwrap()
    );
    let (code, r) = post(&h, "/api/open", json!({"path": "fig6.toml"}));
    assert_eq!(code, 200, "{r}");
    assert_eq!(r["parts"], s["parts"]);
    assert_eq!(r["file"], "fig6.toml");
    let (code, glb) = request(&h, "GET", "/api/model.glb", &[], b"");
    assert_eq!((code, &glb[..4]), (200, &b"glTF"[..]));
    h.stop();
}

#[test]
fn duplicating_the_centre_adds_an_entrance_each_side() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    post(
        &h,
        "/api/edit",
        json!({"op": "add", "id": "L11", "kind": "flower_board"}),
    );
    let (code, r) = post(&h, "/api/edit", json!({"op": "duplicate", "id": "L11"}));
    assert_eq!(code, 200, "{r}");
    let chart = r["state"]["chart"].as_str().unwrap();
    assert!(chart.starts_with("level 1  [G21 ][G11 ][G21 ]"), "{chart}");
    // Removing one side's copy removes its mirror too: back to one entrance.
    let (code, r) = post(&h, "/api/edit", json!({"op": "remove", "id": "Pn1R"}));
    assert_eq!(code, 200, "{r}");
    assert!(r["state"]["chart"]
        .as_str()
        .unwrap()
        .starts_with("level 1  [G11 ]"));
    h.stop();
}

/// The studio refuses an illegal attachment with the CLI's own words.
#[test]
fn illegal_attachment_diagnostic_is_the_clis() {
    let dir = tempfile::tempdir().unwrap();
    let graph = "centre = \"L11\"\n[components]\nL11 = \"lintel\"\nP1R = \"pillar\"\nP1L = \"pillar\"\nIB = \"inscribed_board\"\n[attach]\nL11 = [\"P1R\", \"P1L\"]\nIB = [\"P1R\"]\n";
    std::fs::write(dir.path().join("bad.toml"), graph).unwrap();
    let h = studio(&dir.path().join("bad.toml"));
    let (_, s) = get(&h, "/api/state");
    let out = common::lsys_in(
        dir.path(),
        &["--color", "never", "pailou", "bad.toml", "-o", "x.glb"],
    );
    assert_eq!(out.status.code(), Some(65));
    assert_eq!(
        s["error"]["rendered"].as_str().unwrap(),
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(s["error"]["code"], "lsys::pailou::graph");
    assert_eq!(
        (s["error"]["line"].as_u64(), s["error"]["col"].as_u64()),
        (Some(9), Some(7))
    );
    // An edit through the API is refused the same way, and nothing changes.
    let h2 = studio(dir.path());
    let (code, r) = post(
        &h2,
        "/api/edit",
        json!({"op": "add", "id": "P1R", "kind": "inscribed_board"}),
    );
    assert_eq!(code, 422);
    assert!(r["refused"]["message"]
        .as_str()
        .unwrap()
        .contains("(inscribed_board) cannot attach to `P1R` (pillar)"));
    assert_eq!(r["state"]["components"].as_array().unwrap().len(), 3);
    h.stop();
    h2.stop();
}

#[test]
fn paths_stay_inside_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let inside = dir.path().join("open");
    std::fs::create_dir(&inside).unwrap();
    let outside = dir.path().join("secret");
    std::fs::create_dir(&outside).unwrap();
    std::fs::write(
        outside.join("g.toml"),
        lsys::internals::studio::DEFAULT_ENTRANCE,
    )
    .unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&outside, inside.join("link")).unwrap();
    let h = studio(&inside);
    let abs = outside.join("x.toml").display().to_string();
    for p in [
        "../secret/x.toml",
        abs.as_str(),
        "link/x.toml",
        "",
        "a/../../x.toml",
    ] {
        let (code, r) = post(&h, "/api/save", json!({"path": p}));
        assert_eq!(code, 403, "save {p}: {r}");
    }
    for p in ["../secret/g.toml", "link/g.toml", "/etc/passwd"] {
        let (code, r) = post(&h, "/api/open", json!({"path": p}));
        assert_eq!(code, 403, "open {p}: {r}");
    }
    assert!(!outside.join("x.toml").exists());
    let (code, _) = request(&h, "GET", "/assets/../../Cargo.toml", &[], b"");
    assert!(code == 403 || code == 404, "{code}");
    let (code, r) = post(&h, "/api/save", json!({"path": "mine.toml"}));
    assert_eq!(code, 200, "{r}");
    assert!(inside.join("mine.toml").is_file());
    h.stop();
}

#[test]
fn foreign_hosts_origins_and_big_bodies_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let (code, _) = request(
        &h,
        "GET",
        "/api/state",
        &[("Host", "attacker.example:80")],
        b"",
    );
    assert_eq!(code, 403);
    let own = format!("http://127.0.0.1:{}", h.addr.port());
    let (code, _) = request(&h, "GET", "/api/state", &[("Origin", own.as_str())], b"");
    assert_eq!(code, 200);
    let (code, _) = request(
        &h,
        "POST",
        "/api/edit",
        &[("Origin", "http://attacker.example")],
        b"{}",
    );
    assert_eq!(code, 403);
    let big = vec![b' '; (1 << 20) + 10];
    let (code, _) = request(&h, "POST", "/api/edit", &[], &big);
    assert_eq!(code, 413);
    // Not JSON, unknown edits, unknown ids: answered, never a crash.
    let (code, _) = request(&h, "POST", "/api/edit", &[], b"{not json");
    assert_eq!(code, 400);
    assert_eq!(post(&h, "/api/edit", json!({"op": "explode"})).0, 422);
    assert_eq!(
        post(&h, "/api/edit", json!({"op": "remove", "id": "nope"})).0,
        422
    );
    assert_eq!(get(&h, "/api/state").0, 200);
    // Without a built front end the page says how to build it; a binary
    // built after `npm run build` serves the front end it carries.
    let (code, page) = request(&h, "GET", "/", &[], b"");
    assert_eq!(code, 200);
    let page = String::from_utf8_lossy(&page).into_owned();
    if lsys::internals::studio::has_embedded_page() {
        let script = page
            .split("src=\"/")
            .nth(1)
            .and_then(|r| r.split('"').next())
            .unwrap_or_else(|| panic!("the page loads a script: {page}"));
        let (code, js) = request(&h, "GET", &format!("/{script}"), &[], b"");
        assert_eq!(code, 200, "/{script}");
        assert!(js.len() > 1000, "/{script} is {} bytes", js.len());
    } else {
        assert!(page.contains("npm ci &amp;&amp; npm run build"), "{page}");
    }
    h.stop();
}

#[test]
fn grammar_mode_keeps_the_last_good_model() {
    let dir = tempfile::tempdir().unwrap();
    let g = dir.path().join("bush.lsys");
    std::fs::write(&g, "#define N 2\n#define ANGLE 25.7\nangle: ANGLE\nderivation length: N\nAxiom: F\nF --> F[+F]F[-F]F\n").unwrap();
    let h = studio(&g);
    let (_, s) = get(&h, "/api/state");
    assert_eq!(s["mode"], "grammar");
    assert_eq!(
        (s["step"].as_u64(), s["length"].as_u64()),
        (Some(2), Some(2))
    );
    assert_eq!(
        s["defines"][0],
        json!({"name": "N", "value": "2", "number": 2.0, "override": null, "range": [0.0, 7.0], "integer": true})
    );
    let t2 = s["triangles"].as_u64().unwrap();
    let (_, s) = post(&h, "/api/grammar", json!({"defines": {"N": 3}}));
    let t3 = s["triangles"].as_u64().unwrap();
    assert!(t3 > t2, "{t2} -> {t3}");
    let (_, s) = post(&h, "/api/grammar", json!({"step": 1}));
    assert!(s["triangles"].as_u64().unwrap() < t2);
    // A syntax error: a diagnostic with its place and code, the model kept.
    std::fs::write(
        &g,
        "#define N 2\nderivation length: N\nAxiom: F\nF --> F[+F]F[-F]F(\n",
    )
    .unwrap();
    let (_, s) = post(&h, "/api/grammar", json!({"step": null}));
    let d = &s["diagnostics"][0];
    assert_eq!(d["severity"], "error");
    // Named relative to the opened folder, in the list and the rendering.
    assert_eq!(d["file"], "bush.lsys", "{d}");
    let rendered = d["rendered"].as_str().unwrap();
    assert!(rendered.contains("[bush.lsys:4:"), "{rendered}");
    let folder = dir.path().canonicalize().unwrap();
    assert!(!rendered.contains(folder.to_str().unwrap()), "{rendered}");
    assert_eq!(d["line"], 4);
    assert!(d["code"].as_str().unwrap().starts_with("lsys::"), "{d}");
    assert_eq!(s["current"], false);
    assert!(s["triangles"].as_u64().unwrap() > 0);
    h.stop();
}

/// `GET /api/state` until `done` says yes (20 s at most).
fn state_until(h: &Handle, what: &str, done: impl Fn(&Value) -> bool) -> Value {
    let t0 = std::time::Instant::now();
    loop {
        let (_, s) = get(h, "/api/state");
        if done(&s) {
            return s;
        }
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(20),
            "{what}: still {s}"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// Grammar mode follows saves of the file: one made by rename (as editors
/// save) while the first build runs, after it has read the file, which
/// is missed unless the file was watched before that read; then one in
/// place.
#[test]
fn grammar_mode_follows_saves_even_right_after_opening() {
    use notify::event::{AccessKind, EventKind};
    use notify::Watcher as _;
    let dir = tempfile::tempdir().unwrap();
    let g = dir.path().join("bush.lsys");
    let grammar = |n: u32| {
        format!("#define N {n}\nangle: 25.7\nderivation length: N\nAxiom: F\nF --> F[+F]F[-F]F\n")
    };
    // A first build long enough for the save to come while it runs.
    std::fs::write(&g, grammar(7)).unwrap();
    // The test's own watcher, to see the studio open the file.
    let (tx, rx) = std::sync::mpsc::channel();
    let mut reads = notify::recommended_watcher(tx).unwrap();
    reads
        .watch(dir.path(), notify::RecursiveMode::NonRecursive)
        .unwrap();
    let opening = {
        let g = g.clone();
        std::thread::spawn(move || studio(&g))
    };
    let key = dir.path().canonicalize().unwrap().join("bush.lsys");
    loop {
        let ev = rx
            .recv_timeout(std::time::Duration::from_secs(30))
            .expect("the studio reads the grammar")
            .unwrap();
        if matches!(ev.kind, EventKind::Access(AccessKind::Open(_))) && ev.paths.contains(&key) {
            break;
        }
    }
    let tmp = dir.path().join(".bush.lsys.new");
    std::fs::write(&tmp, grammar(2)).unwrap();
    std::fs::rename(&tmp, &g).unwrap();
    let during = !opening.is_finished();
    drop(reads);
    let h = opening.join().unwrap();
    let s = state_until(&h, "the save right after opening", |s| {
        s["defines"][0]["value"] == "2" && s["length"] == 2
    });
    assert_eq!(s["current"], true, "{s}");
    let t2 = s["triangles"].as_u64().unwrap();
    // Said after the rebuild, so that a failure above is the rebuild's.
    assert!(
        during,
        "the save came after the first build ended: the test proves nothing"
    );
    std::fs::write(&g, grammar(3)).unwrap();
    let s = state_until(&h, "a save in place", |s| s["defines"][0]["value"] == "3");
    assert_eq!(s["length"], 3, "{s}");
    assert!(s["triangles"].as_u64().unwrap() > t2, "{s}");
    h.stop();
}

/// The studio saves what it opened: every example graph, parsed by the
/// editor and written again, reads back to the same layout and defines.
#[test]
fn example_graphs_survive_the_editor() {
    use lsys::internals::pailou::graph::{read, RELATIONS};
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pailou");
    let mut n = 0;
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let g = lsys::internals::pailou::GraphDocument::parse(&text).unwrap();
        let again = g.to_toml();
        let (a, b) = (
            read("a", &text, RELATIONS).unwrap(),
            read("b", &again, RELATIONS).unwrap(),
        );
        assert_eq!(a.layout, b.layout, "{}", p.display());
        assert_eq!(a.defines, b.defines, "{}", p.display());
        assert_eq!(
            lsys::internals::pailou::GraphDocument::parse(&again).unwrap(),
            g,
            "{}",
            p.display()
        );
        n += 1;
    }
    assert!(n >= 15, "{n} graphs");
}

/// Save replaces neither a file that is not a Pailou graph (Cargo.toml,
/// a guided scene) nor another graph unless the page says the user
/// agreed; the session's own graph is saved over freely.
#[test]
fn save_never_replaces_what_it_did_not_write() {
    let dir = tempfile::tempdir().unwrap();
    let cargo = "[package]\nname = \"mine\"\nversion = \"0.1.0\"\n";
    std::fs::write(dir.path().join("Cargo.toml"), cargo).unwrap();
    let scene = "steps = 3\n[[guide]]\nkind = \"line\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let h = studio(dir.path());
    for name in ["Cargo.toml", "scene.toml"] {
        let (code, r) = post(&h, "/api/save", json!({"path": name, "replace": true}));
        assert_eq!(code, 409, "{name}: {r}");
        assert!(
            r["error"].as_str().unwrap().contains("not a Pailou graph"),
            "{r}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(dir.path().join("Cargo.toml")).unwrap(),
        cargo
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("scene.toml")).unwrap(),
        scene
    );
    // A new file, then the session's own file again.
    assert_eq!(post(&h, "/api/save", json!({"path": "a.toml"})).0, 200);
    assert_eq!(post(&h, "/api/save", json!({"path": "a.toml"})).0, 200);
    assert_eq!(post(&h, "/api/save", json!({"path": "b.toml"})).0, 200);
    // Another graph: asked first.
    let (code, r) = post(&h, "/api/save", json!({"path": "a.toml"}));
    assert_eq!((code, &r["exists"]), (409, &json!(true)), "{r}");
    assert_eq!(
        post(&h, "/api/save", json!({"path": "a.toml", "replace": true})).0,
        200
    );
    // Opening a file that is not a graph fails and leaves nothing to
    // overwrite it with.
    assert_eq!(post(&h, "/api/open", json!({"path": "Cargo.toml"})).0, 403);
    assert_eq!(post(&h, "/api/save", json!({"path": "Cargo.toml"})).0, 409);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("Cargo.toml")).unwrap(),
        cargo
    );
    h.stop();
}

/// Event streams last as long as their pages: past 16 the next stream is
/// refused, and other requests are still answered at once.
#[test]
fn open_event_streams_do_not_starve_other_requests() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let host = format!("127.0.0.1:{}", h.addr.port());
    let open = || {
        let mut s = TcpStream::connect(h.addr).unwrap();
        let head = format!("GET /api/events HTTP/1.1\r\nHost: {host}\r\n\r\n");
        s.write_all(head.as_bytes()).unwrap();
        let mut first = [0u8; 12];
        s.read_exact(&mut first).unwrap();
        (s, String::from_utf8_lossy(&first[9..12]).into_owned())
    };
    let mut streams = Vec::new();
    for _ in 0..16 {
        let (s, status) = open();
        assert_eq!(status, "200");
        streams.push(s);
    }
    let (_, status) = open();
    assert_eq!(status, "503", "the 17th stream");
    let t0 = std::time::Instant::now();
    for _ in 0..70 {
        assert_eq!(get(&h, "/api/state").0, 200);
    }
    assert!(t0.elapsed() < std::time::Duration::from_secs(10));
    drop(streams);
    h.stop();
}

/// A model over the triangle budget is refused with the mesh stage's
/// diagnostic on the page, instead of being built and served.
#[test]
fn the_studio_builds_within_a_triangle_budget() {
    let dir = tempfile::tempdir().unwrap();
    let g = dir.path().join("big.lsys");
    std::fs::write(
        &g,
        "#define N 6\nderivation length: N\nAxiom: F\nF --> F[+F]F[-F]F\n",
    )
    .unwrap();
    let h = studio_with(&g, Some(10_000));
    let (_, s) = get(&h, "/api/state");
    let d = &s["diagnostics"][0];
    assert_eq!(d["code"], "lsys::mesh::too_many_triangles", "{s}");
    assert_eq!(s["triangles"], 0, "nothing is served");
    let (_, s) = post(&h, "/api/grammar", json!({"defines": {"N": 2}}));
    assert!(s["triangles"].as_u64().unwrap() > 0, "{s}");
    h.stop();
}

/// The Pailou's parameters are checked on the server: NTL = 40 and
/// ω = -5 are refused, the graph unchanged; the defaults pass.
#[test]
fn pailou_parameters_out_of_range_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    for (name, value) in [
        ("NTL", json!(40)),
        ("ω", json!(-5)),
        ("NTL", json!(2.5)),
        ("αEW", json!("50/1")),
    ] {
        let (code, r) = post(
            &h,
            "/api/edit",
            json!({"op": "define", "name": name, "value": value}),
        );
        assert_eq!(code, 422, "{name} = {value}: {r}");
        assert!(
            r["refused"]["message"].as_str().unwrap().contains(name),
            "{r}"
        );
    }
    for (name, value) in [("NTL", json!(7)), ("ω", json!(10)), ("αEW", json!("10/12"))] {
        let (code, r) = post(
            &h,
            "/api/edit",
            json!({"op": "define", "name": name, "value": value}),
        );
        assert_eq!(code, 200, "{name} = {value}: {r}");
    }
    h.stop();
}

/// In grammar mode `.lsys` downloads the grammar; `.toml` (a graph) says
/// why there is none.
#[test]
fn grammar_mode_exports_its_grammar() {
    let dir = tempfile::tempdir().unwrap();
    let text = "derivation length: 2\nAxiom: F\nF --> F[+F]F\n";
    let g = dir.path().join("plant.lsys");
    std::fs::write(&g, text).unwrap();
    let h = studio(&g);
    let (code, body) = request(&h, "GET", "/api/export?format=lsys", &[], b"");
    assert_eq!(
        (code, String::from_utf8_lossy(&body).into_owned()),
        (200, text.to_string())
    );
    let (code, body) = request(&h, "GET", "/api/export?format=toml", &[], b"");
    assert_eq!(code, 409);
    assert!(String::from_utf8_lossy(&body).contains("export .lsys"));
    h.stop();
}

/// A cpfg model's define moves the model (the override wins over the
/// file's #define, as `-D` does), a define with a `/* */` comment is a
/// slider, and grammars in subfolders are listed to open.
#[test]
fn cpfg_defines_move_the_model_and_subfolders_are_listed() {
    let dir = tempfile::tempdir().unwrap();
    let l = "#define N 2 /* steps */\nLsystem: 1\nderivation length: N\nAxiom: F\nF --> F[+F]F\nendlsystem\n";
    std::fs::write(dir.path().join("plant.l"), l).unwrap();
    std::fs::create_dir_all(dir.path().join("more/deeper")).unwrap();
    std::fs::write(dir.path().join("more/deeper/bush.lsys"), "Axiom: F\n").unwrap();
    std::fs::create_dir_all(dir.path().join(".hidden")).unwrap();
    std::fs::write(dir.path().join(".hidden/no.lsys"), "Axiom: F\n").unwrap();
    let h = studio(&dir.path().join("plant.l"));
    let (_, s) = get(&h, "/api/state");
    assert_eq!(s["defines"][0]["number"], 2.0, "{}", s["defines"]);
    let t2 = s["triangles"].as_u64().unwrap();
    let (_, s) = post(&h, "/api/grammar", json!({"defines": {"N": 3}}));
    assert!(s["triangles"].as_u64().unwrap() > t2, "{s}");
    let (_, f) = get(&h, "/api/files");
    assert_eq!(f["files"], json!(["more/deeper/bush.lsys", "plant.l"]));
    let (code, r) = post(&h, "/api/open", json!({"path": "more/deeper/bush.lsys"}));
    assert_eq!(code, 200, "{r}");
    h.stop();
}

/// From the default entrance, a lateral entrance with its Toukungs and
/// roof and no roof on the centre: the side roofs stop at the central
/// pillars and their Toukungs at the lintels' ends, so the clicks give no
/// structural warning (they gave ten: Toukungs off the lintel, roofs
/// through the central pillars and lintel).
#[test]
fn a_lateral_entrance_with_its_roof_stands() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    for (id, kind) in [
        ("P1R", "lintel"),
        ("Ln1R", "middle_toukung"),
        ("TMn1R", "eaves_roof"),
    ] {
        let (code, r) = post(
            &h,
            "/api/edit",
            json!({"op": "add", "id": id, "kind": kind}),
        );
        assert_eq!(code, 200, "{id} + {kind}: {r}");
    }
    let (_, s) = get(&h, "/api/state");
    assert_eq!(s["problems"], json!([]), "{}", s["chart"]);
    assert_eq!(s["unplaced"], json!([]));
    assert!(s["parts"].as_u64().unwrap() > 20, "{}", s["parts"]);
    h.stop();
}

/// A placement that would collide is refused (issue 34): a clipped roof
/// on a lintel that has an eaves roof interpenetrates it; the edit answers
/// 422 with `lsys::studio::collision`, the problems it would make and the
/// component to mark, and the graph, model and active component stay.
#[test]
fn a_colliding_placement_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let (code, r) = post(
        &h,
        "/api/edit",
        json!({"op": "add", "id": "L11", "kind": "eaves_roof"}),
    );
    assert_eq!(code, 200, "{r}");
    let before = r["state"].clone();
    assert_eq!(before["problems"], json!([]));
    let (code, r) = post(&h, "/api/edit", json!({"op": "select", "id": "L11"}));
    assert_eq!(code, 200, "{r}");
    let (code, r) = post(
        &h,
        "/api/edit",
        json!({"op": "add", "id": "L11", "kind": "clipped_roof"}),
    );
    assert_eq!(code, 422, "{r}");
    let refused = &r["refused"];
    assert_eq!(refused["code"], "lsys::studio::collision");
    assert_eq!(refused["at"], "L11");
    let message = refused["message"].as_str().unwrap();
    assert!(
        message.contains("a clipped roof on L11 would collide")
            && message.contains("interpenetrate"),
        "{message}"
    );
    assert!(!refused["parts"].as_array().unwrap().is_empty());
    let after = &r["state"];
    assert_eq!(after["toml"], before["toml"], "the graph is unchanged");
    assert_eq!(
        (after["problems"].clone(), after["active"].clone()),
        (json!([]), json!("L11"))
    );
    assert_eq!(after["triangles"], before["triangles"]);
    h.stop();
}

/// The drawing page's API (issue 33, item 6): a drawing of the folder is
/// read into a tree, a grammar and a hall; a separator stroke (a
/// polyline in the drawing's pixels) restores a lost line; a label
/// correction changes the counts and the grammar; bad edits, labels,
/// paths and pictures are refused with a reason, and the last good
/// reading stays.
#[test]
fn the_drawing_page_reads_strokes_and_corrections() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let svg = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/drawings/five-bay-hall.svg"),
    )
    .unwrap();
    // The line that quarters the second bracket block, lost.
    let lost = r#"<line x1="250.0" y1="277.5" x2="290.0" y2="277.5"/>"#;
    assert!(svg.contains(lost));
    std::fs::write(d.join("lost.svg"), svg.replace(lost, "")).unwrap();
    std::fs::write(d.join("notes.txt"), "not a drawing").unwrap();
    let h = studio(d);
    let (code, _) = get(&h, "/api/drawing/state");
    assert_eq!(code, 404, "no drawing before one is opened");
    let (_, list) = get(&h, "/api/drawings");
    assert_eq!(list["files"], json!(["lost.svg"]));

    let (code, s) = post(&h, "/api/drawing/open", json!({"path": "lost.svg"}));
    assert_eq!(code, 200, "{s}");
    assert_eq!(s["summary"], Value::Null, "a hall has no Pailou summary");
    let counts = |s: &Value, l: &str| s["counts"][l].as_u64().unwrap();
    assert_eq!(
        ["column", "bay", "door", "window", "bracket"].map(|l| counts(&s, l)),
        [6, 5, 1, 4, 7]
    );
    let (code, glb) = request(&h, "GET", "/api/drawing/model.glb", &[], b"");
    assert_eq!((code, &glb[..4]), (200, &b"glTF"[..]));
    let (code, png) = request(&h, "GET", "/api/drawing/image.png", &[], b"");
    assert_eq!((code, &png[1..4]), (200, &b"PNG"[..]));

    let (code, s) = post(
        &h,
        "/api/drawing/edit",
        json!({"strokes": [[[250, 277.5], [270, 277.5], [290, 277.5]]]}),
    );
    assert_eq!(code, 200, "{s}");
    assert_eq!(counts(&s, "bracket"), 8, "the stroke restores the line");

    // The first window's box, as the tree gives it, corrected to a wall.
    fn leaves<'a>(n: &'a Value, out: &mut Vec<&'a Value>) {
        match n["children"].as_array() {
            Some(c) if !c.is_empty() => c.iter().for_each(|c| leaves(c, out)),
            _ => out.push(n),
        }
    }
    let mut all = Vec::new();
    leaves(&s["tree"], &mut all);
    let window = all.iter().find(|n| n["label"] == "window").unwrap()["box"].clone();
    let before = s["grammar"].as_str().unwrap().to_string();
    let (code, s) = post(
        &h,
        "/api/drawing/edit",
        json!({"corrections": [{"box": window, "label": "wall"}]}),
    );
    assert_eq!(code, 200, "{s}");
    assert_eq!(counts(&s, "window"), 3);
    assert_eq!(counts(&s, "bracket"), 8, "the stroke is kept");
    assert_ne!(s["grammar"].as_str().unwrap(), before);
    assert_eq!(s["missed"], json!([]));

    // A box that is no node's is reported, not applied elsewhere.
    let (_, s) = post(
        &h,
        "/api/drawing/edit",
        json!({"corrections": [{"box": [1, 2, 3, 4], "label": "door"}]}),
    );
    assert_eq!((s["missed"].clone(), counts(&s, "door")), (json!([0]), 1));

    for (bad, says) in [
        (
            json!({"corrections": [{"box": window, "label": "Door"}]}),
            "not a label",
        ),
        (json!({"strokes": [[[1, "x"]]]}), "strokes:"),
        (json!({"gap": 40}), "gap:"),
    ] {
        let (code, r) = post(&h, "/api/drawing/edit", bad.clone());
        assert_eq!(code, 422, "{bad}: {r}");
        assert!(
            r["refused"]["message"].as_str().unwrap().contains(says),
            "{r}"
        );
        assert_eq!(counts(&r["state"], "bracket"), 8, "the reading stays");
    }

    let (code, r) = post(&h, "/api/drawing/open", json!({"path": "../x.svg"}));
    assert_eq!(code, 403, "{r}");
    let (code, r) = post(&h, "/api/drawing/open", json!({"path": "notes.txt"}));
    assert_eq!(code, 403, "{r}");
    let (code, r) = request(
        &h,
        "POST",
        "/api/drawing/upload?name=photo.png",
        &[],
        b"\x89PNG\r\n\x1a\nnot really",
    );
    let r: Value = serde_json::from_slice(&r).unwrap();
    assert_eq!(code, 422, "{r}");
    assert_eq!(
        r["problem"]["diagnostics"][0]["code"],
        "lsys::infer::unreadable"
    );
    let (_, s) = get(&h, "/api/drawing/state");
    assert_eq!(s["name"], "lost.svg", "the drawing before stays open");

    let (code, body) = request(&h, "GET", "/api/drawing/grammar.lsys", &[], b"");
    assert_eq!(code, 200);
    assert_eq!(
        String::from_utf8(body).unwrap(),
        s["grammar"].as_str().unwrap()
    );
    h.stop();
}

/// A Pailou's front opened on the drawing page says which style, type
/// and Toukung levels it was read as (the counts of columns and bays do
/// not), and its hall is built with those levels.
#[test]
fn the_drawing_page_says_what_pailou_it_read() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let grammar = common::lsys_ok(
        d,
        &[
            "pailou",
            "--style",
            "2-1-2",
            "--type",
            "pillar",
            "--emit-lsys",
        ],
    );
    std::fs::write(d.join("p.lsys"), &grammar.stdout).unwrap();
    common::lsys_ok(
        d,
        &[
            "render", "p.lsys", "--view", "front", "--style", "lines", "--size", "1000x600", "-o",
            "gate.png",
        ],
    );
    std::fs::remove_file(d.join("p.lsys")).unwrap();
    let h = studio(d);
    let (code, s) = post(&h, "/api/drawing/open", json!({"path": "gate.png"}));
    assert_eq!(code, 200, "{s}");
    let summary = s["summary"].as_str().unwrap_or_default();
    assert!(
        summary.contains("style 2-1-2, pillar type, 5 Toukung levels"),
        "{s}"
    );
    assert_eq!(s["counts"]["bay"], 1, "{s}");
    let (code, glb) = request(&h, "GET", "/api/drawing/model.glb", &[], b"");
    assert_eq!((code, &glb[..4]), (200, &b"glTF"[..]));
    h.stop();
}

#[test]
fn the_guides_page_edits_runs_and_saves_scenes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let guided = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/guided");
    for f in [
        "palm.toml",
        "palm_trunk.lsys",
        "palm_crown.lsys",
        "palm_leaf.lsys",
    ] {
        std::fs::copy(guided.join(f), d.join(f)).unwrap();
    }
    std::fs::write(d.join("Cargo.toml"), "[package]\nname = \"x\"\n").unwrap();
    std::fs::write(d.join("graph.toml"), "not = \"a scene\"\n").unwrap();
    let h = studio(d);
    let (code, _) = get(&h, "/api/guides/state");
    assert_eq!(code, 404, "no scene before one is opened");
    let (_, list) = get(&h, "/api/scenes");
    assert_eq!(list["files"], json!(["palm.toml"]), "only guided scenes");

    let (code, s) = post(&h, "/api/guides/open", json!({"path": "palm.toml"}));
    assert_eq!(code, 200, "{s}");
    assert_eq!(
        (s["seeds_run"].as_u64(), s["messages"].as_u64()),
        (Some(6), Some(5))
    );
    assert_eq!(s["regrown"].as_array().unwrap().len(), 7);
    let (code, glb) = request(&h, "GET", "/api/guides/model.glb", &[], b"");
    assert_eq!((code, &glb[..4]), (200, &b"glTF"[..]));

    // One leaf stretched: only it derives again, and the result is the
    // full run's (checked against `lsys build` of the saved file below).
    let mut scene = s["scene"].clone();
    let leaf = scene["guide"]
        .as_array()
        .unwrap()
        .iter()
        .position(|g| g["name"] == "leaf_right")
        .unwrap();
    scene["guide"][leaf]["points"][3] = json!([7.5, 7.2]);
    let (code, s) = post(&h, "/api/guides/edit", json!({ "scene": scene }));
    assert_eq!(code, 200, "{s}");
    assert_eq!(s["regrown"], json!([leaf]));
    assert!(s["text"].as_str().unwrap().contains("[7.5, 7.2]"));

    // The springs: the trunk's foot held, the crown's corner dragged; the
    // foot stays, the trunk's top and the leaves follow, nothing runs.
    let (code, r) = post(
        &h,
        "/api/guides/springs",
        json!({"scene": scene, "vertex": [1, 5], "to": [0.6, 10.9], "held": [[0, 0], [0, 1]]}),
    );
    assert_eq!(code, 200, "{r}");
    assert_eq!(r["points"][0][0], scene["guide"][0]["points"][0]);
    assert_ne!(r["points"][0][2], scene["guide"][0]["points"][2]);
    assert_eq!(r["points"][1][5], json!([0.6, 10.9]));
    assert_eq!(r["seeds"].as_array().unwrap().len(), 1);
    for bad in [
        json!({"scene": scene, "vertex": [1, 99], "to": [0, 0]}),
        json!({"scene": scene, "vertex": [1, 0], "to": ["x", 0]}),
        json!({"scene": {"steps": 1, "guides": []}, "vertex": [0, 0], "to": [0, 0]}),
    ] {
        let (code, r) = post(&h, "/api/guides/springs", bad);
        assert_eq!(code, 422, "{r}");
    }

    // A scene that reads but does not check keeps the last good run, with
    // the located diagnostic; one that is not a scene is refused whole.
    let mut outside = scene.clone();
    outside["seeds"][0]["position"] = json!([50, 50]);
    let (code, s) = post(&h, "/api/guides/edit", json!({ "scene": outside }));
    assert_eq!(code, 200);
    assert_eq!(s["current"], json!(false));
    let d0 = &s["problem"]["diagnostics"][0];
    assert_eq!(d0["code"], "lsys::guided::scene", "{s}");
    assert!(d0["line"].as_u64().unwrap() > 1);
    assert_eq!(s["seeds_run"].as_u64(), Some(6), "the last good run stays");
    let mut many = scene.clone();
    many["steps"] = json!(100_000);
    let (code, r) = post(&h, "/api/guides/edit", json!({ "scene": many }));
    assert_eq!(code, 422);
    assert!(r["refused"]["message"].as_str().unwrap().contains("steps"));
    let (code, _) = post(&h, "/api/guides/edit", json!({"scene": {"steps": "x"}}));
    assert_eq!(code, 422);

    // Back to the stretched leaf; saved where it was opened, then built
    // from the command line to the page's seeds and messages.
    let (code, s) = post(&h, "/api/guides/edit", json!({ "scene": scene }));
    assert_eq!(code, 200, "{s}");
    let (code, r) = post(&h, "/api/guides/save", json!({}));
    assert_eq!(code, 200, "{r}");
    let spec = lsys::internals::guided::scene::read(
        "palm.toml",
        &std::fs::read_to_string(d.join("palm.toml")).unwrap(),
    )
    .unwrap();
    assert_eq!(spec.guides[leaf].points[3], glam::DVec2::new(7.5, 7.2));
    let loaded =
        lsys::internals::guided::load_file(&d.join("palm.toml"), &Default::default(), &[]).unwrap();
    let run = lsys::internals::guided::run(&loaded).unwrap();
    assert_eq!(
        (run.seeds.len() as u64, run.messages.len() as u64),
        (
            s["seeds_run"].as_u64().unwrap(),
            s["messages"].as_u64().unwrap()
        )
    );

    // Save never replaces a file that is not a scene, nor writes outside
    // the scene's folder.
    for (path, want) in [
        ("Cargo.toml", 409),
        ("graph.toml", 409),
        ("../palm.toml", 403),
        ("notes.txt", 403),
    ] {
        let (code, r) = post(&h, "/api/guides/save", json!({ "path": path }));
        assert_eq!(code, want, "{path}: {r}");
    }
    assert_eq!(
        std::fs::read_to_string(d.join("Cargo.toml")).unwrap(),
        "[package]\nname = \"x\"\n"
    );
    std::fs::create_dir(d.join("sub")).unwrap();
    let (code, _) = post(&h, "/api/guides/save", json!({"path": "sub/palm.toml"}));
    assert_eq!(code, 403, "another folder: the grammars are named relative");
    let (code, r) = post(&h, "/api/guides/save", json!({"path": "palm2.toml"}));
    assert_eq!(code, 200, "{r}");

    // A new scene; one that exists is not overwritten by "new".
    let (code, r) = post(
        &h,
        "/api/guides/open",
        json!({"path": "palm.toml", "new": true}),
    );
    assert_eq!(code, 422, "{r}");
    let (code, s) = post(
        &h,
        "/api/guides/open",
        json!({"path": "fresh.toml", "new": true}),
    );
    assert_eq!(code, 200, "{s}");
    assert_eq!(s["scene"]["guide"], json!([]));
    assert_eq!(s["current"], json!(true), "an empty scene is no error: {s}");
    let (code, r) = post(&h, "/api/guides/open", json!({"path": "graph.toml"}));
    assert_eq!(code, 422, "{r}");
    let (code, _) = post(&h, "/api/guides/open", json!({"path": "../x.toml"}));
    assert_eq!(code, 403);
}

/// Per-entrance ratios (the paper's α^Up_ij, α^Side_ij; issue 34, item 3):
/// the state names each lintel's entrance, `up[i,j]` and `side[i]` are
/// defines of the graph that change that entrance only, out-of-range or
/// misplaced ones are refused, and they survive a save and a reopen.
#[test]
fn an_entrance_has_ratios_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let edit = |v: Value| edit_state(&h, v);
    let (code, s) = edit(json!({"op": "style", "style": "4-3-7", "type": "ridge"}));
    assert_eq!(code, 200, "{s}");
    let lintel = |s: &Value, at: [u64; 2]| -> String {
        s["lintels"]
            .as_object()
            .unwrap()
            .iter()
            .find(|(_, v)| v == &&json!(at))
            .map(|(id, _)| id.clone())
            .unwrap_or_else(|| panic!("no lintel of entrance {at:?}: {}", s["lintels"]))
    };
    // 4-3-7: three ground entrances, three above; both halves' lintels.
    let n = s["lintels"].as_object().unwrap().len();
    assert_eq!(n, 1 + 2 + 1 + 2, "{}", s["lintels"]);
    let side_above = lintel(&s, [2, 2]);
    let (_, glb0) = request(&h, "GET", "/api/model.glb", &[], b"");
    let top = |s: &Value| s["bounds"][1][1].as_f64();

    // The side entrances above lower; the centre's top stays.
    let (code, s1) = edit(json!({"op": "define", "name": "up[2,2]", "value": 0.35}));
    assert_eq!(code, 200, "{s1}");
    assert_eq!(s1["defines"]["up[2,2]"], json!(0.35));
    assert_eq!(s1["problems"], json!([]));
    let (_, glb1) = request(&h, "GET", "/api/model.glb", &[], b"");
    assert_ne!(glb0, glb1, "the model changed");
    assert!(top(&s).is_some());
    assert_eq!(top(&s1), top(&s), "the central entrance above is untouched");
    // The central one above lowers the top.
    let (code, s2) = edit(json!({"op": "define", "name": "up[1,2]", "value": 0.35}));
    assert_eq!(code, 200, "{s2}");
    let (a, b) = (top(&s2).unwrap(), top(&s1).unwrap());
    assert!(a < b - 1.0, "{a} {b}");
    let (code, _) = edit(json!({"op": "define", "name": "side[1]", "value": 0.7}));
    assert_eq!(code, 200);
    defines_are_refused(
        &h,
        &[
            ("up[2,2]", 5.0, "out of range"),
            ("up[2,1]", 0.4, "2..4"),
            ("side[6]", 0.7, "1..5"),
            ("up[x]", 0.4, "up"),
        ],
    );

    // Saved with the graph and read back.
    let (code, r) = post(&h, "/api/save", json!({"path": "mine.toml"}));
    assert_eq!(code, 200, "{r}");
    let saved = std::fs::read_to_string(dir.path().join("mine.toml")).unwrap();
    assert!(saved.contains("\"up[2,2]\" = 0.35"), "{saved}");
    let (code, s3) = post(&h, "/api/open", json!({"path": "mine.toml"}));
    assert_eq!(code, 200, "{s3}");
    assert_eq!(s3["defines"]["up[2,2]"], json!(0.35));
    assert_eq!(s3["defines"]["side[1]"], json!(0.7));
    assert_eq!(lintel(&s3, [2, 2]), side_above);
    h.stop();
}

/// Per-component sizes at an entrance (the paper's α^XW_ij, α^XH_ij,
/// α^XD_ij; issue 34, item 3): the state gives every component its
/// entrance, and `tk[i,j]`, `pw[i,j]`, ... are graph defines checked
/// against their global ratio's range and the tables' indices.
#[test]
fn a_component_has_sizes_of_its_own_at_its_entrance() {
    let dir = tempfile::tempdir().unwrap();
    let h = studio(dir.path());
    let edit = |v: Value| edit_state(&h, v);
    let (code, s) = edit(json!({"op": "style", "style": "4-3-7", "type": "ridge"}));
    assert_eq!(code, 200, "{s}");
    let of = s["entrance_of"].as_object().unwrap();
    assert_eq!(
        of.len(),
        s["components"].as_array().unwrap().len(),
        "{of:?}"
    );
    for (id, at) in [
        ("P1R", [1, 1]),  // the central entrance's pillar
        ("P2R", [2, 1]),  // the outer entrance's outer pillar
        ("B2R", [2, 1]),  // its base
        ("RP2R", [2, 1]), // the clipped roof over it
        ("Y21R", [2, 1]), // a Yundan under a Queti under the lintel
        ("S12a", [1, 2]), // a suspended pillar: the entrance it holds up
        ("TM12", [1, 2]),
        ("RE12", [1, 2]), // the main roof, on the Toukungs
        ("RE22L", [2, 2]),
    ] {
        assert_eq!(of[id], json!(at), "{id}");
    }
    let top = |s: &Value| s["bounds"][1][1].as_f64().unwrap();
    // Bigger Toukungs under the main roof raise it.
    let (code, s1) = edit(json!({"op": "define", "name": "tk[1,2]", "value": 0.16}));
    assert_eq!(code, 200, "{s1}");
    assert_eq!(s1["problems"], json!([]));
    assert!(top(&s1) > top(&s) + 0.1, "{} {}", top(&s1), top(&s));
    let (code, s2) = edit(json!({"op": "define", "name": "pw[2,1]", "value": 0.14}));
    assert_eq!(code, 200, "{s2}");
    assert_eq!(s2["defines"]["pw[2,1]"], json!(0.14));
    defines_are_refused(
        &h,
        &[
            ("tk[1,2]", 0.9, "0.02 to 0.5"),
            ("pw[7,1]", 0.1, "1..6, 1..4"),
            ("rh[1]", 0.3, "rh"),
        ],
    );
    let (code, r) = post(&h, "/api/save", json!({"path": "sized.toml"}));
    assert_eq!(code, 200, "{r}");
    let saved = std::fs::read_to_string(dir.path().join("sized.toml")).unwrap();
    assert!(saved.contains("\"tk[1,2]\" = 0.16"), "{saved}");
    // The saved graph builds the page's model from the command line.
    common::lsys_ok(dir.path(), &["pailou", "sized.toml", "-o", "sized.obj"]);
    h.stop();
}

#[test]
fn the_painting_page_paints_builds_and_saves_sessions() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let painting = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/painting");
    for f in ["house.rules", "villa.lsys"] {
        std::fs::copy(painting.join(f), d.join(f)).unwrap();
    }
    std::fs::write(d.join("plain.lsys"), "Axiom: F\n").unwrap();
    std::fs::write(d.join("photo.png"), b"\x89PNG\r\n\x1a\n").unwrap();
    let h = studio(d);
    let (code, _) = get(&h, "/api/paint/state");
    assert_eq!(code, 404, "no session before one is opened");
    let (_, list) = get(&h, "/api/paintings");
    assert_eq!(
        list["sessions"],
        json!(["villa.lsys"]),
        "only painting sessions"
    );
    assert_eq!(list["rules"], json!(["house.rules"]));
    assert_eq!(list["photos"], json!(["photo.png"]));

    // The villa without its photo: it opens, and its texture header is
    // the located diagnostic; no model.
    let (code, s) = post(&h, "/api/paint/open", json!({"path": "villa.lsys"}));
    assert_eq!(code, 200, "{s}");
    assert_eq!(s["current"], json!(false));
    assert_eq!(s["diagnostics"][0]["code"], "lsys::resolve::bad_value");
    assert!(s["diagnostics"][0]["message"]
        .as_str()
        .unwrap()
        .contains("villa_front.png"));
    assert_eq!(s["diagnostics"][0]["line"], json!(13));

    // With it, the villa opens as it builds from the command line.
    std::fs::copy(painting.join("villa_front.png"), d.join("villa_front.png")).unwrap();
    let (code, s) = post(&h, "/api/paint/open", json!({"path": "villa.lsys"}));
    assert_eq!(code, 200, "{s}");
    assert_eq!(s["current"], json!(true), "{s}");
    assert_eq!(s["session"]["parts"].as_array().unwrap().len(), 16);
    assert_eq!(s["holes"].as_array().unwrap().len(), 11);
    assert_eq!(s["constraints"].as_array().unwrap().len(), 11);
    let (code, glb) = request(&h, "GET", "/api/paint/model.glb", &[], b"");
    assert_eq!((code, &glb[..4]), (200, &b"glTF"[..]));

    // A new session: a wall, then a window painted 0.1 below the wall's
    // top, which the correction moves onto it, through the wall.
    let (code, s) = post(
        &h,
        "/api/paint/open",
        json!({"path": "new.lsys", "rules": "house.rules"}),
    );
    assert_eq!(code, 200, "{s}");
    let paint = |body: Value| post(&h, "/api/paint/paint", body);
    let (code, _) = paint(json!({"view": "front", "rect": [0, 0, 6, 3], "component": "Wall"}));
    assert_eq!(code, 200);
    let (code, s) = paint(json!({"view": "front", "rect": [1, 1, 2, 2.9], "component": "Window"}));
    assert_eq!(code, 200, "{s}");
    assert_eq!(
        s["painted"]["corrections"],
        json!(["its top edge moved by 0.1 to meet Wall 1's top edge"])
    );
    assert_eq!(s["session"]["parts"][1]["max"], json!([2.0, 3.0, 0.3]));
    assert_eq!(
        s["holes"],
        json!(["Window 2 intersects Wall 1: a hole 1 x 2 is cut through it"])
    );
    assert_eq!(s["constraints"].as_array().unwrap().len(), 1);

    // Refused: an unknown component, a rectangle too small, no view, a
    // part that is not there; the session is kept.
    for (bad, says) in [
        (
            json!({"view": "front", "rect": [0, 0, 1, 1], "component": "Tower"}),
            "no component `Tower`",
        ),
        (
            json!({"view": "front", "rect": [0, 0, 0.001, 1], "component": "Wall"}),
            "too small",
        ),
        (
            json!({"view": "side", "rect": [0, 0, 1, 1], "component": "Wall"}),
            "a view is",
        ),
        (
            json!({"part": 9, "view": "left", "rect": [0, 0, 1, 1]}),
            "no part 10",
        ),
    ] {
        let (code, r) = paint(bad);
        assert_eq!(code, 422, "{r}");
        assert!(r["refused"].to_string().contains(says), "{r}");
        assert_eq!(r["state"]["session"]["parts"].as_array().unwrap().len(), 2);
    }
    let mut session = s["session"].clone();
    session["threshold"] = json!(-1);
    let (code, _) = post(&h, "/api/paint/edit", json!({ "session": session }));
    assert_eq!(code, 422, "a negative threshold is refused");

    // Saved beside its rules, rebuilt by `lsys build`; a file that is not
    // a session, or outside the folder, is never replaced.
    let (code, r) = post(&h, "/api/paint/save", json!({}));
    assert_eq!(code, 200, "{r}");
    let text = std::fs::read_to_string(d.join("new.lsys")).unwrap();
    let scene = lsys::Grammar::from_path(d.join("new.lsys"))
        .unwrap()
        .build(16)
        .unwrap();
    assert_eq!(scene.constraints().len(), 1, "{text}");
    for (path, code_wanted) in [
        ("plain.lsys", 409),
        ("house.rules", 403),
        ("../out.lsys", 403),
    ] {
        let (code, r) = post(&h, "/api/paint/save", json!({ "path": path }));
        assert_eq!(code, code_wanted, "{path}: {r}");
    }
    assert_eq!(
        std::fs::read_to_string(d.join("plain.lsys")).unwrap(),
        "Axiom: F\n"
    );
    // Photos only from the folder, only images.
    let (code, _) = request(&h, "GET", "/api/paint/photo?path=photo.png", &[], b"");
    assert_eq!(code, 200);
    for bad in ["house.rules", "../photo.png"] {
        let (code, _) = request(&h, "GET", &format!("/api/paint/photo?path={bad}"), &[], b"");
        assert_eq!(code, 403, "{bad}");
    }
    h.stop();
}
