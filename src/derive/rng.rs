//! The random generator of a derivation: exactly POSIX `drand48`/`erand48`,
//! implemented here so that results are identical on every platform and
//! every crate version (and match cpfg, which uses the same generator).
//!
//! State: 48 bits. Seeding is `srand48(seed)`: the low 32 bits of the seed
//! become the high 32 bits of the state, the low 16 bits are `0x330E`.
//! Each draw advances `x = (0x5DEECE66D * x + 0xB) mod 2^48` and returns
//! `x / 2^48`, uniform in `[0, 1)`.

/// Seed used when neither `--seed` nor the program's `seed:` gives one.
pub const DEFAULT_SEED: u64 = 0;

const A: u64 = 0x5_DEEC_E66D;
const C: u64 = 0xB;
const MASK: u64 = (1 << 48) - 1;

/// POSIX `drand48`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rand48 {
    state: u64,
}

impl Rand48 {
    /// As `srand48(seed)`; only the low 32 bits of `seed` count.
    pub fn new(seed: u64) -> Rand48 {
        Rand48 {
            state: ((seed & 0xFFFF_FFFF) << 16) | 0x330E,
        }
    }

    /// The 48-bit state, as `erand48`'s `xsubi` holds it.
    pub fn state(&self) -> u64 {
        self.state
    }

    /// Advance and return the new 48-bit state (`lrand48` is its top 31 bits).
    pub fn next_u48(&mut self) -> u64 {
        self.state = A.wrapping_mul(self.state).wrapping_add(C) & MASK;
        self.state
    }

    /// `drand48()`: uniform in `[0, 1)`.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        self.next_u48() as f64 / (1u64 << 48) as f64
    }
}
