//! The syntax tree of one source file: output of `parse`, input of
//! `resolve`. Every node carries its [`Span`]. Module names are still raw
//! runs of characters here (`FF`, `CAOCAOPM2`); resolve splits them.

use std::fmt::{self, Write};

use crate::source::Span;

/// One parsed file, statements in source order.
#[derive(Clone, Debug, Default)]
pub struct File {
    pub items: Vec<Item>,
    /// The first line of each statement that failed to parse (reported
    /// already), so that later stages do not report what its absence
    /// causes (an `else` that seems to have no earlier production).
    pub broken: Vec<Span>,
}

#[derive(Clone, Debug)]
pub enum Item {
    /// `#define` with one or more items (the paper's list form).
    Define(Vec<Define>),
    Include(Include),
    /// A `#word` line lsys does not know (cpfg preprocessor lines).
    OtherDirective {
        name: Ident,
        span: Span,
    },
    Header(Header),
    Production(Box<Production>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct Define {
    pub name: Ident,
    /// `NAME(a,b)`: a function-like define.
    pub params: Option<Vec<Ident>>,
    /// `None` for a declared parameter without a value (`#define NTL`).
    pub value: Option<Expr>,
    /// `NAME[lo..hi, ...]`: a table, with each dimension's index range.
    pub dims: Option<Vec<(i64, i64)>>,
    /// A table's braced values, flattened in row-major order, with the
    /// span of the braces.
    pub elems: Option<(Vec<Expr>, Span)>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum Include {
    /// `#include "file.lsys"`, relative to the including file.
    Path { path: String, span: Span },
    /// `#include <name>`: the embedded standard library.
    Std { name: String, span: Span },
    /// `#include MAn, MCa`: declares component surfaces.
    Components(Vec<Ident>),
}

#[derive(Clone, Debug)]
pub struct Header {
    pub kind: HeaderKind,
    /// The keyword, for labels.
    pub keyword: Span,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum HeaderKind {
    Lsystem(String),
    DerivationLength(Expr),
    Axiom(Vec<ModuleTok>),
    Ignore(Vec<PatTok>),
    Consider(Vec<PatTok>),
    Seed(Expr),
    MaximumDepth(Expr),
    Endlsystem,
    /// cpfg's `ring lsystem`: the string's ends are neighbours for context.
    Ring,
    Homomorphism,
    Decomposition,
    /// `module A(x), B`.
    Module(Vec<ModuleDecl>),
    /// cpfg statement blocks: `Start:`, `StartEach:`, `EndEach:`, `End:`
    /// and `define:` with their statements.
    Block(String, Block),
    /// `angle: θ` — the default turning angle in degrees.
    Angle(Expr),
    /// `step: d` — the default step length.
    Step(Expr),
    /// `width: w` — the initial line width.
    Width(Expr),
    /// `dialect: paper|cpfg`, with the name's span.
    Dialect(String, Span),
    /// `environment: NAME(key: value, ...)`: the text after the colon.
    Environment(String, Span),
    /// `colour i: #rrggbb`, with the colour's span.
    Colour(Expr, String, Span),
}

#[derive(Clone, Debug)]
pub struct ModuleDecl {
    pub name: Ident,
    pub params: Vec<Ident>,
    pub span: Span,
}

/// How a module token's name was written, which decides how resolve
/// splits it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TokKind {
    /// Letters, digits, `_`: split by longest match against the alphabet.
    Word,
    /// `@` + letters: split against the turtle's `@` commands.
    At,
    /// `?` + letters: a query module.
    Query,
    /// `~` + word: a component placement.
    Tilde,
    /// One punctuation character.
    Punct,
}

/// A run of module text with the parameter list that follows it (which
/// belongs to the last module once the run is split).
#[derive(Clone, Debug)]
pub struct ModuleTok {
    pub text: String,
    pub kind: TokKind,
    /// Span of the name run.
    pub name_span: Span,
    pub args: Option<Vec<Expr>>,
    /// Span of the whole token including arguments.
    pub span: Span,
}

/// An element of a predecessor or context: a module token or a bracket.
#[derive(Clone, Debug)]
pub enum PatTok {
    Module(ModuleTok),
    Open(Span),
    Close(Span),
}

#[derive(Clone, Debug)]
pub enum Condition {
    Expr(Expr),
    Else(Span),
    Always(Span),
}

#[derive(Clone, Debug)]
pub struct Production {
    pub lctx: Vec<PatTok>,
    pub pred: Vec<PatTok>,
    pub rctx: Vec<PatTok>,
    pub cond: Option<Condition>,
    /// cpfg statement block run before the condition (`: {x = 1;} x > 0`).
    pub pre: Option<Block>,
    /// cpfg statement block run once the condition holds.
    pub post: Option<Block>,
    /// The arrow, if the production was written with one.
    pub arrow: Option<Span>,
    pub succ: Vec<ModuleTok>,
    /// Span of the successor (empty span right after the arrow if none).
    pub succ_span: Span,
    pub prob: Option<Expr>,
    /// Span of the head (`lctx < pred > rctx`).
    pub head_span: Span,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Num(f64),
    Name(String),
    Unary(UnaryOp, Box<Expr>),
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    Ternary(Box<Expr>, Box<Expr>, Box<Expr>),
    Call(Ident, Vec<Expr>),
    /// `name[i,j]` or `name[i][j]` (tables).
    Index(Ident, Vec<Expr>),
    /// `"..."`, as written (with its quotes): an argument of `printf`.
    Str(String),
}

/// A braced list of cpfg's C-like statements.
#[derive(Clone, Debug)]
pub struct Block {
    pub stmts: Vec<CStmt>,
    pub span: Span,
}

/// One C-like statement.
#[derive(Clone, Debug)]
pub enum CStmt {
    /// `x = e;`, `a[i][j] += e;`.
    Assign {
        target: LValue,
        op: AssignOp,
        value: Expr,
        span: Span,
    },
    /// `e;` (a call such as `srand(3)` or `printf(...)`).
    Expr(Expr),
    If {
        cond: Expr,
        then: Vec<CStmt>,
        els: Vec<CStmt>,
        span: Span,
    },
    While {
        cond: Expr,
        body: Vec<CStmt>,
        span: Span,
    },
    DoWhile {
        body: Vec<CStmt>,
        cond: Expr,
        span: Span,
    },
    /// `array a[3] = {1,2,3}, b[2][2];`
    Array(Vec<ArrayDecl>),
}

/// The left-hand side of an assignment: a variable or an array element.
#[derive(Clone, Debug)]
pub struct LValue {
    pub name: Ident,
    pub index: Vec<Expr>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AssignOp {
    Set,
    Add,
    Sub,
    Mul,
    Div,
}

impl AssignOp {
    pub fn text(self) -> &'static str {
        match self {
            AssignOp::Set => "=",
            AssignOp::Add => "+=",
            AssignOp::Sub => "-=",
            AssignOp::Mul => "*=",
            AssignOp::Div => "/=",
        }
    }
}

/// `name[d1][d2] = { ... }` in an `array` statement; the initializer is
/// flattened in row-major order.
#[derive(Clone, Debug)]
pub struct ArrayDecl {
    pub name: Ident,
    pub dims: Vec<Expr>,
    pub init: Option<Vec<Expr>>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    Neg,
    Pos,
    Not,
}

/// Binary operators. `And` and `Or` short-circuit; comparisons and logic
/// yield 1.0 or 0.0. Shared by the AST and the resolved IR (`ir::BinOp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Pow,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    And,
    Or,
}

impl BinaryOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Rem => "%",
            BinaryOp::Pow => "^",
            BinaryOp::Lt => "<",
            BinaryOp::Le => "<=",
            BinaryOp::Gt => ">",
            BinaryOp::Ge => ">=",
            BinaryOp::Eq => "==",
            BinaryOp::Ne => "!=",
            BinaryOp::And => "&&",
            BinaryOp::Or => "||",
        }
    }
}

// ------------------------------------------------------------------ dump
//
// A compact, stable text form of the tree for snapshot tests: one item per
// line, expressions fully parenthesised, spans as `@start..end`.

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ExprKind::Num(n) => write!(f, "{n}"),
            ExprKind::Name(n) => write!(f, "{n}"),
            ExprKind::Unary(op, e) => {
                let s = match op {
                    UnaryOp::Neg => "-",
                    UnaryOp::Pos => "+",
                    UnaryOp::Not => "!",
                };
                write!(f, "({s}{e})")
            }
            ExprKind::Binary(op, a, b) => write!(f, "({a} {} {b})", op.symbol()),
            ExprKind::Ternary(c, a, b) => write!(f, "({c} ? {a} : {b})"),
            ExprKind::Call(n, args) => {
                write!(f, "{}(", n.name)?;
                comma_list(f, args)?;
                write!(f, ")")
            }
            ExprKind::Index(n, args) => {
                write!(f, "{}[", n.name)?;
                comma_list(f, args)?;
                write!(f, "]")
            }
            ExprKind::Str(s) => write!(f, "{s}"),
        }
    }
}

impl fmt::Display for Block {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{{")?;
        for s in &self.stmts {
            write!(f, " {s}")?;
        }
        write!(f, " }}")
    }
}

fn stmt_list(f: &mut fmt::Formatter<'_>, stmts: &[CStmt]) -> fmt::Result {
    write!(f, "{{")?;
    for s in stmts {
        write!(f, " {s}")?;
    }
    write!(f, " }}")
}

impl fmt::Display for CStmt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CStmt::Assign {
                target, op, value, ..
            } => {
                write!(f, "{}", target.name.name)?;
                for i in &target.index {
                    write!(f, "[{i}]")?;
                }
                write!(f, " {} {value};", op.text())
            }
            CStmt::Expr(e) => write!(f, "{e};"),
            CStmt::If {
                cond, then, els, ..
            } => {
                write!(f, "if {cond} ")?;
                stmt_list(f, then)?;
                if !els.is_empty() {
                    write!(f, " else ")?;
                    stmt_list(f, els)?;
                }
                Ok(())
            }
            CStmt::While { cond, body, .. } => {
                write!(f, "while {cond} ")?;
                stmt_list(f, body)
            }
            CStmt::DoWhile { body, cond, .. } => {
                write!(f, "do ")?;
                stmt_list(f, body)?;
                write!(f, " while {cond};")
            }
            CStmt::Array(ds) => {
                write!(f, "array")?;
                for (i, d) in ds.iter().enumerate() {
                    write!(f, "{} {}", if i > 0 { "," } else { "" }, d.name.name)?;
                    for e in &d.dims {
                        write!(f, "[{e}]")?;
                    }
                    if let Some(init) = &d.init {
                        write!(f, " = {{")?;
                        comma_list(f, init)?;
                        write!(f, "}}")?;
                    }
                }
                write!(f, ";")
            }
        }
    }
}

fn comma_list(f: &mut fmt::Formatter<'_>, args: &[Expr]) -> fmt::Result {
    for (i, a) in args.iter().enumerate() {
        if i > 0 {
            write!(f, ", ")?;
        }
        write!(f, "{a}")?;
    }
    Ok(())
}

impl fmt::Display for ModuleTok {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.kind {
            TokKind::Word => "",
            TokKind::At => "at:",
            TokKind::Query => "query:",
            TokKind::Tilde => "tilde:",
            TokKind::Punct => "",
        };
        write!(f, "{kind}{}", self.text)?;
        if let Some(args) = &self.args {
            write!(f, "(")?;
            comma_list(f, args)?;
            write!(f, ")")?;
        }
        Ok(())
    }
}

fn pats(out: &mut String, p: &[PatTok]) {
    for (i, t) in p.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        match t {
            PatTok::Module(m) => {
                let _ = write!(out, "{m}");
            }
            PatTok::Open(_) => out.push('['),
            PatTok::Close(_) => out.push(']'),
        }
    }
}

fn mods(out: &mut String, m: &[ModuleTok]) {
    for (i, t) in m.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        let _ = write!(out, "{t}");
    }
}

impl File {
    /// The snapshot form of the tree.
    pub fn dump(&self) -> String {
        let mut out = String::new();
        for item in &self.items {
            dump_item(&mut out, item);
            out.push('\n');
        }
        out
    }
}

fn dump_item(out: &mut String, item: &Item) {
    match item {
        Item::Define(ds) => {
            out.push_str("define");
            for d in ds {
                let _ = write!(out, " {}", d.name.name);
                if let Some(ps) = &d.params {
                    let names: Vec<_> = ps.iter().map(|p| p.name.as_str()).collect();
                    let _ = write!(out, "({})", names.join(","));
                }
                if let Some(dims) = &d.dims {
                    let ds: Vec<_> = dims.iter().map(|(lo, hi)| format!("{lo}..{hi}")).collect();
                    let _ = write!(out, "[{}]", ds.join(","));
                }
                match (&d.value, &d.elems) {
                    (Some(v), _) => {
                        let _ = write!(out, " = {v}");
                    }
                    (None, Some((es, _))) => {
                        let vs: Vec<_> = es.iter().map(|e| e.to_string()).collect();
                        let _ = write!(out, " = {{{}}}", vs.join(", "));
                    }
                    (None, None) => out.push_str(" = <none>"),
                }
                let _ = write!(out, " @{}..{};", d.span.start, d.span.end);
            }
        }
        Item::Include(Include::Path { path, span }) => {
            let _ = write!(out, "include \"{path}\" @{}..{}", span.start, span.end);
        }
        Item::Include(Include::Std { name, span }) => {
            let _ = write!(out, "include <{name}> @{}..{}", span.start, span.end);
        }
        Item::Include(Include::Components(cs)) => {
            let names: Vec<_> = cs.iter().map(|c| c.name.as_str()).collect();
            let _ = write!(out, "components {}", names.join(", "));
        }
        Item::OtherDirective { name, span } => {
            let _ = write!(
                out,
                "directive #{} @{}..{}",
                name.name, span.start, span.end
            );
        }
        Item::Header(h) => {
            let _ = write!(out, "@{}..{} ", h.span.start, h.span.end);
            match &h.kind {
                HeaderKind::Lsystem(l) => {
                    let _ = write!(out, "lsystem {l:?}");
                }
                HeaderKind::DerivationLength(e) => {
                    let _ = write!(out, "derivation length {e}");
                }
                HeaderKind::Axiom(m) => {
                    out.push_str("axiom ");
                    mods(out, m);
                }
                HeaderKind::Ignore(p) => {
                    out.push_str("ignore ");
                    pats(out, p);
                }
                HeaderKind::Consider(p) => {
                    out.push_str("consider ");
                    pats(out, p);
                }
                HeaderKind::Seed(e) => {
                    let _ = write!(out, "seed {e}");
                }
                HeaderKind::MaximumDepth(e) => {
                    let _ = write!(out, "maximum depth {e}");
                }
                HeaderKind::Endlsystem => out.push_str("endlsystem"),
                HeaderKind::Ring => out.push_str("ring lsystem"),
                HeaderKind::Homomorphism => out.push_str("homomorphism"),
                HeaderKind::Decomposition => out.push_str("decomposition"),
                HeaderKind::Module(ds) => {
                    out.push_str("module");
                    for d in ds {
                        let ps: Vec<_> = d.params.iter().map(|p| p.name.as_str()).collect();
                        let _ = write!(out, " {}({})", d.name.name, ps.join(","));
                    }
                }
                HeaderKind::Block(kw, b) => {
                    let _ = write!(out, "block {kw} {b}");
                }
                HeaderKind::Angle(e) => {
                    let _ = write!(out, "angle {e}");
                }
                HeaderKind::Step(e) => {
                    let _ = write!(out, "step {e}");
                }
                HeaderKind::Width(e) => {
                    let _ = write!(out, "width {e}");
                }
                HeaderKind::Dialect(d, _) => {
                    let _ = write!(out, "dialect {d}");
                }
                HeaderKind::Environment(e, _) => {
                    let _ = write!(out, "environment {}", e.trim());
                }
                HeaderKind::Colour(i, hex, _) => {
                    let _ = write!(out, "colour {i} {hex}");
                }
            }
        }
        Item::Production(p) => {
            let _ = write!(out, "@{}..{} production ", p.span.start, p.span.end);
            if !p.lctx.is_empty() {
                pats(out, &p.lctx);
                out.push_str(" < ");
            }
            pats(out, &p.pred);
            if !p.rctx.is_empty() {
                out.push_str(" > ");
                pats(out, &p.rctx);
            }
            if let Some(b) = &p.pre {
                let _ = write!(out, " : pre {b}");
            }
            match &p.cond {
                Some(Condition::Expr(e)) => {
                    let _ = write!(out, " : {e}");
                }
                Some(Condition::Else(_)) => out.push_str(" : else"),
                Some(Condition::Always(_)) => out.push_str(" : *"),
                None => {}
            }
            if let Some(b) = &p.post {
                let _ = write!(out, " : post {b}");
            }
            out.push_str(if p.arrow.is_some() { " --> " } else { " :: " });
            mods(out, &p.succ);
            if let Some(e) = &p.prob {
                let _ = write!(out, " : {e}");
            }
        }
    }
}
