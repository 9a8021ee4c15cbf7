//! The virtual machine: runs one [`Chunk`] with a production's bindings,
//! the shared constant pool, a preallocated stack and the derivation's
//! generator; modules go to a [`Sink`]. Output: the chunk's value, or a
//! [`Fault`] with the span of the failing instruction (the caller adds the
//! production and the step).

use super::op::{Chunk, Op};
use crate::lang::builtins::{call, table_offset, RandFn};
use crate::lang::rng::Rand48;
use crate::lang::spline::SplineFn;
use crate::resolve::SymId;
use crate::source::Span;

/// Where [`Op::Emit`] writes modules.
pub trait Sink {
    fn emit(&mut self, sym: SymId, params: &[f64]);
}

/// A sink for condition and probability chunks, which never emit.
pub struct NoSink;

impl Sink for NoSink {
    fn emit(&mut self, _sym: SymId, _params: &[f64]) {
        unreachable!("expression chunks do not emit modules")
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FaultKind {
    /// `/` with a zero divisor.
    DivisionByZero,
    /// `%` with a zero divisor.
    RemainderByZero,
    /// A module parameter that is NaN or infinite.
    NotFinite(f64),
    /// Index `dim` (0-based) of table `table` is `value`, outside its range.
    TableIndex { table: u32, dim: u8, value: f64 },
    /// Index `dim` (0-based) of array `array` is `value`, outside its range.
    ArrayIndex { array: u32, dim: u8, value: f64 },
    /// A `while` / `do` loop went round more than [`MAX_LOOP_ITERATIONS`]
    /// times in one run of a chunk.
    LoopLimit,
}

fn b2f(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// Backward jumps the runs of code sharing a [`Machine::rounds`] counter
/// may take (a derivation step: every production block applied to every
/// module), or one run without one: a loop that has not ended after this
/// many rounds is taken to be endless. Counted per run only, a `while`
/// of 9 million rounds in a block applied to each of 20,000 modules ran
/// for hours (issue 36).
pub const MAX_LOOP_ITERATIONS: u64 = 10_000_000;

/// A runtime fault at `span`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fault {
    pub kind: FaultKind,
    pub span: Span,
}

/// What a chunk runs against besides its bindings: the shared constant
/// pool, cpfg's function splines, the statement blocks' variables, a
/// preallocated stack and the derivation's generator.
pub struct Machine<'a> {
    pub consts: &'a [f64],
    pub functions: &'a [SplineFn],
    /// Variables of cpfg's statement blocks.
    pub vars: &'a mut [f64],
    /// At least `chunk.max_stack` values.
    pub stack: &'a mut [f64],
    pub rng: &'a mut Rand48,
    /// Loop rounds taken so far by the runs this machine is one of,
    /// against [`MAX_LOOP_ITERATIONS`]; `None`: counted for this run alone.
    pub rounds: Option<&'a mut u64>,
}

impl<'a> Machine<'a> {
    /// For code that reads no variable and no function (the fast path's
    /// conditions and successors, module counting).
    pub fn pure(consts: &'a [f64], stack: &'a mut [f64], rng: &'a mut Rand48) -> Machine<'a> {
        Machine {
            consts,
            functions: &[],
            vars: &mut [],
            stack,
            rng,
            rounds: None,
        }
    }
}

/// Run `chunk` with `binds` holding every slot the chunk reads. Returns
/// the value on top of the stack at `Ret` (0 if the stack is empty).
#[inline]
pub fn run<S: Sink>(
    chunk: &Chunk,
    binds: &[f64],
    machine: Machine<'_>,
    sink: &mut S,
) -> Result<f64, Fault> {
    // Plain locals, so that the hot loop keeps each in a register.
    let Machine {
        consts,
        functions: funcs,
        vars,
        stack,
        rng,
        rounds,
    } = machine;
    let mut this_run = 0u64;
    let rounds: &mut u64 = rounds.unwrap_or(&mut this_run);
    let code = &chunk.code[..];
    let mut pc = 0usize;
    let mut sp = 0usize;
    macro_rules! bin {
        ($f:expr) => {{
            sp -= 1;
            let b = stack[sp];
            let a = stack[sp - 1];
            stack[sp - 1] = $f(a, b);
        }};
    }
    // A jump backwards is a loop's round: count them (cpfg's `while`).
    macro_rules! jump {
        ($t:expr) => {{
            let t = $t as usize;
            if t < pc {
                *rounds += 1;
                if *rounds > MAX_LOOP_ITERATIONS {
                    return Err(Fault {
                        kind: FaultKind::LoopLimit,
                        span: chunk.spans[pc - 1],
                    });
                }
            }
            pc = t;
        }};
    }
    loop {
        let op = code[pc];
        pc += 1;
        match op {
            Op::Const(i) => {
                stack[sp] = consts[i as usize];
                sp += 1;
            }
            Op::Param(s) => {
                stack[sp] = binds[s as usize];
                sp += 1;
            }
            Op::Neg => stack[sp - 1] = -stack[sp - 1],
            Op::Not => stack[sp - 1] = b2f(stack[sp - 1] == 0.0),
            Op::Add => bin!(|a, b| a + b),
            Op::Sub => bin!(|a, b| a - b),
            Op::Mul => bin!(|a, b| a * b),
            Op::Div | Op::Rem => {
                sp -= 1;
                let b = stack[sp];
                if b == 0.0 {
                    let kind = if op == Op::Div {
                        FaultKind::DivisionByZero
                    } else {
                        FaultKind::RemainderByZero
                    };
                    return Err(Fault {
                        kind,
                        span: chunk.spans[pc - 1],
                    });
                }
                let a = stack[sp - 1];
                stack[sp - 1] = if op == Op::Div { a / b } else { a % b };
            }
            Op::Pow => bin!(f64::powf),
            Op::Lt => bin!(|a, b| b2f(a < b)),
            Op::Le => bin!(|a, b| b2f(a <= b)),
            Op::Gt => bin!(|a, b| b2f(a > b)),
            Op::Ge => bin!(|a, b| b2f(a >= b)),
            Op::Eq => bin!(|a, b| b2f(a == b)),
            Op::Ne => bin!(|a, b| b2f(a != b)),
            Op::Jump(t) => jump!(t),
            Op::JumpIfFalse(t) => {
                sp -= 1;
                if stack[sp] == 0.0 {
                    pc = t as usize;
                }
            }
            Op::JumpIfTrue(t) => {
                sp -= 1;
                if stack[sp] != 0.0 {
                    jump!(t);
                }
            }
            Op::Call(f) => {
                if f.arity() == 2 {
                    bin!(|a, b| call(f, a, b));
                } else {
                    stack[sp - 1] = call(f, stack[sp - 1], 0.0);
                }
            }
            Op::Index { table, desc } => {
                let d = desc as usize;
                let n = consts[d] as usize;
                sp -= n;
                let bounds = (0..n).map(|k| (consts[d + 1 + 2 * k], consts[d + 2 + 2 * k]));
                match table_offset(bounds, &stack[sp..sp + n]) {
                    Ok(at) => {
                        stack[sp] = consts[d + 1 + 2 * n + at];
                        sp += 1;
                    }
                    Err(k) => {
                        return Err(Fault {
                            kind: FaultKind::TableIndex {
                                table,
                                dim: k as u8,
                                value: stack[sp + k],
                            },
                            span: chunk.spans[pc - 1],
                        })
                    }
                }
            }
            Op::Ran => stack[sp - 1] *= rng.next_f64(),
            Op::Emit { sym, arity, args } => {
                let n = arity as usize;
                sp -= n;
                let vals = &stack[sp..sp + n];
                if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
                    return Err(Fault {
                        kind: FaultKind::NotFinite(vals[k]),
                        span: chunk.arg_spans[args as usize + k],
                    });
                }
                sink.emit(sym, vals);
            }
            Op::EmitConst { sym, arity, first } => {
                let f = first as usize;
                sink.emit(sym, &consts[f..f + arity as usize]);
            }
            Op::Load(v) => {
                stack[sp] = vars[v as usize];
                sp += 1;
            }
            Op::Store(v) => {
                sp -= 1;
                vars[v as usize] = stack[sp];
            }
            Op::LoadElem { array, desc } | Op::StoreElem { array, desc } => {
                let store = matches!(op, Op::StoreElem { .. });
                let value = if store {
                    sp -= 1;
                    stack[sp]
                } else {
                    0.0
                };
                let d = desc as usize;
                let n = consts[d] as usize;
                sp -= n;
                let bounds = (0..n).map(|k| (consts[d + 1 + 2 * k], consts[d + 2 + 2 * k]));
                match table_offset(bounds, &stack[sp..sp + n]) {
                    Ok(at) => {
                        let slot = consts[d + 1 + 2 * n] as usize + at;
                        if store {
                            vars[slot] = value;
                        } else {
                            stack[sp] = vars[slot];
                            sp += 1;
                        }
                    }
                    Err(k) => {
                        return Err(Fault {
                            kind: FaultKind::ArrayIndex {
                                array,
                                dim: k as u8,
                                value: stack[sp + k],
                            },
                            span: chunk.spans[pc - 1],
                        })
                    }
                }
            }
            Op::Pop => sp -= 1,
            Op::Random(f) => {
                sp -= 1;
                let (a, b) = (stack[sp - 1], stack[sp]);
                stack[sp - 1] = match f {
                    RandFn::Nran => rng.nran(a, b),
                    RandFn::Bran => rng.bran(a, b),
                    RandFn::Biran => rng.biran(a, b),
                };
            }
            Op::Spline(f) => stack[sp - 1] = funcs[f as usize].value(stack[sp - 1]),
            Op::Srand => {
                rng.reseed(stack[sp - 1]);
                stack[sp - 1] = 0.0;
            }
            Op::Ret => return Ok(if sp > 0 { stack[sp - 1] } else { 0.0 }),
        }
    }
}
