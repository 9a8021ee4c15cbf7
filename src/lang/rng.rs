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
#[derive(Clone, Debug, PartialEq)]
pub struct Rand48 {
    state: u64,
    /// The second normal sample of the last polar-method draw, which the
    /// next `nran` returns (cpfg's `iset`/`gset`).
    spare: Option<f64>,
}

impl Rand48 {
    /// As `srand48(seed)`; only the low 32 bits of `seed` count.
    pub fn new(seed: u64) -> Rand48 {
        Rand48 {
            state: ((seed & 0xFFFF_FFFF) << 16) | 0x330E,
            // cpfg starts with a spare sample of 0 (its `gset` is a zeroed
            // static and `iset` starts non-zero), so the first `nran(m, s)`
            // before any `srand` gives exactly `m`.
            spare: Some(0.0),
        }
    }

    /// The generator cpfg draws its stochastic productions' choices from:
    /// C's own `drand48` state, apart from the `ran` one, which
    /// `seed: n` sets with `seed48({n, 0, 155})` (only n's low 16 bits
    /// count) when n is not 0. With `seed: 0` cpfg leaves it unseeded,
    /// which in the C library of Linux (glibc) is the state 0.
    pub fn cpfg_choice(seed: u64) -> Rand48 {
        let state = if seed == 0 {
            0
        } else {
            (155 << 32) | (seed & 0xFFFF)
        };
        Rand48 { state, spare: None }
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

    /// cpfg's `srand(x)`: seed with C's `(long) x` (truncated toward
    /// zero; NaN and out-of-range values saturate) and forget the spare
    /// normal sample.
    pub fn reseed(&mut self, x: f64) {
        *self = Rand48::new(x as i64 as u64);
        self.spare = None;
    }

    /// cpfg's `nran(mean, sd)`: Marsaglia's polar method, two uniform
    /// draws per attempt, the second sample kept for the next call.
    pub fn nran(&mut self, mean: f64, sd: f64) -> f64 {
        if let Some(g) = self.spare.take() {
            return g * sd + mean;
        }
        loop {
            let v1 = 2.0 * self.next_f64() - 1.0;
            let v2 = 2.0 * self.next_f64() - 1.0;
            let rsq = v1 * v1 + v2 * v2;
            if rsq < 1.0 && rsq != 0.0 {
                let fac = (-2.0 * rsq.ln() / rsq).sqrt();
                self.spare = Some(v1 * fac);
                return v2 * fac * sd + mean;
            }
        }
    }

    /// cpfg's `bran(a, b)`: beta-distributed in (0, 1), by Cheng's
    /// rejection algorithm (two non-zero uniform draws per attempt). Gives
    /// NaN for parameters that are not positive, where cpfg would loop.
    pub fn bran(&mut self, a: f64, b: f64) -> f64 {
        if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
            return f64::NAN;
        }
        let s = a + b;
        let lambda = if a.min(b) <= 1.0 {
            a.min(b)
        } else {
            ((2.0 * a * b - s) / (s - 2.0)).sqrt()
        };
        let u = a + lambda;
        // Each round accepts with probability over 1/4; the cap only stops
        // degenerate parameters from spinning.
        for _ in 0..10_000 {
            let u1 = self.nonzero();
            let u2 = self.nonzero();
            let v = (1.0 / lambda) * (u1 / (1.0 - u1)).ln();
            let ym = a * v.exp();
            if s * (s / (b + ym)).ln() + u * v - 4f64.ln() >= (u1 * u1 * u2).ln() {
                return ym / (b + ym);
            }
        }
        f64::NAN
    }

    /// cpfg's `biran(n, p)`: binomial, by `n` coin flips (`n` truncated
    /// as C's `(int)` does; at most 10^7 flips).
    pub fn biran(&mut self, n: f64, p: f64) -> f64 {
        let n = if n.is_nan() {
            0
        } else {
            (n as i64).clamp(0, 10_000_000)
        };
        (0..n).filter(|_| self.next_f64() <= p).count() as f64
    }

    fn nonzero(&mut self) -> f64 {
        loop {
            let u = self.next_f64();
            if u != 0.0 {
                return u;
            }
        }
    }

    /// `drand48()`: uniform in `[0, 1)`.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        self.next_u48() as f64 / (1u64 << 48) as f64
    }
}
