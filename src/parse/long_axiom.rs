//! A very long axiom line, parsed in pieces. Input: the text at the start
//! of a statement; output: the axiom as one item, holding only where its
//! pieces are, and where it ends, or `None` to parse the statement as
//! usual. [`axiom_piece`] reads a piece's modules when they are used.
//!
//! pest records two queue entries of about 40 bytes per matched rule, for
//! the whole statement at once: a 64 MiB axiom (the size limit of a file)
//! needed 280 bytes per input byte, 12.5 GB, and aborted (issue 36).
//! Split between modules into pieces of [`PIECE`] bytes, each piece's
//! queue is dropped before the next is parsed, and its module tokens are
//! dropped too: the resolver parses each piece again and keeps only the
//! resolved modules.
//!
//! Only plain lines are split: anything the pieces could read differently
//! from the whole line (comments, strings, line joins, arrows, colons,
//! braces, a `(` after a space, a `$` that the dialect hint looks for)
//! leaves the line to the usual parser, and
//! so does any piece that does not parse whole, so that errors are
//! reported exactly as before.

use pest::Parser;

use super::ast::{HeaderKind, Item, ModuleTok};
use super::lower::Lower;
use super::{LsysParser, Rule};
use crate::source::{FileId, SourceFile, Span};

/// Lines shorter than this are parsed whole.
const LONG: usize = 1 << 20;
/// The size a piece grows to before it is cut at the next space.
const PIECE: usize = 1 << 16;

/// The axiom at `pos` parsed piece by piece, and the byte its statement
/// ends at; `None` when the line is short or not plain.
pub(super) fn parse(file_id: FileId, file: &SourceFile, pos: usize) -> Option<(Item, usize)> {
    let text = file.text.as_str();
    let line_end = text[pos..].find('\n').map_or(text.len(), |i| pos + i);
    if line_end - pos < LONG {
        return None;
    }
    let line = &text[pos..line_end];
    let body = header_body(line)?;
    let plain = |b: &[u8]| {
        !b.windows(2)
            .any(|w| matches!(w, b"/*" | b"//" | b"->" | b"=>" | b"*/" | b" (" | b"\t("))
            && !b
                .iter()
                .any(|c| matches!(c, b'"' | b'\\' | b':' | b'{' | b'}' | b'#' | b'\r' | b'$'))
    };
    if !plain(&line.as_bytes()[body..]) || line.contains('→') {
        return None;
    }
    let cuts = cuts(line.as_bytes(), body);
    // The first piece, with the header, as a statement: the header item.
    let first_end = pos + cuts.first().copied().unwrap_or(line.len());
    let mut pairs = super::parse_statement(&text[pos..first_end]).ok()?;
    let pair = pairs.next()?;
    if pos + pair.as_span().end() != trimmed_end(text, pos, first_end) {
        return None;
    }
    let lower = Lower {
        file_id,
        base: pos,
        file,
    };
    let mut item = lower.statement(pair).ok()?;
    let Item::Header(header) = &mut item else {
        return None;
    };
    if !matches!(header.kind, HeaderKind::Axiom(_)) {
        return None;
    }
    // Every piece is checked here exactly as `axiom_piece` will read it;
    // the last one runs on past the line, as a successor continues onto
    // indented lines.
    let starts = std::iter::once(body).chain(cuts.iter().copied());
    let mut pieces = Vec::with_capacity(cuts.len() + 1);
    for (k, start) in starts.enumerate() {
        let start = pos + start;
        let last = k == cuts.len();
        let stop = if last {
            text.len()
        } else {
            trimmed_end(text, start, pos + cuts[k])
        };
        let mut pairs = LsysParser::parse(Rule::successor, &text[start..stop]).ok()?;
        let pair = pairs.next()?;
        let end = start + pair.as_span().end();
        if !last && end != stop {
            return None;
        }
        let span = Span::new(file_id, start, end);
        // Lowering can refuse what parses (a number out of range): the
        // usual parser reports it.
        axiom_piece(file, span)?;
        pieces.push(span);
    }
    let end = pieces.last().map_or(first_end, |s| s.end as usize);
    header.kind = HeaderKind::LongAxiom(pieces);
    header.span = Span::new(file_id, pos, end);
    Some((item, end))
}

/// The modules of one piece of a [`HeaderKind::LongAxiom`], or `None` when
/// the piece no longer parses whole (never for the file it came from).
pub fn axiom_piece(file: &SourceFile, span: Span) -> Option<Vec<ModuleTok>> {
    let text = file.text.get(span.start as usize..span.end as usize)?;
    let mut pairs = LsysParser::parse(Rule::successor, text).ok()?;
    let pair = pairs.next()?;
    if pair.as_span().end() != text.len() {
        return None;
    }
    let lower = Lower {
        file_id: span.file,
        base: span.start as usize,
        file,
    };
    lower.modules(pair).ok()
}

/// Where the modules of an axiom line start: after `Axiom:` (any of the
/// keyword's spellings) and the spaces after it.
fn header_body(line: &str) -> Option<usize> {
    let rest = ["Axiom", "axiom", "ω", "Ω"]
        .iter()
        .find_map(|k| line.strip_prefix(k))?;
    let after = rest.trim_start_matches([' ', '\t']).strip_prefix(':')?;
    let body = after.trim_start_matches([' ', '\t']);
    Some(line.len() - body.len())
}

/// Offsets in `line` where pieces after the first start: the first
/// module after a run of spaces outside parentheses, once the piece has
/// [`PIECE`] bytes.
fn cuts(line: &[u8], body: usize) -> Vec<usize> {
    let mut cuts = Vec::new();
    let mut depth = 0i64;
    let mut piece_start = 0;
    let mut i = body;
    while i < line.len() {
        match line[i] {
            b'(' => depth += 1,
            b')' => depth -= 1,
            b' ' | b'\t' if depth == 0 && i - piece_start >= PIECE => {
                let mut j = i;
                while j < line.len() && matches!(line[j], b' ' | b'\t') {
                    j += 1;
                }
                if j < line.len() {
                    cuts.push(j);
                    piece_start = j;
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    cuts
}

/// The end of `text[start..stop]` without its trailing spaces.
fn trimmed_end(text: &str, start: usize, stop: usize) -> usize {
    start + text[start..stop].trim_end_matches([' ', '\t']).len()
}
