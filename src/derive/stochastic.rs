//! cpfg's stochastic productions (generate.c, `FindApplProductions` and
//! `SelectProd`): a module of the string and the productions that match
//! it in, the production to apply out, drawn from cpfg's separate
//! generator of choices ([`State::choice`], seeded by `seed:`). Used for
//! cpfg model files ([`Profile::cpfg_stochastic`]); the paper's choice
//! is `rewrite.rs`'s.
//!
//! A `seed:` makes the whole L-system stochastic. At every position of a
//! step (a module no production looks at, a `%`, a matched predecessor)
//! cpfg evaluates every production that matches there, in file order
//! (conditions included, so their blocks all run), gives each its
//! probability or 1 without one, and draws one number, whether or not
//! anything matched. Without `seed:` probabilities are ignored, as cpfg
//! ignores them (with a warning), and so are they in the decomposition and
//! homomorphism, which cpfg always applies first-match.
//!
//! [`Profile::cpfg_stochastic`]: crate::lang::Profile::cpfg_stochastic

use super::condition::{applies, weight};
use super::error::Fail;
use super::matching::{match_at, Bound, Input};
use super::state::State;
use super::store::head_sym;
use super::tables::{table_index, Tables};
use crate::resolve::Table;

/// A module: the string, its index and the offset of its parameters.
type Here<'a, 'i> = (&'a Input<'i>, usize, usize);

/// The production to apply at `here` in a cpfg model file.
pub(crate) fn choose(tab: &Tables, st: &mut State, t: Table, here: Here) -> Chosen {
    let (inp, i, off) = here;
    let rules = &tab.rules[table_index(t)];
    let cands = rules.candidates(head_sym(inp.heads[i]));
    let stochastic = t == Table::Main && st.choice.is_some();
    st.weights.clear();
    for &p in cands {
        let p = p as usize;
        if rules.shapes[p].lsystem != inp.lsystem {
            continue;
        }
        let Some(bound) = applies(tab, st, t, p, inp, i, off)? else {
            continue;
        };
        if !stochastic {
            return Ok(Some((p, bound)));
        }
        let w = if rules.shapes[p].has_prob {
            weight(tab, st, t, p, inp, off, bound)?
        } else {
            1.0
        };
        st.weights.push((p as u32, w));
    }
    if !stochastic {
        return Ok(None);
    }
    let u = draw(st);
    // cpfg's arithmetic: probabilities and their sum are C floats, and the
    // draw scaled by the sum is taken off one probability after another
    // until it is no longer positive.
    let total = st.weights.iter().fold(0f32, |t, &(_, w)| t + w as f32);
    let mut left = (total as f64 * u) as f32;
    let Some(&(q, _)) = st.weights.iter().find(|&&(_, w)| {
        left -= w as f32;
        left <= 0.0
    }) else {
        return Ok(None);
    };
    let q = q as usize;
    let bound = match_at(&rules.shapes[q], inp, &tab.skip, i, off, &mut st.binds)
        .expect("the chosen production matched");
    Ok(Some((q, bound)))
}

/// cpfg's draws for `n` positions of the main table that no production
/// rewrites (modules copied, a `%` cut), in a stochastic model file.
pub(crate) fn pass_over(st: &mut State, t: Table, n: usize) {
    if t == Table::Main {
        if let Some(c) = &mut st.choice {
            (0..n).for_each(|_| {
                c.next_f64();
            });
        }
    }
}

type Chosen = Result<Option<(usize, Bound)>, Fail>;

fn draw(st: &mut State) -> f64 {
    st.choice.as_mut().map_or(0.0, |c| c.next_f64())
}
