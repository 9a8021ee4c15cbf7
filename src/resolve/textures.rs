//! `texture i: "file"` headers -> [`Texture`]s of the turtle settings: the
//! image read from beside the file that names it, which must stay inside
//! the top-level grammar's folder (as includes do), be a PNG or a JPEG,
//! and be at most [`MAX_TEXTURE_BYTES`]. Read here, when the grammar is
//! compiled, so that a missing or wrong file is a located diagnostic and
//! the model's export never fails on it. The bytes are kept per path while
//! the file's size and time stay the same: the language server, `watch`
//! and the studio compile on every edit, and a photograph is megabytes.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::SystemTime;

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::Texture;
use super::turtle_headers::TurtleHeaders;
use super::Resolver;
use crate::parse::ast;
use crate::source::Span;

/// An image file read, at most (a photograph of a facade is a few MiB).
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;

/// Images kept between compilations, at most (in all); past it the cache
/// starts again empty.
const MAX_CACHED_BYTES: usize = 256 << 20;

type Cached = (SystemTime, u64, Arc<Vec<u8>>);

/// An image read: its MIME type and bytes, or why not and what to do.
type Read = Result<(&'static str, Arc<Vec<u8>>), (String, String)>;

fn cache() -> &'static Mutex<HashMap<PathBuf, Cached>> {
    static CACHE: OnceLock<Mutex<HashMap<PathBuf, Cached>>> = OnceLock::new();
    CACHE.get_or_init(Default::default)
}

/// The file's bytes, from the cache while its size and time are those it
/// had when it was read.
fn read_cached(full: &Path, meta: &std::fs::Metadata) -> std::io::Result<Arc<Vec<u8>>> {
    let stamp = (meta.modified()?, meta.len());
    let mut c = cache().lock().unwrap_or_else(|e| e.into_inner());
    if let Some((t, n, bytes)) = c.get(full) {
        if (*t, *n) == stamp {
            return Ok(bytes.clone());
        }
    }
    let bytes = Arc::new(std::fs::read(full)?);
    let held: usize = c.values().map(|(_, _, b)| b.len()).sum();
    if held + bytes.len() > MAX_CACHED_BYTES {
        c.clear();
    }
    c.insert(full.to_path_buf(), (stamp.0, stamp.1, bytes.clone()));
    Ok(bytes)
}

impl Resolver {
    pub(super) fn texture_header(
        &mut self,
        h: &ast::Header,
        index: &ast::Expr,
        file: &str,
        span: Span,
        scope: &Scope,
        t: &mut TurtleHeaders,
    ) {
        let Some(i) = self.const_count(index, scope, "texture index", 255) else {
            return;
        };
        let i = i as usize;
        if let Some(first) = t.texture_first(i) {
            self.duplicate(
                h,
                &format!("texture {i}:"),
                first,
                "each texture index is set once",
            );
            return;
        }
        match self.read_texture(file, span) {
            Ok((mime, bytes)) => t.add_texture(
                h.keyword,
                Texture {
                    index: i,
                    name: file.to_string(),
                    mime,
                    bytes,
                },
            ),
            Err((why, help)) => self.error(ResolveError::BadValue {
                what: "texture".to_string(),
                why,
                src: self.sources.named_source(span),
                span: span.into(),
                help: Some(help),
            }),
        }
    }

    /// The image `file` names, beside the file `span` is in: its type and
    /// bytes, or why not and what to do.
    fn read_texture(&self, file: &str, span: Span) -> Read {
        let from = self.sources.get(span.file);
        let Some(dir) = from.dir() else {
            return Err((
                format!(
                    "`{file}` cannot be found: {} is not a file on disk",
                    from.name
                ),
                "textures are read beside the grammar file; build it from a file".to_string(),
            ));
        };
        // `g.lsys` given bare has the folder "": the current one.
        let here = |d: &Path| {
            if d.as_os_str().is_empty() {
                Path::new(".").to_path_buf()
            } else {
                d.to_path_buf()
            }
        };
        let root = here(self.sources.get(0).dir().unwrap_or(dir));
        let full = here(dir).join(file);
        let canon = |p: &Path| {
            p.canonicalize().map_err(|e| {
                (
                    format!("cannot read {}: {e}", p.display()),
                    "the path is relative to the grammar's folder".to_string(),
                )
            })
        };
        let (full, root) = (canon(&full)?, canon(&root)?);
        if !full.starts_with(&root) {
            return Err((
                format!("{} is outside {}", full.display(), root.display()),
                "a texture must be inside the grammar's folder (links followed); copy the image there".to_string(),
            ));
        }
        let unreadable = |e: std::io::Error| {
            (
                format!("cannot read {}: {e}", full.display()),
                "check that the file is readable".to_string(),
            )
        };
        let meta = std::fs::metadata(&full).map_err(unreadable)?;
        if meta.len() > MAX_TEXTURE_BYTES {
            return Err((
                format!(
                    "{file} is {} MiB, more than the {} MiB a texture may be",
                    meta.len() >> 20,
                    MAX_TEXTURE_BYTES >> 20
                ),
                "make the image smaller".to_string(),
            ));
        }
        let bytes = read_cached(&full, &meta).map_err(unreadable)?;
        let mime = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            "image/png"
        } else if bytes.starts_with(&[0xff, 0xd8, 0xff]) {
            "image/jpeg"
        } else {
            return Err((
                format!("{file} is neither a PNG nor a JPEG image"),
                "glTF models carry PNG and JPEG textures: save the image as one".to_string(),
            ));
        };
        Ok((mime, bytes))
    }
}
