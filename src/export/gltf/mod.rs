//! glTF 2.0 export: a [`Scene`] -> the bytes of a binary `.glb` ([`to_glb`],
//! or [`write_glb`] straight into a writer) or of a self-contained `.gltf`
//! whose buffer is a base64 data URI ([`to_gltf`]). The document itself
//! (meshes, nodes, accessors) is built in `document.rs` and its GLB JSON
//! text written by `json_chunk.rs`; this file holds the two file
//! containers and the export's errors.

mod document;
mod json_chunk;

use document::build;
pub(crate) use document::{check, unit_normals};
use gltf_json as json;
use miette::Diagnostic;
use thiserror::Error;

use crate::mesh::Scene;

#[derive(Debug, Error, Diagnostic)]
pub enum ExportError {
    #[error("the model is too large for {format}: {bytes} bytes, at most {limit} are possible")]
    #[diagnostic(
        code(lsys::export::too_large),
        help("derive fewer steps, use coarser tubes, or export OBJ instead")
    )]
    TooLarge {
        format: &'static str,
        bytes: u64,
        limit: u64,
    },

    #[error("cannot export {name}: {detail}")]
    #[diagnostic(
        code(lsys::export::invalid_geometry),
        help("this is a bug in lsys: the scene it built is inconsistent; please report it")
    )]
    InvalidGeometry { name: String, detail: String },

    #[error("cannot encode the glTF document: {0}")]
    #[diagnostic(code(lsys::export::json))]
    Json(#[from] serde_json::Error),

    #[error("cannot write the model: {0}")]
    #[diagnostic(code(lsys::export::io))]
    Io(#[from] std::io::Error),
}

/// The scene as a binary glTF (`.glb`) file.
pub fn to_glb(scene: &Scene) -> Result<Vec<u8>, ExportError> {
    let mut out = Vec::new();
    write_glb(scene, &mut out)?;
    Ok(out)
}

/// Writes the scene as a binary glTF (`.glb`) file to `out` in one pass:
/// the header, the JSON chunk, and the binary chunk encoded from the mesh
/// buffers as it is written, so no copy of the file or of its buffer is
/// ever in memory. Returns the bytes written.
pub fn write_glb(scene: &Scene, out: &mut dyn std::io::Write) -> Result<u64, ExportError> {
    let (mut root, bin) = build(scene)?;
    let mut json = json_chunk::to_vec(&mut root)?;
    // The JSON chunk is padded with spaces, the binary one (its layout
    // padded by `build`) with zeros.
    json.resize(padded(json.len()), b' ');
    // GLB lengths are u32: header 12, chunk headers 8 each.
    let length = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    if length as u64 > u64::from(u32::MAX) {
        return Err(ExportError::TooLarge {
            format: "GLB",
            bytes: length as u64,
            limit: u32::MAX.into(),
        });
    }
    let u32le = |n: usize| (n as u32).to_le_bytes();
    let mut head = Vec::with_capacity(28);
    head.extend_from_slice(b"glTF");
    head.extend_from_slice(&2u32.to_le_bytes());
    head.extend_from_slice(&u32le(length));
    head.extend_from_slice(&u32le(json.len()));
    head.extend_from_slice(b"JSON");
    out.write_all(&head)?;
    out.write_all(&json)?;
    // An empty scene has no buffer, and then no BIN chunk either.
    if !bin.is_empty() {
        let mut chunk = Vec::with_capacity(8);
        chunk.extend_from_slice(&u32le(bin.len()));
        chunk.extend_from_slice(b"BIN\0");
        out.write_all(&chunk)?;
        bin.write_to(out)?;
    }
    Ok(length as u64)
}

/// The scene as one self-contained `.gltf` JSON file (buffer as data URI).
pub fn to_gltf(scene: &Scene) -> Result<Vec<u8>, ExportError> {
    let (mut root, bin) = build(scene)?;
    if let Some(buffer) = root.buffers.first_mut() {
        buffer.uri = Some(format!(
            "data:application/octet-stream;base64,{}",
            base64(&bin.to_vec())
        ));
    }
    Ok(json::serialize::to_vec_pretty(&root)?)
}

fn padded(n: usize) -> usize {
    n.div_ceil(4) * 4
}

/// Standard base64 with padding (RFC 4648), for the `.gltf` data URI.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let byte = |i: usize| u32::from(chunk.get(i).copied().unwrap_or(0));
        let n = byte(0) << 16 | byte(1) << 8 | byte(2);
        for k in 0..4 {
            out.push(if k <= chunk.len() {
                ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn export_base64_matches_rfc_4648() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (input, expected) in cases {
            assert_eq!(base64(input.as_bytes()), expected);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0x00]), "//4A");
    }
}
