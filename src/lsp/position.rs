//! Byte offsets <-> LSP positions. Input: a file's text; output: a
//! [`LineIndex`] that turns miette/[`crate::source::Span`] byte offsets into
//! LSP `Position`s (line, UTF-16 code units, the protocol's default
//! encoding) and back, clamping anything out of range to the nearest valid
//! place instead of failing.

use lsp_types::{Position, Range};

/// Line starts of one text, with the text to measure columns in.
pub struct LineIndex<'t> {
    text: &'t str,
    starts: std::borrow::Cow<'t, [usize]>,
    /// An ASCII text's columns are byte counts: no need to count UTF-16
    /// units from the line's start, which made every position on a long
    /// line (a generated one-line axiom) cost the line's length.
    ascii: bool,
}

impl<'t> LineIndex<'t> {
    pub fn new(text: &'t str) -> LineIndex<'t> {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        LineIndex {
            text,
            starts: starts.into(),
            ascii: text.is_ascii(),
        }
    }

    /// An index that owns its text, measured once and borrowed as often
    /// as needed ([`Lines::index`]).
    pub fn owned(text: String) -> Lines {
        let ix = LineIndex::new(&text);
        let (starts, ascii) = (ix.starts.into_owned(), ix.ascii);
        Lines {
            text,
            starts,
            ascii,
        }
    }

    /// The position of byte `offset` (clamped to the text and moved back to
    /// a character boundary).
    pub fn position(&self, offset: usize) -> Position {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let col = if self.ascii {
            offset - start
        } else {
            self.text[start..offset].encode_utf16().count()
        };
        Position::new(line as u32, col as u32)
    }

    pub fn range(&self, start: usize, end: usize) -> Range {
        Range::new(self.position(start), self.position(end))
    }

    /// The byte offset of `pos`; a column past the line's end is its end
    /// (before the newline), a line past the last is the end of the text.
    pub fn offset(&self, pos: Position) -> usize {
        let Some(&start) = self.starts.get(pos.line as usize) else {
            return self.text.len();
        };
        let end = self
            .starts
            .get(pos.line as usize + 1)
            .map_or(self.text.len(), |&e| e - 1);
        let line = &self.text[start..end.max(start)];
        if self.ascii {
            return start + line.len().min(pos.character as usize);
        }
        let mut units = 0u32;
        for (i, c) in line.char_indices() {
            if units >= pos.character {
                return start + i;
            }
            units += c.len_utf16() as u32;
        }
        start + line.len()
    }

    /// The number of lines (a final line without newline counts).
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }
}

/// A text with its line starts (see [`LineIndex::owned`]).
pub struct Lines {
    text: String,
    starts: Vec<usize>,
    ascii: bool,
}

impl Lines {
    pub fn index(&self) -> LineIndex<'_> {
        LineIndex {
            text: &self.text,
            starts: self.starts.as_slice().into(),
            ascii: self.ascii,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_round_trips() {
        let t = "axiom: F\nF --> F+F\n";
        let ix = LineIndex::new(t);
        assert_eq!(ix.position(0), Position::new(0, 0));
        assert_eq!(ix.position(9), Position::new(1, 0));
        assert_eq!(ix.position(13), Position::new(1, 4));
        for o in 0..=t.len() {
            assert_eq!(ix.offset(ix.position(o)), o, "offset {o}");
        }
    }

    #[test]
    fn counts_utf16_units() {
        // `é` is 2 bytes and 1 unit; `𝔽` is 4 bytes and 2 units (surrogates).
        let t = "é𝔽x\n𝔽y";
        let ix = LineIndex::new(t);
        assert_eq!(ix.position(2), Position::new(0, 1));
        assert_eq!(ix.position(6), Position::new(0, 3));
        assert_eq!(ix.position(7), Position::new(0, 4));
        assert_eq!(ix.position(12), Position::new(1, 2));
        assert_eq!(ix.offset(Position::new(0, 3)), 6);
        assert_eq!(ix.offset(Position::new(1, 2)), 12);
        // Inside a character: back to its start; past the end: the end.
        assert_eq!(ix.position(4), Position::new(0, 1));
        assert_eq!(ix.offset(Position::new(0, 99)), 7);
        assert_eq!(ix.offset(Position::new(9, 0)), t.len());
        assert_eq!(ix.position(999), Position::new(1, 3));
    }

    #[test]
    fn crlf_lines() {
        let t = "a\r\nb";
        let ix = LineIndex::new(t);
        assert_eq!(ix.position(3), Position::new(1, 0));
        assert_eq!(ix.offset(Position::new(0, 5)), 2);
    }
}
