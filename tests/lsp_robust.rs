//! "The language server never dies" (issue 36): a spawned `lsys lsp`
//! with piped standard input and output gets malformed messages (bad
//! JSON, bad or missing or huge `Content-Length`, lone surrogates, bad
//! parameters), a define bomb and documents too large to analyse; after
//! each it must still be running and answer a hover.
//!
//! The time limits are loose (2 s) on purpose: they prove the server is
//! not wedged, not that it is fast (that is benches/lsp.rs's job). The
//! hover latencies are printed (`--nocapture`) for the record.
#![cfg(feature = "cli")]

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::{json, Value};

const ALIVE: Duration = Duration::from_secs(2);

struct Server {
    child: Child,
    stdin: Option<ChildStdin>,
    out: mpsc::Receiver<Value>,
    next: i64,
    hovers: Vec<Duration>,
    _dir: tempfile::TempDir,
    uri: String,
}

impl Server {
    fn start(env: &[(&str, &str)]) -> Server {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().canonicalize().unwrap().join("g.lsys");
        let uri = lsp_types::Url::from_file_path(&path).unwrap().to_string();
        let mut child = Command::new(env!("CARGO_BIN_EXE_lsys"))
            .arg("lsp")
            .envs(env.iter().copied())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, out) = mpsc::channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            loop {
                let mut len = 0;
                loop {
                    let mut line = String::new();
                    if r.read_line(&mut line).unwrap_or(0) == 0 {
                        return;
                    }
                    let line = line.trim();
                    if line.is_empty() {
                        break;
                    }
                    if let Some(v) = line.strip_prefix("Content-Length:") {
                        len = v.trim().parse().unwrap();
                    }
                }
                let mut body = vec![0; len];
                if r.read_exact(&mut body).is_err() {
                    return;
                }
                if tx.send(serde_json::from_slice(&body).unwrap()).is_err() {
                    return;
                }
            }
        });
        let mut s = Server {
            stdin: child.stdin.take(),
            child,
            out,
            next: 0,
            hovers: Vec::new(),
            _dir: dir,
            uri,
        };
        s.request("initialize", json!({"capabilities": {}}));
        s.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
        s
    }

    fn raw(&mut self, bytes: &[u8]) {
        let stdin = self.stdin.as_mut().unwrap();
        stdin.write_all(bytes).unwrap();
        stdin.flush().unwrap();
    }

    fn send(&mut self, v: Value) {
        let body = v.to_string();
        self.raw(format!("Content-Length: {}\r\n\r\n{body}", body.len()).as_bytes());
    }

    /// The next message that `pick` accepts, within [`ALIVE`].
    fn wait(&mut self, what: &str, pick: impl Fn(&Value) -> bool) -> Value {
        self.wait_for(ALIVE, what, pick)
    }

    fn wait_for(&mut self, limit: Duration, what: &str, pick: impl Fn(&Value) -> bool) -> Value {
        let deadline = Instant::now() + limit;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.out.recv_timeout(left) {
                Ok(v) if pick(&v) => return v,
                Ok(_) => {}
                Err(_) => panic!("no {what} within {limit:?}: the server is dead or wedged"),
            }
        }
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next += 1;
        let id = self.next;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        self.wait(method, |v| v["id"] == json!(id))
    }

    /// Opens (or replaces) the document `g.lsys` with `text`.
    fn open(&mut self, version: i32, text: &str) {
        self.send(json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params":
            {"textDocument": {"uri": self.uri, "languageId": "lsys", "version": version, "text": text}}}));
    }

    fn diagnostics(&mut self, version: i32) -> Value {
        self.wait("diagnostics", |v| {
            v["method"] == "textDocument/publishDiagnostics" && v["params"]["version"] == version
        })["params"]["diagnostics"]
            .clone()
    }

    /// A hover at the start of the document, answered within [`ALIVE`].
    fn hover(&mut self) -> Value {
        let t = Instant::now();
        let uri = self.uri.clone();
        let r = self.request(
            "textDocument/hover",
            json!({"textDocument": {"uri": uri}, "position": {"line": 0, "character": 9}}),
        );
        self.hovers.push(t.elapsed());
        r
    }

    fn alive(&mut self) {
        assert!(
            self.child.try_wait().unwrap().is_none(),
            "the server exited"
        );
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let mut h = self.hovers.clone();
        h.sort();
        if !h.is_empty() {
            eprintln!(
                "hover latency: median {:?}, max {:?} over {}",
                h[h.len() / 2],
                h[h.len() - 1],
                h.len()
            );
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

const GOOD: &str = "#define N 3\naxiom: F(N)\n";

#[test]
fn malformed_messages_are_answered_or_skipped() {
    let mut s = Server::start(&[]);
    s.open(1, GOOD);
    s.diagnostics(1);
    assert!(s.hover()["result"]["contents"]["value"]
        .as_str()
        .unwrap()
        .contains("value: `3`"));

    // Not JSON: a parse error with id null.
    s.raw(b"Content-Length: 9\r\n\r\n{not json");
    let e = s.wait("parse error", |v| v.get("error").is_some());
    assert_eq!(e["error"]["code"], -32700);
    assert_eq!(e["id"], Value::Null);
    s.hover();

    // Bad or missing lengths: skipped, reading goes on.
    for header in ["Content-Length: -5", "Content-Length: x", "Content-Type: x"] {
        s.raw(format!("{header}\r\n\r\n{{\"jsonrpc\":\"2.0\",\"method\":\"x\"}}").as_bytes());
        s.hover();
    }

    // JSON that is not a message, a request with bad parameters.
    s.send(json!({"jsonrpc": "2.0", "id": 99, "method": 5}));
    let e = s.wait("invalid request", |v| v["id"] == 99);
    assert_eq!(e["error"]["code"], -32600);
    let e = s.request("textDocument/hover", json!({"textDocument": 5}));
    assert_eq!(e["error"]["code"], -32602);
    // A notification with bad parameters is ignored.
    s.send(json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {}}));
    s.hover();

    // A lone surrogate in an edit: applied as U+FFFD (which does not
    // compile, so the hover shows the new define without a value).
    let uri = s.uri.clone();
    let body = format!(
        r##"{{"jsonrpc":"2.0","method":"textDocument/didChange","params":{{"textDocument":{{"uri":"{uri}","version":2}},"contentChanges":[{{"text":"#define N 4\naxiom: F(N) \ud800\n"}}]}}}}"##
    );
    s.raw(format!("Content-Length: {}\r\n\r\n{body}", body.len()).as_bytes());
    s.diagnostics(2);
    let h = s.hover();
    assert!(
        h["result"]["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("#define N 4"),
        "{h}"
    );

    // A body over the cap (64 MiB) is skipped without being kept.
    let big = 64 << 20 | 1;
    s.raw(format!("Content-Length: {big}\r\n\r\n").as_bytes());
    let chunk = vec![b' '; 1 << 20];
    for _ in 0..64 {
        s.raw(&chunk);
    }
    s.raw(b" ");
    s.hover();
    s.alive();
}

#[test]
fn a_huge_declared_length_is_not_allocated() {
    let mut s = Server::start(&[]);
    s.open(1, GOOD);
    s.diagnostics(1);
    // The old server allocated the declared terabyte and aborted.
    s.raw(b"Content-Length: 999999999999\r\n\r\n");
    s.raw(&vec![b'x'; 1 << 20]);
    std::thread::sleep(Duration::from_millis(300));
    s.alive();
    // The rest of the stream is the skipped body: end it, the server ends.
    drop(s.stdin.take());
    let deadline = Instant::now() + ALIVE;
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(
            Instant::now() < deadline,
            "still running after its input ended"
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.code().is_some(), "killed by a signal: {status:?}");
}

/// 41 defines, each the previous one twice: 2^40 if expanded as macros.
fn define_bomb() -> String {
    let mut s = String::from("#define D0 1\n");
    for i in 1..=40 {
        s.push_str(&format!("#define D{i} (D{}+D{})\n", i - 1, i - 1));
    }
    s + "axiom: F(D40)\n"
}

#[test]
fn a_define_bomb_does_not_wedge_and_a_fixed_text_is_analysed() {
    let mut s = Server::start(&[]);
    s.open(1, &define_bomb());
    s.hover();
    s.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params":
        {"textDocument": {"uri": s.uri, "version": 2}, "contentChanges": [{"text": GOOD}]}}),
    );
    // The bomb's analysis may be given up (budget); the fixed text's is not.
    let deadline = Instant::now() + Duration::from_secs(30);
    while Instant::now() < deadline {
        let h = s.hover();
        if h["result"]["contents"]["value"]
            .as_str()
            .is_some_and(|v| v.contains("value: `3`"))
        {
            return;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    panic!("the fixed text was never analysed");
}

#[test]
fn a_slow_analysis_is_given_up_and_requests_do_not_wait() {
    // A budget of 1 ms: any real analysis runs past it.
    let mut s = Server::start(&[("LSYS_LSP_BUDGET_MS", "1")]);
    let mut text = String::from("axiom: A0\n");
    for i in 0..3000 {
        text.push_str(&format!("A{i} --> F A{}\n", (i + 1) % 3000));
    }
    s.open(1, &text);
    let d = s.diagnostics(1);
    assert_eq!(d[0]["code"], "lsys::lsp::too_slow", "{d}");
    s.hover();
    s.alive();
}

#[test]
fn a_20_mb_one_line_document_gets_a_too_large_notice() {
    let mut s = Server::start(&[]);
    let text = format!("axiom: {}\n", "F".repeat(20 << 20));
    s.open(1, &text);
    let d = s.diagnostics(1);
    assert_eq!(d[0]["code"], "lsys::lsp::too_large", "{d}");
    s.hover();
    // An edit to a small text brings the features back.
    s.open(2, GOOD);
    s.diagnostics(2);
    assert!(s.hover()["result"]["contents"]["value"]
        .as_str()
        .unwrap()
        .contains("value: `3`"));
}

#[test]
fn inlay_hints_on_a_16k_line_grammar_are_not_quadratic() {
    let mut s = Server::start(&[]);
    let mut text = String::from("axiom: M0(1)\n");
    let k = 8000;
    for i in 0..k {
        text.push_str(&format!("M{i}(x) --> F(x) M{}(x+1)\n", (i + 1) % k));
        text.push_str(&format!("// line {i}\n"));
    }
    s.open(1, &text);
    // Analysing it takes a while in a debug build: wait for it.
    let t = Instant::now();
    s.wait_for(Duration::from_secs(60), "diagnostics", |v| {
        v["method"] == "textDocument/publishDiagnostics"
    });
    eprintln!("16k lines analysed in {:?}", t.elapsed());
    let uri = s.uri.clone();
    let t = Instant::now();
    let r = s.request(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": uri}, "range":
            {"start": {"line": 8000, "character": 0}, "end": {"line": 8060, "character": 0}}}),
    );
    eprintln!("inlay hints, 60 lines of 16k: {:?}", t.elapsed());
    assert!(!r["result"].as_array().unwrap().is_empty(), "{r}");
    s.hover();
}

#[test]
fn a_hover_does_not_wait_for_a_running_analysis() {
    let mut s = Server::start(&[]);
    s.open(1, GOOD);
    s.diagnostics(1);
    // About 4 s of analysis in a debug build (the old server analysed
    // before answering any request).
    let mut text = String::from(GOOD);
    for i in 0..32_000 {
        text.push_str(&format!("M{i}(x) --> F(x) M{}(x+1)\n", (i + 1) % 32_000));
    }
    let uri = s.uri.clone();
    s.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params":
        {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": text}]}}),
    );
    for _ in 0..5 {
        // Answered from the analysis of version 1.
        let h = s.hover();
        assert!(h["result"]["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("value: `3`"));
    }
    // Loose: well under the analysis's seconds, not a benchmark.
    let fast = s.hovers.iter().filter(|d| **d < Duration::from_secs(1));
    assert_eq!(fast.count(), 5, "{:?}", s.hovers);
}

#[test]
fn semantic_tokens_on_a_long_line_are_not_quadratic() {
    let mut s = Server::start(&[]);
    // 300,000 modules on one line, under the analysis limit.
    let text = format!("axiom: {}\n", "F ".repeat(300_000));
    s.open(1, &text);
    s.wait_for(Duration::from_secs(60), "diagnostics", |v| {
        v["method"] == "textDocument/publishDiagnostics"
    });
    let uri = s.uri.clone();
    let t = Instant::now();
    let r = s.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": uri}}),
    );
    eprintln!("semantic tokens of a 600 kB line: {:?}", t.elapsed());
    assert!(r["result"]["data"].as_array().unwrap().len() >= 5 * 300_000);
    s.hover();
}

#[test]
fn twenty_thousand_errors_are_converted_in_linear_time() {
    let mut s = Server::start(&[]);
    let mut text = String::from("axiom: A0\n");
    for i in 0..20_000 {
        text.push_str(&format!("A{i} --> F(Q{i})\n"));
    }
    s.open(1, &text);
    // Each diagnostic measured the whole text again: past the 10 s budget.
    let t = Instant::now();
    let d = s.wait_for(Duration::from_secs(15), "diagnostics", |v| {
        v["method"] == "textDocument/publishDiagnostics"
    });
    eprintln!("20,000 diagnostics in {:?}", t.elapsed());
    let d = d["params"]["diagnostics"].as_array().unwrap();
    assert_eq!(d.len(), 20_000, "{}", d[0]);
    assert_eq!(d[0]["code"], "lsys::resolve::unknown_name");
    s.hover();
}
