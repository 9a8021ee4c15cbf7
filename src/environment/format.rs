//! C `printf` conversions as cpfg applies them to the turtle fields it
//! sends an environment (`turtle position:P:%.4f %.4f %.0f`): a value in,
//! the value the program reads back out (`sscanf` into a C `float`).

/// One conversion of a field's format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conversion {
    /// `%.Nf` (N = 6 without a precision).
    Fixed(u8),
    /// `%.Ng` (N = 6 without a precision; `%.0g` is 1 digit).
    General(u8),
    /// `%.Ne` (N = 6 without a precision).
    Exponent(u8),
}

impl Conversion {
    /// The conversions of a format string, in order (`%.4f %.4f %.0f`).
    /// `None` when a conversion is not one of `f`, `g`, `e`, `G`, `E`.
    pub fn parse_all(format: &str) -> Option<Vec<Conversion>> {
        let mut out = Vec::new();
        let mut chars = format.chars().peekable();
        while let Some(c) = chars.next() {
            if c != '%' {
                continue;
            }
            // Flags and width are allowed and do not change the value.
            while chars.peek().is_some_and(|c| "-+ #0".contains(*c)) {
                chars.next();
            }
            while chars.peek().is_some_and(|c| c.is_ascii_digit()) {
                chars.next();
            }
            let mut precision = None;
            if chars.peek() == Some(&'.') {
                chars.next();
                let mut p = 0u32;
                while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
                    p = (p * 10 + d).min(40);
                    chars.next();
                }
                precision = Some(p as u8);
            }
            // Length modifiers (`%lf`).
            while chars.peek().is_some_and(|c| *c == 'l' || *c == 'L') {
                chars.next();
            }
            out.push(match chars.next()? {
                'f' | 'F' => Conversion::Fixed(precision.unwrap_or(6)),
                'g' | 'G' => Conversion::General(precision.unwrap_or(6).max(1)),
                'e' | 'E' => Conversion::Exponent(precision.unwrap_or(6)),
                _ => return None,
            });
        }
        Some(out)
    }

    /// `v` printed with this conversion and read back as a C `float`.
    pub fn round(self, v: f64) -> f32 {
        if !v.is_finite() {
            return v as f32;
        }
        let text = match self {
            Conversion::Fixed(p) => format!("{v:.*}", p as usize),
            // `%.Ng` keeps N significant digits: the same value as `%.{N-1}e`.
            Conversion::General(p) => format!("{v:.*e}", p as usize - 1),
            Conversion::Exponent(p) => format!("{v:.*e}", p as usize),
        };
        text.parse::<f32>().unwrap_or(v as f32)
    }
}
