//! How parameter values are printed: the shortest form that reads back as
//! the value stored (f64, or f32 in the cpfg dialect), rounded to a number
//! of decimals for snapshots, or C's `printf("%g")` as cpfg's `-str` output
//! prints them. Input: an f64 and a [`NumberFormat`]; output: bytes appended
//! to a buffer, with no allocation of their own.

use std::io::Write;

use crate::resolve::Program;

/// How [`ModuleStore::write_string_with`](super::ModuleStore::write_string_with)
/// prints parameter values. The default is Rust's shortest round-trip `{}`
/// for f64 (what [`ModuleStore::write_string`](super::ModuleStore::write_string)
/// prints).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NumberFormat {
    /// The values are f32s (the cpfg dialect stores parameters so): each
    /// is read as `v as f32` first, and the shortest form is the shortest
    /// that round-trips that f32 (`5.695309`, not `5.695309162139893`).
    pub f32: bool,
    pub style: NumberStyle,
}

/// The printed form of a value.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NumberStyle {
    /// The shortest digits that read back as the value (f64, or f32 with
    /// [`NumberFormat::f32`]); never an exponent, `-0` for negative zero.
    #[default]
    Shortest,
    /// Rounded to this many decimal places (the exact binary value, ties
    /// to even), trailing zeros and a trailing `.` removed; never more
    /// digits than `Shortest` prints. A value that rounds to zero prints
    /// `0`, never `-0`, so that snapshots do not flip on noise around 0.
    Decimals(u8),
    /// C's `printf("%g")`, as cpfg's `-str` output prints parameters: six
    /// significant digits, the exponent form (`1e+06`, `1.5e-05`) when the
    /// decimal exponent is below -4 or at least 6, trailing zeros removed;
    /// `-0`, `inf`, `-inf`, `nan` as glibc prints them.
    PrintfG,
}

impl NumberFormat {
    /// Shortest form of the values as `program`'s profile stores them
    /// (f32 in the cpfg dialect).
    pub fn for_program(program: &Program) -> NumberFormat {
        NumberFormat {
            f32: program.profile.f32_params,
            style: NumberStyle::Shortest,
        }
    }

    /// The same, printed in `style`.
    pub fn with_style(self, style: NumberStyle) -> NumberFormat {
        NumberFormat { style, ..self }
    }

    /// Append `v`.
    #[inline]
    pub fn write(self, buf: &mut Vec<u8>, v: f64) {
        let v = if self.f32 { v as f32 as f64 } else { v };
        match self.style {
            NumberStyle::Shortest if self.f32 => write_f32(buf, v),
            NumberStyle::Shortest => write_f64(buf, v),
            NumberStyle::Decimals(n) => write_decimals(buf, v, n as usize, self.f32),
            NumberStyle::PrintfG => write_printf_g(buf, v),
        }
    }

    /// `v` as a `String` (the REPL, tests).
    pub fn format(self, v: f64) -> String {
        let mut b = Vec::with_capacity(24);
        self.write(&mut b, v);
        String::from_utf8(b).expect("numbers print as ASCII")
    }
}

/// 2^53: below it every whole f64 is exact and `{}` prints its digits.
const WHOLE_F64: f64 = 9_007_199_254_740_992.0;
/// 2^24: the same for f32.
const WHOLE_F32: f64 = 16_777_216.0;

/// Append `v` by hand when it is a whole number of magnitude below `below`
/// (the usual parameters): the general float formatter costs more than
/// the rest of printing a module together. `-0.0` prints as `-0`.
#[inline]
fn write_whole(buf: &mut Vec<u8>, v: f64, below: f64) -> bool {
    if !(v.fract() == 0.0 && v.abs() < below) {
        return false;
    }
    if v.is_sign_negative() {
        buf.push(b'-');
    }
    buf.extend_from_slice(itoa::Buffer::new().format(v.abs() as u64).as_bytes());
    true
}

/// Append `v` as Rust's `{}` prints an f64.
#[inline]
pub(crate) fn write_f64(buf: &mut Vec<u8>, v: f64) {
    if !write_whole(buf, v, WHOLE_F64) {
        // Writing to a `Vec` cannot fail.
        let _ = write!(buf, "{v}");
    }
}

/// Append `v` (an f32 widened) as Rust's `{}` prints the f32.
#[inline]
pub(crate) fn write_f32(buf: &mut Vec<u8>, v: f64) {
    if !write_whole(buf, v, WHOLE_F32) {
        let _ = write!(buf, "{}", v as f32);
    }
}

/// Remove trailing zeros after a `.` in `buf[start..]`, and the `.` if
/// nothing is left after it.
fn trim_fraction(buf: &mut Vec<u8>, start: usize) {
    if !buf[start..].contains(&b'.') {
        return;
    }
    while buf.last() == Some(&b'0') {
        buf.pop();
    }
    if buf.last() == Some(&b'.') {
        buf.pop();
    }
}

fn write_decimals(buf: &mut Vec<u8>, v: f64, n: usize, f32: bool) {
    if v == 0.0 {
        buf.push(b'0');
        return;
    }
    // The shortest form when it has no more than `n` decimals (it never
    // has an exponent): it already is the value rounded to `n` places.
    let start = buf.len();
    if f32 {
        write_f32(buf, v);
    } else {
        write_f64(buf, v);
    }
    let decimals = match buf[start..].iter().position(|&c| c == b'.') {
        Some(p) => buf.len() - start - p - 1,
        None => 0,
    };
    if decimals <= n {
        return;
    }
    buf.truncate(start);
    // `v` is exactly the f32 when `f32` is set: the same digits.
    let _ = write!(buf, "{v:.n$}");
    trim_fraction(buf, start);
    if buf[start..] == *b"-0" {
        buf.truncate(start);
        buf.push(b'0');
    }
}

fn write_printf_g(buf: &mut Vec<u8>, v: f64) {
    if !v.is_finite() {
        let s: &[u8] = if v.is_nan() {
            b"nan"
        } else if v > 0.0 {
            b"inf"
        } else {
            b"-inf"
        };
        buf.extend_from_slice(s);
        return;
    }
    // Whole numbers of at most six digits print as they are.
    if write_whole(buf, v, 1e6) {
        return;
    }
    // The exponent X of `v` rounded to six significant digits decides:
    // `%f` with 5 - X decimals when -4 <= X < 6, else `%e` with 5.
    let start = buf.len();
    let _ = write!(buf, "{v:.5e}");
    let e = start
        + buf[start..]
            .iter()
            .position(|&c| c == b'e')
            .expect("`{:e}` writes an exponent");
    let exp: i32 = std::str::from_utf8(&buf[e + 1..])
        .ok()
        .and_then(|s| s.parse().ok())
        .expect("`{:e}` writes a decimal exponent");
    if (-4..6).contains(&exp) {
        buf.truncate(start);
        let _ = write!(buf, "{v:.*}", (5 - exp) as usize);
        trim_fraction(buf, start);
    } else {
        buf.truncate(e);
        trim_fraction(buf, start);
        buf.push(b'e');
        buf.push(if exp < 0 { b'-' } else { b'+' });
        if exp.abs() < 10 {
            buf.push(b'0');
        }
        let _ = write!(buf, "{}", exp.abs());
    }
}
