//! Statements: the flattened statement list -> the [`Program`]: headers
//! evaluated, sections tracked, productions lowered and checked (`else`
//! placement, unreachable productions).

use std::collections::HashMap;

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::*;
use super::Resolver;
use crate::parse::ast::{self, Condition, HeaderKind, Item};
use crate::source::Span;

/// A predecessor's identity for `else` and reachability checks: its
/// symbols and parameter counts.
type PredKey = Vec<(SymId, u8)>;

#[derive(Default)]
struct Sections {
    table: Option<Table>,
    ended: Option<Span>,
    lsystem: Option<Span>,
    /// `ring lsystem` was given.
    ring: bool,
    /// The label of the L-system being read (`Lsystem: 2`). Once a
    /// sub-L-system (not the file's first) has started (`sub_labels` not
    /// empty), its axiom, derivation length and other headers are for
    /// running it alone.
    label: u32,
    main_label: u32,
    sub_labels: Vec<u32>,
    axiom: Option<(Vec<SuccModule>, Span)>,
    dlength: Option<(u32, Span)>,
    seed: Option<(u64, Span)>,
    context: Option<(ContextFilter, Span)>,
    depth: HashMap<Table, (u32, Span)>,
    /// Per table and predecessor: was there a production, and which
    /// production always applies first (no context, condition, probability).
    seen: HashMap<(Table, PredKey), Option<Span>>,
    /// The other ways an earlier production takes a later one's place.
    shadows: super::shadowing::Shadows,
    turtle: super::turtle_headers::TurtleHeaders,
    /// `environment:` and where it was given.
    environment: Option<(String, Span)>,
}

impl Resolver {
    pub(super) fn statements(&mut self, items: &[(u32, Item)]) -> Option<Program> {
        self.record_arities(items);
        self.declare_globals(items);
        let mut s = Sections::default();
        let mut tables: HashMap<Table, Vec<Production>> = HashMap::new();
        for (order, (_, item)) in items.iter().enumerate() {
            match item {
                Item::Production(p) => {
                    if let Some(end) = s.ended {
                        self.after_end(p.span, end);
                        continue;
                    }
                    let table = s.table.unwrap_or(Table::Main);
                    if let Some(prod) = self.production(p, table, order, &mut s) {
                        tables.entry(table).or_default().push(prod);
                    }
                }
                Item::Header(h) => self.header(h, order, &mut s),
                Item::OtherDirective { name, span } => self.error(ResolveError::Unsupported {
                    what: format!("the preprocessor directive `#{}`", name.name),
                    src: self.sources.named_source(*span),
                    span: (*span).into(),
                    help: "lsys understands #define and #include; cpfg's C preprocessor conditionals (#if, #ifdef, ...) are planned with cpfg compatibility. Remove the line, or keep one branch of the conditional".to_string(),
                }),
                Item::Define(_) | Item::Include(_) => {}
            }
        }
        if self.profile.cpfg_model_file {
            let axiom = s.axiom.as_ref().map_or(&[][..], |(a, _)| a.as_slice());
            self.command_twins(&mut tables, axiom);
            if let Some((filter, _)) = &mut s.context {
                self.cpfg_context_letters(filter);
            }
        }
        // Before the program takes the sources.
        self.report_missing_names();
        let root = Span::new(0, 0, 0);
        let Some((axiom, _)) = s.axiom.take() else {
            // After other errors (an axiom line that did not parse, a file
            // refused as too deep) a missing axiom is their echo.
            if self.errors.is_empty() {
                self.error(ResolveError::NoAxiom {
                    src: self.sources.named_source(root),
                    span: root.into(),
                });
            }
            return None;
        };
        let defines = self.define_infos();
        let mut turtle = std::mem::take(&mut s.turtle.settings);
        let mut environment = None;
        if s.environment.is_none() && self.environment_files.is_none() {
            if let Some(text) = self.environment_option.take() {
                // The option as a source of its own, for its diagnostics.
                let id = self.sources.add(crate::source::SourceFile::new(
                    "--environment",
                    crate::source::Origin::Memory,
                    text.clone(),
                ));
                s.environment = Some((text.clone(), Span::new(id, 0, text.len())));
            }
        }
        if let Some((text, span)) = s.environment.take() {
            match crate::environment::environment_header(
                &text,
                &self.environment_images,
                self.sources.named_source(span),
                span.into(),
            ) {
                Ok(env) => environment = Some(env),
                Err(e) if crate::diag::is_error(&*e) => self.errors.push(miette::Report::new(*e)),
                Err(e) => self.warnings.push(miette::Report::new(*e)),
            }
        } else if let Some(Some(span)) = self
            .symbols
            .get("?E")
            .map(|id| self.symbols.list[id as usize].span)
        {
            match &self.environment_files {
                Some(files) => match crate::environment::configure(&self.sources, files) {
                    Ok(env) => environment = Some(env),
                    Err(e) if crate::diag::is_error(&*e) => {
                        self.errors.push(miette::Report::new(*e))
                    }
                    Err(e) => self.warnings.push(miette::Report::new(*e)),
                },
                None => self.warn(ResolveError::Environment {
                    src: self.sources.named_source(span),
                    span: span.into(),
                }),
            }
        }
        // A cpfg model's turning angle is in its view file.
        if self.profile.cpfg_model_file && turtle.angle.is_none() {
            turtle.angle = self.view_angle;
        }
        // The view file's first colour index means something only with
        // the model's own colours (lsys's 16-colour palette would wrap it).
        if self.profile.cpfg_model_file && !self.view_colours.is_empty() {
            turtle.colour = self.view_initial_colour;
        }
        // Its line widths are in its view file (a `width:` header wins).
        if let Some(lines) = self.view_lines.take() {
            turtle.width = turtle.width.or(Some(lines.width));
            turtle.width_increment = Some(lines.increment);
            turtle.pixel_lines = lines.pixels;
        }
        turtle.contours = std::mem::take(&mut self.view_contours);
        turtle.view_box = self.profile.cpfg_model_file && self.view_box;
        // Its colours are in its colour map and material files; the
        // file's own `colour i:` headers come after, and win.
        if self.profile.cpfg_model_file && !self.view_colours.is_empty() {
            let mut palette = std::mem::take(&mut self.view_colours);
            palette.append(&mut turtle.palette);
            turtle.palette = palette;
        }
        let vars = self.take_vars();
        let mut take = |t| tables.remove(&t).unwrap_or_default();
        Some(Program {
            sources: std::mem::take(&mut self.sources),
            symbols: std::mem::take(&mut self.symbols),
            axiom,
            derivation_length: s.dlength.map_or(0, |d| d.0),
            derivation_length_given: s.dlength.is_some(),
            seed: s.seed.map(|d| d.0),
            ring: s.ring,
            main_lsystem: s.main_label,
            sub_lsystems: std::mem::take(&mut s.sub_labels),
            context: s.context.map(|c| c.0).unwrap_or_default(),
            productions: take(Table::Main),
            decomposition: take(Table::Decomposition),
            homomorphism: take(Table::Homomorphism),
            decomposition_depth: s
                .depth
                .get(&Table::Decomposition)
                .map_or(DEFAULT_DEPTH, |d| d.0),
            homomorphism_depth: s
                .depth
                .get(&Table::Homomorphism)
                .map_or(DEFAULT_DEPTH, |d| d.0),
            defines,
            profile: self.profile,
            turtle,
            tables: std::mem::take(&mut self.tables),
            vars: vars.vars,
            var_init: vars.init,
            arrays: vars.arrays,
            hooks: vars.hooks,
            functions: vars.functions.unwrap_or_default(),
            cpfg_surfaces: std::mem::take(&mut self.cpfg_surfaces),
            environment,
        })
    }

    fn after_end(&mut self, span: Span, end: Span) {
        self.error(ResolveError::Misplaced {
            what: "statement after `endlsystem`".to_string(),
            src: self.sources.named_source(span),
            span: span.into(),
            help: format!(
                "`endlsystem` ({}) ends the L-system; move this above it, or start a sub-L-system first with `Lsystem: N`",
                self.sources.location(end)
            ),
        });
    }

    fn header(&mut self, h: &ast::Header, order: usize, s: &mut Sections) {
        let scope = Scope {
            order,
            ..Scope::EMPTY
        };
        if let Some(end) = s.ended {
            if !matches!(h.kind, HeaderKind::Endlsystem | HeaderKind::Lsystem(_)) {
                self.after_end(h.span, end);
                return;
            }
        }
        if self.turtle_header(h, &scope, &mut s.turtle) {
            return;
        }
        match &h.kind {
            HeaderKind::Lsystem(label) => {
                // cpfg's label is a number (`?(2, s)` calls L-system 2);
                // anything else counts as 0.
                let label = label.trim().parse::<u32>().unwrap_or(0);
                if s.lsystem.is_some() {
                    if label == s.main_label || s.sub_labels.contains(&label) {
                        self.error(ResolveError::Misplaced {
                            what: format!("a second L-system labelled {label}"),
                            src: self.sources.named_source(h.span),
                            span: h.span.into(),
                            help: "give each `Lsystem:` its own number; `?(n, scale)` calls L-system n".to_string(),
                        });
                    }
                    s.sub_labels.push(label);
                    s.ended = None;
                    s.table = None;
                    s.seen.clear();
                    s.shadows = Default::default();
                } else {
                    s.main_label = label;
                    s.lsystem = Some(h.keyword);
                }
                s.label = label;
            }
            HeaderKind::DerivationLength(_)
            | HeaderKind::Axiom(_)
            | HeaderKind::LongAxiom(_)
            | HeaderKind::Seed(_)
            | HeaderKind::Ignore(_)
            | HeaderKind::Consider(_)
            | HeaderKind::MaximumDepth(_)
                if !s.sub_labels.is_empty() => {}
            HeaderKind::DerivationLength(e) => {
                if let Some((_, first)) = s.dlength {
                    self.duplicate(
                        h,
                        "derivation length:",
                        first,
                        "keep one `derivation length:`; to change it for one run use `-n STEPS`",
                    );
                } else if let Some(n) = self.const_count(e, &scope, "derivation length", 10_000_000)
                {
                    s.dlength = Some((n as u32, h.keyword));
                }
            }
            HeaderKind::Axiom(_) | HeaderKind::LongAxiom(_) => {
                if let Some((_, first)) = &s.axiom {
                    let first = *first;
                    self.duplicate(
                        h,
                        "Axiom:",
                        first,
                        "a grammar has one axiom; remove one of them",
                    );
                    return;
                }
                let mut balance = super::brackets::Balance::default();
                let mut m = Vec::new();
                match &h.kind {
                    HeaderKind::Axiom(toks) => {
                        balance.feed(toks);
                        m = self.successor(toks, &scope);
                    }
                    HeaderKind::LongAxiom(pieces) => {
                        // One piece's tokens at a time: only the resolved
                        // modules of the whole line are kept.
                        for &p in pieces {
                            let toks = crate::parse::axiom_piece(self.sources.get(p.file), p)
                                .unwrap_or_default();
                            balance.feed(&toks);
                            m.extend(self.successor(&toks, &scope));
                        }
                        m.shrink_to_fit();
                    }
                    _ => {}
                }
                self.report_brackets(balance, super::brackets::Place::Axiom);
                s.axiom = Some((m, h.keyword));
            }
            HeaderKind::Ignore(toks) | HeaderKind::Consider(toks) => {
                let is_ignore = matches!(h.kind, HeaderKind::Ignore(_));
                if let Some((_, first)) = &s.context {
                    let first = *first;
                    self.duplicate(h, "ignore:/consider:", first, "use one `ignore:` or one `consider:` list, not both; list every symbol in it");
                    return;
                }
                let mut syms = Vec::new();
                for t in toks {
                    match t {
                        ast::PatTok::Module(m) => {
                            for p in self.split(m) {
                                syms.push(self.intern(&p.name, Some(p.span)));
                            }
                        }
                        // `Consider: ![]`: brackets listed are considered
                        // (they end a context at a branch's end).
                        ast::PatTok::Open(_) => syms.push(OPEN_BRACKET),
                        ast::PatTok::Close(_) => syms.push(CLOSE_BRACKET),
                    }
                }
                let f = if is_ignore {
                    ContextFilter::Ignore(syms)
                } else {
                    ContextFilter::Consider(syms)
                };
                s.context = Some((f, h.keyword));
            }
            HeaderKind::Seed(e) => {
                if let Some((_, first)) = s.seed {
                    self.duplicate(
                        h,
                        "seed:",
                        first,
                        "keep one `seed:`; to change it for one run use `--seed N`",
                    );
                } else if let Some(n) = self.const_count(e, &scope, "seed", u32::MAX as u64) {
                    s.seed = Some((n, h.keyword));
                }
            }
            HeaderKind::MaximumDepth(e) => {
                let Some(t @ (Table::Homomorphism | Table::Decomposition)) = s.table else {
                    self.error(ResolveError::Misplaced {
                        what: "`maximum depth:` outside a homomorphism or decomposition section".to_string(),
                        src: self.sources.named_source(h.span),
                        span: h.span.into(),
                        help: "put `maximum depth:` right after the `homomorphism` or `decomposition` line it applies to".to_string(),
                    });
                    return;
                };
                if let Some((_, first)) = s.depth.get(&t) {
                    let first = *first;
                    self.duplicate(
                        h,
                        "maximum depth:",
                        first,
                        "each section has one `maximum depth:`",
                    );
                } else if let Some(n) = self.const_count(e, &scope, "maximum depth", 100_000) {
                    s.depth.insert(t, (n.max(1) as u32, h.keyword));
                }
            }
            HeaderKind::Endlsystem => s.ended = Some(h.span),
            HeaderKind::Ring => s.ring = true,
            HeaderKind::Homomorphism => s.table = Some(Table::Homomorphism),
            HeaderKind::Decomposition => s.table = Some(Table::Decomposition),
            HeaderKind::Module(_) => {}
            HeaderKind::Environment(text, span) => {
                if let Some((_, first)) = &s.environment {
                    let first = *first;
                    self.duplicate(h, "environment:", first, "a grammar has one environment");
                } else {
                    s.environment = Some((text.clone(), *span));
                }
            }
            HeaderKind::Angle(_)
            | HeaderKind::Step(_)
            | HeaderKind::Width(_)
            | HeaderKind::Dialect(..)
            | HeaderKind::Colour(..)
            | HeaderKind::Texture(..) => unreachable!("handled by turtle_header"),
            HeaderKind::Block(kw, b) => self.hook_block(kw, b, order),
        }
    }

    pub(super) fn duplicate(&mut self, h: &ast::Header, what: &str, first: Span, help: &str) {
        self.error(ResolveError::DuplicateHeader {
            what: what.to_string(),
            src: self.sources.named_source(h.keyword),
            span: h.keyword.into(),
            first: (first.file == h.keyword.file).then(|| first.into()),
            help: help.to_string(),
        });
    }

    /// The value of a constant expression; reports one that is not.
    pub(super) fn const_num(&mut self, e: &ast::Expr, scope: &Scope, what: &str) -> Option<f64> {
        let v = self.expr(e, scope)?;
        let ExprKind::Num(x) = v.kind else {
            self.error(ResolveError::NotConstant {
                what: format!("the {what}"),
                src: self.sources.named_source(e.span),
                span: e.span.into(),
                help: "use numbers and #defines only".to_string(),
            });
            return None;
        };
        Some(x)
    }

    /// A constant whole number in `0..=max` (derivation length, seed, depth).
    pub(super) fn const_count(
        &mut self,
        e: &ast::Expr,
        scope: &Scope,
        what: &str,
        max: u64,
    ) -> Option<u64> {
        let x = self.const_num(e, scope, what)?;
        if x < 0.0 || x.fract() != 0.0 || x > max as f64 {
            self.error(ResolveError::BadValue {
                what: what.to_string(),
                why: format!("{x} is not a whole number from 0 to {max}"),
                src: self.sources.named_source(e.span),
                span: e.span.into(),
                help: None,
            });
            return None;
        }
        Some(x as u64)
    }

    fn production(
        &mut self,
        p: &ast::Production,
        table: Table,
        order: usize,
        s: &mut Sections,
    ) -> Option<Production> {
        let errors_before = self.errors.len();
        let mut params = Vec::new();
        let mut spans = Vec::new();
        let lctx = self.pattern(&p.lctx, false, &mut params, &mut spans, false);
        let pred = self.pattern(&p.pred, false, &mut params, &mut spans, true);
        let rctx = self.pattern(&p.rctx, true, &mut params, &mut spans, false);
        let lctx: Vec<PatModule> = lctx
            .into_iter()
            .filter_map(|i| match i {
                PatItem::Module(m) => Some(m),
                _ => None,
            })
            .collect();
        let pred: Vec<PatModule> = pred
            .into_iter()
            .filter_map(|i| match i {
                PatItem::Module(m) => Some(m),
                _ => None,
            })
            .collect();
        if table != Table::Main && (!lctx.is_empty() || !rctx.is_empty()) {
            self.error(ResolveError::Unsupported {
                what: "context in a homomorphism or decomposition production".to_string(),
                src: self.sources.named_source(p.head_span),
                span: p.head_span.into(),
                help: "these sections rewrite each module on its own; move the context-sensitive production above the `homomorphism`/`decomposition` line".to_string(),
            });
        }
        let (locals, mut pre) = self.production_locals(p, &params);
        let scope = Scope {
            params: &params,
            locals: &locals,
            order,
        };
        if let Some(b) = &p.pre {
            pre.extend(self.stmts(&b.stmts, &scope));
        }
        let post = p
            .post
            .as_ref()
            .map(|b| self.stmts(&b.stmts, &scope))
            .unwrap_or_default();
        let key: PredKey = pred.iter().map(|m| (m.sym, m.arity)).collect();
        let pred_text = self.sources.slice(p.head_span).trim().to_string();
        let mut cond_failed = false;
        let cond = match &p.cond {
            None | Some(Condition::Always(_)) => Cond::Always,
            Some(Condition::Else(span)) => {
                if !s.seen.contains_key(&(table, key.clone()))
                    && !self.broken_production_before(p.span, &pred_text)
                {
                    self.error(ResolveError::ElseFirst {
                        pred: pred_text.clone(),
                        src: self.sources.named_source(*span),
                        span: (*span).into(),
                    });
                }
                Cond::Else(*span)
            }
            Some(Condition::Expr(e)) => match self.expr(e, &scope) {
                Some(Expr {
                    kind: ExprKind::Num(v),
                    ..
                }) if v != 0.0 => Cond::Always,
                // Written with the names of defines, not as `0` or `!1`
                // (cpfg's idioms for a production switched off): a
                // production that cannot fire by accident.
                Some(
                    c @ Expr {
                        kind: ExprKind::Num(_),
                        ..
                    },
                ) if self
                    .sources
                    .slice(e.span)
                    .contains(|ch: char| ch.is_ascii_alphabetic()) =>
                {
                    self.warn(ResolveError::ConstantCondition {
                        src: self.sources.named_source(e.span),
                        span: e.span.into(),
                    });
                    Cond::Expr(c)
                }
                Some(e) => Cond::Expr(e),
                None => {
                    // Already reported; the production does not compile.
                    // It must not count as unconditional, or every later
                    // production for the predecessor would be "unreachable".
                    cond_failed = true;
                    Cond::Always
                }
            },
        };
        self.check_brackets(&p.succ, super::brackets::Place::Successor);
        let succ = self.successor(&p.succ, &scope);
        let prob = p.prob.as_ref().and_then(|e| self.expr(e, &scope));
        let always = lctx.is_empty()
            && rctx.is_empty()
            && prob.is_none()
            && !cond_failed
            && matches!(cond, Cond::Always | Cond::Else(_));
        let candidate = super::shadowing::Candidate {
            table,
            pred: &pred,
            lctx: &lctx,
            rctx: &rctx,
            unconditional: !cond_failed && matches!(cond, Cond::Always | Cond::Else(_)),
            stochastic: prob.is_some(),
        };
        let paper_choice = !self.profile.cpfg_stochastic;
        let shadowed = s.shadows.check(&candidate, p.head_span, paper_choice);
        let entry = s.seen.entry((table, key)).or_insert(None);
        let shadowed = match (*entry, shadowed) {
            (Some(earlier), _) => Some((earlier, "an earlier production for the same predecessor has no condition, context or probability, so it always wins; add a condition to it or remove this one")),
            (None, other) => other.map(|o| (o.earlier, o.help)),
        };
        if let Some((earlier, help)) = shadowed {
            self.warn(ResolveError::Unreachable {
                src: self.sources.named_source(p.span),
                span: p.head_span.into(),
                earlier: (earlier.file == p.span.file).then(|| earlier.into()),
                pred: pred_text,
                help: help.to_string(),
            });
        } else if always {
            *entry = Some(p.head_span);
        }
        if self.errors.len() > errors_before {
            return None;
        }
        Some(Production {
            table,
            lsystem: s.label,
            span: p.span,
            head_span: p.head_span,
            lctx,
            pred,
            rctx,
            nparams: params.len() as u16,
            param_names: params.into_iter().map(|(n, _)| n).collect(),
            cond,
            succ,
            prob,
            pre,
            post,
        })
    }
}

impl Resolver {
    /// Whether a statement above `at` in its file that did not parse
    /// begins with the predecessor `pred` (`A(x) : x = 2 --> F`): it is
    /// probably what an `else` for `pred` is the alternative of, and its
    /// syntax error is already reported.
    fn broken_production_before(&self, at: Span, pred: &str) -> bool {
        self.broken
            .iter()
            .filter(|b| b.file == at.file && b.start < at.start)
            .any(|b| {
                let line = self.sources.slice(*b);
                line.strip_prefix(pred).is_some_and(|rest| {
                    let rest = rest.trim_start();
                    rest.starts_with(':')
                        || ["-->", "->", "→", "⟶"].iter().any(|a| rest.starts_with(a))
                })
            })
    }
}

/// `maximum depth:` when a section does not say.
pub const DEFAULT_DEPTH: u32 = 1;
