//! Whether a production applies where its pattern matches, and how much
//! it weighs: a production, the string and a position in; its pattern
//! matched (`matching.rs`), its condition and probability run on the
//! bindings out, or a located fault. The paper's choice (`rewrite.rs`) and
//! cpfg's (`stochastic.rs`) both ask here.

use std::mem;

use super::error::{DeriveError, Fail};
use super::faults::{fault_error, site_context, src, Site};
use super::matching::{match_at, Bound, Input};
use super::state::State;
use super::tables::{table_index, Tables};
use crate::bytecode::vm::{self, NoSink};
use crate::bytecode::{Chunk, CondCode};
use crate::resolve::Table;

/// Run an expression chunk (condition or probability).
#[inline(always)]
fn eval(
    tab: &Tables,
    st: &mut State,
    chunk: &Chunk,
    binds: &[f64],
    site: Site,
) -> Result<f64, Fail> {
    vm::run(chunk, binds, st.machine(tab.compiled), &mut NoSink)
        .map_err(|f| fault_error(tab, f, site, st.step))
}

/// The slice a match's bindings are in.
#[inline(always)]
pub(crate) fn bindings<'a>(
    bound: Bound,
    params: &'a [f64],
    off: usize,
    n: usize,
    buf: &'a [f64],
) -> &'a [f64] {
    match bound {
        Bound::Direct => &params[off..off + n],
        Bound::Buffer => buf,
    }
}

/// Whether production `p` of table `t` applies at `i` (pattern and
/// condition); leaves its bindings in place.
#[inline(always)]
pub(crate) fn applies(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    i: usize,
    off: usize,
) -> Result<Option<Bound>, Fail> {
    let shape = &tab.rules[table_index(t)].shapes[p];
    let Some(bound) = match_at(shape, inp, &tab.skip, i, off, &mut st.binds) else {
        return Ok(None);
    };
    if let CondCode::Code(ch) = &tab.compiled.table(t)[p].cond {
        let binds = mem::take(&mut st.binds);
        let b = bindings(bound, inp.params, off, shape.pred_params, &binds);
        let v = eval(tab, st, ch, b, Site::Prod(t, p));
        st.binds = binds;
        if v? == 0.0 {
            return Ok(None);
        }
    }
    Ok(Some(bound))
}

/// The weight of stochastic production `p` of table `t`, matched with
/// `bound` at the module whose parameters start at `off`: its probability,
/// evaluated. A negative, NaN or infinite weight is an error.
pub(crate) fn weight(
    tab: &Tables,
    st: &mut State,
    t: Table,
    p: usize,
    inp: &Input,
    off: usize,
    bound: Bound,
) -> Result<f64, Fail> {
    let ch = tab.compiled.table(t)[p]
        .prob
        .as_ref()
        .expect("stochastic productions have a probability chunk");
    let binds = mem::take(&mut st.binds);
    let pred_params = tab.rules[table_index(t)].shapes[p].pred_params;
    let b = bindings(bound, inp.params, off, pred_params, &binds);
    let w = eval(tab, st, ch, b, Site::Prod(t, p));
    st.binds = binds;
    let w = w?;
    if !(w >= 0.0 && w.is_finite()) {
        let (context, prod) = site_context(tab, Site::Prod(t, p));
        let span = ch.spans.last().copied().unwrap_or_default();
        return Err(Box::new(DeriveError::BadProbability {
            value: w,
            context,
            step: st.step,
            src: src(tab, span),
            span: span.into(),
            production: prod.filter(|s| s.file == span.file).map(Into::into),
        }));
    }
    Ok(w)
}
