//! The edge where byte offsets meet LSP positions. Everything inside the server is bytes;
//! positions are converted here, in the negotiated encoding, and nowhere else.

use rotlang::Span;
use rotlang::diagnostic::floor_char_boundary;
use tower_lsp_server::ls_types::{Position, PositionEncodingKind, Range};

/// The position encoding agreed with the client at `initialize`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Encoding {
    /// LSP's default: columns in UTF-16 code units.
    #[default]
    Utf16,
    /// Columns in bytes, when the client offers it (no conversion cost, no ambiguity).
    Utf8,
}

impl Encoding {
    /// Pick UTF-8 when the client offers it, UTF-16 otherwise (the only one every client
    /// must support).
    pub fn negotiate(offered: Option<&[PositionEncodingKind]>) -> Encoding {
        match offered {
            Some(kinds) if kinds.contains(&PositionEncodingKind::UTF8) => Encoding::Utf8,
            _ => Encoding::Utf16,
        }
    }

    pub fn kind(self) -> PositionEncodingKind {
        match self {
            Encoding::Utf16 => PositionEncodingKind::UTF16,
            Encoding::Utf8 => PositionEncodingKind::UTF8,
        }
    }
}

/// Where lines start and end by LSP's definition: a line ends at `\r\n`, `\n` or a lone
/// `\r` (the library's own index, made for terminals, counts `\n` only).
struct Lines {
    /// The byte offset where each line's text starts.
    starts: Vec<usize>,
    /// The byte offset where each line's text ends (before its terminator).
    ends: Vec<usize>,
}

impl Lines {
    fn new(text: &str) -> Lines {
        let bytes = text.as_bytes();
        let (mut starts, mut ends) = (vec![0], Vec::new());
        let mut i = 0;
        while i < bytes.len() {
            let width = match bytes[i] {
                b'\r' if bytes.get(i + 1) == Some(&b'\n') => 2,
                b'\r' | b'\n' => 1,
                _ => {
                    i += 1;
                    continue;
                }
            };
            ends.push(i);
            i += width;
            starts.push(i);
        }
        ends.push(text.len());
        Lines { starts, ends }
    }

    fn count(&self) -> usize {
        self.starts.len()
    }

    /// The line holding a byte offset; an offset inside a terminator belongs to the line
    /// the terminator ends.
    fn line(&self, offset: usize) -> usize {
        self.starts
            .partition_point(|&s| s <= offset)
            .saturating_sub(1)
    }
}

/// A document's text with its line index and encoding: converts in both directions.
pub struct Positions<'a> {
    text: &'a str,
    lines: Lines,
    encoding: Encoding,
}

impl<'a> Positions<'a> {
    pub fn new(text: &'a str, encoding: Encoding) -> Self {
        Positions {
            text,
            lines: Lines::new(text),
            encoding,
        }
    }

    pub fn position(&self, offset: usize) -> Position {
        let offset = floor_char_boundary(self.text, offset);
        let line = self.lines.line(offset);
        // Inside a `\r\n` pair: the end of the line's text.
        let offset = offset.min(self.lines.ends[line]);
        let walked = &self.text[self.lines.starts[line]..offset];
        let col = match self.encoding {
            Encoding::Utf16 => walked.encode_utf16().count(),
            Encoding::Utf8 => walked.len(),
        };
        Position::new(to_u32(line), to_u32(col))
    }

    pub fn range(&self, span: Span) -> Range {
        Range::new(self.position(span.start), self.position(span.end))
    }

    /// The byte offset of a client position, or `None` when the line does not exist.
    /// A column past the line's end is clamped to it, as the protocol asks.
    pub fn offset(&self, position: Position) -> Option<usize> {
        let line = position.line as usize;
        if line >= self.lines.count() {
            return None;
        }
        let col = position.character as usize;
        let (start, end) = (self.lines.starts[line], self.lines.ends[line]);
        Some(match self.encoding {
            Encoding::Utf16 => {
                let mut units = 0;
                let mut at = end;
                for (i, c) in self.text[start..end].char_indices() {
                    if units >= col {
                        at = start + i;
                        break;
                    }
                    units += c.len_utf16();
                }
                at
            }
            Encoding::Utf8 => floor_char_boundary(self.text, (start + col).min(end)),
        })
    }

    /// The number of lines (a text ending in a line break has an empty last line).
    pub fn line_count(&self) -> usize {
        self.lines.count()
    }

    /// A client range as a byte span (clamped); `None` if its start line does not exist.
    pub fn span(&self, range: Range) -> Option<Span> {
        let start = self.offset(range.start)?;
        let end = self.offset(range.end).unwrap_or(self.text.len()).max(start);
        Some(Span::new(start, end))
    }

    /// The length of a single-line span in the encoding's units (semantic tokens).
    pub fn width(&self, span: Span) -> u32 {
        let text = self.text.get(span.range()).unwrap_or("");
        to_u32(match self.encoding {
            Encoding::Utf16 => text.encode_utf16().count(),
            Encoding::Utf8 => text.len(),
        })
    }

    pub fn text(&self) -> &'a str {
        self.text
    }
}

/// Converts offsets visited in increasing order in time proportional to the distance
/// walked, not to the line's length: a 1 MB one-line template has a hundred thousand
/// tokens, and converting each from the line's start would be quadratic.
pub struct Cursor<'p, 'a> {
    positions: &'p Positions<'a>,
    offset: usize,
    position: Position,
}

impl<'p, 'a> Cursor<'p, 'a> {
    pub fn new(positions: &'p Positions<'a>) -> Self {
        Cursor {
            positions,
            offset: 0,
            position: Position::new(0, 0),
        }
    }

    pub fn position(&mut self, offset: usize) -> Position {
        let text = self.positions.text;
        let offset = floor_char_boundary(text, offset);
        let same_line = offset >= self.offset
            && !text.as_bytes()[self.offset..offset]
                .iter()
                .any(|&b| b == b'\n' || b == b'\r');
        let position = if same_line {
            let walked = &text[self.offset..offset];
            let units = match self.positions.encoding {
                Encoding::Utf16 => walked.encode_utf16().count(),
                Encoding::Utf8 => walked.len(),
            };
            Position::new(self.position.line, self.position.character + to_u32(units))
        } else {
            self.positions.position(offset)
        };
        (self.offset, self.position) = (offset, position);
        position
    }
}

fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_and_utf8_differ_after_wide_characters() {
        let text = "°α𝕏+1";
        let plus = text.find('+').unwrap();
        let p16 = Positions::new(text, Encoding::Utf16);
        let p8 = Positions::new(text, Encoding::Utf8);
        assert_eq!(p16.position(plus), Position::new(0, 4));
        assert_eq!(p8.position(plus), Position::new(0, 8));
        assert_eq!(p16.offset(Position::new(0, 4)), Some(plus));
        assert_eq!(p8.offset(Position::new(0, 8)), Some(plus));
        assert_eq!(p16.offset(Position::new(9, 0)), None);
        assert_eq!(p16.offset(Position::new(0, 999)), Some(text.len()));
        let mut cursor = Cursor::new(&p16);
        assert_eq!(cursor.position(plus), Position::new(0, 4));
        assert_eq!(cursor.position(text.len()), Position::new(0, 6));
        assert_eq!(cursor.position(2), Position::new(0, 1));
    }

    #[test]
    fn lines_end_at_cr_lf_and_crlf() {
        let text = "a\rb\nc\r\nd";
        let p = Positions::new(text, Encoding::Utf16);
        let at = |c: char| text.find(c).unwrap();
        assert_eq!(p.position(at('b')), Position::new(1, 0));
        assert_eq!(p.position(at('c')), Position::new(2, 0));
        assert_eq!(p.position(at('d')), Position::new(3, 0));
        // Inside `\r\n`: the end of line 2.
        assert_eq!(p.position(at('c') + 2), Position::new(2, 1));
        assert_eq!(p.offset(Position::new(2, 9)), Some(at('c') + 1));
        assert_eq!(p.offset(Position::new(3, 0)), Some(at('d')));
        assert_eq!(p.offset(Position::new(4, 0)), None);
        let mut cursor = Cursor::new(&p);
        assert_eq!(cursor.position(at('a')), Position::new(0, 0));
        assert_eq!(cursor.position(at('b')), Position::new(1, 0));
        assert_eq!(cursor.position(at('d')), Position::new(3, 0));
    }
}
