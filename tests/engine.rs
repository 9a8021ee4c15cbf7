//! Tests of `bytecode` and `derive` on hand-built programs.
//!
//! There is no dependency on the parser: a small private helper below
//! builds a resolved `Program` from a line-based mini format whose text is
//! also the source file, so spans point at real text.

use lsys::internals::bytecode::{self, disasm, Compiled};
use lsys::internals::derive::{
    homomorphism, Derivation, DeriveError, DeriveOptions, ModuleStore, Rand48,
};
use lsys::internals::resolve::*;
use lsys::internals::source::{Origin, SourceFile, SourceMap, Span};
use std::sync::Arc;

// ---------------------------------------------------------------------
// Mini program builder
//
//   axiom: A(1) B          successor syntax: one-character module names
//   ignore: + -            (or consider:)
//   seed: 3
//   ddepth: 4 / hdepth: 2  maximum depths
//   p: B(y) < A(x) > C : x < 3 --> A(x+y) ~ 0.5     (main table)
//   d: ...  / h: ...       decomposition / homomorphism
//
// `~ e` gives a probability; `else` and `*` are conditions.
// ---------------------------------------------------------------------

fn off(text: &str, sub: &str) -> usize {
    sub.as_ptr() as usize - text.as_ptr() as usize
}

fn sp(a: usize, b: usize) -> Span {
    Span::new(0, a, b)
}

struct Syms(Symbols);

impl Syms {
    fn new() -> Syms {
        let mut s = Syms(Symbols::default());
        s.id('[');
        s.id(']');
        s
    }
    fn id(&mut self, c: char) -> SymId {
        let name = c.to_string();
        if let Some(i) = self.0.get(&name) {
            return i;
        }
        let i = self.0.list.len() as SymId;
        self.0.list.push(Symbol {
            name: name.clone(),
            kind: SymbolKind::User,
            span: None,
        });
        self.0.by_name.insert(name, i);
        i
    }
}

/// Recursive-descent expression parser over `s[pos..end]` of the file text.
struct Ex<'a> {
    s: &'a [u8],
    pos: usize,
    end: usize,
    names: &'a [String],
}

impl Ex<'_> {
    fn ws(&mut self) {
        while self.pos < self.end && self.s[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }
    fn eat(&mut self, tok: &str) -> bool {
        self.ws();
        let t = tok.as_bytes();
        if self.pos + t.len() <= self.end && &self.s[self.pos..self.pos + t.len()] == t {
            self.pos += t.len();
            true
        } else {
            false
        }
    }
    fn mk(kind: ExprKind, a: usize, b: usize) -> Expr {
        Expr {
            kind,
            span: sp(a, b),
        }
    }
    fn expr(&mut self) -> Expr {
        let c = self.or();
        if self.eat("?") {
            let t = self.expr();
            assert!(self.eat(":"), "expected ':' in ternary");
            let f = self.expr();
            let (a, b) = (c.span.start as usize, f.span.end as usize);
            return Ex::mk(ExprKind::Cond(Arc::new(c), Arc::new(t), Arc::new(f)), a, b);
        }
        c
    }
    fn binary(&mut self, ops: &[(&str, BinOp)], next: fn(&mut Self) -> Expr) -> Expr {
        let mut l = next(self);
        'outer: loop {
            for &(tok, op) in ops {
                let save = self.pos;
                if self.eat(tok) {
                    // `<` must not take `<=`'s place, `!` not `!=`'s.
                    if self.pos < self.end && tok.len() == 1 && self.s[self.pos] == b'=' {
                        self.pos = save;
                        continue;
                    }
                    let r = next(self);
                    let (a, b) = (l.span.start as usize, r.span.end as usize);
                    l = Ex::mk(ExprKind::Binary(op, Arc::new(l), Arc::new(r)), a, b);
                    continue 'outer;
                }
            }
            return l;
        }
    }
    fn or(&mut self) -> Expr {
        self.binary(&[("||", BinOp::Or)], Self::and)
    }
    fn and(&mut self) -> Expr {
        self.binary(&[("&&", BinOp::And)], Self::eq)
    }
    fn eq(&mut self) -> Expr {
        self.binary(&[("==", BinOp::Eq), ("!=", BinOp::Ne)], Self::cmp)
    }
    fn cmp(&mut self) -> Expr {
        self.binary(
            &[
                ("<=", BinOp::Le),
                (">=", BinOp::Ge),
                ("<", BinOp::Lt),
                (">", BinOp::Gt),
            ],
            Self::add,
        )
    }
    fn add(&mut self) -> Expr {
        self.binary(&[("+", BinOp::Add), ("-", BinOp::Sub)], Self::mul)
    }
    fn mul(&mut self) -> Expr {
        self.binary(
            &[("*", BinOp::Mul), ("/", BinOp::Div), ("%", BinOp::Rem)],
            Self::unary,
        )
    }
    fn unary(&mut self) -> Expr {
        self.ws();
        let a = self.pos;
        for (tok, op) in [("-", UnOp::Neg), ("!", UnOp::Not)] {
            if self.eat(tok) {
                let e = self.unary();
                let b = e.span.end as usize;
                return Ex::mk(ExprKind::Unary(op, Arc::new(e)), a, b);
            }
        }
        self.pow()
    }
    fn pow(&mut self) -> Expr {
        let base = self.primary();
        if self.eat("^") {
            let e = self.unary();
            let (a, b) = (base.span.start as usize, e.span.end as usize);
            return Ex::mk(
                ExprKind::Binary(BinOp::Pow, Arc::new(base), Arc::new(e)),
                a,
                b,
            );
        }
        base
    }
    fn primary(&mut self) -> Expr {
        self.ws();
        let a = self.pos;
        if self.eat("(") {
            let mut e = self.expr();
            assert!(self.eat(")"), "expected ')'");
            e.span = sp(a, self.pos);
            return e;
        }
        let c = self.s[self.pos];
        if c.is_ascii_digit() || c == b'.' {
            while self.pos < self.end
                && (self.s[self.pos].is_ascii_digit() || self.s[self.pos] == b'.')
            {
                self.pos += 1;
            }
            let t = std::str::from_utf8(&self.s[a..self.pos]).unwrap();
            return Ex::mk(ExprKind::Num(t.parse().unwrap()), a, self.pos);
        }
        assert!(c.is_ascii_alphabetic(), "unexpected {:?}", c as char);
        while self.pos < self.end && self.s[self.pos].is_ascii_alphanumeric() {
            self.pos += 1;
        }
        let name = std::str::from_utf8(&self.s[a..self.pos])
            .unwrap()
            .to_string();
        if let Some(f) = Func::from_name(&name) {
            assert!(self.eat("("));
            let mut args = vec![self.expr()];
            while self.eat(",") {
                args.push(self.expr());
            }
            assert!(self.eat(")"));
            return Ex::mk(ExprKind::Call(f, args), a, self.pos);
        }
        let slot = self
            .names
            .iter()
            .position(|n| *n == name)
            .unwrap_or_else(|| panic!("unknown name {name}"));
        Ex::mk(ExprKind::Param(slot as u16), a, self.pos)
    }
}

fn expr(text: &str, sub: &str, names: &[String]) -> Expr {
    let sub = sub.trim();
    let start = off(text, sub);
    let mut p = Ex {
        s: text.as_bytes(),
        pos: start,
        end: start + sub.len(),
        names,
    };
    let e = p.expr();
    p.ws();
    assert_eq!(p.pos, p.end, "trailing text in {sub:?}");
    e
}

/// Split a module list into (name char, byte offset, optional args text).
fn modules<'t>(text: &'t str, sub: &'t str) -> Vec<(char, usize, usize, Option<&'t str>)> {
    let base = off(text, sub);
    let b = sub.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        let c = b[i] as char;
        i += 1;
        let mut args = None;
        if i < b.len() && b[i] == b'(' {
            let mut depth = 0;
            let a = i + 1;
            loop {
                match b[i] {
                    b'(' => depth += 1,
                    b')' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                i += 1;
            }
            args = Some(&sub[a..i]);
            i += 1;
        }
        out.push((c, base + start, base + i, args));
    }
    out
}

/// Split `a,b` at top-level commas.
fn split_args(s: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut last) = (0, 0);
    for (i, c) in s.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&s[last..i]);
                last = i + 1;
            }
            _ => {}
        }
    }
    out.push(&s[last..]);
    out
}

fn succ(text: &str, sub: &str, syms: &mut Syms, names: &[String]) -> Vec<SuccModule> {
    modules(text, sub)
        .into_iter()
        .map(|(c, a, b, args)| SuccModule {
            sym: syms.id(c),
            args: args
                .map(|s| {
                    split_args(s)
                        .into_iter()
                        .map(|x| expr(text, x, names))
                        .collect()
                })
                .unwrap_or_default(),
            span: sp(a, b),
        })
        .collect()
}

fn pattern(text: &str, sub: &str, syms: &mut Syms, names: &mut Vec<String>) -> Vec<PatItem> {
    modules(text, sub)
        .into_iter()
        .map(|(c, a, b, args)| match c {
            '[' => PatItem::Open(sp(a, b)),
            ']' => PatItem::Close(sp(a, b)),
            _ => {
                let formals: Vec<&str> = args
                    .map(|s| s.split(',').map(str::trim).collect())
                    .unwrap_or_default();
                let first = names.len() as u16;
                names.extend(formals.iter().map(|s| s.to_string()));
                PatItem::Module(PatModule {
                    sym: syms.id(c),
                    arity: formals.len() as u8,
                    first_param: first,
                    span: sp(a, b),
                })
            }
        })
        .collect()
}

fn mods(items: Vec<PatItem>) -> Vec<PatModule> {
    items
        .into_iter()
        .map(|i| match i {
            PatItem::Module(m) => m,
            _ => panic!("brackets only in right contexts"),
        })
        .collect()
}

fn production(text: &str, line: &str, table: Table, syms: &mut Syms) -> Production {
    let (left, right) = line.split_once("-->").expect("-->");
    let (head, cond) = match left.split_once(':') {
        Some((h, c)) => (h, Some(c)),
        None => (left, None),
    };
    let (lctx, rest) = match head.split_once(" < ") {
        Some((l, r)) => (Some(l), r),
        None => (None, head),
    };
    let (pred, rctx) = match rest.split_once(" > ") {
        Some((p, r)) => (p, Some(r)),
        None => (rest, None),
    };
    let (succ_text, prob) = match right.split_once('~') {
        Some((s, p)) => (s, Some(p)),
        None => (right, None),
    };
    let mut names = Vec::new();
    let lctx = lctx.map_or(Vec::new(), |l| mods(pattern(text, l, syms, &mut names)));
    let pred_text = pred.trim();
    let pred = mods(pattern(text, pred, syms, &mut names));
    let rctx = rctx.map_or(Vec::new(), |r| pattern(text, r, syms, &mut names));
    let cond = match cond.map(str::trim) {
        None | Some("*") => Cond::Always,
        Some("else") => {
            let c = cond.unwrap().trim();
            let a = off(text, c);
            Cond::Else(sp(a, a + c.len()))
        }
        Some(c) => Cond::Expr(expr(text, c, &names)),
    };
    let line = line.trim();
    let start = off(text, line);
    let head_start = off(text, pred_text);
    Production {
        table,
        lsystem: 0,
        span: sp(start, start + line.len()),
        head_span: sp(head_start, head_start + pred_text.len()),
        lctx,
        pred,
        rctx,
        nparams: names.len() as u16,
        succ: succ(text, succ_text, syms, &names),
        prob: prob.map(|p| expr(text, p, &names)),
        param_names: names,
        cond,
        pre: Vec::new(),
        post: Vec::new(),
    }
}

fn program(src: &str) -> Program {
    let mut sources = SourceMap::new();
    sources.add(SourceFile::new("test.lsys", Origin::Memory, src));
    // Parse from the map's own copy so that offsets are those of the file.
    let text: &str = &sources.get(0).text.clone();
    let mut syms = Syms::new();
    let mut p = Program {
        sources: SourceMap::new(),
        symbols: Symbols::default(),
        axiom: Vec::new(),
        derivation_length: 0,
        derivation_length_given: false,
        seed: None,
        ring: false,
        main_lsystem: 0,
        sub_lsystems: Vec::new(),
        context: ContextFilter::All,
        productions: Vec::new(),
        decomposition: Vec::new(),
        homomorphism: Vec::new(),
        decomposition_depth: 16,
        homomorphism_depth: 16,
        defines: Vec::new(),
        profile: Default::default(),
        turtle: Default::default(),
        tables: Vec::new(),
        vars: Vec::new(),
        var_init: Vec::new(),
        arrays: Vec::new(),
        hooks: Default::default(),
        functions: Vec::new(),
        cpfg_surfaces: Vec::new(),
        environment: None,
    };
    for line in text.lines() {
        let Some((key, rest)) = line.trim_start().split_once(':') else {
            continue;
        };
        match key {
            "axiom" => p.axiom = succ(text, rest, &mut syms, &[]),
            "ignore" | "consider" => {
                let ids = rest
                    .split_whitespace()
                    .flat_map(|w| w.chars())
                    .map(|c| syms.id(c))
                    .collect();
                p.context = if key == "ignore" {
                    ContextFilter::Ignore(ids)
                } else {
                    ContextFilter::Consider(ids)
                };
            }
            "seed" => p.seed = Some(rest.trim().parse().unwrap()),
            "ddepth" => p.decomposition_depth = rest.trim().parse().unwrap(),
            "hdepth" => p.homomorphism_depth = rest.trim().parse().unwrap(),
            "p" => p
                .productions
                .push(production(text, rest, Table::Main, &mut syms)),
            "d" => p
                .decomposition
                .push(production(text, rest, Table::Decomposition, &mut syms)),
            "h" => p
                .homomorphism
                .push(production(text, rest, Table::Homomorphism, &mut syms)),
            _ => panic!("unknown line {line:?}"),
        }
    }
    p.symbols = syms.0;
    p.sources = sources;
    p
}

fn compile(p: &Program) -> Compiled {
    bytecode::compile(p).expect("compiles")
}

fn opts() -> DeriveOptions {
    DeriveOptions::default()
}

/// Every string from the axiom to `steps`, printed.
fn strings(src: &str, steps: u32) -> Vec<String> {
    let p = program(src);
    let c = compile(&p);
    let mut out = Vec::new();
    lsys::internals::simulation::derive_each(&p, &c, opts(), steps, |_, s| {
        out.push(s.display(&p.symbols))
    })
    .expect("derives");
    out
}

fn last(src: &str, steps: u32) -> String {
    strings(src, steps).pop().unwrap()
}

fn err(src: &str, steps: u32) -> (Program, DeriveError) {
    let p = program(src);
    let c = compile(&p);
    let e = lsys::internals::simulation::derive(&p, &c, opts(), steps).expect_err("fails");
    (p, e)
}

fn text_at(p: &Program, s: miette::SourceSpan) -> &str {
    let f = &p.sources.get(0).text;
    &f[s.offset()..s.offset() + s.len()]
}

// ---------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------

const W2: &str = "\
axiom: A(1)
p: A(x) : x < 18 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]
p: A(x) --> F(x)
";

#[test]
fn w2_first_steps_print_exactly() {
    let s = strings(W2, 2);
    assert_eq!(s[0], "A(1)");
    assert_eq!(s[1], "F(1) [ +(25) A(2) ] [ -(25) A(2) ]");
    assert_eq!(
        s[2],
        "F(1) [ +(25) F(2) [ +(25) A(3) ] [ -(25) A(3) ] ] \
         [ -(25) F(2) [ +(25) A(3) ] [ -(25) A(3) ] ]"
    );
}

#[test]
fn w2_derives_1048569_modules_in_18_steps() {
    let p = program(W2);
    let c = compile(&p);
    let mut d = Derivation::new(&p, &c, opts()).unwrap();
    for k in 1..=18u32 {
        d.step().unwrap();
        // 1 + 8 (2^k - 1) while A(x) still branches (x < 18), then A -> F.
        let expect = 1 + 8 * ((1usize << k.min(17)) - 1);
        assert_eq!(d.current().len(), expect, "step {k}");
    }
    assert_eq!(d.step_number(), 18);
    let s = d.current();
    let f = p.symbols.get("F").unwrap();
    let a = p.symbols.get("A").unwrap();
    assert_eq!(s.len(), 1_048_569);
    assert_eq!(s.count(a), 0);
    assert_eq!(s.count(f), (1 << 18) - 1);
    let counts = s.counts(p.symbols.len());
    assert_eq!(counts[OPEN_BRACKET as usize], (1 << 18) - 2);
    assert_eq!(counts[CLOSE_BRACKET as usize], (1 << 18) - 2);
    // The deepest F carries 18, there are 2^17 of them.
    let f18 = s
        .iter()
        .filter(|m| m.sym == f && m.params == [18.0])
        .count();
    assert_eq!(f18, 1 << 17);
}

#[test]
fn algae_lengths_are_fibonacci() {
    let s = strings("axiom: a\np: a --> a b\np: b --> a\n", 6);
    let want = [
        "a",
        "ab",
        "aba",
        "abaab",
        "abaababa",
        "abaababaabaab",
        "abaababaabaababaababa",
    ];
    for (got, want) in s.iter().zip(want) {
        assert_eq!(got.replace(' ', ""), want);
    }
    let lens: Vec<usize> = s.iter().map(|x| x.split(' ').count()).collect();
    assert_eq!(lens, [1, 2, 3, 5, 8, 13, 21]);
}

#[test]
fn quadratic_koch_island() {
    let src = "axiom: F-F-F-F\np: F --> F-F+F+FF-F-F+F\n";
    let s = strings(src, 2);
    let one = "F-F+F+FF-F-F+F";
    let want1 = [one, one, one, one].join("-");
    assert_eq!(s[1].replace(' ', ""), want1);
    let toks: Vec<&str> = s[2].split(' ').collect();
    // F -> 14 modules (8 F): 4*14 + 3 = 59 (32 F), then 32*14 + 27 = 475.
    assert_eq!(s[1].split(' ').count(), 59);
    assert_eq!(toks.len(), 475);
    assert_eq!(toks.iter().filter(|t| **t == "F").count(), 256);
}

#[test]
fn parameters_and_arity_must_match() {
    // `A(x)` matches only one-parameter A's.
    assert_eq!(
        last("axiom: A A(1) A(1,2)\np: A(x) --> B(x*10)\n", 1),
        "A B(10) A(1,2)"
    );
}

#[test]
fn expressions_builtins_and_short_circuit() {
    let src = "\
axiom: A(0) A(4)
p: A(x) : x > 0 && 8/x > 1 --> B(sin(90), cos(0), atan2(1,1), sign(0-3), 7 % 3, 2^10, x > 1 ? 10 : 20, sqrt(x), log(1), floor(2.5), max(x,7))
p: A(x) : x == 0 || 1/x > 2 --> C(!x, -x, abs(0-2), min(1,2) != 1)
";
    let p = program(src);
    let c = compile(&p);
    let s = lsys::internals::simulation::derive(&p, &c, opts(), 1).unwrap();
    let ms: Vec<_> = s.iter().collect();
    assert_eq!(p.symbols.name(ms[0].sym), "C");
    assert_eq!(ms[0].params, [1.0, -0.0, 2.0, 0.0]);
    assert_eq!(p.symbols.name(ms[1].sym), "B");
    let b = ms[1].params;
    assert!((b[0] - 1.0).abs() < 1e-12 && (b[1] - 1.0).abs() < 1e-12);
    assert!((b[2] - 45.0).abs() < 1e-12);
    assert_eq!(&b[3..], [-1.0, 1.0, 1024.0, 10.0, 2.0, 0.0, 2.0, 7.0]);
}

#[test]
fn else_applies_when_earlier_conditions_fail() {
    let src = "\
axiom: A(1) A(2) A(3)
p: A(x) : x == 2 --> B(x)
p: A(x) : else --> C(x)
";
    assert_eq!(last(src, 1), "C(1) B(2) C(3)");
}

#[test]
fn first_match_in_file_order_wins() {
    let src = "axiom: A(5)\np: A(x) : x > 1 --> B\np: A(x) : x > 2 --> C\np: A(x) --> D\n";
    assert_eq!(last(src, 1), "B");
    // A constant false condition never applies, a constant true one always.
    let src = "axiom: A A\np: A : 0 --> B\np: A : 1 --> C\n";
    assert_eq!(last(src, 1), "C C");
}

#[test]
fn multi_module_predecessor() {
    let src = "axiom: A(1) B(2) A(3) A(4) B(5) B(6) A(7)\np: A(x) B(y) --> C(x+y)\n";
    assert_eq!(last(src, 1), "C(3) A(3) C(9) B(6) A(7)");
}

#[test]
fn left_context_skips_branches_and_climbs_out() {
    let src = "axiom: B[A]A[A]A\np: B < A --> B\n";
    let s = strings(src, 2);
    assert_eq!(s[1], "B [ B ] B [ A ] A");
    assert_eq!(s[2], "B [ B ] B [ B ] B");
}

#[test]
fn ignore_and_consider_in_context() {
    let axiom = "axiom: B[+A]-A[-A]+A\n";
    let rule = "p: B < A --> B\n";
    // Without a filter `+` and `-` block the context.
    assert_eq!(
        last(&format!("{axiom}{rule}"), 1),
        "B [ + A ] - A [ - A ] + A"
    );
    let want = "B [ + B ] - B [ - A ] + A";
    assert_eq!(last(&format!("{axiom}ignore: + -\n{rule}"), 1), want);
    assert_eq!(last(&format!("{axiom}consider: A B\n{rule}"), 1), want);
    // Ignored symbols can still be matched by the strict predecessor.
    assert_eq!(
        last("axiom: B+A\nignore: +\np: B < A --> X\np: + --> -\n", 1),
        "B - X"
    );
}

#[test]
fn right_context_skips_branches_and_stops_at_branch_end() {
    let src = "axiom: A[C]B[A]BACB\np: A > B --> X\n";
    assert_eq!(last(src, 1), "X [ C ] B [ A ] B A C B");
}

#[test]
fn right_context_with_brackets_in_the_pattern() {
    let src = "axiom: A[B]CA[BD]CA[D]CAC\np: A > [B]C --> X\n";
    assert_eq!(last(src, 1), "X [ B ] C X [ B D ] C A [ D ] C A C");
}

#[test]
fn context_binds_parameters() {
    let src = "\
axiom: B(2)[A(1)]A(5)C(10)
p: B(y) < A(x) > C(z) --> A(x+y+z)
p: B(y) < A(x) --> A(x+y)
";
    assert_eq!(last(src, 1), "B(2) [ A(3) ] A(17) C(10)");
    // Two-module left context, across a branch.
    let src = "axiom: B[D]CA BDCA\np: B C < A --> X\n";
    assert_eq!(last(src, 1), "B [ D ] C X B D C A");
}

#[test]
fn context_is_checked_when_bindings_come_straight_from_the_string() {
    // Predecessor parameters only: the fast binding path, context still checked.
    let src = "axiom: A(1) B A(2) C A(3)[B]B\np: A(x) > B --> X(x)\n";
    assert_eq!(last(src, 1), "X(1) B A(2) C X(3) [ B ] B");
    let src = "axiom: B A(1) C A(2)\np: B < A(x) --> X(x)\n";
    assert_eq!(last(src, 1), "B X(1) C A(2)");
}

#[test]
fn contexts_use_the_string_before_the_step() {
    // Parallel rewriting: every context sees the old string.
    let s = strings("axiom: BAAA\np: B < A --> B\n", 3);
    assert_eq!(s[1], "B B A A");
    assert_eq!(s[2], "B B B A");
    assert_eq!(s[3], "B B B B");
}

#[test]
fn unbalanced_brackets_fail_context_but_do_not_crash() {
    assert_eq!(last("axiom: B]A\np: B < A --> X\n", 1), "B ] A");
    assert_eq!(last("axiom: A[B\np: A > B --> X\n", 1), "A [ B");
}

/// POSIX drand48 computed independently (128-bit arithmetic).
fn drand48_seq(seed: u64, n: usize) -> Vec<f64> {
    let mut x: u128 = (((seed as u32) as u128) << 16) | 0x330E;
    (0..n)
        .map(|_| {
            x = (x * 25_214_903_917 + 11) % (1u128 << 48);
            x as f64 / 281_474_976_710_656.0
        })
        .collect()
}

#[test]
fn rand48_matches_posix() {
    let want = drand48_seq(0, 3);
    // srand48(0); drand48() is 0.170828036106...: state 0x330E, and
    // 0x5DEECE66D * 0x330E + 0xB = 329558794195201, minus 2^48.
    assert!((want[0] - 0.170_828_036_106).abs() < 1e-11);
    assert_eq!(want[0], 48_083_817_484_545.0 / 281_474_976_710_656.0);
    let mut r = Rand48::new(0);
    let got: Vec<f64> = (0..3).map(|_| r.next_f64()).collect();
    assert_eq!(got, want);
    // Only the low 32 bits of the seed count, as with srand48's long.
    let mut a = Rand48::new(5);
    let mut b = Rand48::new(5 + (1 << 32));
    assert_eq!(a.next_f64(), b.next_f64());
    assert_eq!(drand48_seq(12345, 5), {
        let mut r = Rand48::new(12345);
        (0..5).map(|_| r.next_f64()).collect::<Vec<_>>()
    });
}

#[test]
fn stochastic_choice_follows_the_documented_draws() {
    let src = "axiom: AAAAAAAAAAAA\np: A --> B ~ 1\np: A --> C ~ 3\n";
    let p = program(src);
    let c = compile(&p);
    let run = |seed| {
        let o = DeriveOptions {
            seed: Some(seed),
            ..opts()
        };
        lsys::internals::simulation::derive(&p, &c, o, 1)
            .unwrap()
            .display(&p.symbols)
    };
    let expect = |seed| {
        drand48_seq(seed, 12)
            .into_iter()
            .map(|u| if u * 4.0 < 1.0 { "B" } else { "C" })
            .collect::<Vec<_>>()
            .join(" ")
    };
    assert_eq!(run(0), expect(0));
    assert_eq!(run(0), run(0));
    assert_eq!(run(42), expect(42));
    assert_ne!(run(0), run(42));
    assert!(run(0).contains('B') && run(0).contains('C'));
    // The program's seed is used unless the options override it.
    let p2 = program(&format!("seed: 42\n{src}"));
    let c2 = compile(&p2);
    assert_eq!(
        lsys::internals::simulation::derive(&p2, &c2, opts(), 1)
            .unwrap()
            .display(&p2.symbols),
        expect(42)
    );
}

#[test]
fn stochastic_with_conditions_zero_weights_and_ran() {
    // The conditional production does not take part when its condition fails.
    let src = "axiom: A(0) A(1)\np: A(x) : x > 0 --> B ~ 1\np: A(x) --> C ~ 1\n";
    let u = drand48_seq(0, 2);
    let first = "C"; // only C matches A(0); one draw is still made
    let second = if u[1] * 2.0 < 1.0 { "B" } else { "C" };
    assert_eq!(last(src, 1), format!("{first} {second}"));
    // All weights zero: copied unchanged.
    assert_eq!(
        last("axiom: A A\np: A --> B ~ 0\np: A --> C ~ 0\n", 1),
        "A A"
    );
    // ran() in the axiom draws left to right from the same generator.
    let u = drand48_seq(7, 2);
    assert_eq!(
        last("seed: 7\naxiom: A(ran(10)) B(ran(2))\n", 0),
        format!("A({}) B({})", 10.0 * u[0], 2.0 * u[1])
    );
}

#[test]
fn bad_probability_is_an_error() {
    let (p, e) = err("axiom: A\np: A --> B ~ 0-1\np: A --> C ~ 1\n", 1);
    match &e {
        DeriveError::BadProbability {
            value, step, span, ..
        } => {
            assert_eq!(*value, -1.0);
            assert_eq!(*step, 1);
            assert_eq!(text_at(&p, *span), "0-1");
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn module_limit_stops_the_step_early() {
    let p = program(W2);
    let c = compile(&p);
    let o = DeriveOptions {
        max_modules: 1000,
        ..opts()
    };
    // 505 modules after 6 steps, 1017 after 7.
    let e = lsys::internals::simulation::derive(&p, &c, o, 10).expect_err("limit");
    match &e {
        DeriveError::ModuleLimit {
            step,
            limit,
            reached,
            ..
        } => {
            assert_eq!((*step, *limit), (7, 1000));
            assert!(*reached > 1000 && *reached < 1017, "reached {reached}");
        }
        other => panic!("unexpected {other:?}"),
    }
    assert_eq!(e.step(), Some(7));
    let msg = e.to_string();
    assert!(msg.contains("step 7") && msg.contains("1000"), "{msg}");
    let help = miette::Diagnostic::help(&e).unwrap().to_string();
    assert!(help.contains("--max-modules"), "{help}");
    // Six steps fit.
    assert_eq!(
        lsys::internals::simulation::derive(
            &p,
            &c,
            DeriveOptions {
                max_modules: 1000,
                ..opts()
            },
            6
        )
        .unwrap()
        .len(),
        505
    );
}

#[test]
fn division_by_zero_carries_span_production_and_step() {
    let src = "axiom: A(3)\np: A(x) --> A(x-1) B(1/(x-1))\n";
    let (p, e) = err(src, 5);
    match &e {
        DeriveError::DivisionByZero {
            step,
            span,
            production,
            context,
            ..
        } => {
            // A(3) -> A(2) B(.5) -> A(1) B(1) -> A(0) B(1/0) at step 3.
            assert_eq!(*step, 3);
            assert_eq!(text_at(&p, *span), "1/(x-1)");
            assert_eq!(text_at(&p, production.unwrap()), "A(x)");
            assert!(context.contains("A(x) --> A(x-1) B(1/(x-1))"), "{context}");
        }
        other => panic!("unexpected {other:?}"),
    }
    assert_eq!(
        miette::Diagnostic::code(&e).unwrap().to_string(),
        "lsys::derive::division_by_zero"
    );
    assert!(e.to_string().contains("at step 3: division by zero"), "{e}");
}

#[test]
fn non_finite_parameter_is_caught_at_emit() {
    let (p, e) = err("axiom: A(0-4)\np: A(x) --> B(1, sqrt(x))\n", 1);
    match &e {
        DeriveError::NotFinite {
            value, span, step, ..
        } => {
            assert!(value.is_nan());
            assert_eq!(*step, 1);
            assert_eq!(text_at(&p, *span), "sqrt(x)");
        }
        other => panic!("unexpected {other:?}"),
    }
    // Remainder by zero, in the axiom.
    let (p, e) = err("axiom: A(5 % 0)\n", 0);
    match &e {
        DeriveError::DivisionByZero {
            what,
            span,
            step,
            context,
            ..
        } => {
            assert_eq!((*what, *step), ("remainder", 0));
            assert_eq!(text_at(&p, *span), "5 % 0");
            assert_eq!(context, "in the axiom");
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn decomposition_recurses_up_to_the_depth() {
    let src = "axiom: A(3)\np: A(x) --> A(x+2)\nd: A(x) : x > 0 --> A(x-1) B\n";
    let s = strings(src, 1);
    assert_eq!(s[0], "A(0) B B B");
    assert_eq!(s[1], "A(0) B B B B B");
    // With depth 2 the chain stops early and warns.
    let p = program(&format!("ddepth: 2\n{src}"));
    let c = compile(&p);
    let d = Derivation::new(&p, &c, opts()).unwrap();
    assert_eq!(d.current().display(&p.symbols), "A(1) B B");
    assert_eq!(d.warnings().len(), 1);
    assert_eq!(d.warnings()[0].count, 1);
    assert_eq!(d.warnings()[0].table, "decomposition");
    let p0 = program(src);
    let c0 = compile(&p0);
    let d0 = Derivation::new(&p0, &c0, opts()).unwrap();
    assert!(d0.warnings().is_empty());
}

#[test]
fn homomorphism_is_recursive_and_not_fed_back() {
    let src = "axiom: X Y\np: Y --> Y Y\nh: X --> F F\nh: F --> G(ran(1))\n";
    let p = program(src);
    let c = compile(&p);
    let mut d = Derivation::new(&p, &c, opts()).unwrap();
    d.step().unwrap();
    assert_eq!(d.current().display(&p.symbols), "X Y Y");
    let h = d.homomorphism().unwrap();
    let u = drand48_seq(0, 2);
    assert_eq!(
        h.modules.display(&p.symbols),
        format!("G({}) G({}) Y Y", u[0], u[1])
    );
    assert!(h.warnings.is_empty());
    // Fresh generator every time: same result again, derivation untouched.
    assert_eq!(d.homomorphism().unwrap().modules, h.modules);
    d.step().unwrap();
    assert_eq!(d.current().display(&p.symbols), "X Y Y Y Y");
    // Depth 1: F is left as it is, with a warning.
    let p1 = program(&format!("hdepth: 1\n{src}"));
    let c1 = compile(&p1);
    let s = lsys::internals::simulation::derive(&p1, &c1, opts(), 0).unwrap();
    let h1 = homomorphism(&p1, &c1, &s, &opts(), 0).unwrap();
    assert_eq!(h1.modules.display(&p1.symbols), "F F Y");
    assert_eq!(h1.warnings.len(), 1);
    assert_eq!(h1.warnings[0].count, 2);
}

#[test]
fn store_prints_and_counts() {
    let p = program("axiom: A(1, 2.5, 0.1) B C(-3) B(1000000)\n");
    let c = compile(&p);
    let s = lsys::internals::simulation::derive(&p, &c, opts(), 0).unwrap();
    assert_eq!(s.display(&p.symbols), "A(1,2.5,0.1) B C(-3) B(1000000)");
    assert_eq!(s.len(), 4);
    assert_eq!(s.param_count(), 5);
    assert_eq!(s.count(p.symbols.get("B").unwrap()), 2);
    let mut v = Vec::new();
    s.write_string(&p.symbols, &mut v).unwrap();
    assert_eq!(v, s.display(&p.symbols).as_bytes());
    assert_eq!(ModuleStore::new().display(&p.symbols), "");
}

#[test]
fn disassembly_is_readable_and_stable() {
    let p = program(W2);
    let c = compile(&p);
    let text = disasm(&p, &c);
    assert_eq!(text, disasm(&p, &c));
    assert!(
        text.contains(
            "production 0: A(x) : x < 18 --> F(x)[+(25)A(x+1)][-(25)A(x+1)]  ; test.lsys:2:4"
        ),
        "{text}"
    );
    assert!(text.contains("  slots: 0=x\n"), "{text}");
    assert!(text.contains("  condition: none\n"), "{text}");
    // Condition: param x, const 18, lt, ret.
    let cond: Vec<&str> = text
        .lines()
        .skip_while(|l| *l != "  condition:")
        .skip(1)
        .take(4)
        .map(|l| l.split_whitespace().nth(1).unwrap())
        .collect();
    assert_eq!(cond, ["param", "const", "lt", "ret"]);
    assert!(text.contains("; 18"), "{text}");
    assert!(text.contains("emit_const    +/1 #"), "{text}");
    assert!(text.contains("; +(25)"), "{text}");
    assert!(text.contains("emit          A/1"), "{text}");
    assert!(text.contains("; A(x+1)"), "{text}");
    // `[` is emitted from the pool, 1 is shared by the axiom and `x+1`.
    let ones = c.consts.iter().filter(|&&v| v == 1.0).count();
    assert_eq!(ones, 1);
}

#[test]
fn bytecode_uses_jumps_for_logic_and_ternary() {
    let p = program("axiom: A(1)\np: A(x) : x > 0 && x < 2 --> B(x > 1 ? 1 : 2)\n");
    let c = compile(&p);
    let cond = match &c.main[0].cond {
        bytecode::CondCode::Code(ch) => ch.clone(),
        other => panic!("{other:?}"),
    };
    let jumps = cond
        .code
        .iter()
        .filter(|o| matches!(o, bytecode::Op::JumpIfFalse(_)))
        .count();
    assert_eq!(jumps, 2);
    assert_eq!(cond.code.len(), cond.spans.len());
    assert_eq!(*cond.code.last().unwrap(), bytecode::Op::Ret);
    assert_eq!(
        last(
            "axiom: A(1) A(3)\np: A(x) : x > 0 && x < 2 --> B(x > 1 ? 1 : 2)\n",
            1
        ),
        "B(2) A(3)"
    );
}

#[test]
#[ignore]
fn show_disassembly_and_diagnostic() {
    let p = program("axiom: A(ran(2))\np: A(x) : x > 0 && x < 2 --> B(x > 1 ? 1 : 2)[+(25)]A(x/0) ~ 0.5\nh: B(y) --> F\n");
    let c = compile(&p);
    println!("{}", disasm(&p, &c));
    let e = lsys::internals::simulation::derive(&p, &c, opts(), 1).unwrap_err();
    let mut s = String::new();
    miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
        .render_report(&mut s, &e)
        .unwrap();
    println!("{s}");
}

#[test]
#[ignore]
fn w2_throughput() {
    let p = program(W2);
    let c = compile(&p);
    let mut times = Vec::new();
    for _ in 0..7 {
        let t = std::time::Instant::now();
        let s = lsys::internals::simulation::derive(&p, &c, opts(), 18).unwrap();
        times.push(t.elapsed().as_secs_f64());
        assert_eq!(s.len(), 1_048_569);
    }
    times.sort_by(f64::total_cmp);
    let med = times[times.len() / 2];
    println!(
        "W2: 18 steps, 1048569 modules, median {:.2} ms, {:.3e} modules/s",
        med * 1e3,
        1_048_569.0 / med
    );
}
