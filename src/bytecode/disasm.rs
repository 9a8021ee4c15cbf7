//! The disassembler: [`Program`] + [`Compiled`] in, a deterministic
//! human-readable listing out (for `lsys disasm FILE` and snapshot tests).
//!
//! Layout: a header, the axiom, then each table (`productions`,
//! `decomposition`, `homomorphism`) with, per production, its index, its
//! source text on one line and `file:line:col`, its binding slots, and each
//! chunk as `  0003  op  operands  ; comment`.

use std::fmt::Write;

use super::op::{Chunk, Compiled, CondCode, Op};
use crate::resolve::{Cond, Production, Program, Table};

/// The whole listing.
pub fn disasm(program: &Program, compiled: &Compiled) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "; lsys bytecode: {} constants, stack depth {}",
        compiled.consts.len(),
        compiled.max_stack
    );
    for (name, ch) in compiled.hooks.named() {
        if let Some(ch) = ch {
            let _ = writeln!(out, "\n{name}:");
            chunk(&mut out, program, compiled, ch, &[]);
        }
    }
    out.push_str("\naxiom\n");
    chunk(&mut out, program, compiled, &compiled.axiom, &[]);
    for (table, title) in [
        (Table::Main, "productions"),
        (Table::Decomposition, "decomposition"),
        (Table::Homomorphism, "homomorphism"),
    ] {
        let prods = program.table(table);
        let codes = compiled.table(table);
        if prods.is_empty() {
            continue;
        }
        let _ = writeln!(out, "\n{title}");
        for (i, (p, code)) in prods.iter().zip(codes).enumerate() {
            production(&mut out, program, compiled, i, p, code);
        }
    }
    out
}

/// The listing of one production: `index` in `table` (as numbered in
/// [`disasm`]); `None` when there is no such production.
pub fn disasm_production(
    program: &Program,
    compiled: &Compiled,
    table: Table,
    index: usize,
) -> Option<String> {
    let p = program.table(table).get(index)?;
    let code = compiled.table(table).get(index)?;
    let mut out = String::new();
    production(&mut out, program, compiled, index, p, code);
    Some(out.trim_start().to_string())
}

fn production(
    out: &mut String,
    program: &Program,
    compiled: &Compiled,
    index: usize,
    p: &Production,
    code: &super::op::ProdCode,
) {
    let _ = writeln!(
        out,
        "\nproduction {index}: {}  ; {}",
        one_line(program.sources.slice(p.span)),
        program.sources.location(p.span)
    );
    if p.param_names.is_empty() {
        out.push_str("  slots: none\n");
    } else {
        out.push_str("  slots:");
        for (i, n) in p.param_names.iter().enumerate() {
            let _ = write!(out, " {i}={n}");
        }
        out.push('\n');
    }
    match (&code.cond, &p.cond) {
        (CondCode::Always, Cond::Always) => out.push_str("  condition: none\n"),
        (CondCode::Always, Cond::Else(_)) => out.push_str("  condition: else\n"),
        (CondCode::Always, Cond::Expr(_)) => out.push_str("  condition: constant true\n"),
        (CondCode::Never(ch), _) => {
            out.push_str("  condition: constant false (never applies)\n");
            chunk(out, program, compiled, ch, &p.param_names);
        }
        (CondCode::Code(ch), _) => {
            out.push_str("  condition:\n");
            chunk(out, program, compiled, ch, &p.param_names);
        }
    }
    if let Some(ch) = &code.prob {
        out.push_str("  probability:\n");
        chunk(out, program, compiled, ch, &p.param_names);
    }
    out.push_str("  successor:\n");
    chunk(out, program, compiled, &code.succ, &p.param_names);
}

/// Source text on one line, runs of whitespace squeezed to one space.
pub fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn chunk(out: &mut String, program: &Program, compiled: &Compiled, ch: &Chunk, names: &[String]) {
    for (pc, op) in ch.code.iter().enumerate() {
        let (operands, comment) = describe(program, compiled, ch, pc, op, names);
        let mut line = format!("  {pc:04}  {:<14}{operands}", op.mnemonic());
        if !comment.is_empty() {
            let pad = 32usize.saturating_sub(line.chars().count()).max(1);
            line.push_str(&" ".repeat(pad));
            line.push_str("; ");
            line.push_str(&comment);
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
}

fn describe(
    program: &Program,
    compiled: &Compiled,
    ch: &Chunk,
    pc: usize,
    op: &Op,
    names: &[String],
) -> (String, String) {
    let sym = |id| program.symbols.name(id);
    match *op {
        Op::Const(i) => (format!("#{i}"), format!("{}", compiled.consts[i as usize])),
        Op::Param(s) => (
            s.to_string(),
            names.get(s as usize).cloned().unwrap_or_else(|| "?".into()),
        ),
        Op::Jump(t) | Op::JumpIfFalse(t) | Op::JumpIfTrue(t) => {
            (format!("-> {t:04}"), String::new())
        }
        Op::Call(f) => (f.name().to_string(), String::new()),
        Op::Load(v) | Op::Store(v) => (
            v.to_string(),
            program
                .vars
                .get(v as usize)
                .map_or_else(|| "?".into(), |i| i.name.clone()),
        ),
        Op::LoadElem { array, desc } | Op::StoreElem { array, desc } => {
            let a = &program.arrays[array as usize];
            let shape: String = a.dims.iter().map(|d| format!("[{d}]")).collect();
            (format!("{} @#{desc}", a.name), shape)
        }
        Op::Index { table, desc } => {
            let t = &program.tables[table as usize];
            (format!("{} @#{desc}", t.name), t.dims_text())
        }
        Op::Emit { sym: s, arity, .. } => (
            format!("{}/{arity}", sym(s)),
            one_line(program.sources.slice(ch.spans[pc])),
        ),
        Op::EmitConst {
            sym: s,
            arity,
            first,
        } => {
            let f = first as usize;
            let vals = &compiled.consts[f..f + arity as usize];
            let mut text = sym(s).to_string();
            if !vals.is_empty() {
                text.push('(');
                for (k, v) in vals.iter().enumerate() {
                    if k > 0 {
                        text.push(',');
                    }
                    let _ = write!(text, "{v}");
                }
                text.push(')');
            }
            let operands = if arity == 0 {
                sym(s).to_string()
            } else {
                format!("{}/{arity} #{first}", sym(s))
            };
            (operands, text)
        }
        _ => (String::new(), String::new()),
    }
}
