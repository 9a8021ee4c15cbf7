//! Printing the syntax tree: an AST in, text out. `Display` gives
//! expressions, statement blocks and module tokens back in source form (for
//! messages and the disassembler); [`File::dump`] gives a deterministic
//! outline of a whole file for snapshot tests.

use std::fmt::{self, Write};

use super::ast::*;

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
                HeaderKind::LongAxiom(pieces) => {
                    let _ = write!(out, "axiom in {} pieces", pieces.len());
                    for p in pieces {
                        let _ = write!(out, " @{}..{}", p.start, p.end);
                    }
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
                HeaderKind::Texture(i, file, _) => {
                    let _ = write!(out, "texture {i} {file:?}");
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
