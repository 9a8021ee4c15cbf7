//! Preprocessing tokens: what the lexer produces from one file's text and
//! what macro expansion consumes and produces. A token remembers where it
//! came from (byte span in the current file, output line) so that every
//! expansion result can be placed back on the line of its invocation.

use std::ops::Range;
use std::rc::Rc;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Ident,
    Number,
    /// A `"..."` literal, quotes included.
    Str,
    Punct,
    /// Stands for an empty macro argument next to `##`; never output.
    Placemarker,
}

/// The names of macros a token must not be expanded by again ("painted
/// blue"), kept sorted. `None` is the empty set, the common case.
pub(crate) type HideSet = Option<Rc<Vec<Rc<str>>>>;

#[derive(Debug, Clone)]
pub(crate) struct Token {
    pub kind: Kind,
    pub text: Rc<str>,
    /// Whitespace before the token as written (comments count as one
    /// space); expansion results carry "" or " ".
    pub ws: Rc<str>,
    /// Bytes of the current file's original text this token stands for;
    /// expansion results get the span of their invocation.
    pub span: Range<usize>,
    /// 0-based output line: the first physical line of the token's
    /// backslash-continued group, or the invocation's line.
    pub line: usize,
    /// Whether this token is the first physical token of its logical line
    /// (a `#` there starts a directive).
    pub bol: bool,
    pub hide: HideSet,
    /// A macro boundary lies just before this token: output must not glue
    /// it to the previous token into a different token (cpp's avoid_paste).
    pub pad: bool,
}

impl Token {
    pub fn is_punct(&self, p: &str) -> bool {
        self.kind == Kind::Punct && &*self.text == p
    }

    pub fn is_ident(&self) -> bool {
        self.kind == Kind::Ident
    }

    pub fn hidden(&self, name: &str) -> bool {
        self.hide
            .as_ref()
            .is_some_and(|h| h.iter().any(|n| &**n == name))
    }

    pub fn has_space(&self) -> bool {
        !self.ws.is_empty()
    }
}

/// `a ∪ b`.
pub(crate) fn union(a: &HideSet, b: &HideSet) -> HideSet {
    match (a, b) {
        (None, x) | (x, None) => x.clone(),
        (Some(a), Some(b)) => {
            let mut v: Vec<Rc<str>> = a.iter().chain(b.iter()).cloned().collect();
            v.sort();
            v.dedup();
            Some(Rc::new(v))
        }
    }
}

/// `a ∩ b`.
pub(crate) fn intersect(a: &HideSet, b: &HideSet) -> HideSet {
    match (a, b) {
        (Some(a), Some(b)) => {
            let v: Vec<Rc<str>> = a.iter().filter(|n| b.contains(n)).cloned().collect();
            (!v.is_empty()).then(|| Rc::new(v))
        }
        _ => None,
    }
}

/// `a ∪ {name}`.
pub(crate) fn with(a: &HideSet, name: &Rc<str>) -> HideSet {
    union(a, &Some(Rc::new(vec![name.clone()])))
}
