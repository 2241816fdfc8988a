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

/// The spans of a template's instructions, in text order: per instruction its start
/// (`u32`) and length (`u16`), 6 bytes; the rare instruction of 64 KiB or more keeps its
/// span in `long` as well.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Spans {
    starts: Vec<u32>,
    lens: Vec<u16>,
    /// The spans (start, end) of the instructions whose length is `u16::MAX` or more, in
    /// order.
    long: Vec<[u32; 2]>,
}

/// The leading instruction that keeps a re-read text from being read as quoted.
const LEAD: &str = "0 ";

fn narrow(x: usize) -> u32 {
    // Documents are far below 4 GiB (the server's size limit); saturate rather than wrap.
    u32::try_from(x).unwrap_or(u32::MAX)
}

impl Spans {
    /// The parse of `text` (its diagnostics and counts; no `template`) and its spans.
    pub fn read(text: &str, target: Target) -> (Parse, Spans) {
        let mut spans = Spans::default();
        let parse = rotlang::parse_each(text, target, |i| spans.push(i.span));
        spans.starts.shrink_to_fit();
        spans.lens.shrink_to_fit();
        (parse, spans)
    }

    fn push(&mut self, span: Span) {
        let len = span.end - span.start;
        self.starts.push(narrow(span.start));
        match u16::try_from(len) {
            Ok(l) if l < u16::MAX => self.lens.push(l),
            _ => {
                self.lens.push(u16::MAX);
                self.long.push([narrow(span.start), narrow(span.end)]);
            }
        }
    }

    /// The spans of a template read whole (its `template` is dropped).
    pub fn of_parse(parse: &mut Parse) -> Spans {
        let instructions = std::mem::take(&mut parse.template.instructions);
        let mut spans = Spans::default();
        for i in &instructions {
            spans.push(i.span);
        }
        spans
    }

    pub fn len(&self) -> usize {
        self.starts.len()
    }

    pub fn is_empty(&self) -> bool {
        self.starts.is_empty()
    }

    /// The span of instruction `i`.
    pub fn span(&self, i: usize) -> Option<Span> {
        let start = *self.starts.get(i)? as usize;
        let len = *self.lens.get(i)?;
        if len < u16::MAX {
            return Some(Span::new(start, start + usize::from(len)));
        }
        let k = self.long.partition_point(|s| (s[0] as usize) < start);
        let [a, b] = *self.long.get(k)?;
        Some(Span::new(a as usize, b as usize))
    }

    /// Every span, in order.
    pub fn iter(&self) -> impl Iterator<Item = Span> + '_ {
        (0..self.len()).filter_map(|i| self.span(i))
    }

    /// The index of the first instruction that starts at or after `offset`.
    pub fn first_starting_at(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| (s as usize) < offset)
    }

    /// The instruction with exactly this span.
    pub fn index_of(&self, span: Span) -> Option<usize> {
        let i = self.first_starting_at(span.start);
        (self.span(i)? == span).then_some(i)
    }

    /// The instruction under a template offset (its end included, where a cursor rests
    /// after typing it). A binary search, not a walk through half a million spans.
    pub fn index_at(&self, offset: usize) -> Option<usize> {
        // Instructions do not overlap: the last one starting at or before `offset`.
        let i = self
            .starts
            .partition_point(|&s| (s as usize) <= offset)
            .checked_sub(1)?;
        let s = self.span(i)?;
        (offset <= s.end && !s.is_empty()).then_some(i)
    }

    /// Replace the spans `range` with `with`, and move those after by `delta` (wrapping).
    pub fn splice(
        &mut self,
        range: std::ops::Range<usize>,
        with: impl IntoIterator<Item = Span>,
        delta: usize,
    ) {
        let mut middle = Spans::default();
        for s in with {
            middle.push(s);
        }
        let moved = |x: u32| narrow((x as usize).wrapping_add(delta));
        // The long spans: those before the range stay, those in it go, those after move.
        let from = self.starts.get(range.start).copied().unwrap_or(u32::MAX);
        let past = self.starts.get(range.end).copied().unwrap_or(u32::MAX);
        let before = self.long.partition_point(|s| s[0] < from);
        let after = self.long.partition_point(|s| s[0] < past);
        let mut long: Vec<[u32; 2]> = self.long[after..]
            .iter()
            .map(|&[a, b]| [moved(a), moved(b)])
            .collect();
        self.long.truncate(before);
        self.long.append(&mut middle.long);
        self.long.append(&mut long);
        let shifted = range.start + middle.len();
        self.starts.splice(range.clone(), middle.starts);
        self.lens.splice(range, middle.lens);
        if delta != 0 {
            for s in &mut self.starts[shifted..] {
                *s = moved(*s);
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
                    shift_instruction(i, shift);
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

/// Every span of an instruction, moved by `f`.
fn shift_instruction(i: &mut Instruction, f: impl Fn(Span) -> Span) {
    i.span = f(i.span);
    if let Some(a) = &mut i.angle {
        a.span = f(a.span);
    }
    if let Some(r) = &mut i.repeat {
        r.span = f(r.span);
    }
    for s in [&mut i.dummy, &mut i.one_time, &mut i.flip]
        .into_iter()
        .flatten()
    {
        *s = f(*s);
    }
    if let Some(s) = &mut i.solid {
        s.span = f(s.span);
    }
    if let Some(j) = &mut i.joint {
        j.span = f(j.span);
    }
    if let Some(c) = &mut i.count {
        c.span = f(c.span);
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
        for text in &[
            "0, 90, +10L25%, -10l25%, #14, +15R, +30/5cm*, B!, +5*3".to_owned(),
            "\"0, 90, +30/5mm\"".to_owned(),
            "  «45, +5*2*» ".to_owned(),
            "\"5\", X, +30/ 5cm, 1,5mm, 45 deg, é°, +30/50 %, 1:4".to_owned(),
            "'0, 90, 5' ".to_owned(),
            ",,0 90\n+30\r\n-45\t5\"".to_owned(),
            // An instruction longer than 64 KiB (a decimal of 70,000 digits).
            format!("0, +0.{}1, +30", "0".repeat(70_000)),
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

    /// An edit between instructions longer than 64 KiB: the long ones before and after it
    /// keep their spans (those after moved), as a new reading has them.
    #[test]
    fn a_splice_keeps_the_long_spans() {
        let long = format!("+0.{}1", "0".repeat(70_000));
        let before = format!("0, {long}, 5, {long}, 9");
        let (_, mut spans) = Spans::read(&before, Target::Sparse);
        assert_eq!(spans.long.len(), 2, "{:?}", spans.span(1));
        let at = before.find(", 5, ").unwrap() + 2;
        let five = spans.index_of(Span::new(at, at + 1)).unwrap();
        let after = before.replacen(", 5, ", ", 77, 8, ", 1);
        spans.splice(
            five..five + 1,
            [Span::new(at, at + 2), Span::new(at + 4, at + 5)],
            4,
        );
        assert_eq!(spans, Spans::read(&after, Target::Sparse).1);
        let last = spans.len() - 1;
        assert_eq!(
            spans.span(last),
            Some(Span::new(after.len() - 1, after.len()))
        );
    }
}
