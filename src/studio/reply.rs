//! Replies of the studio's routes: a status and a body -> a tiny_http
//! response with its type and the headers every reply carries (no
//! caching, no type sniffing).

use std::io::Cursor;

use serde_json::Value;
use tiny_http::{Header, Response};

pub type Reply = Response<Cursor<Vec<u8>>>;

pub fn hdr(k: &str, v: &str) -> Header {
    Header::from_bytes(k.as_bytes(), v.as_bytes()).expect("ASCII header")
}

fn common(r: Reply) -> Reply {
    r.with_header(hdr("Cache-Control", "no-store"))
        .with_header(hdr("X-Content-Type-Options", "nosniff"))
}

pub fn bytes(b: Vec<u8>, mime: &str) -> Reply {
    common(Response::from_data(b).with_header(hdr("Content-Type", mime)))
}

pub fn text(code: u16, msg: &str) -> Reply {
    bytes(format!("{msg}\n").into_bytes(), "text/plain; charset=utf-8").with_status_code(code)
}

pub fn json_reply(code: u16, v: Value) -> Reply {
    bytes(v.to_string().into_bytes(), "application/json").with_status_code(code)
}
