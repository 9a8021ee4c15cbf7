//! The syntax tree of one source file: output of `parse`, input of
//! `resolve`. Every node carries its [`Span`]. Module names are still raw
//! runs of characters here (`FF`, `CAOCAOPM2`); resolve splits them.
//! `print.rs` writes the tree back as text.

use crate::source::Span;

/// One parsed file, statements in source order.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct File {
    pub items: Vec<Item>,
    /// The first line of each statement that failed to parse (reported
    /// already), so that later stages do not report what its absence
    /// causes (an `else` that seems to have no earlier production).
    pub broken: Vec<Span>,
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum Include {
    /// `#include "file.lsys"`, relative to the including file.
    Path { path: String, span: Span },
    /// `#include <name>`: the embedded standard library.
    Std { name: String, span: Span },
    /// `#include MAn, MCa`: declares component surfaces.
    Components(Vec<Ident>),
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Header {
    pub kind: HeaderKind,
    /// The keyword, for labels.
    pub keyword: Span,
    pub span: Span,
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum HeaderKind {
    Lsystem(String),
    DerivationLength(Expr),
    Axiom(Vec<ModuleTok>),
    /// An axiom line of over 1 MiB: the spans of its pieces, each parsed
    /// again by [`crate::parse::axiom_piece`] when it is used, so that the
    /// whole line's tokens (80 bytes and more a module) never exist at
    /// once (issue 36).
    LongAxiom(Vec<Span>),
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
    /// `texture i: "file.png"`: the file name (unquoted) and its span.
    Texture(Expr, String, Span),
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct ModuleDecl {
    pub name: Ident,
    pub params: Vec<Ident>,
    pub span: Span,
}

/// How a module token's name was written, which decides how resolve
/// splits it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum PatTok {
    Module(ModuleTok),
    Open(Span),
    Close(Span),
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum Condition {
    Expr(Expr),
    Else(Span),
    Always(Span),
}

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Block {
    pub stmts: Vec<CStmt>,
    pub span: Span,
}

/// One C-like statement.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct LValue {
    pub name: Ident,
    pub index: Vec<Expr>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct ArrayDecl {
    pub name: Ident,
    pub dims: Vec<Expr>,
    pub init: Option<Vec<Expr>>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum UnaryOp {
    Neg,
    Pos,
    Not,
}

/// Binary operators. `And` and `Or` short-circuit; comparisons and logic
/// yield 1.0 or 0.0. Shared by the AST and the resolved IR (`ir::BinOp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
