//! The instructions of an analysed template in compact form: per instruction its span (two
//! `u32`s, 8 bytes), not the library's IR (a few hundred bytes each, which made a `0 0 0 …`
//! template of 2 bytes per instruction cost over 100× its text). Features that need the
//! IR of some instructions (hover, inlay hints, symbols, semantic tokens, formatting) read
//! those again from the text, exactly as the whole parse reads them (`Spans::get`).
//!
//! Why re-reading is exact: the library splits a template at runs of separators into
//! chunks and lowers each chunk on its own (its neighbours change diagnostics only), so
//! the text from the first wanted instruction's start to the last one's end, read alone,
//! gives the same instructions, moved. It is read after a leading `0 ` so that it never
//! looks like a quoted template (which the library reads differently); the extra first
//! instruction is dropped. Should the spans ever disagree, the whole text is read instead.

use rotlang::{Instruction, Parse, Span, Target, Template};

/// The spans of a template's instructions, in text order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Spans {
    spans: Vec<[u32; 2]>,
}

/// The leading instruction that keeps a re-read text from being read as quoted.
const LEAD: &str = "0 ";

fn narrow(span: Span) -> [u32; 2] {
    // Documents are far below 4 GiB (the server's size limit); saturate rather than wrap.
    let n = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
    [n(span.start), n(span.end)]
}

impl Spans {
    /// The parse of `text` (its diagnostics and counts; no `template`) and its spans.
    pub fn read(text: &str, target: Target) -> (Parse, Spans) {
        let mut spans = Vec::new();
        let parse = rotlang::parse_each(text, target, |i| spans.push(narrow(i.span)));
        spans.shrink_to_fit();
        (parse, Spans { spans })
    }

    /// The spans of a template read whole (its `template` is dropped).
    pub fn of_parse(parse: &mut Parse) -> Spans {
        let instructions = std::mem::take(&mut parse.template.instructions);
        Spans {
            spans: instructions.iter().map(|i| narrow(i.span)).collect(),
        }
    }

    pub fn len(&self) -> usize {
        self.spans.len()
    }

    pub fn is_empty(&self) -> bool {
        self.spans.is_empty()
    }

    /// The span of instruction `i`.
    pub fn span(&self, i: usize) -> Option<Span> {
        self.spans
            .get(i)
            .map(|&[a, b]| Span::new(a as usize, b as usize))
    }

    /// Every span, in order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = Span> + ExactSizeIterator + '_ {
        self.spans
            .iter()
            .map(|&[a, b]| Span::new(a as usize, b as usize))
    }

    /// The index of the first instruction that starts at or after `offset`.
    pub fn first_starting_at(&self, offset: usize) -> usize {
        self.spans.partition_point(|s| (s[0] as usize) < offset)
    }

    /// The instruction with exactly this span.
    pub fn index_of(&self, span: Span) -> Option<usize> {
        let i = self.first_starting_at(span.start);
        (self.span(i)? == span).then_some(i)
    }

    /// The instruction under a template offset (its end included, where a cursor rests
    /// after typing it). A binary search, not a walk through half a million spans.
    pub fn index_at(&self, offset: usize) -> Option<usize> {
        let first = self.spans.partition_point(|s| (s[1] as usize) < offset);
        (first..self.spans.len())
            .map_while(|i| {
                let s = self.span(i)?;
                (s.start <= offset).then_some((i, s))
            })
            .find(|(_, s)| offset <= s.end && !s.is_empty())
            .map(|(i, _)| i)
    }

    /// Replace the spans `range` with `with`, and move those after by `delta` (wrapping).
    pub fn splice(
        &mut self,
        range: std::ops::Range<usize>,
        with: impl IntoIterator<Item = Span>,
        delta: usize,
    ) {
        let with: Vec<[u32; 2]> = with.into_iter().map(narrow).collect();
        let after = range.start + with.len();
        self.spans.splice(range, with);
        if delta != 0 {
            for s in &mut self.spans[after..] {
                *s = narrow(Span::new(
                    (s[0] as usize).wrapping_add(delta),
                    (s[1] as usize).wrapping_add(delta),
                ));
            }
        }
    }

    /// Instructions `range` of `text` (the template these spans were read from, for
    /// `target`), as the whole parse gives them.
    pub fn get(
        &self,
        text: &str,
        target: Target,
        range: std::ops::Range<usize>,
    ) -> Vec<Instruction> {
        let range = range.start.min(self.len())..range.end.min(self.len());
        if range.is_empty() {
            return Vec::new();
        }
        let (Some(first), Some(last)) = (self.span(range.start), self.span(range.end - 1)) else {
            return Vec::new();
        };
        if let Some(window) = text.get(first.start..last.end) {
            let mut read = rotlang::parse(&format!("{LEAD}{window}"), target)
                .template
                .instructions;
            if !read.is_empty() {
                read.remove(0);
            }
            let shift = |s: Span| {
                Span::new(
                    s.start + first.start - LEAD.len(),
                    s.end + first.start - LEAD.len(),
                )
            };
            let moved = read.len() == range.len()
                && read.iter().zip(range.clone()).all(|(i, k)| {
                    i.span.start >= LEAD.len() && self.span(k) == Some(shift(i.span))
                });
            if moved {
                for i in &mut read {
                    crate::incremental::shift_instruction(i, shift);
                }
                return read;
            }
        }
        // Never expected: the whole text, read again.
        let mut whole = rotlang::parse(text, target).template.instructions;
        whole.truncate(range.end);
        whole.drain(..range.start);
        whole
    }

    /// The template of instructions `range` (the whole template with `0..len()`).
    pub fn template(&self, text: &str, target: Target, range: std::ops::Range<usize>) -> Template {
        Template {
            instructions: self.get(text, target, range),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every range of instructions read again is the whole parse's, including quoted
    /// templates, text outside ASCII, errors between instructions and a template that
    /// starts with a quote it does not close.
    #[test]
    fn instructions_read_again_are_the_whole_parses() {
        for text in [
            "0, 90, +10L25%, -10l25%, #14, +15R, +30/5cm*, B!, +5*3",
            "\"0, 90, +30/5mm\"",
            "  «45, +5*2*» ",
            "\"5\", X, +30/ 5cm, 1,5mm, 45 deg, é°, +30/50 %, 1:4",
            "'0, 90, 5' ",
            ",,0 90\n+30\r\n-45\t5\"",
        ] {
            for target in [Target::Sparse, Target::Solid] {
                let full = rotlang::parse(text, target);
                let (parse, spans) = Spans::read(text, target);
                assert_eq!(parse.diagnostics, full.diagnostics, "{text}");
                let n = full.template.instructions.len();
                assert_eq!(spans.len(), n, "{text}");
                for a in 0..=n {
                    for b in a..=n {
                        assert_eq!(
                            spans.get(text, target, a..b),
                            full.template.instructions[a..b],
                            "{text}: {a}..{b}"
                        );
                    }
                }
            }
        }
    }
}
