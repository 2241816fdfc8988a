//! Splitting a template into instructions at runs of commas and whitespace.

use pest::Parser;

use super::grammar::{RotParser, Rule};
use crate::diagnostic::Span;

/// One instruction's text and where it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Chunk<'a> {
    pub text: &'a str,
    pub span: Span,
    /// The separator run before this chunk held no comma (only whitespace), and there was
    /// an instruction before it.
    pub after_space_only: bool,
}

/// The whole split at once (for tests: the parser streams [`Pieces`]).
/// Whether `text` is one instruction the grammar accepts.
pub(crate) fn is_instruction(text: &str) -> bool {
    RotParser::parse(Rule::instruction, text).is_ok()
}

/// `+30/ 5cm`: the previous instruction ends with a joint and this chunk, after a space
/// alone, is the count it lost. The pair (not the chunk) is what was meant.
pub(crate) fn after_joint(prev: &Chunk<'_>, chunk: &Chunk<'_>) -> bool {
    chunk.after_space_only
        && prev
            .text
            .ends_with(|c: char| crate::ir::Joint::from_symbol(c).is_some())
        && chunk
            .text
            .starts_with(|c: char| c.is_ascii_digit() || matches!(c, 'B' | 'T' | '-'))
        && is_instruction(prev.text)
        && is_instruction(&format!("{}{}", prev.text, chunk.text))
}

#[cfg(test)]
#[derive(Debug, Default)]
pub(crate) struct Split<'a> {
    pub chunks: Vec<Chunk<'a>>,
    /// Spans of the separator runs that hold an empty instruction.
    pub empties: Vec<Span>,
}

pub(crate) fn is_separator(c: char) -> bool {
    matches!(c, ',' | ' ' | '\t' | '\r' | '\n')
}

#[cfg(test)]
pub(crate) fn split(text: &str) -> Split<'_> {
    let mut out = Split::default();
    for piece in Pieces::new(text, 0) {
        match piece {
            Piece::Empty(span) => out.empties.push(span),
            Piece::Chunk(chunk) => out.chunks.push(chunk),
        }
    }
    out
}

/// What the splitter finds, in source order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Piece<'a> {
    /// A separator run holding an empty instruction (`,,`, a leading `,`).
    Empty(Span),
    Chunk(Chunk<'a>),
}

/// The pieces of a template one at a time, so that a parse holds no list of them (a
/// megabyte template has hundreds of thousands).
pub(crate) struct Pieces<'a> {
    text: &'a str,
    /// Added to every span: the position of `text` in the whole template.
    offset: usize,
    i: usize,
    first: bool,
    pending: Option<Chunk<'a>>,
}

impl<'a> Pieces<'a> {
    pub fn new(text: &'a str, offset: usize) -> Self {
        // A byte-order mark some editors write at the start of a file is not part of the
        // template: skipped like a separator (spans stay offsets into the whole text).
        let bom = if offset == 0 && text.starts_with('\u{feff}') {
            '\u{feff}'.len_utf8()
        } else {
            0
        };
        Pieces {
            text,
            offset,
            i: bom,
            first: true,
            pending: None,
        }
    }
}

impl<'a> Iterator for Pieces<'a> {
    type Item = Piece<'a>;

    fn next(&mut self) -> Option<Piece<'a>> {
        if let Some(chunk) = self.pending.take() {
            return Some(Piece::Chunk(chunk));
        }
        let bytes = self.text.as_bytes();
        let mut i = self.i;
        // A separator run.
        let sep_start = i;
        let mut commas = 0;
        while i < bytes.len() && is_separator(bytes[i] as char) {
            commas += usize::from(bytes[i] == b',');
            i += 1;
        }
        // A leading comma (`,` alone too) or two commas in one run (`10,,` too) enclose
        // an instruction with nothing in it. A trailing comma (`0, 90,`) begins one that
        // never comes: the same warning, with a fix that removes it (OrcaSlicer drops a
        // comma that ends the text as well, SEMANTICS 10.2).
        let empty = if self.first { commas >= 1 } else { commas >= 2 };
        if i == bytes.len() {
            self.i = i;
            if empty || commas >= 1 {
                // Up to the last comma: a file's final newline is not part of it.
                let end = sep_start + self.text[sep_start..i].rfind(',').map_or(0, |c| c + 1);
                return Some(Piece::Empty(Span::new(sep_start, end).shift(self.offset)));
            }
            return None;
        }
        let start = i;
        while i < bytes.len() && !is_separator(bytes[i] as char) {
            i += 1;
        }
        self.i = i;
        let chunk = Chunk {
            text: &self.text[start..i],
            span: Span::new(start, i).shift(self.offset),
            after_space_only: !self.first && commas == 0,
        };
        self.first = false;
        if empty {
            self.pending = Some(chunk);
            return Some(Piece::Empty(Span::new(sep_start, start).shift(self.offset)));
        }
        Some(Piece::Chunk(chunk))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(t: &str) -> Vec<&str> {
        split(t).chunks.iter().map(|c| c.text).collect()
    }

    #[test]
    fn splits_on_commas_and_whitespace() {
        assert_eq!(texts("0, 90"), ["0", "90"]);
        assert_eq!(texts("0 90\n+10\t,\r\n5"), ["0", "90", "+10", "5"]);
        assert_eq!(texts(""), Vec::<&str>::new());
        assert_eq!(texts(" , "), Vec::<&str>::new());
        assert_eq!(texts("α°,𝕏"), ["α°", "𝕏"]);
    }

    #[test]
    fn finds_empty_instructions() {
        assert_eq!(split("10,,20").empties, [Span::new(2, 4)]);
        assert_eq!(split(", +10").empties, [Span::new(0, 2)]);
        assert_eq!(split("10, , 20").empties, [Span::new(2, 6)]);
        // A trailing comma too, up to the comma (a file's final newline is not part of it).
        assert_eq!(split("10, 20,").empties, [Span::new(6, 7)]);
        assert_eq!(split("10, 20, \n").empties, [Span::new(6, 7)]);
        assert_eq!(split("10,,\n").empties, [Span::new(2, 4)]);
        assert_eq!(split(",").empties, [Span::new(0, 1)]);
        assert_eq!(split(" ,\n").empties, [Span::new(0, 2)]);
        assert!(split("10 20").empties.is_empty());
        assert!(split("10 20\n").empties.is_empty());
        assert_eq!(texts("\u{feff}0, 90"), ["0", "90"]);
    }

    #[test]
    fn records_space_only_separators() {
        let s = split("+30 /50%, 5");
        assert!(!s.chunks[0].after_space_only);
        assert!(s.chunks[1].after_space_only);
        assert!(!s.chunks[2].after_space_only);
    }
}
