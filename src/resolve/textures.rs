//! `texture i: "file"` headers -> [`Texture`]s of the turtle settings: the
//! image read from beside the file that names it, which must stay inside
//! the top-level grammar's folder (as includes do), be a PNG or a JPEG,
//! and be at most [`MAX_TEXTURE_BYTES`]. Read here, when the grammar is
//! compiled, so that a missing or wrong file is a located diagnostic and
//! the model's export never fails on it.

use std::path::Path;
use std::sync::Arc;

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::Texture;
use super::turtle_headers::TurtleHeaders;
use super::Resolver;
use crate::parse::ast;
use crate::source::Span;

/// An image file read, at most (a photograph of a facade is a few MiB).
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;

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
                    bytes: Arc::new(bytes),
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
    fn read_texture(
        &self,
        file: &str,
        span: Span,
    ) -> Result<(&'static str, Vec<u8>), (String, String)> {
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
        let root = self.sources.get(0).dir().unwrap_or(dir).to_path_buf();
        let full = dir.join(file);
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
        let len = std::fs::metadata(&full).map(|m| m.len()).unwrap_or(0);
        if len > MAX_TEXTURE_BYTES {
            return Err((
                format!(
                    "{file} is {} MiB, more than the {} MiB a texture may be",
                    len >> 20,
                    MAX_TEXTURE_BYTES >> 20
                ),
                "make the image smaller".to_string(),
            ));
        }
        let bytes = std::fs::read(&full).map_err(|e| {
            (
                format!("cannot read {}: {e}", full.display()),
                "check that the file is readable".to_string(),
            )
        })?;
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
