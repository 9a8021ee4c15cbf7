//! Macro expansion (Prosser's hide-set algorithm, as in C). Input: a queue
//! of tokens and, at the top level, a way to pull the next text line of
//! the file when a function-like invocation needs it. Output: the expanded
//! tokens; expansion results sit on the line of their invocation.

use std::collections::VecDeque;
use std::ops::Range;
use std::rc::Rc;

use super::error::{ErrorKind, PreprocessError};
use super::lexer::lex_fragment;
use super::macros::{Macro, Macros};
use super::token::{intersect, union, with, HideSet, Kind, Token};

/// Where more tokens come from once the queue runs dry (the next text line
/// of the file); `None` when there are no more (end of file, a directive
/// line, or an expansion that must stay within its tokens).
pub(crate) type More<'m> = &'m mut dyn FnMut() -> Option<Vec<Token>>;

pub(crate) struct Expander<'a> {
    pub macros: &'a Macros,
    pub errors: &'a mut Vec<PreprocessError>,
    pub file: usize,
    pub file_name: &'a str,
    pub max_depth: usize,
    /// How many more tokens expansions may produce in this file; guards
    /// against exponential growth (`#define A B B`, `#define B C C`, ...).
    pub budget: &'a mut usize,
}

fn no_more() -> Option<Vec<Token>> {
    None
}

impl Expander<'_> {
    fn error(
        &mut self,
        kind: ErrorKind,
        span: Range<usize>,
        message: String,
    ) -> &mut PreprocessError {
        self.errors
            .push(PreprocessError::new(kind, self.file, span, message));
        let n = self.errors.len() - 1;
        &mut self.errors[n]
    }

    /// Expands everything in `q` (and whatever `more` supplies while an
    /// invocation is incomplete).
    pub fn expand(&mut self, mut q: VecDeque<Token>, more: More<'_>, depth: usize) -> Vec<Token> {
        let mut out = Vec::with_capacity(q.len());
        while let Some(t) = q.pop_front() {
            if t.kind != Kind::Ident || t.hidden(&t.text) || *self.budget == 0 {
                out.push(t);
                continue;
            }
            let Some(m) = self.macros.get(&t.text).cloned() else {
                out.push(self.builtin(t));
                continue;
            };
            if m.params.is_none() {
                let hs = with(&t.hide, &m.name);
                let span = t.span.clone();
                let res = self.subst(&m, &t, span, &[], &hs, depth);
                self.push_front(&mut q, res);
                continue;
            }
            // A function-like macro name is only an invocation when `(` follows,
            // possibly on a later line.
            let mut pulled = 0;
            if q.is_empty() {
                if let Some(line) = more() {
                    pulled = line.len();
                    q.extend(line);
                }
            }
            if !q.front().is_some_and(|n| n.is_punct("(")) {
                out.push(t);
                continue;
            }
            // Like GNU cpp, a multi-line invocation and the rest of its last
            // line are output on the line of the macro's name.
            for n in q.iter_mut().take(pulled) {
                n.line = t.line;
            }
            match self.collect_args(&m, &t, &mut q, more) {
                Ok((args, rparen)) => {
                    let hs = with(&intersect(&t.hide, &rparen.hide), &m.name);
                    let span = t.span.start..rparen.span.end.max(t.span.start);
                    let res = self.subst(&m, &t, span, &args, &hs, depth);
                    self.push_front(&mut q, res);
                }
                Err(consumed) => {
                    // Leave the name and its would-be arguments as they are.
                    let mut t = t;
                    t.hide = with(&t.hide, &m.name);
                    out.push(t);
                    for c in consumed.into_iter().rev() {
                        q.push_front(c);
                    }
                }
            }
        }
        out
    }

    /// `__LINE__` and `__FILE__` (when not `#define`d).
    fn builtin(&self, t: Token) -> Token {
        let (kind, text) = match &*t.text {
            "__LINE__" => (Kind::Number, (t.line + 1).to_string()),
            "__FILE__" => (Kind::Str, format!("\"{}\"", escape(self.file_name))),
            _ => return t,
        };
        Token {
            kind,
            text: Rc::from(text),
            pad: true,
            ..t
        }
    }

    fn push_front(&mut self, q: &mut VecDeque<Token>, res: Vec<Token>) {
        if let Some(next) = q.front_mut() {
            next.pad = true;
        }
        if *self.budget == 0 {
            // Already reported; what is left is not expanded any more.
        } else if res.len() >= *self.budget {
            *self.budget = 0;
            let span = res.first().map_or(0..0, |t| t.span.clone());
            self.error(
                ErrorKind::Recursion,
                span,
                "macro expansion grows without bound; the rest is left unexpanded".into(),
            )
            .help = Some("look for macros whose bodies use other macros several times over".into());
        } else {
            *self.budget -= res.len();
        }
        for t in res.into_iter().rev() {
            q.push_front(t);
        }
    }

    /// Reads `( args )` after a function-like macro's name. On failure the
    /// error is reported and the tokens read are handed back.
    #[allow(clippy::type_complexity)]
    fn collect_args(
        &mut self,
        m: &Macro,
        name: &Token,
        q: &mut VecDeque<Token>,
        more: More<'_>,
    ) -> Result<(Vec<Vec<Token>>, Token), Vec<Token>> {
        let nparams = m.params.as_ref().map_or(0, |p| p.len());
        let mut consumed: Vec<Token> = Vec::new();
        if let Some(lp) = q.pop_front() {
            consumed.push(lp);
        }
        let mut args: Vec<Vec<Token>> = vec![Vec::new()];
        let mut nest = 0usize;
        let rparen = loop {
            let Some(t) = q.pop_front() else {
                match more() {
                    Some(line) => {
                        q.extend(line.into_iter().map(|mut n| {
                            n.line = name.line;
                            n
                        }));
                        continue;
                    }
                    None => {
                        self.error(
                            ErrorKind::UnterminatedCall,
                            name.span.clone(),
                            format!("unterminated argument list invoking macro `{}`", m.name),
                        )
                        .help = Some(
                            "close the argument list with `)` (an invocation may span lines, but not a directive or the end of the file)"
                                .into(),
                        );
                        return Err(consumed);
                    }
                }
            };
            consumed.push(t.clone());
            if t.is_punct("(") {
                nest += 1;
            } else if t.is_punct(")") {
                if nest == 0 {
                    break t;
                }
                nest -= 1;
            } else if t.is_punct(",") && nest == 0 && !(m.variadic && args.len() >= nparams) {
                args.push(Vec::new());
                continue;
            }
            if let Some(a) = args.last_mut() {
                a.push(t);
            }
        };
        if nparams == 0 && args.len() == 1 && args[0].is_empty() {
            args.clear();
        }
        if m.variadic && args.len() + 1 == nparams {
            args.push(Vec::new());
        }
        if args.len() != nparams {
            let given = args.len();
            let params = m.params.as_ref().map(|p| p.join(", ")).unwrap_or_default();
            self.error(
                ErrorKind::MacroArgs,
                name.span.start..rparen.span.end.max(name.span.start),
                format!(
                    "macro `{}` takes {} argument{}, but {} {} given",
                    m.name,
                    nparams,
                    if nparams == 1 { "" } else { "s" },
                    given,
                    if given == 1 { "was" } else { "were" }
                ),
            )
            .help = Some(format!(
                "it is defined as `{}({params})`; commas inside parentheses do not separate arguments",
                m.name
            ));
            return Err(consumed);
        }
        Ok((args, rparen))
    }

    /// The body of `m` with arguments substituted, `#` and `##` applied,
    /// placed at the invocation (`name`, `span`) and hidden from `hs`.
    fn subst(
        &mut self,
        m: &Macro,
        name: &Token,
        span: Range<usize>,
        args: &[Vec<Token>],
        hs: &HideSet,
        depth: usize,
    ) -> Vec<Token> {
        let body = &m.body;
        let fnlike = m.params.is_some();
        let param = |t: &Token| {
            if t.is_ident() {
                m.param_index(&t.text).filter(|&p| p < args.len())
            } else {
                None
            }
        };
        let is_paste = |i: usize| i > 0 && i + 1 < body.len() && body[i].is_punct("##");
        let mut expanded: Vec<Option<Vec<Token>>> = vec![None; args.len()];
        let mut out: Vec<Token> = Vec::with_capacity(body.len());
        let mut glue = false;
        let mut pad_next = false;
        let mut i = 0;
        while i < body.len() {
            if is_paste(i) {
                glue = true;
                i += 1;
                continue;
            }
            let bt = &body[i];
            let mut from_arg = false;
            let mut va_placemarker = false;
            let mut item: Vec<Token> =
                if fnlike && bt.is_punct("#") && body.get(i + 1).and_then(param).is_some() {
                    let p = body.get(i + 1).and_then(param).unwrap_or(0);
                    i += 2;
                    vec![stringify(&args[p], bt)]
                } else if let Some(p) = param(bt) {
                    i += 1;
                    from_arg = true;
                    if glue || is_paste(i) {
                        if args[p].is_empty() {
                            va_placemarker = m.variadic && p + 1 == args.len();
                            vec![Token {
                                kind: Kind::Placemarker,
                                text: Rc::from(""),
                                ..bt.clone()
                            }]
                        } else {
                            args[p].clone()
                        }
                    } else {
                        if expanded[p].is_none() {
                            expanded[p] = Some(self.expand_arg(&args[p], depth));
                        }
                        expanded[p].clone().unwrap_or_default()
                    }
                } else {
                    i += 1;
                    vec![bt.clone()]
                };
            if let Some(first) = item.first_mut() {
                if from_arg {
                    first.ws = bt.ws.clone();
                    first.pad = true;
                } else if pad_next {
                    first.pad = true;
                }
            }
            pad_next = from_arg;
            if glue {
                glue = false;
                if va_placemarker && out.last().is_some_and(|t| t.is_punct(",")) {
                    // GNU `, ## __VA_ARGS__`: the comma goes when there are no variable arguments.
                    out.pop();
                    continue;
                }
                let rest = if item.is_empty() {
                    Vec::new()
                } else {
                    item.split_off(1)
                };
                match (out.pop(), item.pop()) {
                    (Some(l), Some(r)) => out.extend(paste(l, r)),
                    (l, r) => out.extend(l.into_iter().chain(r)),
                }
                out.extend(rest);
            } else {
                out.extend(item);
            }
        }
        out.retain(|t| t.kind != Kind::Placemarker);
        for (k, t) in out.iter_mut().enumerate() {
            t.hide = union(&t.hide, hs);
            t.line = name.line;
            t.span = span.clone();
            t.bol = false;
            if k == 0 {
                t.ws = name.ws.clone();
                t.pad = true;
            } else if t.has_space() {
                t.ws = Rc::from(" ");
            }
        }
        out
    }

    /// An argument fully macro-expanded on its own, before substitution.
    fn expand_arg(&mut self, arg: &[Token], depth: usize) -> Vec<Token> {
        if depth >= self.max_depth {
            if let Some(t) = arg.first() {
                self.error(
                    ErrorKind::Recursion,
                    t.span.clone(),
                    format!(
                        "macro arguments nested more than {} deep; left unexpanded",
                        self.max_depth
                    ),
                );
                *self.budget = 0;
            }
            return arg.to_vec();
        }
        let mut none = no_more;
        self.expand(arg.iter().cloned().collect(), &mut none, depth + 1)
    }
}

/// `#x`: the argument's spelling as a string literal.
fn stringify(arg: &[Token], hash: &Token) -> Token {
    let mut s = String::from("\"");
    for (k, t) in arg.iter().enumerate() {
        if k > 0 && t.has_space() {
            s.push(' ');
        }
        if t.kind == Kind::Str {
            s.push_str(&escape(&t.text));
        } else {
            s.push_str(&t.text);
        }
    }
    s.push('"');
    Token {
        kind: Kind::Str,
        text: Rc::from(s),
        pad: true,
        ..hash.clone()
    }
}

fn escape(s: &str) -> String {
    s.replace('\\', "\\\\").replace('"', "\\\"")
}

/// `l ## r`: the two spellings joined and lexed again. Unlike GNU cpp, a
/// join that is not one token is not an error: its tokens are kept.
fn paste(l: Token, r: Token) -> Vec<Token> {
    if l.kind == Kind::Placemarker {
        return vec![r];
    }
    if r.kind == Kind::Placemarker {
        return vec![l];
    }
    let joined = format!("{}{}", l.text, r.text);
    let mut toks = lex_fragment(&joined, l.span.clone(), l.line);
    if toks.is_empty() {
        // e.g. `/ ## /` lexes as a comment; keep the two tokens instead.
        return vec![l, r];
    }
    let hide = union(&l.hide, &r.hide);
    for t in &mut toks {
        t.hide = hide.clone();
    }
    if let Some(first) = toks.first_mut() {
        first.ws = l.ws.clone();
    }
    toks
}
