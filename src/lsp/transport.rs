//! The stdio transport, ours instead of `lsp-server`'s. Input: the bytes
//! the editor writes to standard input; output: [`Message`]s on a
//! channel for the server's loop, and the loop's messages framed on
//! standard output.
//!
//! `lsp-server`'s reader ends the process on the first malformed message
//! and allocates whatever `Content-Length` declares before reading it.
//! This one never gives up on the stream:
//!
//! - headers are read leniently (any case, spaces, `\n` or `\r\n`, lines
//!   of at most [`MAX_HEADER_LINE`] bytes); a message without a usable
//!   `Content-Length` (missing, negative, not a number) is skipped with a
//!   line on standard error, and reading starts again at the next header;
//! - a body longer than [`MAX_MESSAGE`] is skipped in bounded chunks,
//!   never allocated;
//! - a body that is not JSON is answered with a JSON-RPC `-32700 Parse
//!   error` (id `null`), JSON that is not a message with `-32600 Invalid
//!   Request`;
//! - invalid UTF-8 and lone UTF-16 surrogate escapes (`"\ud800"`, which
//!   serde_json refuses) become U+FFFD, so the edit still applies.

use std::io::{self, BufRead, Read, Write};
use std::sync::{Arc, Mutex};

use lsp_server::{Connection, Message};
use serde_json::{json, Value};

/// The largest message body read (64 MiB, the size limit of a grammar
/// file, docs/limits.md, plus room for JSON escapes would not fit a
/// larger document anyway). Longer bodies are skipped.
pub const MAX_MESSAGE: usize = 64 << 20;

/// The longest header line kept; the rest of a longer line is skipped.
pub const MAX_HEADER_LINE: usize = 8 << 10;

/// Serves `serve` over standard input and output: a reader thread parses
/// the input into messages for `conn`, a writer thread frames the
/// server's messages. Returns `serve`'s result once it returns (the
/// reader thread is left blocked on standard input; the process ends).
pub fn stdio<T>(serve: impl FnOnce(Connection) -> T) -> T {
    let (server, client) = Connection::memory();
    let out = Arc::new(Mutex::new(io::stdout()));
    let reader_out = out.clone();
    let Connection {
        sender: to_server,
        receiver: from_server,
    } = client;
    // Not joined: it waits on standard input, which the editor may keep open.
    let _reader = std::thread::Builder::new()
        .name("lsp-reader".into())
        .spawn(move || {
            let stdin = io::stdin();
            read_messages(stdin.lock(), |m| to_server.send(m).is_ok(), &reader_out);
        });
    let writer = std::thread::Builder::new()
        .name("lsp-writer".into())
        .spawn(move || {
            for m in from_server {
                let mut o = out.lock().unwrap_or_else(|e| e.into_inner());
                if m.write(&mut *o).is_err() {
                    // The editor closed its end: nothing more to say.
                    break;
                }
            }
        });
    let result = serve(server);
    if let Ok(w) = writer {
        let _ = w.join();
    }
    result
}

/// Reads messages from `input` until it ends (or `deliver` returns
/// false), answering malformed ones on `out` itself.
pub fn read_messages<W: Write>(
    mut input: impl BufRead,
    mut deliver: impl FnMut(Message) -> bool,
    out: &Mutex<W>,
) {
    let reply = |v: Value| {
        let text = v.to_string();
        let mut o = out.lock().unwrap_or_else(|e| e.into_inner());
        let _ = write!(o, "Content-Length: {}\r\n\r\n{text}", text.len());
        let _ = o.flush();
    };
    loop {
        let length = match read_headers(&mut input) {
            Ok(Some(l)) => l,
            Ok(None) | Err(_) => return,
        };
        let length = match length {
            Length::Missing => {
                log("a message without Content-Length: skipped");
                continue;
            }
            Length::Bad(v) => {
                log(&format!("a message with Content-Length {v:?}: skipped"));
                continue;
            }
            Length::Of(n) if n > MAX_MESSAGE as u64 => {
                log(&format!(
                    "a message of {n} bytes, over the limit of {MAX_MESSAGE}: skipped"
                ));
                // Bounded chunks (io::copy's buffer), never the whole body.
                match io::copy(&mut (&mut input).take(n), &mut io::sink()) {
                    Ok(k) if k == n => continue,
                    _ => return,
                }
            }
            Length::Of(n) => n as usize,
        };
        let mut body = vec![0; length];
        if input.read_exact(&mut body).is_err() {
            return;
        }
        let text = String::from_utf8_lossy(&body);
        let value: Value = match serde_json::from_str(&lenient_json(&text)) {
            Ok(v) => v,
            Err(e) => {
                log(&format!(
                    "a message that is not JSON ({e}): answered -32700"
                ));
                reply(error(Value::Null, -32700, format!("Parse error: {e}")));
                continue;
            }
        };
        let id = value.get("id").cloned().unwrap_or(Value::Null);
        match serde_json::from_value::<Message>(value) {
            Ok(m) => {
                if !deliver(m) {
                    return;
                }
            }
            Err(e) => {
                log(&format!(
                    "JSON that is not a message ({e}): answered -32600"
                ));
                let id = match id {
                    Value::Number(_) | Value::String(_) => id,
                    _ => Value::Null,
                };
                reply(error(id, -32600, format!("Invalid Request: {e}")));
            }
        }
    }
}

fn error(id: Value, code: i32, message: String) -> Value {
    json!({"jsonrpc": "2.0", "id": id, "error": {"code": code, "message": message}})
}

fn log(what: &str) {
    eprintln!("lsys lsp: {what}");
}

enum Length {
    Missing,
    Bad(String),
    Of(u64),
}

/// Reads header lines up to the blank line that ends them; `None` at the
/// end of the input. Blank lines before any header are skipped, and so
/// is any text before a `Content-Length` on its line (the rest of a
/// skipped message's body), which lets the reader find the next message.
fn read_headers(input: &mut impl BufRead) -> io::Result<Option<Length>> {
    let mut length = Length::Missing;
    let mut seen = false;
    loop {
        let Some(line) = read_line(input)? else {
            return Ok(None);
        };
        let line = String::from_utf8_lossy(&line);
        let line = line.trim();
        if line.is_empty() {
            if seen {
                return Ok(Some(length));
            }
            continue;
        }
        seen = true;
        let lower = line.to_ascii_lowercase();
        if let Some(at) = lower.rfind("content-length") {
            let rest = line[at + "content-length".len()..].trim_start();
            let value = rest.strip_prefix(':').unwrap_or(rest).trim();
            length = match value.parse::<u64>() {
                Ok(n) => Length::Of(n),
                Err(_) => Length::Bad(value.chars().take(40).collect()),
            };
        }
    }
}

/// One line without its `\n`, at most [`MAX_HEADER_LINE`] bytes kept;
/// `None` at the end of the input.
fn read_line(input: &mut impl BufRead) -> io::Result<Option<Vec<u8>>> {
    let mut line = Vec::new();
    let mut any = false;
    loop {
        let buf = input.fill_buf()?;
        if buf.is_empty() {
            return Ok(any.then_some(line));
        }
        any = true;
        let (take, done) = match buf.iter().position(|&b| b == b'\n') {
            Some(i) => (i + 1, true),
            None => (buf.len(), false),
        };
        let room = MAX_HEADER_LINE.saturating_sub(line.len());
        line.extend_from_slice(&buf[..take.min(room)]);
        input.consume(take);
        if done {
            if line.last() == Some(&b'\n') {
                line.pop();
            }
            return Ok(Some(line));
        }
    }
}

/// `text` with every `\uXXXX` escape of a lone UTF-16 surrogate replaced
/// by `\ufffd`: serde_json refuses them, editors send them (a document
/// cut in the middle of a surrogate pair). Pairs stay as they are.
pub fn lenient_json(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.contains("\\u") {
        return text.into();
    }
    fn unit(b: &[u8], at: usize) -> Option<u16> {
        if b.get(at) != Some(&b'\\') || b.get(at + 1) != Some(&b'u') {
            return None;
        }
        let hex = std::str::from_utf8(b.get(at + 2..at + 6)?).ok()?;
        u16::from_str_radix(hex, 16).ok()
    }
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut copied = 0;
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'\\' {
            i += 1;
            continue;
        }
        let Some(u) = unit(b, i) else {
            // Another escape (`\\`, `\"`, ...): skip both characters.
            i += 2;
            continue;
        };
        let high = (0xD800..0xDC00).contains(&u);
        let low = (0xDC00..0xE000).contains(&u);
        if high && unit(b, i + 6).is_some_and(|v| (0xDC00..0xE000).contains(&v)) {
            i += 12;
        } else if high || low {
            out.push_str(&text[copied..i]);
            out.push_str("\\ufffd");
            i += 6;
            copied = i;
        } else {
            i += 6;
        }
    }
    if copied == 0 {
        return text.into();
    }
    out.push_str(&text[copied..]);
    out.into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lone_surrogates_become_replacement_characters() {
        let s = r#"{"a":"x\ud800y","b":"\ud83d\ude00","c":"\\ud800","d":"\udc00"}"#;
        let v: Value = serde_json::from_str(&lenient_json(s)).unwrap();
        assert_eq!(v["a"], "x\u{fffd}y");
        assert_eq!(v["b"], "😀");
        assert_eq!(v["c"], "\\ud800");
        assert_eq!(v["d"], "\u{fffd}");
    }

    fn read(input: &[u8]) -> (Vec<Message>, String) {
        let out = Mutex::new(Vec::new());
        let mut got = Vec::new();
        read_messages(
            input,
            |m| {
                got.push(m);
                true
            },
            &out,
        );
        (got, String::from_utf8(out.into_inner().unwrap()).unwrap())
    }

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    #[test]
    fn malformed_messages_are_answered_or_skipped_and_reading_goes_on() {
        let ok = r#"{"jsonrpc":"2.0","method":"x","params":{}}"#;
        let input = [
            frame("{not json"),
            format!("Content-Length: -5\r\n\r\n{ok}"),
            format!("Content-Type: x\r\n\r\n{ok}"),
            "Content-Length: 999999999999\r\n\r\n".to_string(),
        ]
        .concat();
        // The huge body "ends" with the input: only what came before counts.
        let (got, out) = read(input.as_bytes());
        assert!(got.is_empty(), "{got:?}");
        assert!(out.contains("-32700"), "{out}");
        let input = [
            frame("{not json"),
            format!("Content-Length: -5\r\n\r\n{ok}"),
            format!("content-length:   x\n\n{ok}"),
            frame(ok),
            frame(r#"{"jsonrpc":"2.0","id":7,"method":5}"#),
            format!("Content-Length: {}\r\n\r\n", MAX_MESSAGE + 1),
            " ".repeat(MAX_MESSAGE + 1),
            frame(ok),
        ]
        .concat();
        let (got, out) = read(input.as_bytes());
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(
            out.contains(r#""id":null"#) && out.contains("-32700"),
            "{out}"
        );
        assert!(out.contains(r#""id":7"#) && out.contains("-32600"), "{out}");
    }
}
