//! Splitting a template into instructions at runs of commas and whitespace.

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

/// What the splitter found besides instructions: empty instructions (`,,`, a leading `,`).
#[derive(Debug, Default)]
pub(crate) struct Split<'a> {
    pub chunks: Vec<Chunk<'a>>,
    /// Spans of the separator runs that hold an empty instruction.
    pub empties: Vec<Span>,
}

impl Split<'_> {
    /// The same split with every span moved right by `offset` bytes (for a split of a
    /// slice of the template).
    pub fn shifted(mut self, offset: usize) -> Self {
        for c in &mut self.chunks {
            c.span = c.span.shift(offset);
        }
        for e in &mut self.empties {
            *e = e.shift(offset);
        }
        self
    }
}

pub(crate) fn is_separator(c: char) -> bool {
    matches!(c, ',' | ' ' | '\t' | '\r' | '\n')
}

pub(crate) fn split(text: &str) -> Split<'_> {
    let mut out = Split::default();
    let bytes = text.as_bytes();
    let mut i = 0;
    let mut first = true;
    while i < bytes.len() {
        // A separator run.
        let sep_start = i;
        let mut commas = 0;
        while i < bytes.len() && is_separator(bytes[i] as char) {
            commas += usize::from(bytes[i] == b',');
            i += 1;
        }
        let at_end = i == bytes.len();
        // A leading comma or two commas in one run enclose an instruction with nothing in
        // it. A trailing comma is common style and is not flagged.
        let empty = if first { commas >= 1 } else { commas >= 2 };
        if empty && !at_end {
            out.empties.push(Span::new(sep_start, i));
        }
        if at_end {
            break;
        }
        let start = i;
        while i < bytes.len() && !is_separator(bytes[i] as char) {
            i += 1;
        }
        out.chunks.push(Chunk {
            text: &text[start..i],
            span: Span::new(start, i),
            after_space_only: !first && commas == 0,
        });
        first = false;
    }
    out
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
        assert!(split("10, 20,").empties.is_empty());
        assert!(split("10 20").empties.is_empty());
    }

    #[test]
    fn records_space_only_separators() {
        let s = split("+30 /50%, 5");
        assert!(!s.chunks[0].after_space_only);
        assert!(s.chunks[1].after_space_only);
        assert!(!s.chunks[2].after_space_only);
    }
}
