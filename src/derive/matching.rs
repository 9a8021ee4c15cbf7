//! Pattern matching: productions of one table in, per-symbol candidate
//! lists and precomputed pattern shapes out; [`match_at`] tests one
//! production at one position of a string and binds its parameters.
//! The semantics are documented in the [`derive`](crate::derive) module.

use super::store::{head_arity, head_sym, pack, ContextIndex};
use crate::resolve::{PatItem, PatModule, Production, CLOSE_BRACKET, OPEN_BRACKET};

/// A pattern module: packed head (symbol and arity, compared in one go)
/// and its first binding slot.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pat {
    pub head: u32,
    pub first: u16,
}

impl Pat {
    fn new(m: &PatModule) -> Pat {
        Pat {
            head: pack(m.sym, m.arity),
            first: m.first_param,
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum RItem {
    Module(Pat),
    Open,
    Close,
}

/// What matching needs to know about one production.
#[derive(Clone, Debug)]
pub(crate) struct Shape {
    pub pred: Vec<Pat>,
    pub lctx: Vec<Pat>,
    pub rctx: Vec<RItem>,
    /// Parameters of the strict predecessor modules together.
    pub pred_params: usize,
    /// The bindings are exactly the predecessor's parameters as they lie
    /// in the arena (no left context, no right-context parameters); the
    /// contexts must still match.
    pub direct: bool,
    pub has_prob: bool,
    /// The L-system the production belongs to.
    pub lsystem: u32,
}

impl Shape {
    fn new(p: &Production) -> Shape {
        let pred: Vec<Pat> = p.pred.iter().map(Pat::new).collect();
        let pred_params = p.pred.iter().map(|m| m.arity as usize).sum();
        let mut next = 0usize;
        let consecutive = p.pred.iter().all(|m| {
            let ok = m.first_param as usize == next;
            next += m.arity as usize;
            ok
        });
        Shape {
            direct: p.lctx.is_empty() && consecutive && p.nparams as usize == pred_params,
            pred,
            lctx: p.lctx.iter().map(Pat::new).collect(),
            rctx: p
                .rctx
                .iter()
                .map(|it| match it {
                    PatItem::Module(m) => RItem::Module(Pat::new(m)),
                    PatItem::Open(_) => RItem::Open,
                    PatItem::Close(_) => RItem::Close,
                })
                .collect(),
            pred_params,
            has_prob: p.prob.is_some(),
            lsystem: p.lsystem,
        }
    }
}

/// The productions of one table, ready for dispatch.
#[derive(Clone, Debug, Default)]
pub(crate) struct Rules {
    pub shapes: Vec<Shape>,
    /// Candidates of symbol `s`: `list[start[s]..start[s + 1]]`, production
    /// indices in file order.
    pub start: Vec<u32>,
    pub list: Vec<u32>,
    /// Whether symbol `s` has any candidate.
    pub has_rules: Vec<bool>,
    pub has_context: bool,
}

impl Rules {
    /// `never[i]`: production `i`'s condition folded to false.
    pub fn new(prods: &[Production], never: &[bool], nsyms: usize) -> Rules {
        let shapes: Vec<Shape> = prods.iter().map(Shape::new).collect();
        let mut per: Vec<Vec<u32>> = vec![Vec::new(); nsyms];
        for (i, p) in prods.iter().enumerate() {
            if never[i] {
                continue;
            }
            if let Some(first) = p.pred.first() {
                per[first.sym as usize].push(i as u32);
            }
        }
        let mut start = Vec::with_capacity(nsyms + 1);
        let mut list = Vec::new();
        for v in &per {
            start.push(list.len() as u32);
            list.extend_from_slice(v);
        }
        start.push(list.len() as u32);
        Rules {
            has_rules: per.iter().map(|v| !v.is_empty()).collect(),
            has_context: prods.iter().any(Production::has_context),
            shapes,
            start,
            list,
        }
    }

    #[inline]
    pub fn candidates(&self, sym: u32) -> &[u32] {
        let s = sym as usize;
        &self.list[self.start[s] as usize..self.start[s + 1] as usize]
    }
}

/// Where the bindings of a match are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Bound {
    /// `params[off..off + pred_params]` of the input.
    Direct,
    /// The binding buffer.
    Buffer,
}

/// The string being rewritten.
pub(crate) struct Input<'a> {
    pub heads: &'a [u32],
    pub params: &'a [f64],
    /// Present when the table has context productions.
    pub index: Option<&'a ContextIndex>,
    /// A ring L-system: context passes over the string's ends to the
    /// other end (once per context module, so a string of nothing but
    /// skipped modules still ends the search).
    pub ring: bool,
    /// The L-system whose productions apply here (see `Switch` in rewrite).
    pub lsystem: u32,
}

#[inline]
fn bind(binds: &mut [f64], first: u16, params: &[f64], off: usize, head: u32) {
    let a = head_arity(head);
    let f = first as usize;
    binds[f..f + a].copy_from_slice(&params[off..off + a]);
}

/// Test production `shape` with its strict predecessor starting at module
/// `i` (whose parameters start at `off`); on success the bindings are where
/// the returned [`Bound`] says. `skip[s]`: context matching passes over
/// symbol `s`.
#[inline(always)]
pub(crate) fn match_at(
    shape: &Shape,
    inp: &Input,
    skip: &[bool],
    i: usize,
    off: usize,
    binds: &mut [f64],
) -> Option<Bound> {
    let heads = inp.heads;
    let n = heads.len();
    let plen = shape.pred.len();
    if i + plen > n {
        return None;
    }
    for (k, p) in shape.pred.iter().enumerate() {
        if heads[i + k] != p.head {
            return None;
        }
    }
    let bound = if shape.direct {
        Bound::Direct
    } else {
        Bound::Buffer
    };
    let params = inp.params;
    if !shape.direct {
        let mut o = off;
        for p in &shape.pred {
            bind(binds, p.first, params, o, p.head);
            o += head_arity(p.head);
        }
    }
    if shape.lctx.is_empty() && shape.rctx.is_empty() {
        return Some(bound);
    }
    let idx = inp
        .index
        .expect("a context index is built for tables with context");
    // Left context, right to left.
    let mut j = i;
    for p in shape.lctx.iter().rev() {
        let mut wrapped = false;
        loop {
            if j == 0 {
                if !inp.ring || wrapped {
                    return None;
                }
                wrapped = true;
                j = n;
            }
            j -= 1;
            let s = head_sym(heads[j]);
            if skip[s as usize] {
                // Skipped (a bracket only in the cpfg dialect).
            } else if s == CLOSE_BRACKET {
                // A branch to our left: skip it whole, continue left of its `[`.
                j = idx.partner_of(j)?;
            } else if s == OPEN_BRACKET {
                // `[`: climb out of our branch to its parent.
            } else {
                break;
            }
        }
        if heads[j] != p.head {
            return None;
        }
        bind(binds, p.first, params, idx.offsets[j] as usize, p.head);
    }
    // Right context, left to right.
    let mut j = i + plen;
    for item in &shape.rctx {
        match *item {
            RItem::Module(p) => {
                let mut wrapped = false;
                loop {
                    if j >= n {
                        if !inp.ring || wrapped {
                            return None;
                        }
                        wrapped = true;
                        j = 0;
                    }
                    let s = head_sym(heads[j]);
                    if skip[s as usize] {
                        j += 1;
                    } else if s == OPEN_BRACKET {
                        // A branch the pattern does not enter: skip it.
                        j = idx.partner_of(j)? + 1;
                    } else if s == CLOSE_BRACKET {
                        return None; // end of our branch
                    } else {
                        break;
                    }
                }
                if heads[j] != p.head {
                    return None;
                }
                bind(binds, p.first, params, idx.offsets[j] as usize, p.head);
                j += 1;
            }
            RItem::Open => loop {
                if j >= n {
                    return None;
                }
                let s = head_sym(heads[j]);
                j += 1;
                if s == OPEN_BRACKET {
                    break;
                }
                if s == CLOSE_BRACKET || !skip[s as usize] {
                    return None;
                }
            },
            RItem::Close => loop {
                // Skip the rest of the current branch, past its `]`.
                if j >= n {
                    return None;
                }
                let s = head_sym(heads[j]);
                if s == OPEN_BRACKET {
                    j = idx.partner_of(j)? + 1;
                } else {
                    j += 1;
                    if s == CLOSE_BRACKET {
                        break;
                    }
                }
            },
        }
    }
    Some(bound)
}
