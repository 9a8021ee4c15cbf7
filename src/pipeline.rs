//! The front half of the compiler in one call: input -> load -> parse ->
//! resolve -> bytecode, with every diagnostic collected. The CLI, the
//! tests, the REPL and the library API all go through here.

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::bytecode::{self, Compiled};
use crate::diag::Diagnostics;
use crate::load::{self, Input, Options};
use crate::resolve::{self, Program, SymbolKind};

/// A grammar ready to derive.
pub struct Compilation {
    pub program: Program,
    pub compiled: Compiled,
    /// Warnings (the grammar still compiled).
    pub warnings: Vec<Report>,
}

/// A define given as an option, `NS.NAME=VALUE`, whose namespace is no
/// component of the grammar.
#[derive(Debug, Error, Diagnostic)]
#[error("the define `{name}` given as an option names a component `~{namespace}` the grammar does not place")]
#[diagnostic(code(lsys::options::unknown_namespace), help("{help}"))]
pub struct UnknownNamespace {
    pub name: String,
    pub namespace: String,
    pub help: String,
}

/// Compiles `input`. Defines without a namespace are this grammar's;
/// namespaced ones (`TM.NTL=5`) are kept for its grammar components and
/// must name a component the grammar places.
pub fn compile(input: &Input, opts: &Options) -> Result<Compilation, Diagnostics> {
    let loaded = load::load(input, &own_options(opts)).map_err(Diagnostics::input)?;
    compile_loaded(loaded, opts)
}

/// The options loading gets: the grammar's own defines, without the
/// namespaced ones.
pub fn own_options(opts: &Options) -> Options {
    Options {
        defines: opts.split_defines().0,
        ..opts.clone()
    }
}

/// The rest of [`compile`] for a model already loaded with
/// [`own_options`] (the language server keeps the loaded syntax, so it
/// loads once and compiles from that).
pub fn compile_loaded(loaded: load::Loaded, opts: &Options) -> Result<Compilation, Diagnostics> {
    let (own, namespaced) = opts.split_defines();
    let own_opts = Options {
        defines: own,
        ..opts.clone()
    };
    let files = loaded.sources.disk_paths();
    let resolved = match resolve::resolve(loaded, &own_opts) {
        Err(f) => return Err(Diagnostics::new(f.diagnostics).with_files(files)),
        Ok(r) => r,
    };
    check_namespaces(&resolved.program, &namespaced).map_err(|d| d.with_files(files.clone()))?;
    match bytecode::compile(&resolved.program) {
        Ok(compiled) => Ok(Compilation {
            program: resolved.program,
            compiled,
            warnings: resolved.warnings,
        }),
        Err(e) => {
            let mut diagnostics = vec![Report::new(e)];
            diagnostics.extend(resolved.warnings);
            Err(Diagnostics::new(diagnostics).with_files(files))
        }
    }
}

fn check_namespaces(program: &Program, namespaced: &[(String, String)]) -> Result<(), Diagnostics> {
    let components: Vec<&str> = program
        .symbols
        .list
        .iter()
        .filter(|s| s.kind == SymbolKind::Component)
        .map(|s| s.name.trim_start_matches('~'))
        .collect();
    let unknown: Vec<Report> = namespaced
        .iter()
        .filter_map(|(name, _)| {
            let ns = name.split('.').next().unwrap_or_default();
            if components.contains(&ns) {
                return None;
            }
            let help = if components.is_empty() {
                "this grammar places no components; give its own defines without a namespace (`NAME=VALUE`)"
                    .to_string()
            } else {
                let near = components
                    .iter()
                    .min_by_key(|c| strsim::levenshtein(c, ns))
                    .filter(|c| strsim::levenshtein(c, ns) <= 2)
                    .map(|c| format!("did you mean `{c}`? "))
                    .unwrap_or_default();
                format!(
                    "{near}a namespace names a component the grammar places: {}",
                    components.join(", ")
                )
            };
            Some(Report::new(UnknownNamespace {
                name: name.clone(),
                namespace: ns.to_string(),
                help,
            }))
        })
        .collect();
    if unknown.is_empty() {
        Ok(())
    } else {
        Err(Diagnostics::new(unknown))
    }
}
