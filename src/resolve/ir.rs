//! The resolved program: output of `resolve`, input of `bytecode` and
//! `derive`. Every name is bound (modules to [`SymId`]s, expression names to
//! parameter slots or inlined `#define` values), every arity checked, and
//! constants folded. Nothing here refers back to the AST.

use std::collections::HashMap;
use std::sync::Arc;

use crate::source::{SourceMap, Span};

/// Index of a module symbol in [`Symbols`].
pub type SymId = u32;

/// Symbol 0 is always `[` and symbol 1 always `]`, so the engine can test
/// for brackets without a lookup.
pub const OPEN_BRACKET: SymId = 0;
pub const CLOSE_BRACKET: SymId = 1;

/// What a module symbol is, which decides how the turtle treats it and
/// how strictly the checker treats its arity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SymbolKind {
    /// A name the grammar defines (a predecessor, or a declared module).
    User,
    /// A turtle command from the command table (`F`, `+`, `@O`, ...).
    Turtle,
    /// A component placement `~X` (a surface, OBJ model or sub-grammar).
    Component,
    /// A query module `?P`, `?H`, ... (filled by interpretation, later).
    Query,
    /// A name that appears only in successors or the axiom, with no
    /// production, declaration or turtle meaning (cpfg's inert letters).
    Inert,
}

#[derive(Clone, Debug)]
pub struct Symbol {
    pub name: String,
    pub kind: SymbolKind,
    /// Where the name was first seen, for "declared here" labels.
    pub span: Option<Span>,
}

/// The grammar's alphabet.
#[derive(Clone, Debug, Default)]
pub struct Symbols {
    pub list: Vec<Symbol>,
    pub by_name: HashMap<String, SymId>,
}

impl Symbols {
    pub fn name(&self, id: SymId) -> &str {
        &self.list[id as usize].name
    }

    pub fn get(&self, name: &str) -> Option<SymId> {
        self.by_name.get(name).copied()
    }

    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }
}

/// A resolved, constant-folded expression on f64.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

/// Sub-expressions are shared (`Arc`, not `Box`): a define's expansion is
/// one tree that every use of the define points at, so a Pailou's
/// thousands of uses of its defines are not thousands of copies.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Num(f64),
    /// A bound parameter: index into the production's bindings (see
    /// [`Production::nparams`]).
    Param(u16),
    Unary(UnOp, Arc<Expr>),
    /// `And` and `Or` short-circuit; comparisons and logic yield 1.0 or 0.0.
    Binary(BinOp, Arc<Expr>, Arc<Expr>),
    /// `c ? a : b` (cpfg's C heritage).
    Cond(Arc<Expr>, Arc<Expr>, Arc<Expr>),
    Call(Func, Vec<Expr>),
    /// `NAME[i, j, ...]`: an element of table [`Program::tables`]`[id]`.
    Index(u32, Vec<Expr>),
    /// A variable of cpfg's C-like statements: slot in [`Program::vars`].
    Var(u32),
    /// `a[i][j]`: an element of array [`Program::arrays`]`[id]`.
    Elem(u32, Vec<Expr>),
    /// cpfg's two-argument random functions (`nran`, `bran`, `biran`),
    /// drawn from the derivation's generator as cpfg draws them.
    Random(RandFn, Arc<Expr>, Arc<Expr>),
    /// `srand(seed)`: reseed the generator; yields 0.
    Srand(Arc<Expr>),
    /// cpfg's `func(id, x)`: function [`Program::functions`]`[index]` at x.
    Spline(u32, Arc<Expr>),
}

/// A cpfg C-like statement, resolved.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `target = value` (compound assignments are expanded: `x += 1` is
    /// `x = x + 1`).
    Set {
        target: Target,
        value: Expr,
    },
    /// An expression evaluated for its effect (`srand(3);`).
    Eval(Expr),
    If(Expr, Vec<Stmt>, Vec<Stmt>),
    While(Expr, Vec<Stmt>),
    DoWhile(Vec<Stmt>, Expr),
}

/// Where an assignment stores.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    Var(u32, Span),
    Elem(u32, Vec<Expr>, Span),
}

/// A variable slot: a global (statement blocks of the L-system), a
/// production's own, or one element of an array.
#[derive(Clone, Debug, PartialEq)]
pub struct VarInfo {
    pub name: String,
    pub span: Span,
}

/// `array name[d1][d2]`: `len` slots from `base` in the variables, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct ArrayInfo {
    pub name: String,
    pub dims: Vec<usize>,
    pub base: u32,
    pub span: Span,
}

/// cpfg's statement blocks of the L-system, run by the derivation:
/// `Start:` before the axiom is evaluated, `StartEach:` / `EndEach:` around
/// every step, `End:` after the last one.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Hooks {
    pub start: Vec<Stmt>,
    pub start_each: Vec<Stmt>,
    pub end_each: Vec<Stmt>,
    pub end: Vec<Stmt>,
}

impl Hooks {
    pub fn is_empty(&self) -> bool {
        self.start.is_empty()
            && self.start_each.is_empty()
            && self.end_each.is_empty()
            && self.end.is_empty()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Not,
}

/// Binary operators: the parser's enum, used unchanged by every stage.
pub use crate::parse::ast::BinaryOp as BinOp;

pub use crate::lang::builtins::{Func, RandFn};

/// One module of a predecessor or context pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct PatModule {
    pub sym: SymId,
    /// Number of formal parameters; a pattern matches only modules with
    /// exactly this many parameters (cpfg's rule).
    pub arity: u8,
    /// Binding slot of the first formal parameter; the others follow.
    pub first_param: u16,
    pub span: Span,
}

/// One element of a context pattern. Brackets occur only in right contexts.
#[derive(Clone, Debug, PartialEq)]
pub enum PatItem {
    Module(PatModule),
    Open(Span),
    Close(Span),
}

#[derive(Clone, Debug, PartialEq)]
pub enum Cond {
    /// No condition, or `*`.
    Always,
    /// `else`: applies when no earlier production for this predecessor
    /// matched. With first-match semantics that is "always" at run time;
    /// the checker makes sure an earlier conditional production exists.
    Else(Span),
    Expr(Expr),
}

/// One module a successor (or the axiom) writes.
#[derive(Clone, Debug, PartialEq)]
pub struct SuccModule {
    pub sym: SymId,
    /// A thin vector (one pointer; none allocated when empty), not a
    /// `Vec`: 24 bytes a module instead of 40, for axioms of millions of
    /// modules (issue 36).
    pub args: thin_vec::ThinVec<Expr>,
    pub span: Span,
}

/// Which table a production belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Table {
    /// Ordinary productions, applied in parallel once per derivation step.
    Main,
    /// Applied recursively after every step (and to the axiom).
    Decomposition,
    /// Applied recursively to produce the string the turtle interprets;
    /// never fed back into the derivation.
    Homomorphism,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Production {
    pub table: Table,
    /// The label of the L-system it belongs to ([`Program::main_lsystem`]
    /// unless the file has sub-L-systems).
    pub lsystem: u32,
    /// The whole production, for runtime error labels.
    pub span: Span,
    /// The strict predecessor's source text span, e.g. `A(x)`.
    pub head_span: Span,
    /// Left context, left to right as written (matched right to left).
    pub lctx: Vec<PatModule>,
    /// Strict predecessor: one or more consecutive modules.
    pub pred: Vec<PatModule>,
    /// Right context, left to right, possibly with brackets.
    pub rctx: Vec<PatItem>,
    /// Total binding slots: formal parameters of lctx, then pred, then
    /// rctx, in that order.
    pub nparams: u16,
    /// Names of the binding slots, for the disassembler and errors.
    pub param_names: Vec<String>,
    pub cond: Cond,
    /// Empty means the predecessor is erased.
    pub succ: Vec<SuccModule>,
    /// Relative weight in a stochastic choice.
    pub prob: Option<Expr>,
    /// cpfg's statements before the condition and once it holds.
    pub pre: Vec<Stmt>,
    pub post: Vec<Stmt>,
}

impl Production {
    pub fn has_context(&self) -> bool {
        !self.lctx.is_empty() || !self.rctx.is_empty()
    }
}

/// A `#define` after overrides, for `:defines` in the REPL and for docs.
#[derive(Clone, Debug, PartialEq)]
pub struct DefineInfo {
    pub name: String,
    /// The folded value when it is a constant.
    pub value: Option<f64>,
    pub span: Span,
    /// Whether `-D` replaced the file's value.
    pub overridden: bool,
}

/// Which modules context matching looks at.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum ContextFilter {
    #[default]
    All,
    /// `ignore:` these symbols are skipped.
    Ignore(Vec<SymId>),
    /// `consider:` only these symbols are looked at.
    Consider(Vec<SymId>),
}

/// The whole resolved grammar.
#[derive(Clone, Debug)]
pub struct Program {
    pub sources: SourceMap,
    pub symbols: Symbols,
    pub axiom: Vec<SuccModule>,
    /// Steps to derive when the user does not say (`derivation length:`).
    pub derivation_length: u32,
    /// Whether the file says `derivation length:` (0 steps without it).
    pub derivation_length_given: bool,
    /// `seed:`; the user's `--seed` wins.
    pub seed: Option<u64>,
    /// cpfg's `ring lsystem`: context matching wraps around the string's
    /// ends (the last module is the first one's left neighbour).
    pub ring: bool,
    /// The label of the file's first L-system (`Lsystem: 1`, else 0) and
    /// of the sub-L-systems after it, which `?(n, scale) ... $` calls: a
    /// module between them is rewritten by L-system n's productions.
    pub main_lsystem: u32,
    pub sub_lsystems: Vec<u32>,
    pub context: ContextFilter,
    pub productions: Vec<Production>,
    pub decomposition: Vec<Production>,
    pub homomorphism: Vec<Production>,
    /// `maximum depth:` of the decomposition and homomorphism sections.
    pub decomposition_depth: u32,
    pub homomorphism_depth: u32,
    pub defines: Vec<DefineInfo>,
    /// The language profile the loader decided (dialect and all it implies).
    pub profile: crate::lang::Profile,
    /// The turtle headers (`angle:`, `step:`, ...).
    pub turtle: TurtleSettings,
    /// Tables (`#define NAME[dims] {...}`), indexed by [`ExprKind::Index`].
    pub tables: Vec<TableDef>,
    /// Variables of the C-like statements with their initial values
    /// (0, or an array's initializer).
    pub vars: Vec<VarInfo>,
    pub var_init: Vec<f64>,
    pub arrays: Vec<ArrayInfo>,
    pub hooks: Hooks,
    /// The functions of a cpfg model's view file (`func(id, x)`).
    pub functions: Vec<crate::lang::spline::SplineFn>,
    /// The cpfg surfaces a model's view file names (`surface: NAME ...`):
    /// `~NAME` draws one.
    pub cpfg_surfaces: Vec<crate::load::CpfgSurface>,
    /// The environment that answers `?E` (a cpfg model's `-e FILE.e`).
    pub environment: Option<crate::environment::EnvironmentSpec>,
}

/// A table of constants: `#define dec[1..3, 1..2, 0..7] {...}`.
#[derive(Clone, Debug, PartialEq)]
pub struct TableDef {
    pub name: String,
    /// Each dimension's first and last index.
    pub dims: Vec<(i64, i64)>,
    /// Row-major: the last index varies fastest.
    pub values: Vec<f64>,
    pub span: Span,
    /// Some element was set with `-D NAME[...]=v` or `-D NAME={...}`.
    pub overridden: bool,
}

impl TableDef {
    /// (first index, count) per dimension, as the VM reads them.
    pub fn bounds(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.dims
            .iter()
            .map(|&(lo, hi)| (lo as f64, (hi - lo + 1) as f64))
    }

    /// The number of elements.
    pub fn size(dims: &[(i64, i64)]) -> usize {
        dims.iter()
            .map(|&(lo, hi)| (hi - lo + 1) as usize)
            .product()
    }

    /// `dims` as text, e.g. `[1..3, 0..7]`.
    pub fn dims_text(&self) -> String {
        let d: Vec<String> = self
            .dims
            .iter()
            .map(|(lo, hi)| format!("{lo}..{hi}"))
            .collect();
        format!("[{}]", d.join(", "))
    }
}

/// An image `texture i: "file"` names, read when the grammar is compiled.
#[derive(Clone, PartialEq)]
pub struct Texture {
    pub index: usize,
    /// The file name as written (the glTF image's name).
    pub name: String,
    /// `image/png` or `image/jpeg`, from the file's first bytes.
    pub mime: &'static str,
    pub bytes: std::sync::Arc<Vec<u8>>,
}

/// The bytes are not shown (a photograph is megabytes).
impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Texture({} {:?}, {}, {} bytes)",
            self.index,
            self.name,
            self.mime,
            self.bytes.len()
        )
    }
}

/// What the file's turtle headers say; `None` where a header is absent, so
/// that the command line and the turtle's defaults can fill in.
#[derive(Clone, Debug, Default)]
pub struct TurtleSettings {
    /// `angle:` in degrees.
    pub angle: Option<f64>,
    /// `step:`.
    pub step: Option<f64>,
    /// `width:`.
    pub width: Option<f64>,
    /// `colour i: #rrggbb` entries, sRGB 0..=1, in file order.
    pub palette: Vec<(usize, [f32; 3])>,
    /// `texture i: "file"` entries, in file order (resolve/textures.rs).
    pub textures: Vec<Texture>,
    /// The turtle's first colour index (a cpfg view file's `initial
    /// color:`); 0 without it.
    pub colour: Option<u32>,
    /// What `#` and `!` without a parameter add and take away (a cpfg
    /// view file's `line width increment:`); a tenth of the width without.
    pub width_increment: Option<f64>,
    /// Line widths are cpfg screen pixels, not model units (a cpfg view
    /// file without `initial line width:`, or with `p` after it).
    pub pixel_lines: bool,
    /// The cross-sections of a cpfg view file's `contour:` lines, which
    /// `@#(id)` selects for generalized cylinders.
    pub contours: Vec<crate::load::Contour>,
    /// A cpfg model whose view file gives its bounding box (`box:`):
    /// cpfg then computes no view volume, the interpretation that
    /// otherwise sets the final string's `?P`, `?H`, ... and draws the
    /// homomorphism's random numbers before the string is printed.
    pub view_box: bool,
}

impl Program {
    pub fn table(&self, t: Table) -> &[Production] {
        match t {
            Table::Main => &self.productions,
            Table::Decomposition => &self.decomposition,
            Table::Homomorphism => &self.homomorphism,
        }
    }

    /// Whether context matching is needed by any main production.
    pub fn has_context(&self) -> bool {
        self.productions.iter().any(Production::has_context)
    }

    /// Whether context matching skips this symbol.
    /// Brackets come out skipped when `consider:` does not list them (or
    /// `ignore:` does): cpfg then reads context straight through branches;
    /// the engine honours that in the cpfg dialect only.
    pub fn skips_in_context(&self, sym: SymId) -> bool {
        match &self.context {
            ContextFilter::All => false,
            ContextFilter::Ignore(v) => v.contains(&sym),
            ContextFilter::Consider(v) => !v.contains(&sym),
        }
    }
}
