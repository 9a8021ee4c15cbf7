//! The flat module store: a string of modules as two vectors, with no
//! allocation per module. Input: modules pushed by the VM or copied in
//! bulk; output: iteration, printing in the CLI format (numbers as
//! [`NumberFormat`] says), symbol counts.
//!
//! `heads[i]` packs module `i`'s parameter count into the top 8 bits and
//! its symbol id into the low 24 bits; the parameters of all modules follow
//! each other in `params`. A module's parameters start at the sum of the
//! arities before it ([`ContextIndex`] precomputes these offsets and the
//! bracket pairs when context matching needs random access).

use std::io::{self, Write};

use super::number::{write_f32, write_f64, NumberFormat, NumberStyle};
use crate::bytecode::Sink;
use crate::resolve::{SymId, Symbols, CLOSE_BRACKET, OPEN_BRACKET};

/// Bits of a head that hold the symbol id.
pub const SYM_BITS: u32 = 24;
pub const SYM_MASK: u32 = (1 << SYM_BITS) - 1;
/// Largest symbol id a store can hold.
pub const MAX_SYMBOLS: usize = 1 << SYM_BITS;

/// Pack a symbol and its parameter count into a head.
#[inline]
pub fn pack(sym: SymId, arity: u8) -> u32 {
    debug_assert!(sym <= SYM_MASK);
    ((arity as u32) << SYM_BITS) | sym
}

/// Symbol id of a head.
#[inline]
pub fn head_sym(head: u32) -> SymId {
    head & SYM_MASK
}

/// Parameter count of a head.
#[inline]
pub fn head_arity(head: u32) -> usize {
    (head >> SYM_BITS) as usize
}

/// One module, borrowed from a store.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Module<'a> {
    pub sym: SymId,
    pub params: &'a [f64],
}

/// A string of modules.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModuleStore {
    pub(crate) heads: Vec<u32>,
    pub(crate) params: Vec<f64>,
}

impl ModuleStore {
    pub fn new() -> ModuleStore {
        ModuleStore::default()
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.heads.len()
    }

    pub fn is_empty(&self) -> bool {
        self.heads.is_empty()
    }

    /// Number of parameter values of all modules together.
    pub fn param_count(&self) -> usize {
        self.params.len()
    }

    /// Empty the store, keeping its memory.
    pub fn clear(&mut self) {
        self.heads.clear();
        self.params.clear();
    }

    /// Append a module. Panics (in debug builds) beyond 255 parameters or
    /// 2^24 symbols; the compiler and `Derivation::new` guarantee both.
    #[inline(always)]
    pub fn push(&mut self, sym: SymId, params: &[f64]) {
        debug_assert!(params.len() <= u8::MAX as usize);
        self.heads.push(pack(sym, params.len() as u8));
        // Short runs by hand: `extend_from_slice` calls `memcpy`.
        match *params {
            [] => {}
            [a] => self.params.push(a),
            [a, b] => {
                self.params.push(a);
                self.params.push(b);
            }
            _ => self.params.extend_from_slice(params),
        }
    }

    /// The packed heads (see the module docs).
    pub fn heads(&self) -> &[u32] {
        &self.heads
    }

    /// All parameters, module after module.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// All parameters, to overwrite in place (an environment answering
    /// query modules); the modules themselves cannot change.
    pub fn params_mut(&mut self) -> &mut [f64] {
        &mut self.params
    }

    /// Iterate over the modules in order.
    pub fn iter(&self) -> Iter<'_> {
        Iter {
            heads: self.heads.iter(),
            params: &self.params,
        }
    }

    /// Number of modules with symbol `sym`.
    pub fn count(&self, sym: SymId) -> usize {
        self.heads.iter().filter(|&&h| head_sym(h) == sym).count()
    }

    /// Number of modules of every symbol, indexed by symbol id
    /// (`nsyms` is `program.symbols.len()`).
    pub fn counts(&self, nsyms: usize) -> Vec<usize> {
        let mut c = vec![0usize; nsyms];
        for &h in &self.heads {
            let s = head_sym(h) as usize;
            if s >= c.len() {
                c.resize(s + 1, 0);
            }
            c[s] += 1;
        }
        c
    }

    /// Print in the CLI format: modules separated by one space, parameters
    /// as `A(1,2.5)` with Rust's shortest round-trip `{}` for f64, no
    /// trailing newline. Buffered internally; no allocation per module.
    pub fn write_string<W: Write>(&self, symbols: &Symbols, out: &mut W) -> io::Result<()> {
        self.write_modules(symbols, out, write_f64)
    }

    /// [`write_string`](Self::write_string) with the parameters printed
    /// as `fmt` says.
    pub fn write_string_with<W: Write>(
        &self,
        symbols: &Symbols,
        fmt: NumberFormat,
        out: &mut W,
    ) -> io::Result<()> {
        match fmt {
            NumberFormat {
                f32: false,
                style: NumberStyle::Shortest,
            } => self.write_modules(symbols, out, write_f64),
            NumberFormat {
                f32: true,
                style: NumberStyle::Shortest,
            } => self.write_modules(symbols, out, |b, v| write_f32(b, v as f32 as f64)),
            _ => self.write_modules(symbols, out, |b, v| fmt.write(b, v)),
        }
    }

    /// The modules, each parameter printed by `number`.
    #[inline(always)]
    fn write_modules<W: Write>(
        &self,
        symbols: &Symbols,
        out: &mut W,
        number: impl Fn(&mut Vec<u8>, f64),
    ) -> io::Result<()> {
        let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
        for (i, m) in self.iter().enumerate() {
            if i > 0 {
                buf.push(b' ');
            }
            buf.extend_from_slice(symbols.name(m.sym).as_bytes());
            if !m.params.is_empty() {
                buf.push(b'(');
                for (k, v) in m.params.iter().enumerate() {
                    if k > 0 {
                        buf.push(b',');
                    }
                    number(&mut buf, *v);
                }
                buf.push(b')');
            }
            if buf.len() >= 1 << 16 {
                out.write_all(&buf)?;
                buf.clear();
            }
        }
        out.write_all(&buf)
    }

    /// The CLI format as a `String` (tests, the REPL).
    pub fn display(&self, symbols: &Symbols) -> String {
        self.display_with(symbols, NumberFormat::default())
    }

    /// [`display`](Self::display) with the parameters printed as `fmt`
    /// says.
    pub fn display_with(&self, symbols: &Symbols, fmt: NumberFormat) -> String {
        let mut v = Vec::new();
        self.write_string_with(symbols, fmt, &mut v)
            .expect("writing to a Vec cannot fail");
        String::from_utf8(v).expect("symbol names are UTF-8")
    }

    /// Append modules `heads` whose parameters are `params` (bulk copy).
    #[inline(always)]
    pub(crate) fn extend_raw(&mut self, heads: &[u32], params: &[f64]) {
        // Runs are often a few modules long; `memcpy` calls cost more then.
        if heads.len() <= 8 {
            self.heads.reserve(heads.len());
            for &h in heads {
                self.heads.push(h);
            }
        } else {
            self.heads.extend_from_slice(heads);
        }
        if params.len() <= 8 {
            self.params.reserve(params.len());
            for &v in params {
                self.params.push(v);
            }
        } else {
            self.params.extend_from_slice(params);
        }
    }
}

impl Sink for ModuleStore {
    #[inline(always)]
    fn emit(&mut self, sym: SymId, params: &[f64]) {
        self.push(sym, params);
    }
}

impl<'a> IntoIterator for &'a ModuleStore {
    type Item = Module<'a>;
    type IntoIter = Iter<'a>;
    fn into_iter(self) -> Iter<'a> {
        self.iter()
    }
}

/// Iterator over the modules of a store.
pub struct Iter<'a> {
    heads: std::slice::Iter<'a, u32>,
    params: &'a [f64],
}

impl<'a> Iterator for Iter<'a> {
    type Item = Module<'a>;

    #[inline]
    fn next(&mut self) -> Option<Module<'a>> {
        let &h = self.heads.next()?;
        let (p, rest) = self.params.split_at(head_arity(h));
        self.params = rest;
        Some(Module {
            sym: head_sym(h),
            params: p,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.heads.size_hint()
    }
}

impl ExactSizeIterator for Iter<'_> {}

/// No partner bracket (unbalanced string).
pub const NO_MATCH: u32 = u32::MAX;

/// Random access into a store for context matching, rebuilt per step:
/// the parameter offset of every module and the index of the partner of
/// every bracket.
#[derive(Clone, Debug, Default)]
pub struct ContextIndex {
    /// `offsets[i]`: where module `i`'s parameters start.
    pub offsets: Vec<u32>,
    /// For `[` the index of its `]`, for `]` the index of its `[`,
    /// [`NO_MATCH`] if unbalanced; unspecified for other modules.
    pub partner: Vec<u32>,
    stack: Vec<u32>,
}

impl ContextIndex {
    /// The index of the bracket matching the one at `j`; `None` when it
    /// is unbalanced (then no context can be matched across it).
    #[inline]
    pub fn partner_of(&self, j: usize) -> Option<usize> {
        match self.partner[j] {
            NO_MATCH => None,
            k => Some(k as usize),
        }
    }

    /// Rebuild for `store`, reusing memory. The store's parameters must
    /// number fewer than 2^32 (the derivation's arena limit ensures it).
    pub fn build(&mut self, store: &ModuleStore) {
        let n = store.heads.len();
        self.offsets.clear();
        self.offsets.reserve(n);
        self.partner.clear();
        self.partner.resize(n, NO_MATCH);
        self.stack.clear();
        let mut off = 0u32;
        for (i, &h) in store.heads.iter().enumerate() {
            self.offsets.push(off);
            off += head_arity(h) as u32;
            match head_sym(h) {
                OPEN_BRACKET => self.stack.push(i as u32),
                CLOSE_BRACKET => {
                    if let Some(o) = self.stack.pop() {
                        self.partner[o as usize] = i as u32;
                        self.partner[i] = o;
                    }
                }
                _ => {}
            }
        }
    }
}

/// From module `i`, the index of the `]` that closes the current branch
/// (or the end of the string) and the number of parameter values passed
/// over: what cpfg's cut `%` removes.
pub fn rest_of_branch(heads: &[u32], mut i: usize) -> (usize, usize) {
    let mut depth = 0usize;
    let mut params = 0;
    while i < heads.len() {
        let s = head_sym(heads[i]);
        if s == OPEN_BRACKET {
            depth += 1;
        } else if s == CLOSE_BRACKET {
            if depth == 0 {
                break;
            }
            depth -= 1;
        }
        params += head_arity(heads[i]);
        i += 1;
    }
    (i, params)
}

#[cfg(test)]
mod tests {
    use crate::derive::number::write_f64;

    #[test]
    fn whole_numbers_print_as_display_does() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            25.0,
            -123456789.0,
            9_007_199_254_740_991.0,
            -9_007_199_254_740_991.0,
            9_007_199_254_740_992.0,
            1e300,
            0.5,
            -2.25,
            1e-7,
            f64::MAX,
        ] {
            let mut b = Vec::new();
            write_f64(&mut b, v);
            assert_eq!(String::from_utf8(b).unwrap(), format!("{v}"), "{v:e}");
        }
    }
}
