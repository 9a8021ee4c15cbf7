//! Derivation faults: a VM fault or a module/parameter limit overrun, and
//! where it happened (the axiom, a production, a statement block), in; the
//! located [`DeriveError`] out, naming the production and the step.

use std::sync::Arc;

use super::error::{DeriveError, Fail, Src};
use super::store::ModuleStore;
use super::tables::{table_name, Tables};
use crate::bytecode::{Fault, FaultKind};
use crate::resolve::Table;
use crate::source::Span;

pub(super) fn src(tab: &Tables, span: Span) -> Src {
    Arc::new(tab.program.sources.named_source(span))
}

/// Where code ran, for error messages.
#[derive(Clone, Copy)]
pub(crate) enum Site {
    Axiom,
    Prod(Table, usize),
    /// A statement block of the L-system (`Start`, `StartEach`, ...).
    Hook(&'static str),
}

pub(super) fn site_context(tab: &Tables, site: Site) -> (String, Option<Span>) {
    match site {
        Site::Axiom => ("in the axiom".to_string(), None),
        Site::Hook(name) => (format!("in the `{name}:` block"), None),
        Site::Prod(t, i) => {
            let p = &tab.program.table(t)[i];
            let mut text = crate::bytecode::one_line(tab.program.sources.slice(p.span));
            if text.chars().count() > 80 {
                text = text.chars().take(77).collect::<String>() + "...";
            }
            (format!("in {} `{text}`", table_name(t)), Some(p.head_span))
        }
    }
}

pub(crate) fn fault_error(tab: &Tables, fault: Fault, site: Site, step: u32) -> Fail {
    let (context, prod) = site_context(tab, site);
    let production = prod.filter(|p| p.file == fault.span.file).map(Into::into);
    let src = src(tab, fault.span);
    let span = fault.span.into();
    Box::new(match fault.kind {
        FaultKind::DivisionByZero | FaultKind::RemainderByZero => DeriveError::DivisionByZero {
            what: if fault.kind == FaultKind::DivisionByZero {
                "division"
            } else {
                "remainder"
            },
            context,
            step,
            src,
            span,
            production,
        },
        FaultKind::TableIndex { table, dim, value } => {
            let t = &tab.program.tables[table as usize];
            let (lo, hi) = t.dims[dim as usize];
            DeriveError::TableIndex {
                what: format!("index {value} of table `{}` is outside {lo}..{hi}", t.name),
                context,
                step,
                src,
                span,
                production,
            }
        }
        FaultKind::ArrayIndex { array, dim, value } => {
            let a = &tab.program.arrays[array as usize];
            DeriveError::TableIndex {
                what: format!(
                    "index {value} of array `{}` is outside 0..{}",
                    a.name,
                    a.dims[dim as usize] - 1
                ),
                context,
                step,
                src,
                span,
                production,
            }
        }
        FaultKind::LoopLimit => DeriveError::EndlessLoop {
            limit: crate::bytecode::vm::MAX_LOOP_ITERATIONS,
            context,
            step,
            src,
            span,
            production,
        },
        FaultKind::NotFinite(value) => DeriveError::NotFinite {
            value,
            context,
            step,
            src,
            span,
            production,
        },
    })
}

#[inline(always)]
pub(crate) fn check_limits(
    tab: &Tables,
    out: &ModuleStore,
    site: Option<Site>,
    step: u32,
) -> Result<(), Fail> {
    if tab.over(out.len(), out.param_count()) {
        return Err(limit_error(tab, out, site, step));
    }
    Ok(())
}

#[cold]
fn limit_error(tab: &Tables, out: &ModuleStore, site: Option<Site>, step: u32) -> Fail {
    let over_modules = out.len() > tab.max_modules;
    let (src, production) = match site {
        Some(Site::Prod(t, i)) => {
            let p = &tab.program.table(t)[i];
            (Some(src(tab, p.head_span)), Some(p.head_span.into()))
        }
        _ => (None, None),
    };
    Box::new(if over_modules {
        DeriveError::ModuleLimit {
            step,
            limit: tab.max_modules,
            reached: out.len(),
            src,
            production,
        }
    } else {
        DeriveError::ParamLimit {
            step,
            limit: tab.max_params,
            reached: out.param_count(),
            src,
            production,
        }
    })
}
