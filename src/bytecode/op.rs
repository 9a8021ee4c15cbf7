//! The instruction set: [`Op`], the [`Chunk`] of code one expression or
//! successor compiles to, and the [`Compiled`] program (all chunks plus the
//! shared constant pool). Input: nothing (pure data); output: the types the
//! compiler fills and the VM runs.
//!
//! The machine is a stack machine on `f64`. Every chunk ends with [`Op::Ret`].
//! A condition or probability chunk leaves its value on top of the stack;
//! a successor chunk leaves the stack empty and writes modules with
//! [`Op::Emit`] / [`Op::EmitConst`]. Jump targets are absolute instruction
//! indices in the same chunk. Truth is C's: zero is false, anything else
//! (NaN included) is true; logic and comparisons produce `1.0` or `0.0`.

use crate::resolve::{Func, RandFn, SymId};
use crate::source::Span;

/// One instruction. Operands are indices, never pointers, so chunks are
/// plain data that can be printed, compared and cached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    /// Push `consts[idx]` from the constant pool of [`Compiled`].
    Const(u32),
    /// Push binding slot `slot` of the production being applied (left
    /// context parameters, then strict predecessor, then right context;
    /// see `Production::nparams`).
    Param(u16),
    /// Pop `a`, push `-a`.
    Neg,
    /// Pop `a`, push `1` if `a == 0`, else `0`.
    Not,
    /// Pop `b`, pop `a`, push `a + b`.
    Add,
    /// Pop `b`, pop `a`, push `a - b`.
    Sub,
    /// Pop `b`, pop `a`, push `a * b`.
    Mul,
    /// Pop `b`, pop `a`, push `a / b`; fault `division by zero` when `b == 0`.
    Div,
    /// Pop `b`, pop `a`, push C's `fmod(a, b)` (sign of `a`); fault when `b == 0`.
    Rem,
    /// Pop `b`, pop `a`, push `a` raised to `b` (`powf`).
    Pow,
    /// Pop `b`, pop `a`, push `1` if `a < b`, else `0`.
    Lt,
    /// Pop `b`, pop `a`, push `1` if `a <= b`, else `0`.
    Le,
    /// Pop `b`, pop `a`, push `1` if `a > b`, else `0`.
    Gt,
    /// Pop `b`, pop `a`, push `1` if `a >= b`, else `0`.
    Ge,
    /// Pop `b`, pop `a`, push `1` if `a == b` (exact), else `0`.
    Eq,
    /// Pop `b`, pop `a`, push `1` if `a != b`, else `0`.
    Ne,
    /// Continue at instruction `target`.
    Jump(u32),
    /// Pop `a`; continue at `target` if `a == 0`.
    JumpIfFalse(u32),
    /// Pop `a`; continue at `target` if `a != 0`.
    JumpIfTrue(u32),
    /// Pop the function's arguments (first argument deepest), push its
    /// result. Trigonometry is in degrees (`sin(90) = 1`, `atan2(y, x)`
    /// in degrees), `log` is natural, `sign` gives -1, 0 or 1. Never
    /// [`Func::Ran`], which has its own instruction.
    Call(Func),
    /// Pop one index per dimension of table `table` (the first index
    /// deepest) and push the element. `desc` is where the table sits in
    /// the constant pool: the number of dimensions n, then (first index,
    /// count) for each dimension, then the values in row-major order.
    /// Faults `table index` when an index is outside its range or not a
    /// whole number.
    Index { table: u32, desc: u32 },
    /// `ran(x)`: pop `x`, push `x * u` with `u` uniform in `[0, 1)` drawn
    /// from the derivation's generator (one draw).
    Ran,
    /// Pop `arity` values (the first parameter deepest) and write module
    /// `sym` with them to the output. Faults `not finite` if a value is
    /// NaN or infinite; `args` indexes [`Chunk::arg_spans`], where the
    /// spans of the `arity` argument expressions start.
    Emit { sym: SymId, arity: u8, args: u32 },
    /// Write module `sym` whose `arity` parameters are the constants
    /// `consts[first..first + arity]` (all finite).
    EmitConst { sym: SymId, arity: u8, first: u32 },
    /// Push variable `slot` (cpfg's C-like statements).
    Load(u32),
    /// Pop `a` into variable `slot`.
    Store(u32),
    /// Pop one index per dimension of array `array` (first index deepest)
    /// and push the element. `desc` is where the array's layout sits in
    /// the constant pool: n, then (0, count) per dimension, then the slot
    /// of its first element. Faults `array index` outside its range.
    LoadElem { array: u32, desc: u32 },
    /// Pop the value, then the indices, and store the value in the element.
    StoreElem { array: u32, desc: u32 },
    /// Pop and discard (an expression statement).
    Pop,
    /// `nran(mean, sd)`, `bran(a, b)`, `biran(n, p)`: pop the second
    /// argument, pop the first, push a sample drawn from the derivation's
    /// generator.
    Random(RandFn),
    /// `srand(seed)`: pop the seed, reseed the generator, push 0.
    Srand,
    /// cpfg's `func`: pop `x`, push function `func` of the program at `x`.
    /// The VM reads the function from [`Compiled::functions`].
    Spline(u32),
    /// End of chunk; the value on top of the stack (0 if empty) is the result.
    Ret,
}

impl Op {
    /// The mnemonic used by the disassembler.
    pub fn mnemonic(&self) -> &'static str {
        match self {
            Op::Const(_) => "const",
            Op::Param(_) => "param",
            Op::Neg => "neg",
            Op::Not => "not",
            Op::Add => "add",
            Op::Sub => "sub",
            Op::Mul => "mul",
            Op::Div => "div",
            Op::Rem => "rem",
            Op::Pow => "pow",
            Op::Lt => "lt",
            Op::Le => "le",
            Op::Gt => "gt",
            Op::Ge => "ge",
            Op::Eq => "eq",
            Op::Ne => "ne",
            Op::Jump(_) => "jump",
            Op::JumpIfFalse(_) => "jump_if_false",
            Op::JumpIfTrue(_) => "jump_if_true",
            Op::Call(_) => "call",
            Op::Index { .. } => "index",
            Op::Ran => "ran",
            Op::Emit { .. } => "emit",
            Op::EmitConst { .. } => "emit_const",
            Op::Load(_) => "load",
            Op::Store(_) => "store",
            Op::LoadElem { .. } => "load_elem",
            Op::StoreElem { .. } => "store_elem",
            Op::Pop => "pop",
            Op::Random(f) => f.name(),
            Op::Srand => "srand",
            Op::Spline(_) => "func",
            Op::Ret => "ret",
        }
    }
}

/// The code of one expression or successor, with the source span of every
/// instruction (`spans[pc]` belongs to `code[pc]`) so a runtime fault can
/// label the exact sub-expression.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Chunk {
    pub code: Vec<Op>,
    pub spans: Vec<Span>,
    /// Spans of the argument expressions of every [`Op::Emit`], in order.
    pub arg_spans: Vec<Span>,
    /// Deepest stack this chunk reaches.
    pub max_stack: usize,
}

impl Chunk {
    pub fn len(&self) -> usize {
        self.code.len()
    }

    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }
}

/// The compiled condition of a production.
#[derive(Clone, Debug, PartialEq)]
pub enum CondCode {
    /// No condition, `*`, `else`, or a condition folded to a non-zero
    /// constant: no code runs.
    Always,
    /// A condition folded to zero: the production never applies (the
    /// chunk is kept for the disassembly only).
    Never(Chunk),
    /// Run the chunk; non-zero means the production applies.
    Code(Chunk),
}

/// The code of one production.
#[derive(Clone, Debug, PartialEq)]
pub struct ProdCode {
    pub cond: CondCode,
    /// Relative weight in a stochastic choice.
    pub prob: Option<Chunk>,
    pub succ: Chunk,
}

/// A whole program's code. Indices of `main`, `decomposition` and
/// `homomorphism` are those of `Program::productions`, `decomposition`
/// and `homomorphism`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Compiled {
    /// Constant pool shared by all chunks (single constants are
    /// deduplicated by bit pattern; `EmitConst` parameter runs follow).
    pub consts: Vec<f64>,
    /// The axiom, compiled as a successor with no bindings.
    pub axiom: Chunk,
    pub main: Vec<ProdCode>,
    pub decomposition: Vec<ProdCode>,
    pub homomorphism: Vec<ProdCode>,
    /// cpfg's `Start:`, `StartEach:`, `EndEach:` and `End:` blocks (see
    /// `resolve::Hooks`); `None` where the grammar has none.
    pub hooks: HookCode,
    /// cpfg's view-file functions, for [`Op::Spline`].
    pub functions: Vec<crate::lang::spline::SplineFn>,
    /// Deepest stack of any chunk: the VM's stack size.
    pub max_stack: usize,
}

/// The compiled statement blocks of the L-system.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HookCode {
    pub start: Option<Chunk>,
    pub start_each: Option<Chunk>,
    pub end_each: Option<Chunk>,
    pub end: Option<Chunk>,
}

impl HookCode {
    /// Each hook with its name as written in a grammar.
    pub fn named(&self) -> [(&'static str, Option<&Chunk>); 4] {
        [
            ("Start", self.start.as_ref()),
            ("StartEach", self.start_each.as_ref()),
            ("EndEach", self.end_each.as_ref()),
            ("End", self.end.as_ref()),
        ]
    }
}

impl Compiled {
    pub fn table(&self, t: crate::resolve::Table) -> &[ProdCode] {
        use crate::resolve::Table;
        match t {
            Table::Main => &self.main,
            Table::Decomposition => &self.decomposition,
            Table::Homomorphism => &self.homomorphism,
        }
    }
}
