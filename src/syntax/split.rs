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
    // A byte-order mark some editors write at the start of a file is not part of the
    // template: skipped like a separator (spans stay offsets into the whole text).
    if text.starts_with('\u{feff}') {
        i = '\u{feff}'.len_utf8();
    }
    while i < bytes.len() {
        // A separator run.
        let sep_start = i;
        let mut commas = 0;
        while i < bytes.len() && is_separator(bytes[i] as char) {
            commas += usize::from(bytes[i] == b',');
            i += 1;
        }
        let at_end = i == bytes.len();
        // A leading comma (`,` alone too) or two commas in one run (`10,,` too) enclose
        // an instruction with nothing in it. One trailing comma only ends the last
        // instruction: common style, which OrcaSlicer drops as well (SEMANTICS 10.2).
        let empty = if first { commas >= 1 } else { commas >= 2 };
        if empty {
            // At the end, up to the last comma: a file's final newline is not part of it.
            let end = if at_end {
                sep_start + text[sep_start..i].rfind(',').map_or(0, |c| c + 1)
            } else {
                i
            };
            out.empties.push(Span::new(sep_start, end));
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
