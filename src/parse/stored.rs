//! Syntax trees stored for the standard library's files: a file's text ->
//! the statements of a library file's stored tree that its parse would
//! give again, for `parse_statements` to take instead of parsing them.
//!
//! `build.rs` parses each library grammar with this parser and stores its
//! tree with where each statement starts and ends ([`Stored`]). A text that
//! is a library file's shares all of it; a text made from one (`lsys
//! pailou` writes the library's Pailou with a style's tables in place of
//! its own) shares a first and a last part of it, and the statements there.
//!
//! Why a shared statement parses the same: a statement is parsed from where
//! it starts, without looking back. Looking forward, the parser reads past
//! its end only to find that the next line does not continue it: through
//! blank lines and comments to the next line, and at most through that
//! line's statement. So a statement whose next statement lies in the shared
//! first part parses the same in both texts; in the shared last part, a
//! statement parses the same wherever the parse of the text arrives at its
//! start. The statements in between are parsed.

use serde::{Deserialize, Serialize};

use super::ast;
use crate::source::FileId;

/// A library file's tree with each statement's start and end (bytes of
/// the file), one per item of the tree (a library file parses with no
/// error, so every statement gave an item).
#[derive(Serialize, Deserialize)]
pub struct Stored {
    pub tree: ast::File,
    pub bounds: Vec<(u32, u32)>,
}

/// What a text shares with a library file's stored tree.
pub(super) enum Shared {
    /// The text is the library file's: its whole tree.
    Whole(Vec<ast::Item>),
    /// A first and a last part of it.
    Parts(Reuse),
}

/// The statements at the start and at the end of a stored tree that a text
/// shares with it.
pub(super) struct Reuse {
    /// The statements at the start, and where the parse goes on after them.
    pub first: Vec<ast::Item>,
    pub resume: usize,
    /// The statements at the end, with where each starts in the text (its
    /// spans are the text's already), in order.
    pub last: Vec<(usize, ast::Item)>,
}

impl Reuse {
    /// The statements from the one that starts at `pos` on, if one of the
    /// shared last part starts there.
    pub fn last_from(&mut self, pos: usize) -> Option<Vec<ast::Item>> {
        let k = self.last.iter().position(|&(start, _)| start == pos)?;
        Some(self.last.drain(k..).map(|(_, item)| item).collect())
    }
}

/// Shorter shared parts than this are not worth reading a tree for.
const AT_LEAST: usize = 256;

/// What `text` (file `file_id`) shares with the library file it has most in
/// common with; `None` when that is too little.
pub(super) fn reuse(file_id: FileId, text: &str) -> Option<Shared> {
    let (lib, first, last) = crate::stdlib::FILES
        .iter()
        .map(|lib| {
            let first = common_prefix(text, lib.text);
            let most = text.len().min(lib.text.len()) - first;
            (lib, first, common_suffix(text, lib.text, most))
        })
        .max_by_key(|&(_, first, last)| first + last)?;
    if first + last < AT_LEAST {
        return None;
    }
    // Spans in the shared last part move with it.
    let last_from = lib.text.len() - last;
    let shift = text.len() as i64 - lib.text.len() as i64;
    let stored: Stored = crate::source::in_file(file_id, last_from as u32, shift, || {
        postcard::from_bytes(lib.tree)
    })
    .ok()?;
    let Stored { tree, bounds } = stored;
    if bounds.len() != tree.items.len() {
        return None;
    }
    if first == text.len() && first == lib.text.len() {
        return Some(Shared::Whole(tree.items));
    }
    // Statement k is shared at the start when statement k + 1 ends in the
    // shared first part.
    let n_first = bounds
        .iter()
        .skip(1)
        .take_while(|&&(_, end)| end as usize <= first)
        .count();
    let resume = match n_first {
        0 => 0,
        n => super::skip_inline(text, bounds[n - 1].1 as usize),
    };
    let mut first_items = Vec::with_capacity(n_first);
    let mut last_items = Vec::new();
    for (k, (item, &(start, _))) in tree.items.into_iter().zip(&bounds).enumerate() {
        if k < n_first {
            first_items.push(item);
        } else if start as usize >= last_from {
            last_items.push(((start as i64 + shift) as usize, item));
        }
    }
    Some(Shared::Parts(Reuse {
        first: first_items,
        resume,
        last: last_items,
    }))
}

fn common_prefix(a: &str, b: &str) -> usize {
    a.bytes().zip(b.bytes()).take_while(|(x, y)| x == y).count()
}

/// The common suffix of `a` and `b`, at most `most` bytes long.
fn common_suffix(a: &str, b: &str, most: usize) -> usize {
    a.bytes()
        .rev()
        .zip(b.bytes().rev())
        .take(most)
        .take_while(|(x, y)| x == y)
        .count()
}
