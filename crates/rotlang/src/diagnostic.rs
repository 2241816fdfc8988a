//! Diagnostics as data: one source, three renderings (miette for embedders,
//! codespan-reporting in the CLI, LSP diagnostics in the server).

use std::fmt;

/// A half-open byte range into the template text. Always bytes, never chars.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    /// The first byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// The span `start..end`.
    pub const fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }

    /// Its length in bytes.
    pub const fn len(self) -> usize {
        self.end - self.start
    }

    /// Whether it covers no byte (an insertion point).
    pub const fn is_empty(self) -> bool {
        self.start == self.end
    }

    /// The smallest span covering both.
    pub fn cover(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }

    /// This span moved right by `offset` bytes.
    pub const fn shift(self, offset: usize) -> Span {
        Span::new(self.start + offset, self.end + offset)
    }

    /// Whether the byte at `offset` is inside.
    pub fn contains(self, offset: usize) -> bool {
        self.start <= offset && offset < self.end
    }

    /// As a range, to slice the text: `&text[span.range()]`.
    pub fn range(self) -> std::ops::Range<usize> {
        self.start..self.end
    }
}

impl From<Span> for miette::SourceSpan {
    fn from(s: Span) -> Self {
        miette::SourceSpan::new(s.start.into(), s.len())
    }
}

/// How bad a diagnostic is: an error stops the template from being used (a slicer must
/// not print it); a warning marks a legal template that is likely a mistake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Severity {
    /// A legal template that likely does not do what was meant.
    Warning,
    /// The template (or this instruction) cannot be read.
    Error,
}

impl Severity {
    /// `"warning"` or `"error"`, as the JSON output and the LSP write it.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Warning => "warning",
            Severity::Error => "error",
        }
    }
}

/// A labelled span. The primary label marks the characters at fault.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// The characters it marks.
    pub span: Span,
    /// What it says about them.
    pub message: String,
    /// The primary label (the fault) rather than a secondary one (context).
    pub primary: bool,
}

/// A safe, meaning-preserving (or obviously intended) edit that fixes a diagnostic.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fix {
    /// What the fix does, e.g. "remove the space".
    pub title: String,
    /// The bytes to replace.
    pub span: Span,
    /// Their replacement.
    pub replacement: String,
}

/// One diagnostic. `code` is stable across releases (`rotlang::unknown-sign`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// The stable code, `prefix::kebab-case` (`rotlang explain CODE` explains it).
    pub code: &'static str,
    /// Error or warning.
    pub severity: Severity,
    /// One sentence: what is wrong.
    pub message: String,
    /// The spans it marks (at most one primary).
    pub labels: Vec<Label>,
    /// How to fix it, in words.
    pub help: Option<String>,
    /// The edit that fixes it, when one is safe.
    pub fix: Option<Fix>,
}

impl Diagnostic {
    /// An error with `code` and `message`, no labels yet.
    ///
    /// ```
    /// let d = rotlang::Diagnostic::error("rotlang::unknown-sign", "unknown sign `X`")
    ///     .with_primary(rotlang::Span::new(3, 4), "not a sign of the language");
    /// assert!(d.is_error());
    /// assert_eq!(d.primary_span(), rotlang::Span::new(3, 4));
    /// ```
    pub fn error(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: Severity::Error,
            message: message.into(),
            labels: Vec::new(),
            help: None,
            fix: None,
        }
    }

    /// A warning with `code` and `message`, no labels yet.
    pub fn warning(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, message)
        }
    }

    /// Adds the primary label: the characters at fault.
    pub fn with_primary(mut self, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: message.into(),
            primary: true,
        });
        self
    }

    /// Adds a secondary label: context for the primary one.
    pub fn with_secondary(mut self, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: message.into(),
            primary: false,
        });
        self
    }

    /// Sets the help: how to fix it, in words.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Sets the fix: replacing `span` by `replacement` (titled `title`).
    pub fn with_fix(
        mut self,
        title: impl Into<String>,
        span: Span,
        replacement: impl Into<String>,
    ) -> Self {
        self.fix = Some(Fix {
            title: title.into(),
            span,
            replacement: replacement.into(),
        });
        self
    }

    /// Whether it is an error.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// The span of the primary label (or of the first label).
    pub fn primary_span(&self) -> Span {
        self.labels
            .iter()
            .find(|l| l.primary)
            .or(self.labels.first())
            .map(|l| l.span)
            .unwrap_or_default()
    }

    /// Every span moved right by `offset` bytes (used when a template is embedded in a
    /// larger text, as in the language server).
    pub fn shifted(mut self, offset: usize) -> Self {
        for l in &mut self.labels {
            l.span = l.span.shift(offset);
        }
        if let Some(f) = &mut self.fix {
            f.span = f.span.shift(offset);
        }
        self
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Diagnostic {}

impl miette::Diagnostic for Diagnostic {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        Some(Box::new(self.code))
    }

    fn severity(&self) -> Option<miette::Severity> {
        Some(match self.severity {
            Severity::Warning => miette::Severity::Warning,
            Severity::Error => miette::Severity::Error,
        })
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn fmt::Display + 'a>)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        Some(Box::new(self.labels.iter().map(|l| {
            let text = (!l.message.is_empty()).then(|| l.message.clone());
            if l.primary {
                miette::LabeledSpan::new_primary_with_span(text, l.span)
            } else {
                miette::LabeledSpan::new_with_span(text, l.span)
            }
        })))
    }
}

/// The byte offset of every line's start. Lines end at `\n`, `\r\n` or a lone `\r`, as
/// in the LSP and in editors (a file saved with old Mac line ends is many lines).
pub fn line_starts(text: &str) -> Vec<usize> {
    let bytes = text.as_bytes();
    let mut starts = vec![0];
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')) {
            starts.push(i + 1);
        }
    }
    starts
}

/// The byte-order mark some editors write at the start of a file. Editors hide it, so
/// columns do not count it.
pub const BYTE_ORDER_MARK: &str = "\u{feff}";

/// Byte offset → line/column conversions, for the edges (terminal, JSON, LSP).
pub struct LineIndex<'a> {
    text: &'a str,
    line_starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// Indexes the line starts of `text` (lines end at `\n`, `\r\n` or `\r`).
    ///
    /// ```
    /// let index = rotlang::LineIndex::new("0, 90\n+30");
    /// assert_eq!(index.line_count(), 2);
    /// assert_eq!(index.line_start(1), 6);
    /// ```
    pub fn new(text: &'a str) -> Self {
        LineIndex {
            text,
            line_starts: line_starts(text),
        }
    }

    /// Zero-based line of a byte offset (clamped to the text).
    pub fn line(&self, offset: usize) -> usize {
        let offset = offset.min(self.text.len());
        self.line_starts.partition_point(|&s| s <= offset) - 1
    }

    /// The byte offset where 0-based `line` starts (the text's length past the last line).
    pub fn line_start(&self, line: usize) -> usize {
        self.line_starts
            .get(line)
            .copied()
            .unwrap_or(self.text.len())
    }

    /// One-based line and one-based column in characters (Unicode scalar values), as a
    /// person counts them in a terminal. A byte-order mark at the start of the text is not
    /// counted: editors hide it and put the cursor after it at column 1.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = floor_char_boundary(self.text, offset);
        let line = self.line(offset);
        let mut start = self.line_starts[line];
        if start == 0 && self.text.starts_with(BYTE_ORDER_MARK) {
            start = BYTE_ORDER_MARK.len().min(offset);
        }
        (line + 1, self.text[start..offset].chars().count() + 1)
    }

    /// Zero-based line and zero-based column in UTF-16 code units (the LSP default).
    pub fn utf16_position(&self, offset: usize) -> (usize, usize) {
        let offset = floor_char_boundary(self.text, offset);
        let line = self.line(offset);
        let start = self.line_starts[line];
        (line, self.text[start..offset].encode_utf16().count())
    }

    /// Zero-based line and UTF-16 column → byte offset (clamped to the line's end).
    pub fn offset_of_utf16(&self, line: usize, col: usize) -> usize {
        let start = self.line_start(line);
        let end = self.line_end(line);
        let mut units = 0;
        for (i, c) in self.text[start..end].char_indices() {
            if units >= col {
                return start + i;
            }
            units += c.len_utf16();
        }
        end
    }

    /// Zero-based line and UTF-8 column → byte offset (clamped, on a char boundary).
    pub fn offset_of_utf8(&self, line: usize, col: usize) -> usize {
        let start = self.line_start(line);
        let end = self.line_end(line);
        floor_char_boundary(self.text, (start + col).min(end))
    }

    /// Byte offset of the end of a line, excluding its line end (`\n`, `\r\n` or `\r`).
    pub fn line_end(&self, line: usize) -> usize {
        match self.line_starts.get(line + 1) {
            Some(&next) => {
                let end = next - 1;
                if self.text.as_bytes()[end] == b'\n'
                    && end > 0
                    && self.text.as_bytes()[end - 1] == b'\r'
                {
                    end - 1
                } else {
                    end
                }
            }
            None => self.text.len(),
        }
    }

    /// How many lines the text has (an empty text has one).
    pub fn line_count(&self) -> usize {
        self.line_starts.len()
    }
}

/// The largest char boundary at or below `offset`.
pub fn floor_char_boundary(text: &str, offset: usize) -> usize {
    let mut o = offset.min(text.len());
    while !text.is_char_boundary(o) {
        o -= 1;
    }
    o
}

/// The smallest char boundary at or above `offset` (clamped to the text).
pub fn ceil_char_boundary(text: &str, offset: usize) -> usize {
    let mut o = offset.min(text.len());
    while !text.is_char_boundary(o) {
        o += 1;
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_chars_not_bytes() {
        let text = "+30°, α\n𝕏 +10";
        let idx = LineIndex::new(text);
        let plus = text.rfind('+').unwrap();
        assert_eq!(idx.line_col(plus), (2, 3));
        assert_eq!(idx.utf16_position(plus), (1, 3)); // 𝕏 is two UTF-16 units
        assert_eq!(idx.offset_of_utf16(1, 3), plus);
        let alpha = text.find('α').unwrap();
        assert_eq!(idx.line_col(alpha), (1, 7));
        assert_eq!(idx.utf16_position(alpha), (0, 6));
        // A column inside a surrogate pair or past the end is clamped, never panics.
        assert_eq!(idx.offset_of_utf16(1, 1), text.find('𝕏').unwrap() + 4);
        assert_eq!(idx.offset_of_utf16(7, 99), text.len());
        assert_eq!(idx.offset_of_utf8(1, 2), text.find('𝕏').unwrap());
    }

    #[test]
    fn lines_end_at_cr_lf_and_crlf() {
        let text = "0\r90\r\n+30\nX";
        let idx = LineIndex::new(text);
        assert_eq!(idx.line_count(), 4);
        assert_eq!(idx.line_col(text.find('9').unwrap()), (2, 1));
        assert_eq!(idx.line_col(text.find('+').unwrap()), (3, 1));
        assert_eq!(idx.line_col(text.find('X').unwrap()), (4, 1));
        assert_eq!(idx.line_end(0), 1);
        assert_eq!(idx.line_end(1), 4);
        assert_eq!(idx.line_end(2), 9);
    }

    #[test]
    fn a_byte_order_mark_is_not_a_column() {
        let text = "\u{feff}0, +30X5\n1";
        let idx = LineIndex::new(text);
        assert_eq!(idx.line_col(text.find('X').unwrap()), (1, 7));
        assert_eq!(idx.line_col(0), (1, 1));
        assert_eq!(idx.line_col(3), (1, 1));
        assert_eq!(idx.line_col(text.find('1').unwrap()), (2, 1));
    }
}
