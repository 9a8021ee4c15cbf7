//! Resolve: the [`Loaded`] model (every file parsed, side files read) -> a
//! [`Program`]: defines applied (with `-D` overrides), the alphabet built
//! and module runs split, every name bound, every arity checked, constants
//! folded. All errors of all files are collected and reported together.
//! Resolve reads no file: loading read them all.

pub mod alphabet;
mod brackets;
mod colours;
mod cpfg_commands;
mod cstmt;
pub mod error;
mod expr;
mod fold;
mod hints;
pub mod ir;
mod modules;
mod reach;
mod shadowing;
mod statements;
mod tables;
mod textures;
mod turtle_headers;
mod view_functions;

use std::collections::HashMap;

use miette::Report;

/// The options of one compilation; loading reads them first.
use crate::load::Options;
pub use error::ResolveError;
pub use ir::*;

use crate::load::Loaded;
use crate::parse::ast;
use crate::source::{Origin, SourceFile, SourceMap, Span};

/// A resolved grammar and the warnings found on the way.
pub struct Resolved {
    pub program: Program,
    pub warnings: Vec<Report>,
}

/// The grammar has errors; `diagnostics` holds all of them (and warnings),
/// each with the source text it points into.
pub struct Failure {
    pub diagnostics: Vec<Report>,
}

/// Resolves the loaded model.
pub fn resolve(loaded: Loaded, opts: &Options) -> Result<Resolved, Failure> {
    // A cpfg file's -D definitions went to the preprocessor.
    let no_defines = Options {
        defines: Vec::new(),
        ..opts.clone()
    };
    let opts = if loaded.preprocessed {
        &no_defines
    } else {
        opts
    };
    let mut r = Resolver {
        sources: loaded.sources,
        errors: loaded.errors,
        warnings: loaded.warnings,
        defines: HashMap::new(),
        define_order: Vec::new(),
        expansions: Default::default(),
        symbols: Symbols::default(),
        alphabet: alphabet::Alphabet::new(),
        arities: HashMap::new(),
        tables: Vec::new(),
        table_ids: HashMap::new(),
        vars: cstmt::Vars::default(),
        profile: loaded.profile,
        warned_at: Default::default(),
        strings: Vec::new(),
        view_angle: loaded.side.angle,
        view_colours: loaded.side.colours,
        view_initial_colour: loaded.side.initial_colour,
        view_box: loaded.side.view_box,
        view_lines: loaded.side.lines,
        view_curves: loaded.side.curves,
        view_contours: loaded.side.contours,
        cpfg_surfaces: loaded.side.surfaces,
        environment_files: loaded.environment,
        environment_images: loaded.environment_images,
        environment_option: opts.environment.clone(),
        view_functions: loaded.side.functions,
        broken: loaded.broken,
        failed_includes: loaded.failed_includes,
        missing_names: Vec::new(),
        evaluating_for_display: false,
    };
    let program = r.run(loaded.items, opts);
    if let (true, Some(p)) = (r.errors.is_empty(), &program) {
        for w in reach::never_fires(p)
            .into_iter()
            .chain(colours::out_of_palette(p))
        {
            r.warn(w);
        }
    }
    if r.errors.is_empty() {
        Ok(Resolved {
            program: program.expect("no errors means a program"),
            warnings: r.warnings,
        })
    } else {
        let mut diagnostics = r.errors;
        diagnostics.extend(r.warnings);
        Err(Failure { diagnostics })
    }
}

/// One `#define` as resolve sees it.
#[derive(Clone, Debug)]
pub(crate) struct DefineEntry {
    pub name: String,
    pub params: Option<Vec<String>>,
    pub value: Option<ast::Expr>,
    /// A table's dimensions and braced values (see [`ir::TableDef`]).
    pub dims: Option<Vec<(i64, i64)>>,
    pub elems: Option<(Vec<ast::Expr>, Span)>,
    pub span: Span,
    /// Position in the flattened statement list.
    pub order: usize,
    pub overridden: bool,
}

/// Declared parameter counts of a user symbol and where they were declared.
#[derive(Clone, Debug, Default)]
pub(crate) struct ArityInfo {
    pub counts: Vec<usize>,
    pub names: Vec<Vec<String>>,
    pub decl: Option<Span>,
}

pub(crate) struct Resolver {
    pub sources: SourceMap,
    pub errors: Vec<Report>,
    pub warnings: Vec<Report>,
    /// Shared, so that a use of a define (there are thousands in a
    /// Pailou) does not copy its body.
    pub defines: HashMap<String, std::rc::Rc<DefineEntry>>,
    pub define_order: Vec<String>,
    /// Expansions of defines without arguments, by define name, for the
    /// scope they were made in (see [`expr::Expansions`]).
    pub expansions: expr::Expansions,
    pub symbols: Symbols,
    pub alphabet: alphabet::Alphabet,
    pub arities: HashMap<SymId, ArityInfo>,
    /// Evaluated tables and their ids by name.
    pub tables: Vec<ir::TableDef>,
    pub table_ids: HashMap<String, u32>,
    /// Variables, arrays and hooks of cpfg's C-like statements.
    pub vars: cstmt::Vars,
    /// The root is a cpfg file (`.l`): every module name is one character,
    /// as cpfg's scanner reads them, turtle commands may carry parameters
    /// the turtle ignores, and unknown `@` commands are kept as inert
    /// modules (with a warning).
    pub profile: crate::lang::Profile,
    /// Unknown `@` commands already warned about (one warning per name).
    pub warned_at: std::collections::HashSet<String>,
    /// Strings given as module parameters, numbered from 1 as cpfg does.
    pub strings: Vec<String>,
    /// The turning angle of a cpfg model's view file, read while loading.
    pub view_angle: Option<f64>,
    /// The colours of a cpfg model's colour map and material files.
    pub view_colours: Vec<(usize, [f32; 3])>,
    /// The turtle's first colour index, from a cpfg view file.
    pub view_initial_colour: Option<u32>,
    /// A cpfg view file's `box:` line.
    pub view_box: bool,
    /// A cpfg model's line widths, from its view file.
    pub view_lines: Option<crate::load::ViewLines>,
    /// A cpfg model's contour curves (`curve:` lines of its view file).
    pub view_curves: Vec<Result<crate::lang::curve::Curve, String>>,
    /// A cpfg model's cross-sections (`contour:` lines of its view file).
    pub view_contours: Vec<crate::load::Contour>,
    /// The cpfg surfaces the view file names (`~NAME`).
    pub cpfg_surfaces: Vec<crate::load::CpfgSurface>,
    /// A cpfg model's environment files (`-e FILE.e`).
    pub environment_files: Option<crate::load::EnvironmentFiles>,
    /// The images an `environment:` header names (clover's light image).
    pub environment_images: Vec<(String, crate::load::HeaderImage)>,
    /// `--environment SPEC`, used when the grammar names none.
    pub environment_option: Option<String>,
    /// The view file's functions (or why they could not be read), read
    /// while loading; `func` takes them.
    pub view_functions: crate::load::ViewFunctions,
    /// First lines of statements that did not parse.
    pub broken: Vec<Span>,
    /// `#include` lines whose file could not be loaded.
    pub failed_includes: Vec<Span>,
    /// Unknown names met while an include had failed, with their first
    /// use: reported together once (see [`Resolver::report_missing_names`]).
    pub missing_names: Vec<(String, Span)>,
    /// Set while defines are evaluated for display only (their errors are
    /// dropped): an unknown name then costs no help text, whose suggestion
    /// compares it with every define (most of `lsys pailou`'s compile
    /// time before, as each define body naming a parameter failed).
    pub evaluating_for_display: bool,
}

impl Resolver {
    pub fn error(&mut self, e: ResolveError) {
        self.errors.push(Report::new(e));
    }

    pub fn warn(&mut self, e: ResolveError) {
        self.warnings.push(Report::new(e));
    }

    fn run(&mut self, items: Vec<(u32, ast::Item)>, opts: &Options) -> Option<Program> {
        self.collect_defines(&items);
        let element_overrides = self.apply_overrides(opts);
        self.evaluate_tables(&element_overrides);
        self.build_alphabet(&items);
        self.dialect_hint(&items, opts.dialect.is_some());
        let program = self.statements(&items);
        if !self.errors.is_empty() {
            return None;
        }
        program
    }

    /// One error for every name left undefined by a failed `#include`,
    /// instead of one "unknown name" each: the include's own error says
    /// what to fix.
    pub(crate) fn report_missing_names(&mut self) {
        let Some((&first, _)) = self.missing_names.first().map(|(_, s)| (s, ())) else {
            return;
        };
        let names: Vec<String> = self
            .missing_names
            .iter()
            .map(|(n, _)| format!("`{n}`"))
            .collect();
        let uses = self
            .missing_names
            .iter()
            .filter(|(_, s)| s.file == first.file)
            .map(|(n, s)| miette::LabeledSpan::new_with_span(Some(format!("`{n}`")), *s))
            .collect();
        let include = self.failed_includes[0];
        let (n, list) = (names.len(), names.join(", "));
        self.error(ResolveError::FromFailedInclude {
            what: if n == 1 {
                format!("{list} is not defined")
            } else {
                format!("{n} names are not defined ({list})")
            },
            src: self.sources.named_source(first),
            uses,
            include: (include.file == first.file).then(|| include.into()),
            help: format!(
                "fix the include at {} first (its error is above); a name that is not meant to come from it needs a `#define NAME value` above its first use",
                self.sources.location(include)
            ),
        });
    }

    fn collect_defines(&mut self, items: &[(u32, ast::Item)]) {
        for (order, (_, item)) in items.iter().enumerate() {
            let ast::Item::Define(ds) = item else {
                continue;
            };
            for d in ds {
                if let Some(prev) = self.defines.get(&d.name.name) {
                    let first = (prev.span.file == d.span.file).then(|| prev.span.into());
                    self.error(ResolveError::DuplicateDefine {
                        name: d.name.name.clone(),
                        src: self.sources.named_source(d.name.span),
                        span: d.name.span.into(),
                        first,
                    });
                    continue;
                }
                self.define_order.push(d.name.name.clone());
                self.defines.insert(
                    d.name.name.clone(),
                    std::rc::Rc::new(DefineEntry {
                        name: d.name.name.clone(),
                        params: d
                            .params
                            .as_ref()
                            .map(|ps| ps.iter().map(|p| p.name.clone()).collect()),
                        value: d.value.clone(),
                        dims: d.dims.clone(),
                        elems: d.elems.clone(),
                        span: d.name.span,
                        order,
                        overridden: false,
                    }),
                );
            }
        }
    }

    /// Applies `-D NAME=VALUE` to the defines. Element overrides of tables
    /// (`-D dec[1,2,3]=0`) are returned, to apply once tables are evaluated.
    fn apply_overrides(&mut self, opts: &Options) -> Vec<tables::ElementOverride> {
        let mut elements = Vec::new();
        for (name, value) in &opts.defines {
            let (base, index) = match name.split_once('[') {
                Some((b, rest)) => (b.trim(), Some(rest)),
                None => (name.as_str(), None),
            };
            let Some(entry) = self.defines.get(base) else {
                let known: Vec<&str> = self.define_order.iter().map(String::as_str).collect();
                let help = match expr::suggest(base, known.iter().copied()) {
                    Some(s) => format!(
                        "did you mean `{s}`? the grammar defines: {}",
                        known.join(", ")
                    ),
                    None if known.is_empty() => {
                        "the grammar has no #define to override".to_string()
                    }
                    None => format!("the grammar defines: {}", known.join(", ")),
                };
                let file = self.sources.files().first();
                self.error(ResolveError::UnknownOverride {
                    name: base.to_string(),
                    file: file.map_or_else(|| "the grammar".to_string(), |f| f.name.clone()),
                    help,
                });
                continue;
            };
            if entry.params.is_some() {
                self.error(ResolveError::BadOverride {
                    name: name.clone(),
                    why: "it is a function-like #define".to_string(),
                    help: Some("only #defines without parameters can be overridden".to_string()),
                });
                continue;
            }
            let is_table = entry.dims.is_some();
            if index.is_some() && !is_table {
                self.error(ResolveError::BadOverride {
                    name: name.clone(),
                    why: format!("`{base}` is not a table"),
                    help: Some(format!(
                        "give `{base}` one value, without an index (`{base}=VALUE`)"
                    )),
                });
                continue;
            }
            let file = SourceFile::new(format!("-D {name}"), Origin::Memory, value.clone());
            let id = self.sources.add(file);
            let parsed = match crate::parse::parse_define_value(id, self.sources.get(id)) {
                Ok(v) => v,
                Err(e) => {
                    self.errors.push(Report::new(*e));
                    continue;
                }
            };
            let span = Span::new(id, 0, value.len());
            use crate::parse::DefineValue::{Expr, Table};
            match (index, parsed) {
                (Some(idx), Expr(e)) => match tables::parse_index(idx) {
                    Some(at) => elements.push(tables::ElementOverride {
                        name: base.to_string(),
                        at,
                        value: e,
                        text: name.clone(),
                    }),
                    None => self.error(ResolveError::BadOverride {
                        name: name.clone(),
                        why: "its index is not a list of whole numbers".to_string(),
                        help: Some(format!(
                            "write the index as whole numbers, e.g. `{base}[1,2,3]=0`"
                        )),
                    }),
                },
                (Some(_), Table(_)) => self.error(ResolveError::BadOverride {
                    name: name.clone(),
                    why: "one element takes one value".to_string(),
                    help: Some(format!(
                        "to replace the whole table give `{base}` a list (`{base}={{...}}`)"
                    )),
                }),
                (None, Table(elems)) if is_table => {
                    let entry =
                        std::rc::Rc::make_mut(self.defines.get_mut(base).expect("checked above"));
                    entry.elems = Some((elems, span));
                    entry.value = None;
                    entry.overridden = true;
                }
                (None, Table(_)) => self.error(ResolveError::BadOverride {
                    name: name.clone(),
                    why: format!("`{base}` is not a table, so it takes one value, not a list"),
                    help: None,
                }),
                (None, Expr(e)) => {
                    let entry =
                        std::rc::Rc::make_mut(self.defines.get_mut(base).expect("checked above"));
                    entry.value = Some(e);
                    if is_table {
                        entry.elems = None;
                    }
                    entry.overridden = true;
                }
            }
        }
        elements
    }

    fn define_infos(&mut self) -> Vec<DefineInfo> {
        let names = self.define_order.clone();
        names
            .iter()
            .filter_map(|n| {
                let d = self.defines.get(n)?.clone();
                if d.params.is_some() || d.value.is_none() {
                    return Some(DefineInfo {
                        name: d.name.clone(),
                        value: None,
                        span: d.span,
                        overridden: d.overridden,
                    });
                }
                // Defines are evaluated for display only; errors surface
                // where a define is used.
                let saved = self.errors.len();
                self.evaluating_for_display = true;
                let value = self
                    .expr(d.value.as_ref()?, &expr::Scope::EMPTY)
                    .and_then(|e| match e.kind {
                        ExprKind::Num(v) => Some(v),
                        _ => None,
                    });
                self.evaluating_for_display = false;
                self.errors.truncate(saved);
                Some(DefineInfo {
                    name: d.name.clone(),
                    value,
                    span: d.span,
                    overridden: d.overridden,
                })
            })
            .collect()
    }
}
