//! End-to-end tests of `lsys lsp` over an in-memory connection: a client
//! opens grammars in a temporary folder (one includes another) and the
//! server's responses are snapshotted as JSON, with the folder written as
//! `$DIR` and the standard library's cache folder as `$STD`.
#![cfg(feature = "cli")]

use std::collections::VecDeque;
use std::path::Path;

use lsp_server::{Connection, Message, Notification, Request, RequestId};
use lsp_types::Url;
use serde_json::{json, Value};

const ROOT: &str = "\
#include \"shared.lsys\"
#define N 3
derivation length: N
angle: 30
axiom: A(1) X
A(x) : x < N --> F(x) [+ A(x+1)] B
A(x) --> F(LEN)
B --> B
";

const SHARED: &str = "\
#define LEN 2
X --> F(LEN) X
";

struct Client {
    conn: Connection,
    server: Option<std::thread::JoinHandle<()>>,
    next: i32,
    pending: VecDeque<Notification>,
    dir: tempfile::TempDir,
}

impl Client {
    fn start() -> Client {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("root.lsys"), ROOT).unwrap();
        std::fs::write(dir.path().join("shared.lsys"), SHARED).unwrap();
        let (server, conn) = Connection::memory();
        let server = std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn(move || lsys::internals::lsp::serve(server, Default::default()).unwrap())
            .unwrap();
        let mut c = Client {
            conn,
            server: Some(server),
            next: 0,
            pending: VecDeque::new(),
            dir,
        };
        c.init();
        c
    }

    fn init(&mut self) -> Value {
        let r = self.request("initialize", json!({"capabilities": {}}));
        self.notify("initialized", json!({}));
        r
    }

    fn uri(&self, name: &str) -> Url {
        Url::from_file_path(self.dir.path().canonicalize().unwrap().join(name)).unwrap()
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next += 1;
        let id = RequestId::from(self.next);
        let req = Request::new(id.clone(), method.to_string(), params);
        self.conn.sender.send(req.into()).unwrap();
        loop {
            match self.conn.receiver.recv().unwrap() {
                Message::Response(r) if r.id == id => {
                    return match r.response_result {
                        Err(e) => json!({"error": e.message}),
                        Ok(v) => v,
                    }
                }
                Message::Notification(n) => self.pending.push_back(n),
                other => panic!("unexpected {other:?}"),
            }
        }
    }

    fn notify(&mut self, method: &str, params: Value) {
        let n = Notification::new(method.to_string(), params);
        self.conn.sender.send(n.into()).unwrap();
    }

    /// The next `publishDiagnostics`.
    fn diagnostics(&mut self) -> Value {
        loop {
            let n = match self.pending.pop_front() {
                Some(n) => n,
                None => match self.conn.receiver.recv().unwrap() {
                    Message::Notification(n) => n,
                    other => panic!("unexpected {other:?}"),
                },
            };
            if n.method == "textDocument/publishDiagnostics" {
                return n.params;
            }
        }
    }

    /// The next `publishDiagnostics` for the file `name`.
    fn diagnostics_for(&mut self, name: &str) -> Value {
        let uri = self.uri(name);
        loop {
            let d = self.diagnostics();
            if d["uri"] == json!(uri) {
                return d;
            }
        }
    }

    fn open(&mut self, name: &str, text: &str) -> Value {
        let uri = self.uri(name);
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "lsys", "version": 1, "text": text}}),
        );
        self.diagnostics()
    }

    fn at(&self, name: &str, line: u32, character: u32) -> Value {
        json!({"textDocument": {"uri": self.uri(name)}, "position": {"line": line, "character": character}})
    }

    /// JSON text with the folders replaced by placeholders.
    fn show(&self, v: &Value) -> String {
        let text = serde_json::to_string_pretty(v).unwrap();
        let dir = Url::from_file_path(self.dir.path().canonicalize().unwrap()).unwrap();
        let std_dir = std::env::temp_dir().join(format!("lsys-std-{}", env!("CARGO_PKG_VERSION")));
        let std_dir = Url::from_file_path(std_dir).unwrap();
        let plain = self.dir.path().canonicalize().unwrap();
        text.replace(dir.as_str(), "file://$DIR")
            .replace(std_dir.as_str(), "file://$STD")
            .replace(&plain.display().to_string(), "$DIR")
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        let _ = self.request("shutdown", Value::Null);
        self.notify("exit", Value::Null);
        if let Some(s) = self.server.take() {
            let _ = s.join();
        }
    }
}

fn position_of(text: &str, needle: &str) -> (u32, u32) {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} not in text"));
    let line = text[..at].matches('\n').count() as u32;
    let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1);
    (line, col as u32)
}

#[test]
fn initialize_reports_capabilities() {
    let (server, conn) = Connection::memory();
    let t = std::thread::spawn(move || {
        lsys::internals::lsp::serve(server, Default::default()).unwrap()
    });
    let id = RequestId::from(1);
    conn.sender
        .send(Request::new(id, "initialize".into(), json!({"capabilities": {}})).into())
        .unwrap();
    let Message::Response(r) = conn.receiver.recv().unwrap() else {
        panic!("no response")
    };
    insta::assert_snapshot!(serde_json::to_string_pretty(&r.response_result.unwrap()).unwrap());
    conn.sender
        .send(Notification::new("initialized".into(), json!({})).into())
        .unwrap();
    conn.sender
        .send(Request::new(RequestId::from(2), "shutdown".into(), Value::Null).into())
        .unwrap();
    conn.sender
        .send(Notification::new("exit".into(), Value::Null).into())
        .unwrap();
    t.join().unwrap();
}

#[test]
fn diagnostics_on_open_and_after_an_edit() {
    let mut c = Client::start();
    let clean = c.open("root.lsys", ROOT);
    assert_eq!(clean["diagnostics"], json!([]), "{clean}");
    // Misspell a module's arity and a define, as a user typing would.
    let uri = c.uri("root.lsys");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [
            {"range": {"start": {"line": 6, "character": 11}, "end": {"line": 6, "character": 14}}, "text": "LNE"},
            {"range": {"start": {"line": 7, "character": 0}, "end": {"line": 7, "character": 1}}, "text": "B(y)"}
        ]}),
    );
    let after = c.diagnostics();
    assert_eq!(after["version"], 2);
    insta::assert_snapshot!(c.show(&after));
}

#[test]
fn diagnostics_inside_an_include_point_at_the_include_line() {
    let mut c = Client::start();
    std::fs::write(
        c.dir.path().join("shared.lsys"),
        "#define LEN 2\nX --> F(LEN, LEN, LEN) X\n",
    )
    .unwrap();
    let d = c.open("root.lsys", ROOT);
    insta::assert_snapshot!(c.show(&d));
}

#[test]
fn an_unsaved_edit_in_an_open_include_reaches_the_including_document() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    c.open("shared.lsys", SHARED);
    let uri = c.uri("shared.lsys");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [
            {"range": {"start": {"line": 1, "character": 11}, "end": {"line": 1, "character": 11}}, "text": ", 1, 2"}
        ]}),
    );
    let root = c.diagnostics_for("root.lsys");
    let messages: Vec<&str> = root["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["message"].as_str().unwrap())
        .collect();
    assert_eq!(messages.len(), 1, "{root}");
    assert!(
        messages[0].contains("`F` takes 0 to 2 parameters, found 3"),
        "{root}"
    );
    // Closing the include without saving: the disk's text applies again.
    c.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": uri}}),
    );
    let root = c.diagnostics_for("root.lsys");
    assert_eq!(root["diagnostics"], json!([]), "{root}");
}

#[test]
fn hover_on_a_define_a_module_and_a_turtle_command() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let mut out = String::new();
    for needle in ["N --> F", "LEN)", "F(x)", "+ A", "A(x) -->", "x+1", "B\n"] {
        let (l, col) = position_of(ROOT, needle);
        let h = c.request("textDocument/hover", c.at("root.lsys", l, col));
        out.push_str(&format!(
            "--- {needle:?}\n{}\n",
            h["contents"]["value"].as_str().unwrap_or("(none)")
        ));
    }
    insta::assert_snapshot!(out);
}

#[test]
fn definition_across_an_include() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let (l, col) = position_of(ROOT, "LEN)");
    let define = c.request("textDocument/definition", c.at("root.lsys", l, col));
    let (l, col) = position_of(ROOT, "X\n");
    let module = c.request("textDocument/definition", c.at("root.lsys", l, col));
    let include = c.request("textDocument/definition", c.at("root.lsys", 0, 12));
    let links = c.request(
        "textDocument/documentLink",
        json!({"textDocument": {"uri": c.uri("root.lsys")}}),
    );
    insta::assert_snapshot!(c.show(
        &json!({"define LEN": define, "module X": module, "include": include, "links": links})
    ));
}

#[test]
fn references_of_a_module_and_a_parameter() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let (l, col) = position_of(ROOT, "A(1)");
    let mut p = c.at("root.lsys", l, col);
    p["context"] = json!({"includeDeclaration": true});
    let module = c.request("textDocument/references", p);
    let (l, col) = position_of(ROOT, "x < N");
    let mut p = c.at("root.lsys", l, col);
    p["context"] = json!({"includeDeclaration": true});
    let param = c.request("textDocument/references", p);
    let (l, col) = position_of(ROOT, "LEN)");
    let mut p = c.at("root.lsys", l, col);
    p["context"] = json!({"includeDeclaration": false});
    let define = c.request("textDocument/references", p);
    insta::assert_snapshot!(
        c.show(&json!({"module A": module, "parameter x": param, "define LEN (uses)": define}))
    );
}

#[test]
fn rename_a_define_across_files_and_a_module() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let (l, col) = position_of(ROOT, "LEN)");
    let mut p = c.at("root.lsys", l, col);
    p["newName"] = json!("LENGTH");
    let define = c.request("textDocument/rename", p);
    let (l, col) = position_of(ROOT, "B\n");
    let mut p = c.at("root.lsys", l, col);
    p["newName"] = json!("Bud");
    let module = c.request("textDocument/rename", p);
    let (l, col) = position_of(ROOT, "F(x)");
    let mut p = c.at("root.lsys", l, col);
    p["newName"] = json!("G");
    let turtle = c.request("textDocument/rename", p);
    let sort = |mut v: Value| {
        if let Some(changes) = v["changes"].as_object_mut() {
            for edits in changes.values_mut() {
                edits.as_array_mut().unwrap().sort_by_key(|e| {
                    let s = &e["range"]["start"];
                    (s["line"].as_u64(), s["character"].as_u64())
                });
            }
        }
        v
    };
    insta::assert_snapshot!(
        c.show(&json!({"LEN -> LENGTH": sort(define), "B -> Bud": sort(module), "F": turtle}))
    );
}

#[test]
fn completion() {
    let mut c = Client::start();
    let text = format!("{ROOT}A(2) --> \n#include \n");
    c.open("root.lsys", &text);
    let (l, _) = position_of(&text, "A(2) --> \n");
    let body = c.request("textDocument/completion", c.at("root.lsys", l, 9));
    let mut typed = c.at("root.lsys", l, 9);
    typed["context"] = json!({"triggerKind": 2, "triggerCharacter": "<"});
    let roll = c.request("textDocument/completion", typed);
    assert_eq!(
        roll,
        json!([]),
        "`<` in a successor is a command, not an include"
    );
    let include = c.request("textDocument/completion", c.at("root.lsys", l + 1, 9));
    let start = c.request("textDocument/completion", c.at("root.lsys", l + 2, 0));
    let brief = |v: &Value| -> Vec<String> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|i| {
                format!(
                    "{} | {} | {}",
                    i["label"].as_str().unwrap(),
                    i["insertText"].as_str().unwrap_or("-"),
                    i["detail"].as_str().unwrap_or("-")
                )
            })
            .collect()
    };
    let body: Vec<String> = brief(&body)
        .into_iter()
        .filter(|s| !s.starts_with('@'))
        .collect();
    let start: Vec<String> = brief(&start).into_iter().take(6).collect();
    insta::assert_snapshot!(format!(
        "--- successor\n{}\n--- #include\n{}\n--- line start (first 6)\n{}\n",
        body.join("\n"),
        brief(&include).join("\n"),
        start.join("\n")
    ));
}

#[test]
fn semantic_tokens_and_symbols() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let doc = json!({"textDocument": {"uri": c.uri("root.lsys")}});
    let out = c.tokens("root.lsys", ROOT);
    let symbols = c.request("textDocument/documentSymbol", doc);
    insta::assert_snapshot!(format!("{out}\n{}", c.show(&symbols)));
}

impl Client {
    /// The semantic tokens of `name` (whose text is `text`), one a line:
    /// `line:col "text" type [declaration]`.
    fn tokens(&mut self, name: &str, text: &str) -> String {
        let doc = json!({"textDocument": {"uri": self.uri(name)}});
        let tokens = self.request("textDocument/semanticTokens/full", doc);
        let legend = self.init_legend();
        let data: Vec<u32> = serde_json::from_value(tokens["data"].clone()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let (mut line, mut col) = (0u32, 0u32);
        let mut out = String::new();
        for t in data.chunks(5) {
            line += t[0];
            col = if t[0] == 0 { col + t[1] } else { t[1] };
            let text = &lines[line as usize][col as usize..(col + t[2]) as usize];
            let decl = if t[4] & 1 == 1 { " declaration" } else { "" };
            out.push_str(&format!(
                "{line}:{col} {text:?} {}{decl}\n",
                legend[t[3] as usize]
            ));
        }
        out
    }

    fn init_legend(&self) -> Vec<String> {
        lsys::internals::lsp::capabilities()
            .semantic_tokens_provider
            .map(|p| match p {
                lsp_types::SemanticTokensServerCapabilities::SemanticTokensOptions(o) => o.legend,
                lsp_types::SemanticTokensServerCapabilities::SemanticTokensRegistrationOptions(
                    o,
                ) => o.semantic_tokens_options.legend,
            })
            .unwrap()
            .token_types
            .iter()
            .map(|t| t.as_str().to_string())
            .collect()
    }
}

#[test]
fn quick_fixes_for_a_misspelt_name_an_unquoted_include_and_a_typographic_character() {
    let mut c = Client::start();
    let text = ROOT
        .replace("F(LEN)\nB", "F(LNE)\nB")
        .replace("#include \"shared.lsys\"", "#include shared.lsys")
        .replace("angle: 30", "angle: 30 × 1");
    let d = c.open("root.lsys", &text);
    let mut out = Vec::new();
    for diag in d["diagnostics"].as_array().unwrap() {
        let actions = c.request(
            "textDocument/codeAction",
            json!({"textDocument": {"uri": c.uri("root.lsys")}, "range": diag["range"],
                   "context": {"diagnostics": [diag]}}),
        );
        out.push(json!({"diagnostic": diag["message"], "actions": actions}));
    }
    insta::assert_snapshot!(c.show(&json!(out)));
}

#[test]
fn code_lens_counts_firings() {
    let mut c = Client::start();
    c.open("root.lsys", ROOT);
    let lenses = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": c.uri("root.lsys")}}),
    );
    insta::assert_snapshot!(c.show(&lenses));
}

#[test]
fn standard_library_includes_resolve() {
    let mut c = Client::start();
    let text = "#include <toukung_middle>\n";
    let d = c.open("std.lsys", text);
    let (l, col) = position_of(text, "<toukung");
    let def = c.request("textDocument/definition", c.at("std.lsys", l, col + 1));
    assert!(
        Path::new(def[0]["uri"].as_str().unwrap_or(""))
            .to_string_lossy()
            .contains("toukung_middle"),
        "{def}"
    );
    insta::assert_snapshot!(c.show(&json!({"diagnostics": d, "definition": def})));
}

#[test]
fn a_cpfg_model_is_preprocessed_and_positions_stay_in_the_file_as_written() {
    let mut c = Client::start();
    let text = "\
#define LEAF [&(30)~l]
Lsystem: 1
derivation length: 2
Axiom: A(LEN)
A(x) --> F(x) LEAF B(x)
endlsystem
";
    let d = c.open("tree.l", text);
    let tokens = c.tokens("tree.l", text);
    insta::assert_snapshot!(format!("{}\n{tokens}", c.show(&d)));
}

#[test]
fn inlay_hints_show_define_values_and_parameter_names() {
    let mut c = Client::start();
    let text = format!("{ROOT}#define W N*2\nC(a, b) --> C(a+W, b) A(a)\n");
    c.open("root.lsys", &text);
    let hints = c.request(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": c.uri("root.lsys")},
               "range": {"start": {"line": 0, "character": 0}, "end": {"line": 20, "character": 0}}}),
    );
    let lines: Vec<&str> = text.lines().collect();
    let out: Vec<String> = hints
        .as_array()
        .unwrap()
        .iter()
        .map(|h| {
            let (l, c) = (
                h["position"]["line"].as_u64().unwrap() as usize,
                h["position"]["character"].as_u64().unwrap() as usize,
            );
            format!(
                "{l}:{c} {} | {}⟨⟩{}",
                h["label"].as_str().unwrap(),
                &lines[l][..c],
                &lines[l][c..]
            )
        })
        .collect();
    insta::assert_snapshot!(out.join("\n"));
}

#[test]
fn components_hover_and_definition() {
    let mut c = Client::start();
    std::fs::create_dir(c.dir.path().join("components")).unwrap();
    std::fs::write(c.dir.path().join("components/Gate.obj"), "v 0 0 0\n").unwrap();
    let text = "#include MP\naxiom: ~MP(1) ~TM(1) ~Gate ~Nope\n";
    c.open("comp.lsys", text);
    let mut out = String::new();
    for needle in ["MP(1)", "TM", "Gate", "Nope"] {
        let (l, col) = position_of(text, needle);
        let h = c.request("textDocument/hover", c.at("comp.lsys", l, col));
        let d = c.request("textDocument/definition", c.at("comp.lsys", l, col));
        out.push_str(&format!(
            "--- {needle}\n{}\n{}\n",
            h["contents"]["value"].as_str().unwrap_or("(none)"),
            c.show(&d)
        ));
    }
    insta::assert_snapshot!(out);
}
