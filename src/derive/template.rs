//! Successor and condition templates for the fast step: a production's
//! bytecode in, a straight-line description out when the code is simple
//! enough — modules whose parameters are constants, a binding, or a
//! binding plus or times a constant, and conditions comparing a binding
//! with a constant — so the fast step writes them without running the VM
//! (the profile of W2 put the VM's dispatch at the top). `None` for
//! anything else, which keeps running on the VM.
//!
//! Results are bit-for-bit the VM's: each template operation is the one
//! IEEE operation the VM would do on the same operands (`x - c` is done as
//! `x - c`, never as `x + (-c)`).

use crate::bytecode::{Chunk, Op};

use super::store::pack;

/// One parameter value of an emitted module.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Arg {
    Const(f64),
    Param(u16),
    Add(u16, f64),
    Sub(u16, f64),
    Mul(u16, f64),
}

impl Arg {
    #[inline(always)]
    fn eval(self, b: &[f64]) -> f64 {
        match self {
            Arg::Const(c) => c,
            Arg::Param(s) => b[s as usize],
            Arg::Add(s, c) => b[s as usize] + c,
            Arg::Sub(s, c) => b[s as usize] - c,
            Arg::Mul(s, c) => b[s as usize] * c,
        }
    }
}

/// A successor as a list of modules.
#[derive(Clone, Debug)]
pub(crate) struct Succ {
    /// Packed head of every module.
    heads: Vec<u32>,
    /// Its parameters, `arity` per module, module after module.
    args: Vec<Arg>,
    /// Whether every parameter is a constant (then `consts` has them).
    all_const: bool,
    consts: Vec<f64>,
}

impl Succ {
    /// The template of a successor chunk, if it is straight-line.
    pub(crate) fn new(chunk: &Chunk, consts: &[f64]) -> Option<Succ> {
        let mut stack: Vec<Arg> = Vec::new();
        let mut heads = Vec::new();
        let mut args = Vec::new();
        for op in &chunk.code {
            match *op {
                Op::Const(i) => stack.push(Arg::Const(*consts.get(i as usize)?)),
                Op::Param(s) => stack.push(Arg::Param(s)),
                Op::Add | Op::Sub | Op::Mul => {
                    let b = stack.pop()?;
                    let a = stack.pop()?;
                    stack.push(combine(*op, a, b)?);
                }
                Op::Emit { sym, arity, .. } => {
                    let n = arity as usize;
                    if stack.len() < n {
                        return None;
                    }
                    let vals = stack.split_off(stack.len() - n);
                    // A constant argument that is not finite must fault
                    // at run time: leave that to the VM.
                    if vals
                        .iter()
                        .any(|v| matches!(v, Arg::Const(c) if !c.is_finite()))
                    {
                        return None;
                    }
                    heads.push(pack(sym, arity));
                    args.extend(vals);
                }
                Op::EmitConst { sym, arity, first } => {
                    let f = first as usize;
                    let vals = consts.get(f..f + arity as usize)?;
                    heads.push(pack(sym, arity));
                    args.extend(vals.iter().map(|&c| Arg::Const(c)));
                }
                Op::Ret => {
                    if !stack.is_empty() {
                        return None;
                    }
                    let all_const = args.iter().all(|a| matches!(a, Arg::Const(_)));
                    let consts = args
                        .iter()
                        .map(|a| if let Arg::Const(c) = a { *c } else { 0.0 })
                        .collect();
                    return Some(Succ {
                        heads,
                        args,
                        all_const,
                        consts,
                    });
                }
                _ => return None,
            }
        }
        None
    }

    /// Modules and parameter values written.
    pub(crate) fn size(&self) -> (usize, usize) {
        (self.heads.len(), self.args.len())
    }

    /// Write the successor with bindings `b`; `Err` when a value is not
    /// finite (the VM faults there; the general engine reports it).
    #[inline(always)]
    pub(crate) fn write(
        &self,
        b: &[f64],
        heads: &mut Vec<u32>,
        params: &mut Vec<f64>,
    ) -> Result<(), ()> {
        heads.extend_from_slice(&self.heads);
        if self.all_const {
            params.extend_from_slice(&self.consts);
            return Ok(());
        }
        let mut finite = true;
        params.reserve(self.args.len());
        for a in &self.args {
            let v = a.eval(b);
            finite &= v.is_finite();
            params.push(v);
        }
        if finite {
            Ok(())
        } else {
            Err(())
        }
    }
}

impl Succ {
    /// [`write`](Succ::write) into slots of a preallocated output.
    #[inline(always)]
    pub(crate) fn write_into(
        &self,
        b: &[f64],
        heads: &mut [std::mem::MaybeUninit<u32>],
        params: &mut [std::mem::MaybeUninit<f64>],
    ) -> Result<(), ()> {
        for (slot, &h) in heads.iter_mut().zip(&self.heads) {
            slot.write(h);
        }
        let mut finite = true;
        for (slot, a) in params.iter_mut().zip(&self.args) {
            let v = a.eval(b);
            finite &= v.is_finite();
            slot.write(v);
        }
        if finite {
            Ok(())
        } else {
            Err(())
        }
    }
}

fn combine(op: Op, a: Arg, b: Arg) -> Option<Arg> {
    Some(match (op, a, b) {
        (Op::Add, Arg::Const(x), Arg::Const(y)) => Arg::Const(x + y),
        (Op::Sub, Arg::Const(x), Arg::Const(y)) => Arg::Const(x - y),
        (Op::Mul, Arg::Const(x), Arg::Const(y)) => Arg::Const(x * y),
        // IEEE addition and multiplication commute exactly.
        (Op::Add, Arg::Param(s), Arg::Const(c)) | (Op::Add, Arg::Const(c), Arg::Param(s)) => {
            Arg::Add(s, c)
        }
        (Op::Mul, Arg::Param(s), Arg::Const(c)) | (Op::Mul, Arg::Const(c), Arg::Param(s)) => {
            Arg::Mul(s, c)
        }
        (Op::Sub, Arg::Param(s), Arg::Const(c)) => Arg::Sub(s, c),
        _ => return None,
    })
}

/// A condition `binding <op> constant` (or `constant <op> binding`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cond {
    slot: u16,
    op: Op,
    c: f64,
    /// The constant is on the left.
    flipped: bool,
}

impl Cond {
    pub(crate) fn new(chunk: &Chunk, consts: &[f64]) -> Option<Cond> {
        let [a, b, op, Op::Ret] = chunk.code[..] else {
            return None;
        };
        if !matches!(op, Op::Lt | Op::Le | Op::Gt | Op::Ge | Op::Eq | Op::Ne) {
            return None;
        }
        let (slot, k, flipped) = match (a, b) {
            (Op::Param(s), Op::Const(k)) => (s, k, false),
            (Op::Const(k), Op::Param(s)) => (s, k, true),
            _ => return None,
        };
        Some(Cond {
            slot,
            op,
            c: *consts.get(k as usize)?,
            flipped,
        })
    }

    /// Whether the condition holds for bindings `b`.
    #[inline(always)]
    pub(crate) fn holds(&self, b: &[f64]) -> bool {
        let (x, y) = if self.flipped {
            (self.c, b[self.slot as usize])
        } else {
            (b[self.slot as usize], self.c)
        };
        match self.op {
            Op::Lt => x < y,
            Op::Le => x <= y,
            Op::Gt => x > y,
            Op::Ge => x >= y,
            Op::Eq => x == y,
            _ => x != y,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chunk(code: Vec<Op>) -> Chunk {
        Chunk {
            code,
            ..Chunk::default()
        }
    }

    #[test]
    fn straight_line_successors_become_templates() {
        let consts = [1.0, 25.0];
        let c = chunk(vec![
            Op::Param(0),
            Op::Emit {
                sym: 3,
                arity: 1,
                args: 0,
            },
            Op::EmitConst {
                sym: 4,
                arity: 1,
                first: 1,
            },
            Op::Param(0),
            Op::Const(0),
            Op::Add,
            Op::Emit {
                sym: 5,
                arity: 1,
                args: 1,
            },
            Op::Ret,
        ]);
        let t = Succ::new(&c, &consts).unwrap();
        assert_eq!(t.size(), (3, 3));
        let (mut h, mut p) = (Vec::new(), Vec::new());
        t.write(&[2.0], &mut h, &mut p).unwrap();
        assert_eq!(h, vec![pack(3, 1), pack(4, 1), pack(5, 1)]);
        assert_eq!(p, vec![2.0, 25.0, 3.0]);
        assert!(t.write(&[f64::MAX], &mut h, &mut p).is_ok());
        let big = Succ::new(
            &chunk(vec![
                Op::Param(0),
                Op::Const(1),
                Op::Mul,
                Op::Emit {
                    sym: 3,
                    arity: 1,
                    args: 0,
                },
                Op::Ret,
            ]),
            &consts,
        )
        .unwrap();
        assert!(big.write(&[f64::MAX], &mut h, &mut p).is_err());
        // Division stays on the VM.
        let div = chunk(vec![Op::Param(0), Op::Const(0), Op::Div, Op::Ret]);
        assert!(Succ::new(&div, &consts).is_none());
    }

    #[test]
    fn comparisons_with_constants_become_conditions() {
        let consts = [18.0];
        let c = Cond::new(
            &chunk(vec![Op::Param(0), Op::Const(0), Op::Lt, Op::Ret]),
            &consts,
        )
        .unwrap();
        assert!(c.holds(&[17.0]) && !c.holds(&[18.0]) && !c.holds(&[f64::NAN]));
        let f = Cond::new(
            &chunk(vec![Op::Const(0), Op::Param(0), Op::Lt, Op::Ret]),
            &consts,
        )
        .unwrap();
        assert!(f.holds(&[19.0]) && !f.holds(&[18.0]));
    }
}
