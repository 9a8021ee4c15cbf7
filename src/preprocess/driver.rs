//! One preprocessor run. Input: the root file, the resolver, the options.
//! Output: every file read with its preprocessed text, and the errors.
//! Files are processed one logical line at a time: directives here, text
//! lines through [`Expander`], included files recursively at their
//! `#include` line (so their macros are defined for what follows).

use std::collections::{HashMap, VecDeque};
use std::ops::Range;
use std::rc::Rc;

use super::conditional::{Conditionals, Misplaced};
use super::error::{ErrorKind, PreprocessError};
use super::expand::Expander;
use super::if_expr::{eval, replace_defined};
use super::lexer::{lex, lex_fragment};
use super::macros::{parse_define, Macros};
use super::render::Render;
use super::token::{Kind, Token};
use super::{IncludeSite, Options, OutFile, Output, RawFile, Resolver};
use super::{MAX_FILES, MAX_TOTAL_BYTES};

/// Tokens the expansions of one line may produce before expansion stops
/// (`#define A B B`, `#define B C C`, ... grows exponentially).
const LINE_BUDGET: usize = if cfg!(test) { 50_000 } else { 1_000_000 };
/// The same for a whole run, so many such lines cannot take long either.
/// A token is about 100 bytes while expanded and its text is parsed after
/// (docs/limits.md): 50 million took 3.7 GB and 38 s, then aborted.
/// The largest expansion among the corpus models is far below this.
const RUN_BUDGET: usize = 2_000_000;

struct Pp<'r> {
    macros: Macros,
    /// The `-D` names: they win over the files' own `#define`s.
    overrides: super::overrides::Overrides,
    /// Every name a file `#define`s, for suggestions.
    file_macros: Vec<String>,
    errors: Vec<PreprocessError>,
    files: Vec<OutFile>,
    resolver: &'r mut dyn Resolver,
    max_include: usize,
    max_expansion: usize,
    /// What the current line's expansions may still produce.
    budget: usize,
    /// What the rest of the run may still produce.
    run_budget: usize,
    run_budget_reported: bool,
    /// Indices of the files being processed, outermost first.
    chain: Vec<usize>,
    /// After one depth or count error, further includes are refused, so a
    /// file that includes itself twice cannot take exponential time.
    includes_stopped: bool,
    /// Bytes of all files read so far, the root's too.
    bytes_read: usize,
}

pub(crate) fn run(
    root: RawFile,
    resolver: &mut dyn Resolver,
    opts: &Options,
) -> (Output, Vec<PreprocessError>) {
    let bytes_read = root.text.len();
    let mut pp = Pp {
        macros: HashMap::new(),
        overrides: super::overrides::Overrides::new(&opts.defines),
        file_macros: Vec::new(),
        errors: Vec::new(),
        files: vec![OutFile {
            raw: root,
            text: String::new(),
            includes: Vec::new(),
        }],
        resolver,
        max_include: opts.max_include_depth.min(256),
        max_expansion: opts.max_expansion_depth.clamp(1, 256),
        budget: 0,
        run_budget: RUN_BUDGET,
        run_budget_reported: false,
        chain: Vec::new(),
        includes_stopped: false,
        bytes_read,
    };
    pp.predefine(&opts.defines);
    pp.process(0);
    pp.report_unmatched_overrides();
    (Output { files: pp.files }, pp.errors)
}

/// A `#` first on a line followed by a name, a number (a line marker) or
/// nothing. Unlike GNU cpp (which reports "invalid preprocessing
/// directive"), `#(w)` at the start of a line is cpfg's turtle command and
/// stays text: real cpfg models begin continuation lines with it.
fn is_directive(line: &[Token]) -> bool {
    line.first().is_some_and(|t| t.bol && t.is_punct("#"))
        && line
            .get(1)
            .map_or(true, |t| matches!(t.kind, Kind::Ident | Kind::Number))
}

/// Tokens spelled back as text, with single spaces where there was space.
fn spell(toks: &[Token]) -> String {
    let mut s = String::new();
    for (k, t) in toks.iter().enumerate() {
        if k > 0 && t.has_space() {
            s.push(' ');
        }
        s.push_str(&t.text);
    }
    s
}

fn span_of(toks: &[Token], fallback: &Range<usize>) -> Range<usize> {
    match (toks.first(), toks.last()) {
        (Some(a), Some(b)) => a.span.start..b.span.end.max(a.span.start),
        _ => fallback.clone(),
    }
}

impl Pp<'_> {
    fn error(
        &mut self,
        kind: ErrorKind,
        file: usize,
        span: Range<usize>,
        message: String,
    ) -> &mut PreprocessError {
        self.errors
            .push(PreprocessError::new(kind, file, span, message));
        let n = self.errors.len() - 1;
        &mut self.errors[n]
    }

    /// An error, on the root file, for each `-D` the model never defines
    /// or mentions (a misspelt name did nothing before).
    fn report_unmatched_overrides(&mut self) {
        let texts = self.files.iter().map(|f| f.raw.text.as_str());
        let unmatched = self.overrides.unmatched(texts, &self.file_macros);
        let root = self.files[0].raw.name.clone();
        for (name, near) in unmatched {
            let near = near.map_or(String::new(), |n| format!("did you mean `{n}`? "));
            let e = PreprocessError::new(
                ErrorKind::UnknownDefine,
                0,
                0..0,
                format!("the define `{name}` given as an option matches no #define in {root}"),
            )
            .help(format!("{near}a define given with -D replaces the model's own `#define NAME ...`; check the name"));
            self.errors.push(e);
        }
    }

    fn predefine(&mut self, defines: &[(String, String)]) {
        for (name, value) in defines {
            let toks = lex_fragment(&format!("{name} {value}"), 0..0, 0);
            match parse_define(&toks) {
                Ok(m) => {
                    self.macros.insert(m.name.clone(), Rc::new(m));
                }
                Err(e) => {
                    self.error(
                        ErrorKind::BadDirective,
                        0,
                        0..0,
                        format!("in the definition -D {name}={value}: {}", e.message),
                    );
                }
            }
        }
    }

    fn process(&mut self, idx: usize) {
        let Some(raw) = self.files.get(idx).map(|f| f.raw.clone()) else {
            return;
        };
        self.chain.push(idx);
        let lexed = lex(&raw.text, idx, &mut self.errors);
        let mut render = Render::new(lexed.line_count);
        let mut conds = Conditionals::default();
        let mut lines: VecDeque<Vec<Token>> = lexed.lines.into();
        while let Some(line) = lines.pop_front() {
            if is_directive(&line) {
                self.directive(idx, &raw, &line, &mut conds, &mut render);
                continue;
            }
            if !conds.active() {
                continue;
            }
            // An invocation may continue on the next lines, up to a directive.
            let mut more = || {
                if lines.front().is_some_and(|l| is_directive(l)) {
                    None
                } else {
                    lines.pop_front()
                }
            };
            if self.run_budget == 0 && !self.run_budget_reported {
                self.run_budget_reported = true;
                let span = span_of(&line, &(0..0));
                self.error(
                    ErrorKind::Recursion,
                    idx,
                    span,
                    format!("macro expansions produced over {RUN_BUDGET} tokens; from here on nothing is expanded"),
                );
            }
            self.start_budget();
            let mut ex = Expander {
                macros: &self.macros,
                errors: &mut self.errors,
                file: idx,
                file_name: &raw.name,
                max_depth: self.max_expansion,
                budget: &mut self.budget,
            };
            let out = ex.expand(line.into(), &mut more, 0);
            self.end_budget();
            render.emit(&out);
        }
        let open: Vec<Range<usize>> = conds.unterminated().collect();
        for span in open {
            self.error(
                ErrorKind::UnterminatedIf,
                idx,
                span,
                format!(
                    "this conditional is not closed by #endif before the end of {}",
                    raw.name
                ),
            )
            .help =
                Some("add `#endif`; every #if/#ifdef/#ifndef needs one in the same file".into());
        }
        if let Some(f) = self.files.get_mut(idx) {
            f.text = render.finish();
        }
        self.chain.pop();
    }

    fn expand_alone(&mut self, idx: usize, name: &str, toks: &[Token]) -> Vec<Token> {
        let mut none = || None;
        self.start_budget();
        let mut ex = Expander {
            macros: &self.macros,
            errors: &mut self.errors,
            file: idx,
            file_name: name,
            max_depth: self.max_expansion,
            budget: &mut self.budget,
        };
        let out = ex.expand(toks.iter().cloned().collect(), &mut none, 0);
        self.end_budget();
        out
    }

    fn start_budget(&mut self) {
        self.budget = LINE_BUDGET.min(self.run_budget);
    }

    fn end_budget(&mut self) {
        let used = LINE_BUDGET.min(self.run_budget) - self.budget;
        self.run_budget -= used;
    }

    fn eval_if(&mut self, idx: usize, raw: &RawFile, rest: &[Token], whole: &Range<usize>) -> bool {
        let result = replace_defined(rest, &self.macros).and_then(|toks| {
            let expanded = self.expand_alone(idx, &raw.name, &toks);
            eval(&expanded, whole.clone())
        });
        match result {
            Ok(v) => v != 0,
            Err(e) => {
                let err = self.error(ErrorKind::IfExpression, idx, e.span, e.message);
                err.help = e.help;
                false
            }
        }
    }

    fn misplaced(&mut self, idx: usize, what: &str, m: Misplaced, span: Range<usize>) {
        let (kind, message) = match m {
            Misplaced::WithoutIf => (
                match what {
                    "else" => ErrorKind::ElseWithoutIf,
                    "elif" => ErrorKind::ElifWithoutIf,
                    _ => ErrorKind::EndifWithoutIf,
                },
                format!("#{what} without #if"),
            ),
            Misplaced::AfterElse => (ErrorKind::ElseAfterElse, format!("#{what} after #else")),
        };
        self.error(kind, idx, span, message);
    }

    fn directive(
        &mut self,
        idx: usize,
        raw: &RawFile,
        line: &[Token],
        conds: &mut Conditionals,
        render: &mut Render,
    ) {
        let Some(hash) = line.first() else { return };
        let Some(name_tok) = line.get(1) else {
            return; // The null directive.
        };
        let whole = span_of(line, &hash.span);
        let rest = line.get(2..).unwrap_or(&[]);
        let name: &str = match name_tok.kind {
            Kind::Ident => &name_tok.text,
            // `# 12 "file"`: a line marker, like #line.
            Kind::Number => "line",
            _ => "",
        };
        match name {
            "if" => {
                let c = conds.active() && self.eval_if(idx, raw, rest, &whole);
                conds.push(c, whole);
            }
            "ifdef" | "ifndef" => {
                let c = if conds.active() {
                    match rest.first() {
                        Some(t) if t.is_ident() => {
                            self.macros.contains_key(&t.text) == (name == "ifdef")
                        }
                        _ => {
                            self.error(
                                ErrorKind::BadDirective,
                                idx,
                                whole.clone(),
                                format!("#{name} needs a macro name"),
                            );
                            false
                        }
                    }
                } else {
                    false
                };
                conds.push(c, whole);
            }
            "elif" => {
                let c = conds.elif_needs_eval() && self.eval_if(idx, raw, rest, &whole);
                if let Err(m) = conds.elif(c) {
                    self.misplaced(idx, name, m, whole);
                }
            }
            "else" => {
                if let Err(m) = conds.else_() {
                    self.misplaced(idx, name, m, whole);
                }
            }
            "endif" => {
                if let Err(m) = conds.endif() {
                    self.misplaced(idx, name, m, whole);
                }
            }
            // Everything below only counts in a kept region.
            _ if !conds.active() => {}
            "define" => self.define(idx, rest, &whole),
            "undef" => match rest.first() {
                Some(t) if t.is_ident() => {
                    self.macros.remove(&t.text);
                }
                _ => {
                    self.error(
                        ErrorKind::BadDirective,
                        idx,
                        whole,
                        "#undef needs a macro name".into(),
                    );
                }
            },
            "include" | "include_next" | "import" => {
                self.include(idx, raw, hash, rest, &whole, render)
            }
            "line" | "pragma" | "ident" | "sccs" | "assert" | "unassert" => {}
            "error" => {
                self.error(
                    ErrorKind::ErrorDirective,
                    idx,
                    whole,
                    format!("#error {}", spell(rest)),
                );
            }
            "warning" => {
                self.error(
                    ErrorKind::WarningDirective,
                    idx,
                    whole,
                    format!("#warning {}", spell(rest)),
                );
            }
            _ => {
                let shown = if name.is_empty() {
                    name_tok.text.to_string()
                } else {
                    name.to_string()
                };
                self.error(
                    ErrorKind::BadDirective,
                    idx,
                    name_tok.span.clone(),
                    format!("unknown preprocessor directive `#{shown}`"),
                )
                .help = Some(
                    "a `#` first on a line followed by a name starts a directive (#define, #include, #if, ...)"
                        .into(),
                );
            }
        }
    }

    fn define(&mut self, idx: usize, rest: &[Token], whole: &Range<usize>) {
        match parse_define(rest) {
            // The option's value stands, as `-D` does in `.lsys` files.
            Ok(m) if self.overrides.claims(&m.name) => {}
            Ok(m) => {
                self.file_macros.push(m.name.to_string());
                let name_span = rest.first().map_or(whole.clone(), |t| t.span.clone());
                if let Some(old) = self.macros.get(&m.name) {
                    if !old.same_as(&m) {
                        self.error(
                            ErrorKind::Redefined,
                            idx,
                            name_span,
                            format!(
                                "`{}` redefined; the new definition replaces the old one",
                                m.name
                            ),
                        );
                    }
                }
                self.macros.insert(m.name.clone(), Rc::new(m));
            }
            Err(e) => {
                let span =
                    e.at.and_then(|i| rest.get(i))
                        .map_or(whole.clone(), |t| t.span.clone());
                self.error(ErrorKind::BadDirective, idx, span, e.message);
            }
        }
    }

    /// `"name"` or `<name>` (after macro expansion if neither is written).
    fn include_operand(
        &mut self,
        idx: usize,
        raw: &RawFile,
        rest: &[Token],
    ) -> Option<(String, bool, Range<usize>)> {
        let direct = |toks: &[Token]| -> Option<(String, bool, Range<usize>)> {
            let first = toks.first()?;
            if first.kind == Kind::Str {
                let name = first.text.get(1..first.text.len() - 1)?.to_string();
                return Some((name, false, first.span.clone()));
            }
            if first.is_punct("<") {
                let close = toks.iter().position(|t| t.is_punct(">"))?;
                let inner = toks.get(1..close)?;
                let name: String = inner
                    .iter()
                    .enumerate()
                    .map(|(k, t)| {
                        if k > 0 {
                            format!("{}{}", t.ws, t.text)
                        } else {
                            t.text.to_string()
                        }
                    })
                    .collect();
                return Some((name, true, first.span.start..toks[close].span.end));
            }
            None
        };
        if let Some(r) = direct(rest) {
            return Some(r);
        }
        let expanded = self.expand_alone(idx, &raw.name, rest);
        direct(&expanded)
    }

    fn include(
        &mut self,
        idx: usize,
        raw: &RawFile,
        hash: &Token,
        rest: &[Token],
        whole: &Range<usize>,
        render: &mut Render,
    ) {
        let Some((name, angled, name_span)) = self.include_operand(idx, raw, rest) else {
            self.error(
                ErrorKind::BadDirective,
                idx,
                whole.clone(),
                "#include expects \"file\" or <file>".into(),
            );
            return;
        };
        if self.includes_stopped {
            return;
        }
        let file = match self.resolver.resolve(raw, &name, angled) {
            Ok(f) => f,
            Err(why) => {
                let shown = if angled {
                    format!("<{name}>")
                } else {
                    format!("\"{name}\"")
                };
                self.error(
                    ErrorKind::IncludeNotFound,
                    idx,
                    name_span,
                    format!("cannot include {shown}: {why}"),
                );
                return;
            }
        };
        if self.files.len() >= MAX_FILES || self.bytes_read + file.text.len() > MAX_TOTAL_BYTES {
            self.includes_stopped = true;
            self.error(
                ErrorKind::IncludeLimit,
                idx,
                name_span,
                format!(
                    "this include would read file {} and {} bytes in all, past the limits of {MAX_FILES} files and {} MiB for one model; nothing more is included",
                    self.files.len() + 1,
                    self.bytes_read + file.text.len(),
                    MAX_TOTAL_BYTES >> 20
                ),
            )
            .help = Some("an include tree that reads files more than once grows exponentially (each file including the next twice): guard each file with `#ifndef NAME` / `#define NAME` ... `#endif`, or include it once".into());
            return;
        }
        self.bytes_read += file.text.len();
        if self.chain.len() > self.max_include {
            self.includes_stopped = true;
            let message = self.depth_message(&file);
            self.error(ErrorKind::IncludeDepth, idx, name_span, message).help = Some(
                "guard the file with `#ifndef NAME` / `#define NAME` ... `#endif`, or remove an include from the chain".into(),
            );
            return;
        }
        let new_idx = self.files.len();
        self.files.push(OutFile {
            raw: file,
            text: String::new(),
            includes: Vec::new(),
        });
        if let Some(f) = self.files.get_mut(idx) {
            f.includes.push(IncludeSite {
                line: hash.line + 1,
                file: new_idx,
            });
        }
        let shown = if angled {
            format!("<{name}>")
        } else {
            format!("\"{name}\"")
        };
        render.set_line(hash.line, format!("{}#include {shown}", hash.ws));
        self.process(new_idx);
    }

    /// "include cycle: a.l -> b.l -> a.l", or the whole chain when no file repeats.
    fn depth_message(&self, next: &RawFile) -> String {
        let files: Vec<&RawFile> = self
            .chain
            .iter()
            .filter_map(|&i| self.files.get(i).map(|f| &f.raw))
            .collect();
        let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
        // The innermost earlier inclusion of the same file closes the shortest cycle.
        if let Some(start) = files.iter().rposition(|f| f.key == next.key) {
            return format!(
                "include cycle: {} -> {} (includes nest more than {} deep)",
                names[start..].join(" -> "),
                next.name,
                self.max_include
            );
        }
        let shown: Vec<&str> = if names.len() > 12 {
            names[..4]
                .iter()
                .chain(["..."].iter())
                .chain(names[names.len() - 6..].iter())
                .copied()
                .collect()
        } else {
            names
        };
        format!(
            "#include nested more than {} deep: {} -> {}",
            self.max_include,
            shown.join(" -> "),
            next.name
        )
    }
}
