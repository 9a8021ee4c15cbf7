//! Built-in functions of the expression language: the names resolve binds
//! (`sin`, `ran`, cpfg's `nran`...), what each computes ([`call`]) and how
//! a table index becomes an offset ([`table_offset`]). Constant folding in
//! resolve and the VM in bytecode both call these, so a folded expression
//! and a run one always agree.

/// cpfg's random distributions beyond `ran`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RandFn {
    /// `nran(mean, sd)`: normal.
    Nran,
    /// `bran(a, b)`: beta.
    Bran,
    /// `biran(n, p)`: binomial.
    Biran,
}

impl RandFn {
    pub fn name(self) -> &'static str {
        match self {
            RandFn::Nran => "nran",
            RandFn::Bran => "bran",
            RandFn::Biran => "biran",
        }
    }
}

/// Built-in functions. Trigonometry works in degrees, as in cpfg.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Sqrt,
    Exp,
    Log,
    Floor,
    Ceil,
    Trunc,
    Abs,
    Sign,
    Min,
    Max,
    /// `ran(x)`: uniform in [0, x) from the derivation's seeded generator.
    Ran,
    /// `flo(w)`: a floating size of weight w in a split (docs/shapes.md).
    Flo,
    /// `rel(f)`: a size that is the fraction f of the scope in a split.
    Rel,
}

/// Where `rel(f)` puts its fraction: sizes at or below `-REL_BASE` are
/// relative, other negative sizes floating (docs/shapes.md). Small enough
/// that `REL_BASE + f` keeps f to about 1e-10 in an f64 parameter.
pub const REL_BASE: f64 = 1e6;

impl Func {
    pub const ALL: [Func; 20] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Atan2,
        Func::Sqrt,
        Func::Exp,
        Func::Log,
        Func::Floor,
        Func::Ceil,
        Func::Trunc,
        Func::Abs,
        Func::Sign,
        Func::Min,
        Func::Max,
        Func::Ran,
        Func::Flo,
        Func::Rel,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Atan2 => "atan2",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Log => "log",
            Func::Floor => "floor",
            Func::Ceil => "ceil",
            Func::Trunc => "trunc",
            Func::Abs => "abs",
            Func::Sign => "sign",
            Func::Min => "min",
            Func::Max => "max",
            Func::Ran => "ran",
            Func::Flo => "flo",
            Func::Rel => "rel",
        }
    }

    pub fn arity(self) -> usize {
        match self {
            Func::Atan2 | Func::Min | Func::Max => 2,
            _ => 1,
        }
    }

    pub fn from_name(name: &str) -> Option<Func> {
        // cpfg writes C's name for the absolute value.
        if name == "fabs" {
            return Some(Func::Abs);
        }
        Func::ALL.into_iter().find(|f| f.name() == name)
    }

    /// Whether the result depends on state (so it must never be folded).
    pub fn is_pure(self) -> bool {
        self != Func::Ran
    }
}

/// Apply a builtin to its arguments (`b` unused for unary functions).
pub fn call(f: Func, a: f64, b: f64) -> f64 {
    match f {
        Func::Sin => a.to_radians().sin(),
        Func::Cos => a.to_radians().cos(),
        Func::Tan => a.to_radians().tan(),
        Func::Asin => a.asin().to_degrees(),
        Func::Acos => a.acos().to_degrees(),
        Func::Atan => a.atan().to_degrees(),
        Func::Atan2 => a.atan2(b).to_degrees(),
        Func::Sqrt => a.sqrt(),
        Func::Exp => a.exp(),
        Func::Log => a.ln(),
        Func::Floor => a.floor(),
        Func::Ceil => a.ceil(),
        Func::Trunc => a.trunc(),
        Func::Abs => a.abs(),
        Func::Sign => {
            if a > 0.0 {
                1.0
            } else if a < 0.0 {
                -1.0
            } else if a.is_nan() {
                a
            } else {
                0.0
            }
        }
        Func::Min => a.min(b),
        Func::Max => a.max(b),
        Func::Ran => unreachable!("ran has its own instruction"),
        // Encoded as negative numbers the splits decode: a module's
        // parameters are plain numbers.
        Func::Flo => -a.abs(),
        Func::Rel => -REL_BASE - a.abs(),
    }
}

/// Row-major offset of the element at `idx` in a table whose dimensions
/// are `(first index, count)`. `Err(k)`: index k is outside its range or
/// not a whole number. Constant folding and the VM both use it, so both
/// agree on every lookup.
#[inline]
pub fn table_offset(bounds: impl Iterator<Item = (f64, f64)>, idx: &[f64]) -> Result<usize, usize> {
    let mut flat = 0usize;
    for (k, ((lo, len), &v)) in bounds.zip(idx).enumerate() {
        let off = v - lo;
        // `off < len` is false for NaN, so NaN indices fail too.
        if !(off >= 0.0 && off < len && off.fract() == 0.0) {
            return Err(k);
        }
        flat = flat * len as usize + off as usize;
    }
    Ok(flat)
}
