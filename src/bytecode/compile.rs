//! The compiler: resolved [`Program`] (constant-folded expressions, bound
//! parameter slots) in, [`Compiled`] chunks out. One condition chunk
//! (unless the condition is absent, `else` or a constant), one optional
//! probability chunk and one successor chunk per production, and one chunk
//! for the axiom.

use std::collections::HashMap;

use super::error::BytecodeError;
use super::op::{Chunk, Compiled, CondCode, HookCode, Op, ProdCode};
use crate::resolve::{
    BinOp, Cond, Expr, ExprKind, Func, Production, Program, Stmt, SuccModule, Target, UnOp,
};
use crate::source::Span;

/// Compile every production of every table, and the axiom.
pub fn compile(program: &Program) -> Result<Compiled, BytecodeError> {
    let mut c = Compiler {
        program,
        consts: Vec::new(),
        single: HashMap::new(),
        tuples: HashMap::new(),
        tables: HashMap::new(),
        arrays: HashMap::new(),
    };
    let h = &program.hooks;
    let hooks = HookCode {
        start: c.hook(&h.start)?,
        start_each: c.hook(&h.start_each)?,
        end_each: c.hook(&h.end_each)?,
        end: c.hook(&h.end)?,
    };
    let axiom = c.successor(&program.axiom)?;
    let main = c.table(&program.productions)?;
    let decomposition = c.table(&program.decomposition)?;
    let homomorphism = c.table(&program.homomorphism)?;
    let mut out = Compiled {
        consts: c.consts,
        axiom,
        main,
        decomposition,
        homomorphism,
        hooks,
        functions: program.functions.clone(),
        max_stack: 0,
    };
    let mut max = out.axiom.max_stack;
    for (_, ch) in out.hooks.named() {
        max = max.max(ch.map_or(0, |c| c.max_stack));
    }
    for p in out
        .main
        .iter()
        .chain(&out.decomposition)
        .chain(&out.homomorphism)
    {
        let cond = match &p.cond {
            CondCode::Always => 0,
            CondCode::Never(ch) | CondCode::Code(ch) => ch.max_stack,
        };
        let prob = p.prob.as_ref().map_or(0, |ch| ch.max_stack);
        max = max.max(cond).max(prob).max(p.succ.max_stack);
    }
    out.max_stack = max;
    Ok(out)
}

struct Compiler<'p> {
    program: &'p Program,
    consts: Vec<f64>,
    /// Single constants by bit pattern.
    single: HashMap<u64, u32>,
    /// Parameter runs of `EmitConst` by bit patterns.
    tuples: HashMap<Vec<u64>, u32>,
    /// Where each table used so far starts in the pool.
    tables: HashMap<u32, u32>,
    /// Where each array's layout starts in the pool.
    arrays: HashMap<u32, u32>,
}

/// Code being built, with the static stack depth.
struct Builder {
    chunk: Chunk,
    depth: usize,
}

impl Builder {
    fn new() -> Builder {
        Builder {
            chunk: Chunk::default(),
            depth: 0,
        }
    }

    /// Append `op`, which changes the stack depth by `delta`.
    fn push(&mut self, op: Op, span: Span, delta: isize) -> usize {
        self.chunk.code.push(op);
        self.chunk.spans.push(span);
        self.depth = (self.depth as isize + delta) as usize;
        self.chunk.max_stack = self.chunk.max_stack.max(self.depth);
        self.chunk.code.len() - 1
    }

    fn here(&self) -> u32 {
        self.chunk.code.len() as u32
    }

    /// Point the jump at `at` to the next instruction.
    fn patch(&mut self, at: usize) {
        let target = self.here();
        match &mut self.chunk.code[at] {
            Op::Jump(t) | Op::JumpIfFalse(t) | Op::JumpIfTrue(t) => *t = target,
            _ => unreachable!("patching a non-jump"),
        }
    }
}

impl Compiler<'_> {
    fn table(&mut self, prods: &[Production]) -> Result<Vec<ProdCode>, BytecodeError> {
        prods.iter().map(|p| self.production(p)).collect()
    }

    fn production(&mut self, p: &Production) -> Result<ProdCode, BytecodeError> {
        if !p.pre.is_empty() || !p.post.is_empty() {
            return Ok(ProdCode {
                cond: CondCode::Code(self.block_condition(p)?),
                prob: p.prob.as_ref().map(|e| self.expr_chunk(e)).transpose()?,
                succ: self.successor(&p.succ)?,
            });
        }
        let cond = match &p.cond {
            Cond::Always | Cond::Else(_) => CondCode::Always,
            Cond::Expr(e) => match e.kind {
                // NaN is true, as in C.
                ExprKind::Num(v) if v != 0.0 || v.is_nan() => CondCode::Always,
                ExprKind::Num(_) => CondCode::Never(self.expr_chunk(e)?),
                _ => CondCode::Code(self.expr_chunk(e)?),
            },
        };
        let prob = p.prob.as_ref().map(|e| self.expr_chunk(e)).transpose()?;
        let succ = self.successor(&p.succ)?;
        Ok(ProdCode { cond, prob, succ })
    }

    /// A condition with cpfg statement blocks: the block before it, the
    /// condition, and the block after it only when the condition holds.
    fn block_condition(&mut self, p: &Production) -> Result<Chunk, BytecodeError> {
        let mut b = Builder::new();
        self.stmts(&mut b, &p.pre)?;
        let span = match &p.cond {
            Cond::Expr(e) => {
                self.expr(&mut b, e)?;
                e.span
            }
            Cond::Always | Cond::Else(_) => {
                let one = self.constant(1.0)?;
                b.push(Op::Const(one), p.head_span, 1);
                p.head_span
            }
        };
        if !p.post.is_empty() {
            let skip = b.push(Op::JumpIfFalse(0), span, -1);
            self.stmts(&mut b, &p.post)?;
            let one = self.constant(1.0)?;
            b.push(Op::Const(one), span, 1);
            b.push(Op::Ret, span, 0);
            b.patch(skip);
            // The `Ret` above left the depth counted once; the false
            // branch starts from the depth before it.
            b.depth -= 1;
            let zero = self.constant(0.0)?;
            b.push(Op::Const(zero), span, 1);
        }
        b.push(Op::Ret, span, 0);
        self.finish(b, span)
    }

    fn hook(&mut self, stmts: &[Stmt]) -> Result<Option<Chunk>, BytecodeError> {
        if stmts.is_empty() {
            return Ok(None);
        }
        let mut b = Builder::new();
        self.stmts(&mut b, stmts)?;
        b.push(Op::Ret, Span::default(), 0);
        Ok(Some(self.finish(b, Span::default())?))
    }

    fn stmts(&mut self, b: &mut Builder, stmts: &[Stmt]) -> Result<(), BytecodeError> {
        for s in stmts {
            match s {
                Stmt::Set { target, value } => match target {
                    Target::Var(slot, span) => {
                        self.expr(b, value)?;
                        b.push(Op::Store(*slot), *span, -1);
                    }
                    Target::Elem(a, idx, span) => {
                        for i in idx {
                            self.expr(b, i)?;
                        }
                        self.expr(b, value)?;
                        let desc = self.array_desc(*a)?;
                        b.push(
                            Op::StoreElem { array: *a, desc },
                            *span,
                            -(idx.len() as isize) - 1,
                        );
                    }
                },
                Stmt::Eval(e) => {
                    self.expr(b, e)?;
                    b.push(Op::Pop, e.span, -1);
                }
                Stmt::If(c, t, e) => {
                    self.expr(b, c)?;
                    let to_else = b.push(Op::JumpIfFalse(0), c.span, -1);
                    self.stmts(b, t)?;
                    if e.is_empty() {
                        b.patch(to_else);
                    } else {
                        let to_end = b.push(Op::Jump(0), c.span, 0);
                        b.patch(to_else);
                        self.stmts(b, e)?;
                        b.patch(to_end);
                    }
                }
                Stmt::While(c, body) => {
                    let top = b.here();
                    self.expr(b, c)?;
                    let exit = b.push(Op::JumpIfFalse(0), c.span, -1);
                    self.stmts(b, body)?;
                    b.push(Op::Jump(top), c.span, 0);
                    b.patch(exit);
                }
                Stmt::DoWhile(body, c) => {
                    let top = b.here();
                    self.stmts(b, body)?;
                    self.expr(b, c)?;
                    b.push(Op::JumpIfTrue(top), c.span, -1);
                }
            }
        }
        Ok(())
    }

    /// An array's layout in the pool, once: `[dimensions, (0, count) per
    /// dimension..., first slot]`, the layout `Op::LoadElem` reads.
    fn array_desc(&mut self, id: u32) -> Result<u32, BytecodeError> {
        if let Some(&at) = self.arrays.get(&id) {
            return Ok(at);
        }
        let a = &self.program.arrays[id as usize];
        let mut desc = vec![a.dims.len() as f64];
        for &d in &a.dims {
            desc.extend([0.0, d as f64]);
        }
        desc.push(a.base as f64);
        let at = self.alloc(desc.len())?;
        self.consts.extend_from_slice(&desc);
        self.arrays.insert(id, at);
        Ok(at)
    }

    fn expr_chunk(&mut self, e: &Expr) -> Result<Chunk, BytecodeError> {
        let mut b = Builder::new();
        self.expr(&mut b, e)?;
        b.push(Op::Ret, e.span, 0);
        self.finish(b, e.span)
    }

    fn successor(&mut self, succ: &[SuccModule]) -> Result<Chunk, BytecodeError> {
        let mut b = Builder::new();
        // At least one op a module: no doubling past that for an axiom of
        // millions of modules.
        b.chunk.code.reserve(succ.len() + 1);
        b.chunk.spans.reserve(succ.len() + 1);
        for m in succ {
            if m.args.len() > u8::MAX as usize {
                return Err(BytecodeError::TooManyParameters {
                    name: self.program.symbols.name(m.sym).to_string(),
                    count: m.args.len(),
                    src: self.program.sources.named_source(m.span),
                    span: m.span.into(),
                });
            }
            let arity = m.args.len() as u8;
            let consts: Option<Vec<f64>> = m
                .args
                .iter()
                .map(|a| match a.kind {
                    ExprKind::Num(v) if v.is_finite() => Some(v),
                    _ => None,
                })
                .collect();
            match consts {
                Some(vals) => {
                    // cpfg stores parameters as f32: a constant past its
                    // range would be written as inf, with no word.
                    if self.program.profile.f32_params {
                        if let Some(k) = vals.iter().position(|v| v.abs() > f32::MAX as f64) {
                            return Err(BytecodeError::F32Overflow {
                                value: vals[k],
                                src: self.program.sources.named_source(m.args[k].span),
                                span: m.args[k].span.into(),
                            });
                        }
                    }
                    let first = self.tuple(&vals)?;
                    b.push(
                        Op::EmitConst {
                            sym: m.sym,
                            arity,
                            first,
                        },
                        m.span,
                        0,
                    );
                }
                None => {
                    for a in &m.args {
                        self.expr(&mut b, a)?;
                    }
                    let args = b.chunk.arg_spans.len() as u32;
                    b.chunk.arg_spans.extend(m.args.iter().map(|a| a.span));
                    b.push(
                        Op::Emit {
                            sym: m.sym,
                            arity,
                            args,
                        },
                        m.span,
                        -(arity as isize),
                    );
                }
            }
        }
        let end = succ.last().map_or_else(Span::default, |m| m.span);
        b.push(Op::Ret, end, 0);
        self.finish(b, end)
    }

    fn finish(&self, b: Builder, span: Span) -> Result<Chunk, BytecodeError> {
        if b.chunk.code.len() > u32::MAX as usize {
            return Err(BytecodeError::ChunkTooLong {
                limit: u32::MAX as u64,
                src: self.program.sources.named_source(span),
                span: span.into(),
            });
        }
        Ok(b.chunk)
    }

    fn constant(&mut self, v: f64) -> Result<u32, BytecodeError> {
        if let Some(&i) = self.single.get(&v.to_bits()) {
            return Ok(i);
        }
        let i = self.alloc(1)?;
        self.consts.push(v);
        self.single.insert(v.to_bits(), i);
        Ok(i)
    }

    fn tuple(&mut self, vals: &[f64]) -> Result<u32, BytecodeError> {
        if vals.is_empty() {
            return Ok(0);
        }
        if vals.len() == 1 {
            return self.constant(vals[0]);
        }
        let key: Vec<u64> = vals.iter().map(|v| v.to_bits()).collect();
        if let Some(&i) = self.tuples.get(&key) {
            return Ok(i);
        }
        let i = self.alloc(vals.len())?;
        self.consts.extend_from_slice(vals);
        self.tuples.insert(key, i);
        Ok(i)
    }

    /// A table in the pool, once: `[dimensions, (first index, count)
    /// per dimension..., values...]`, the layout `Op::Index` reads.
    fn table_desc(&mut self, id: u32) -> Result<u32, BytecodeError> {
        if let Some(&at) = self.tables.get(&id) {
            return Ok(at);
        }
        let t = &self.program.tables[id as usize];
        let mut desc = vec![t.dims.len() as f64];
        for (lo, len) in t.bounds() {
            desc.extend([lo, len]);
        }
        desc.extend_from_slice(&t.values);
        let at = self.alloc(desc.len())?;
        self.consts.extend_from_slice(&desc);
        self.tables.insert(id, at);
        Ok(at)
    }

    fn alloc(&self, n: usize) -> Result<u32, BytecodeError> {
        if self.consts.len() + n > u32::MAX as usize {
            return Err(BytecodeError::TooManyConstants {
                limit: u32::MAX as u64,
            });
        }
        Ok(self.consts.len() as u32)
    }

    fn expr(&mut self, b: &mut Builder, e: &Expr) -> Result<(), BytecodeError> {
        let span = e.span;
        match &e.kind {
            ExprKind::Num(v) => {
                let i = self.constant(*v)?;
                b.push(Op::Const(i), span, 1);
            }
            ExprKind::Param(slot) => {
                b.push(Op::Param(*slot), span, 1);
            }
            ExprKind::Var(slot) => {
                b.push(Op::Load(*slot), span, 1);
            }
            ExprKind::Elem(a, idx) => {
                for i in idx {
                    self.expr(b, i)?;
                }
                let desc = self.array_desc(*a)?;
                b.push(
                    Op::LoadElem { array: *a, desc },
                    span,
                    1 - idx.len() as isize,
                );
            }
            ExprKind::Random(f, a, c) => {
                self.expr(b, a)?;
                self.expr(b, c)?;
                b.push(Op::Random(*f), span, -1);
            }
            ExprKind::Spline(f, x) => {
                self.expr(b, x)?;
                b.push(Op::Spline(*f), span, 0);
            }
            ExprKind::Srand(seed) => {
                self.expr(b, seed)?;
                b.push(Op::Srand, span, 0);
            }
            ExprKind::Unary(op, a) => {
                self.expr(b, a)?;
                let op = match op {
                    UnOp::Neg => Op::Neg,
                    UnOp::Not => Op::Not,
                };
                b.push(op, span, 0);
            }
            ExprKind::Binary(BinOp::And, l, r) => {
                // l; jif F; r; jif F; const 1; jump E; F: const 0; E:
                self.expr(b, l)?;
                let j1 = b.push(Op::JumpIfFalse(0), span, -1);
                self.expr(b, r)?;
                let j2 = b.push(Op::JumpIfFalse(0), span, -1);
                self.logic_tail(b, span, 1.0, 0.0, j1, j2)?;
            }
            ExprKind::Binary(BinOp::Or, l, r) => {
                self.expr(b, l)?;
                let j1 = b.push(Op::JumpIfTrue(0), span, -1);
                self.expr(b, r)?;
                let j2 = b.push(Op::JumpIfTrue(0), span, -1);
                self.logic_tail(b, span, 0.0, 1.0, j1, j2)?;
            }
            ExprKind::Binary(op, l, r) => {
                self.expr(b, l)?;
                self.expr(b, r)?;
                let op = match op {
                    BinOp::Add => Op::Add,
                    BinOp::Sub => Op::Sub,
                    BinOp::Mul => Op::Mul,
                    BinOp::Div => Op::Div,
                    BinOp::Rem => Op::Rem,
                    BinOp::Pow => Op::Pow,
                    BinOp::Lt => Op::Lt,
                    BinOp::Le => Op::Le,
                    BinOp::Gt => Op::Gt,
                    BinOp::Ge => Op::Ge,
                    BinOp::Eq => Op::Eq,
                    BinOp::Ne => Op::Ne,
                    BinOp::And | BinOp::Or => unreachable!("handled above"),
                };
                b.push(op, span, -1);
            }
            ExprKind::Cond(c, t, f) => {
                self.expr(b, c)?;
                let jf = b.push(Op::JumpIfFalse(0), span, -1);
                self.expr(b, t)?;
                let je = b.push(Op::Jump(0), span, 0);
                b.patch(jf);
                b.depth -= 1; // the `then` value is not on the `else` path
                self.expr(b, f)?;
                b.patch(je);
            }
            ExprKind::Call(Func::Ran, args) => {
                for a in args {
                    self.expr(b, a)?;
                }
                b.push(Op::Ran, span, 1 - args.len() as isize);
            }
            ExprKind::Call(f, args) => {
                for a in args {
                    self.expr(b, a)?;
                }
                b.push(Op::Call(*f), span, 1 - args.len() as isize);
            }
            ExprKind::Index(id, args) => {
                for a in args {
                    self.expr(b, a)?;
                }
                let desc = self.table_desc(*id)?;
                b.push(
                    Op::Index { table: *id, desc },
                    span,
                    1 - args.len() as isize,
                );
            }
        }
        Ok(())
    }

    /// End of a short-circuit: fall-through pushes `through`, the two
    /// jumps land on pushing `jumped`.
    fn logic_tail(
        &mut self,
        b: &mut Builder,
        span: Span,
        through: f64,
        jumped: f64,
        j1: usize,
        j2: usize,
    ) -> Result<(), BytecodeError> {
        let t = self.constant(through)?;
        let f = self.constant(jumped)?;
        b.push(Op::Const(t), span, 1);
        let je = b.push(Op::Jump(0), span, 0);
        b.patch(j1);
        b.patch(j2);
        b.depth -= 1;
        b.push(Op::Const(f), span, 1);
        b.patch(je);
        Ok(())
    }
}
