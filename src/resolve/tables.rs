//! Tables: `#define NAME[lo..hi, ...] {...}` and the command line's
//! `-D 'NAME[i,j]=v'` / `-D 'NAME={...}'` -> [`TableDef`]s of constants,
//! evaluated once, before any production; `NAME[i, j]` in an expression
//! reads an element (see `expr.rs`).

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::{ExprKind, TableDef};
use super::Resolver;
use crate::parse::ast;

/// `-D 'NAME[i,j,...]=VALUE'`: one element, applied after evaluation.
pub(super) struct ElementOverride {
    pub name: String,
    pub at: Vec<i64>,
    pub value: ast::Expr,
    /// The option as typed, for errors.
    pub text: String,
}

/// `1,2,3]` (the text after `NAME[`) -> the indices.
pub(super) fn parse_index(text: &str) -> Option<Vec<i64>> {
    let inner = text.trim().strip_suffix(']')?;
    inner
        .split(',')
        .map(|t| t.trim().replace('−', "-").parse::<i64>().ok())
        .collect()
}

impl Resolver {
    /// Evaluates every table define in file order, then the element
    /// overrides.
    pub(super) fn evaluate_tables(&mut self, overrides: &[ElementOverride]) {
        for name in self.define_order.clone() {
            let Some(d) = self.defines.get(&name).cloned() else {
                continue;
            };
            let Some(dims) = d.dims.clone() else {
                continue;
            };
            let size = TableDef::size(&dims);
            let dims_text = TableDef {
                name: String::new(),
                dims: dims.clone(),
                values: Vec::new(),
                span: d.span,
                overridden: false,
            }
            .dims_text();
            let values = match (&d.value, &d.elems) {
                (Some(fill), _) => self
                    .constant(fill, &format!("the values of table `{name}`"))
                    .map(|v| vec![v; size]),
                (None, Some((elems, span))) => {
                    if elems.len() != size {
                        self.error(ResolveError::TableSize {
                            name: name.clone(),
                            found: elems.len(),
                            expected: size,
                            dims: dims_text.clone(),
                            src: self.sources.named_source(*span),
                            span: (*span).into(),
                            help: format!(
                                "list the values row by row, the last index varying fastest, or give one value for every element: `#define {name}{dims_text} 0`"
                            ),
                        });
                        None
                    } else {
                        elems
                            .iter()
                            .map(|e| self.constant(e, &format!("an element of table `{name}`")))
                            .collect()
                    }
                }
                (None, None) => {
                    self.error(ResolveError::TableUse {
                        name: name.clone(),
                        dims: dims_text.clone(),
                        problem: "it has no values".to_string(),
                        src: self.sources.named_source(d.span),
                        span: d.span.into(),
                        help: format!("give every element one value (`#define {name}{dims_text} 0`) or list them in braces"),
                    });
                    None
                }
            };
            let Some(values) = values else { continue };
            self.table_ids
                .insert(name.clone(), self.tables.len() as u32);
            self.tables.push(TableDef {
                name,
                dims,
                values,
                span: d.span,
                overridden: d.overridden,
            });
        }
        for o in overrides {
            let Some(&id) = self.table_ids.get(&o.name) else {
                continue; // the table itself failed and was reported
            };
            let Some(v) = self.constant(
                &o.value,
                &format!("the define `{}` given as an option", o.text),
            ) else {
                continue;
            };
            let t = &self.tables[id as usize];
            let idx: Vec<f64> = o.at.iter().map(|&i| i as f64).collect();
            let at = (idx.len() == t.dims.len())
                .then(|| crate::lang::builtins::table_offset(t.bounds(), &idx).ok())
                .flatten();
            match at {
                Some(at) => {
                    let t = &mut self.tables[id as usize];
                    t.values[at] = v;
                    t.overridden = true;
                }
                None => {
                    let dims = t.dims_text();
                    self.error(ResolveError::BadOverride {
                        name: o.text.clone(),
                        why: format!("the index is not within `{}`{dims}", o.name),
                        help: Some(format!(
                            "give {} whole-number indices within {dims}",
                            t.dims.len()
                        )),
                    })
                }
            }
        }
    }

    /// A constant expression's value; reports one that is not constant.
    fn constant(&mut self, e: &ast::Expr, what: &str) -> Option<f64> {
        let v = self.expr(e, &Scope::EMPTY)?;
        match v.kind {
            ExprKind::Num(x) => Some(x),
            _ => {
                self.error(ResolveError::NotConstant {
                    what: what.to_string(),
                    src: self.sources.named_source(e.span),
                    span: e.span.into(),
                    help: "table values are numbers and #defines".to_string(),
                });
                None
            }
        }
    }
}
