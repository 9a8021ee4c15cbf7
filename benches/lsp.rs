//! `lsys lsp` latency (issue 16: under 50 ms for a 1,000-line grammar):
//! a client changes a generated 1,000-line grammar over an in-memory
//! connection and waits for the diagnostics published for that version;
//! and the stages underneath (load, compile) on the same text.
#![cfg(feature = "cli")]

use divan::{black_box, Bencher};
use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::json;

fn main() {
    divan::main();
}

/// The grammar `scripts/lsp_client.py --generate 1000` writes (the
/// numbers in docs/editors.md): 333 defines, 666 productions and an
/// include of [`SHARED`].
fn generated() -> String {
    let k = (1000 - 3) / 3;
    let mut s = String::from("#include \"gen_shared.lsys\"\nderivation length: 6\naxiom: M0(1)\n");
    for i in 0..k {
        s.push_str(&format!("#define K{i} {}\n", i % 7 + 1));
    }
    for i in 0..k {
        let n = (i + 1) % k;
        s.push_str(&format!(
            "M{i}(x) : x < K{i} --> F(x) [+(K{i}) M{n}(x+1)] S(LEN)\n"
        ));
        s.push_str(&format!("M{i}(x) --> F(LEN) M{n}(x)\n"));
    }
    s
}

const SHARED: &str = "#define LEN 2\nS(a) --> F(a)\n";

/// A 1,000-line grammar with more in each line: two defines per line,
/// conditions joined by `&&`, calls, several branches per successor.
fn rich() -> String {
    let mut s = String::from("derivation length: 4\nangle: 25\n");
    let groups = 140;
    for i in 0..groups {
        s.push_str(&format!("#define K{i} {}.5, W{i} K{i}*0.7\n", i % 9 + 1));
    }
    s.push_str("axiom: A0(1, 2)\n");
    for i in 0..groups {
        let n = (i + 1) % groups;
        s.push_str(&format!(
            "A{i}(x, y) : x < K{i} && y > 0 --> F(x) [+(30) A{n}(x*0.9, y-1)] -(20) B{i}(y) /(137.5) !(W{i})\n"
        ));
        s.push_str(&format!(
            "A{i}(x, y) : x >= K{i} --> F(x/2) B{i}(sqrt(y + 1))\n"
        ));
        s.push_str(&format!(
            "B{i}(y) : y > 1 --> [&(45) F(y) C{i}] ^(10) B{i}(y - 1)\n"
        ));
        s.push_str(&format!("B{i}(y) --> F(y) ;(2)\n"));
        s.push_str(&format!("C{i} --> F [+F] [-F] C{i}\n"));
        s.push_str(&format!("// group {i}: five productions\n"));
    }
    while s.lines().count() < 1000 {
        s.push_str("// padding\n");
    }
    s
}

struct Client {
    conn: Connection,
    server: Option<std::thread::JoinHandle<()>>,
    version: i32,
    uri: String,
    _dir: tempfile::TempDir,
}

impl Client {
    fn open(text: &str) -> Client {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().canonicalize().expect("dir").join("big.lsys");
        std::fs::write(&path, text).expect("writes");
        std::fs::write(path.with_file_name("gen_shared.lsys"), SHARED).expect("writes");
        let uri = lsp_types::Url::from_file_path(&path)
            .expect("uri")
            .to_string();
        let (server, conn) = Connection::memory();
        let server = std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn(move || lsys::internals::lsp::serve(server, Default::default()).expect("serves"))
            .expect("thread");
        let c = Client {
            conn,
            server: Some(server),
            version: 1,
            uri,
            _dir: dir,
        };
        let init = Request::new(
            RequestId::from(1),
            "initialize".into(),
            json!({"capabilities": {}}),
        );
        c.conn.sender.send(init.into()).expect("sends");
        loop {
            if let Message::Response(_) = c.conn.receiver.recv().expect("answers") {
                break;
            }
        }
        c.notify("initialized", json!({}));
        c.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": c.uri, "languageId": "lsys", "version": 1, "text": text}}),
        );
        c.wait_diagnostics();
        c
    }

    fn notify(&self, method: &str, params: serde_json::Value) {
        let n = Notification::new(method.into(), params);
        self.conn.sender.send(n.into()).expect("sends");
    }

    /// The number of diagnostics published for the current version.
    fn wait_diagnostics(&self) -> usize {
        loop {
            if let Message::Notification(n) = self.conn.receiver.recv().expect("publishes") {
                if n.method == "textDocument/publishDiagnostics"
                    && n.params["version"] == json!(self.version)
                {
                    return n.params["diagnostics"].as_array().map_or(0, Vec::len);
                }
            }
        }
    }

    /// Replaces the whole text and waits for its diagnostics.
    fn change(&mut self, text: &str) -> usize {
        self.version += 1;
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": self.uri, "version": self.version},
                   "contentChanges": [{"text": text}]}),
        );
        self.wait_diagnostics()
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        self.notify("exit", json!(null));
        if let Some(s) = self.server.take() {
            let _ = s.join();
        }
    }
}

/// An edit (one character typed in a production, then taken back) to the
/// diagnostics published for it: what the editor waits for.
fn change_to_diagnostics(bencher: Bencher, text: String) {
    let edited = text
        .replacen("F(LEN)", "F(LEM)", 1)
        .replacen("F(x/2)", "F(x/3)", 1);
    assert_ne!(edited, text);
    let mut client = Client::open(&text);
    let mut flip = false;
    bencher.bench_local(|| {
        flip = !flip;
        black_box(client.change(if flip { &edited } else { &text }))
    });
}

#[divan::bench(sample_count = 30, sample_size = 1)]
fn change_to_diagnostics_generated(bencher: Bencher) {
    change_to_diagnostics(bencher, generated());
}

#[divan::bench(sample_count = 30, sample_size = 1)]
fn change_to_diagnostics_rich(bencher: Bencher) {
    change_to_diagnostics(bencher, rich());
}

/// A grammar of about `bytes` bytes, in lines like [`generated`]'s.
fn sized(bytes: usize) -> String {
    let mut s = String::from("#define LEN 2\nderivation length: 2\naxiom: M0(1) F(LEN)\n");
    let mut i = 0;
    while s.len() < bytes {
        s.push_str(&format!(
            "M{i}(x) : x < 3 --> F(x) [+(30) M{}(x+1)]\n",
            i + 1
        ));
        i += 1;
    }
    s.push_str(&format!("M{i}(x) --> F(x)\n"));
    s
}

/// The largest document the server analyses (src/lsp/server.rs,
/// `MAX_ANALYSED`, 1 MiB): an edit to its diagnostics.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn change_to_diagnostics_1mb(bencher: Bencher) {
    change_to_diagnostics(bencher, sized((1 << 20) - 100));
}

/// A 5 MB document: over the limit, an edit gets the "too large" notice.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn change_to_diagnostics_5mb(bencher: Bencher) {
    change_to_diagnostics(bencher, sized(5_000_000));
}

/// The document as the server compiles it: text at a path in a folder
/// with the include beside it.
fn edited_input(dir: &tempfile::TempDir, text: String) -> lsys::internals::load::Input {
    let path = dir.path().join("gen.lsys");
    std::fs::write(path.with_file_name("gen_shared.lsys"), SHARED).expect("writes");
    lsys::internals::load::Input::Edited { path, text }
}

/// Load alone (read and parse the file and its include).
#[divan::bench(sample_count = 30, sample_size = 1)]
fn load_generated(bencher: Bencher) {
    let dir = tempfile::tempdir().expect("temp dir");
    let input = edited_input(&dir, generated());
    let opts = lsys::internals::load::Options::default();
    bencher.bench_local(|| black_box(lsys::internals::load::load(&input, &opts).is_ok()));
}

/// Load and compile (every stage `lsys check` runs).
#[divan::bench(sample_count = 30, sample_size = 1)]
fn compile_generated(bencher: Bencher) {
    let dir = tempfile::tempdir().expect("temp dir");
    let input = edited_input(&dir, generated());
    let opts = lsys::internals::load::Options::default();
    bencher.bench_local(|| black_box(lsys::internals::pipeline::compile(&input, &opts).is_ok()));
}
