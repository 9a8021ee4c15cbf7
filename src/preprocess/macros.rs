//! Macro definitions. Input: the tokens of a `#define` line after the
//! word `define`. Output: a [`Macro`] (or why the line is malformed), and
//! the table of defined macros.

use std::collections::HashMap;
use std::rc::Rc;

use super::token::{Kind, Token};

#[derive(Debug, Clone)]
pub(crate) struct Macro {
    pub name: Rc<str>,
    /// `None` for an object-like macro.
    pub params: Option<Vec<Rc<str>>>,
    /// The last parameter is `__VA_ARGS__` and takes the remaining arguments.
    pub variadic: bool,
    pub body: Vec<Token>,
}

impl Macro {
    pub fn param_index(&self, name: &str) -> Option<usize> {
        self.params.as_ref()?.iter().position(|p| &**p == name)
    }

    /// Same definition in the sense of C's "benign redefinition".
    pub fn same_as(&self, other: &Macro) -> bool {
        self.params == other.params
            && self.variadic == other.variadic
            && self.body.len() == other.body.len()
            && self
                .body
                .iter()
                .zip(&other.body)
                .enumerate()
                .all(|(i, (a, b))| a.text == b.text && (i == 0 || a.has_space() == b.has_space()))
    }
}

pub(crate) type Macros = HashMap<Rc<str>, Rc<Macro>>;

/// Why a `#define` is malformed, and which token to point at.
pub(crate) struct DefineError {
    pub at: Option<usize>,
    pub message: String,
}

/// Parses `NAME body` or `NAME(params) body`; `toks` starts at NAME.
pub(crate) fn parse_define(toks: &[Token]) -> Result<Macro, DefineError> {
    let Some(name_tok) = toks.first() else {
        return Err(DefineError {
            at: None,
            message: "#define needs a macro name".into(),
        });
    };
    if name_tok.kind != Kind::Ident {
        return Err(DefineError {
            at: Some(0),
            message: format!("macro names must be identifiers, not `{}`", name_tok.text),
        });
    }
    if &*name_tok.text == "defined" {
        return Err(DefineError {
            at: Some(0),
            message: "`defined` cannot be used as a macro name".into(),
        });
    }
    let mut i = 1;
    let mut params = None;
    let mut variadic = false;
    // Function-like only when `(` touches the name.
    if toks
        .get(1)
        .is_some_and(|t| t.is_punct("(") && !t.has_space())
    {
        let mut ps: Vec<Rc<str>> = Vec::new();
        i = 2;
        let bad = |at: usize, what: &str| DefineError {
            at: Some(at.min(toks.len() - 1)),
            message: format!(
                "bad parameter list in #define of `{}`: {what}",
                name_tok.text
            ),
        };
        if toks.get(i).is_some_and(|t| t.is_punct(")")) {
            i += 1;
        } else {
            loop {
                match toks.get(i) {
                    Some(t) if t.is_ident() => {
                        if ps.contains(&t.text) {
                            return Err(bad(i, &format!("`{}` appears twice", t.text)));
                        }
                        ps.push(t.text.clone());
                    }
                    Some(t) if t.is_punct("...") => {
                        ps.push(Rc::from("__VA_ARGS__"));
                        variadic = true;
                        if !toks.get(i + 1).is_some_and(|t| t.is_punct(")")) {
                            return Err(bad(i, "`...` must be the last parameter"));
                        }
                    }
                    Some(t) => {
                        return Err(bad(
                            i,
                            &format!("expected a parameter name, found `{}`", t.text),
                        ))
                    }
                    None => return Err(bad(i, "missing `)`")),
                }
                i += 1;
                match toks.get(i) {
                    Some(t) if t.is_punct(",") => i += 1,
                    Some(t) if t.is_punct(")") => {
                        i += 1;
                        break;
                    }
                    Some(t) => {
                        return Err(bad(i, &format!("expected `,` or `)`, found `{}`", t.text)))
                    }
                    None => return Err(bad(i, "missing `)`")),
                }
            }
        }
        params = Some(ps);
    }
    let mut body: Vec<Token> = toks.get(i..).unwrap_or(&[]).to_vec();
    for t in &mut body {
        t.bol = false;
        // Only whether there was whitespace matters inside a body.
        if t.has_space() {
            t.ws = Rc::from(" ");
        }
    }
    if let Some(first) = body.first_mut() {
        first.ws = Rc::from("");
    }
    Ok(Macro {
        name: name_tok.text.clone(),
        params,
        variadic,
        body,
    })
}
