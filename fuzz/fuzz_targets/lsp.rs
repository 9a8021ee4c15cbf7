//! Fuzz target: the language server's message loop. The bytes are read
//! twice: as the raw stdio stream (framing, headers, JSON), whose messages
//! are then delivered to a server, and as the text of a document that the
//! same session opens, edits and asks about at positions taken from the
//! bytes. No input may panic the transport or end the server before the
//! client's `exit`.
#![no_main]

use std::sync::Mutex;

use libfuzzer_sys::fuzz_target;
use lsp_server::{Connection, Message, Notification, Request};
use lsys::internals::load::Options;
use lsys::internals::lsp::{serve, transport::read_messages};
use serde_json::{json, Value};

fn request(id: i32, method: &str, params: Value) -> Message {
    Message::Request(Request::new(id.into(), method.into(), params))
}

fn notify(method: &str, params: Value) -> Message {
    Message::Notification(Notification::new(method.into(), params))
}

fuzz_target!(|data: &[u8]| {
    // An analysis that would take the default 10 s is stopped sooner.
    std::env::set_var("LSYS_LSP_BUDGET_MS", "2000");
    let out = Mutex::new(Vec::new());
    let mut framed = Vec::new();
    read_messages(
        data,
        |m| {
            framed.push(m);
            framed.len() < 32
        },
        &out,
    );

    let uri = if data.first().is_some_and(|b| b & 1 == 1) {
        "file:///fuzz/model.l"
    } else {
        "file:///fuzz/model.lsys"
    };
    let text = String::from_utf8_lossy(data).into_owned();
    let lines = text.lines().count() as u32;
    let (server, client) = Connection::memory();
    let running = std::thread::spawn(move || serve(server, Options::default()));
    let mut msgs = vec![
        request(1, "initialize", json!({"capabilities": {}})),
        notify("initialized", json!({})),
        notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "lsys", "version": 1, "text": text}}),
        ),
    ];
    let doc = json!({"uri": uri});
    for (k, pair) in data.chunks(2).take(4).enumerate() {
        let line = u32::from(pair[0]) % (lines + 1);
        let character = u32::from(*pair.get(1).unwrap_or(&0));
        let at = json!({"textDocument": doc, "position": {"line": line, "character": character}});
        let id = 10 + 10 * k as i32;
        msgs.push(request(id, "textDocument/hover", at.clone()));
        msgs.push(request(id + 1, "textDocument/completion", at.clone()));
        msgs.push(request(id + 2, "textDocument/definition", at.clone()));
        msgs.push(request(id + 3, "textDocument/references", json!({"textDocument": doc, "position": at["position"], "context": {"includeDeclaration": true}})));
        msgs.push(request(id + 4, "textDocument/prepareRename", at));
    }
    let whole = json!({"start": {"line": 0, "character": 0}, "end": {"line": lines + 1, "character": 0}});
    msgs.push(request(100, "textDocument/inlayHint", json!({"textDocument": doc, "range": whole})));
    msgs.push(request(101, "textDocument/semanticTokens/full", json!({"textDocument": doc})));
    msgs.push(request(102, "textDocument/documentSymbol", json!({"textDocument": doc})));
    msgs.push(request(103, "textDocument/codeLens", json!({"textDocument": doc})));
    msgs.push(request(104, "textDocument/documentLink", json!({"textDocument": doc})));
    let half: String = text.chars().take(text.chars().count() / 2).collect();
    msgs.push(notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": half}]}),
    ));
    msgs.push(request(105, "textDocument/hover", json!({"textDocument": doc, "position": {"line": 0, "character": 1}})));
    msgs.extend(framed);
    msgs.push(request(1_000_000, "shutdown", Value::Null));
    msgs.push(notify("exit", Value::Null));
    for m in msgs {
        if client.sender.send(m).is_err() {
            break;
        }
    }
    drop(client.sender);
    // Every answer is read, so the server never waits on a full channel.
    for _ in client.receiver.iter() {}
    let _ = running.join().expect("the server's loop panicked");
});
