//! The studio's safety rules: a path from the page -> a file inside the
//! opened folder or a refusal (no `..`, no absolute paths, symlinks
//! resolved before the check); a request's `Host`/`Origin` -> whether it
//! is the server's own (DNS-rebinding and cross-site protection); a body
//! -> at most [`MAX_BODY`] bytes.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// The largest request body the studio reads (a graph or an edit is a few
/// kilobytes).
pub const MAX_BODY: usize = 1 << 20;

#[derive(Debug, PartialEq)]
pub enum ConfineError {
    /// Empty, absolute, or with `..`.
    NotRelative(String),
    /// Leads outside the folder (through a symlink).
    Outside(String),
    Io(String),
}

impl std::fmt::Display for ConfineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ConfineError::NotRelative(p) => write!(
                f,
                "`{p}` is not a path inside the opened folder: give a relative path without `..`"
            ),
            ConfineError::Outside(p) => {
                write!(
                    f,
                    "`{p}` leads outside the opened folder (through a symlink)"
                )
            }
            ConfineError::Io(m) => write!(f, "{m}"),
        }
    }
}

/// `rel` inside `root` (canonical): the path to read or write. The file
/// need not exist (saving a new graph), but its folder must, and both are
/// resolved through symlinks before the check.
pub fn confine(root: &Path, rel: &str) -> Result<PathBuf, ConfineError> {
    let p = Path::new(rel);
    let plain = !rel.is_empty()
        && !rel.contains('\0')
        && p.components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if !plain {
        return Err(ConfineError::NotRelative(rel.to_string()));
    }
    let root = root
        .canonicalize()
        .map_err(|e| ConfineError::Io(format!("the opened folder: {e}")))?;
    let joined = root.join(p);
    let resolved = match joined.canonicalize() {
        Ok(r) => r,
        Err(_) => {
            // A new file: its folder must exist and be inside; the name
            // itself must not be a dangling symlink.
            if joined.symlink_metadata().is_ok() {
                return Err(ConfineError::Outside(rel.to_string()));
            }
            let parent = joined.parent().unwrap_or(&root);
            let parent = parent
                .canonicalize()
                .map_err(|e| ConfineError::Io(format!("cannot open the folder of `{rel}`: {e}")))?;
            parent.join(joined.file_name().unwrap_or_default())
        }
    };
    if resolved.starts_with(&root) {
        Ok(resolved)
    } else {
        Err(ConfineError::Outside(rel.to_string()))
    }
}

/// Whether `host` (the `Host` header) is one of the server's own names.
pub fn host_ok(host: Option<&str>, hosts: &[String]) -> bool {
    host.is_some_and(|h| hosts.iter().any(|x| x.eq_ignore_ascii_case(h.trim())))
}

/// Whether `origin` (the `Origin` header, when sent) is the server's own.
pub fn origin_ok(origin: Option<&str>, hosts: &[String]) -> bool {
    match origin {
        None => true,
        Some(o) => o
            .trim()
            .strip_prefix("http://")
            .is_some_and(|h| hosts.iter().any(|x| x.eq_ignore_ascii_case(h))),
    }
}

/// Reads a body of at most [`MAX_BODY`] bytes; `None` when it is larger
/// (declared or sent).
pub fn read_body(declared: Option<usize>, body: &mut dyn Read) -> Option<Vec<u8>> {
    if declared.is_some_and(|n| n > MAX_BODY) {
        return None;
    }
    let mut buf = Vec::new();
    body.take(MAX_BODY as u64 + 1).read_to_end(&mut buf).ok()?;
    (buf.len() <= MAX_BODY).then_some(buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hosts_and_origins() {
        let hosts = vec!["127.0.0.1:8080".to_string(), "localhost:8080".to_string()];
        assert!(host_ok(Some("localhost:8080"), &hosts));
        assert!(!host_ok(Some("evil.example:8080"), &hosts));
        assert!(!host_ok(None, &hosts));
        assert!(origin_ok(None, &hosts));
        assert!(origin_ok(Some("http://127.0.0.1:8080"), &hosts));
        assert!(!origin_ok(Some("http://evil.example"), &hosts));
        assert!(!origin_ok(Some("https://127.0.0.1:8080"), &hosts));
    }

    #[test]
    fn bodies_are_limited() {
        let big = vec![b'x'; MAX_BODY + 1];
        assert!(read_body(None, &mut big.as_slice()).is_none());
        assert!(read_body(Some(MAX_BODY + 1), &mut &b"{}"[..]).is_none());
        assert_eq!(read_body(Some(2), &mut &b"{}"[..]).unwrap(), b"{}");
    }
}
