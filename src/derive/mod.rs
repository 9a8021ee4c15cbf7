//! Derive: [`Program`](crate::resolve::Program) and its
//! [`Compiled`](crate::bytecode::Compiled) code in, strings of modules
//! ([`ModuleStore`]) out, one parallel rewriting step at a time.
//!
//! # Semantics
//!
//! * **Axiom.** Step 0 is the axiom's successor chunk (it may call `ran`),
//!   followed by the decomposition in the paper's profile; the cpfg
//!   profile (`Profile::decompose_axiom` off) decomposes only after each
//!   step's productions, as cpfg does, so its step 0 is the axiom as
//!   written.
//! * **Dispatch.** At every position the candidates are the productions
//!   whose strict predecessor starts with the module's symbol, in file
//!   order. Modules without candidates are copied (in bulk runs).
//! * **Matching.** A strict predecessor of several modules (`A B --> C`)
//!   matches consecutive modules, nothing skipped. Each pattern module
//!   matches a module with the same symbol and the same number of
//!   parameters, and binds the parameters into the production's slots
//!   (left context, strict predecessor, right context). A production
//!   matches when its strict predecessor and contexts match and its
//!   condition is non-zero (`else` and no condition are true; NaN is true,
//!   as in C). The first match wins; the modules it covers are replaced by
//!   its successor and scanning continues after them. Without a match the
//!   module is copied unchanged.
//! * **Stochastic choice.** When the first match has a probability, every
//!   matching production of the candidate list from there on that also has
//!   one takes part, weighted by its evaluated probability (weights need
//!   not sum to 1; a negative, NaN or infinite weight is an error). Each
//!   such decision draws exactly one number `u` from the generator (after
//!   evaluating the weights); the production chosen is the first whose
//!   running sum of weights exceeds `u * total`. All weights zero: the
//!   module is copied unchanged (the draw still happens). A cpfg model
//!   file chooses as cpfg does instead (`stochastic.rs`).
//! * **Context** (cpfg/lpfg). Symbols the `ignore:` / `consider:` filter
//!   removes are passed over. The left context is matched right to left
//!   from just left of the strict predecessor: a `]` skips the whole branch
//!   to its `[`, a `[` climbs out of the current branch to its parent. The
//!   right context is matched left to right after the strict predecessor:
//!   a `[` the pattern does not expect skips that whole branch, a `]` (end
//!   of our branch) fails, a `[` in the pattern enters the next branch, a
//!   `]` in the pattern skips the rest of the current branch past its `]`.
//!   Unbalanced brackets fail the match.
//! * **Generator.** POSIX `drand48` ([`crate::lang::rng`]), seeded by `--seed`, else the
//!   program's `seed:` (not in a cpfg model file, where it seeds only the
//!   choices), else 0; one per derivation, consumed in string order
//!   (conditions, weights, the draw, then the successor's `ran` calls).
//! * **Decomposition.** After the axiom and after every step, each module
//!   is rewritten by the decomposition productions (first match,
//!   conditions and probabilities as above), and every module of the
//!   successor again, recursively. A module whose chain reaches
//!   `maximum depth:` productions is left as it is, with a warning
//!   ([`Derivation::warnings`]). It uses the derivation's generator.
//! * **Homomorphism.** [`homomorphism`] applies the homomorphism table the
//!   same way to produce the string the turtle interprets, never fed back,
//!   with a fresh generator seeded like the derivation's; in a cpfg model
//!   file ([`crate::lang::Profile::shared_random_stream`]) with the
//!   derivation's own ([`Derivation::interpret`]).
//! * **Limits.** A step stops as soon as its output passes
//!   [`DeriveOptions::max_modules`] modules or
//!   [`DeriveOptions::max_params`] parameter values.

mod budget;
mod condition;
pub mod count;
mod depth_first;
mod engine;
pub mod error;
mod fast;
mod faults;
mod matching;
pub mod number;
mod options;
mod parallel;
mod rewrite;
mod run;
mod state;
mod stochastic;
pub mod store;
mod sublsystem;
mod tables;
mod template;

pub use crate::lang::rng::{Rand48, DEFAULT_SEED};
pub use count::{count, Counts};
pub use engine::{homomorphism, Checkpoint, Derivation, Interpreted};
pub use error::{DepthWarning, DeriveError};
pub use number::{NumberFormat, NumberStyle};
pub use options::DeriveOptions;
pub use parallel::threads;
pub use store::{ContextIndex, Module, ModuleStore};
