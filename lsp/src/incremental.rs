//! Re-reading only what an edit touched: the parse of a template's new text from the parse
//! of its previous text, exactly as `rotlang::parse` gives it, in time proportional to the
//! edit (plus moving the instructions after it), not to the template.
//!
//! Instructions are separated by runs of commas and whitespace and parse one by one
//! (SEMANTICS: a template is its instructions in order). What one instruction's reading
//! depends on beyond its own text is its neighbours: the diagnostics look at the two
//! chunks before and the one after (a count cut off from its joint, a unit split off its
//! number, a decimal comma, a space that splits an instruction). So:
//!
//! - the edit is the bytes between the common prefix and the common suffix of the two
//!   texts (the server gets whole texts: full sync);
//! - the *core* is the edit widened by `MARGIN` chunks on each side: every instruction
//!   and diagnostic that can differ starts in it. It is re-read from a *window* widened
//!   again by `MARGIN` chunks and at least `CONTEXT` bytes, so each of its chunks is read
//!   with the same neighbours as in the whole text;
//! - what starts before the core is kept, what starts after it is kept and moved by the
//!   change in length.
//!
//! Where that is not provably the full parse's answer, the whole text is parsed: short
//! templates (cheap anyway, and the library words some help differently below 4 KiB),
//! quoted templates (the quotes are at both ends), and templates with more diagnostics
//! than the library keeps (100: which ones it keeps depends on all of them).
//! `tests::matches_a_full_parse` compares the two on random edits.

use rotlang::{Diagnostic, MAX_DIAGNOSTICS, Parse, Span, Target};

use crate::instructions::Spans;

/// Below this many bytes a template is parsed whole (a few milliseconds at most).
pub const MIN_INCREMENTAL: usize = 32 * 1024;
/// Chunks around the edit whose reading may change (a diagnostic depends on at most the two
/// chunks before its own and the one after), with room to spare.
const MARGIN: usize = 5;
/// The window read around the core extends at least this far on each side that is not the
/// end of the text (the library words an empty instruction's help by the text's length,
/// differently up to 4 KiB).
const CONTEXT: usize = 8 * 1024;

/// The opening quotes the library recognises around a whole template.
const OPENING_QUOTES: [char; 7] = ['"', '\'', '`', '\u{201C}', '\u{2018}', '«', '\u{201E}'];

/// The parse of `new`, given the parse of `old` (both read for `target`). `old` is taken
/// by value: its instructions are reused in place.
pub fn reparse(
    old_text: &str,
    old: (Parse, Spans),
    new_text: &str,
    target: Target,
) -> (Parse, Spans) {
    match splice(old_text, old, new_text, target, MIN_INCREMENTAL) {
        Ok(parse) => parse,
        Err(()) => Spans::read(new_text, target),
    }
}

/// The parse of `new` made from `old` and a window around the edit, or `Err` where that
/// would not be exactly the full parse.
/// `shortest`: the shortest text spliced (`MIN_INCREMENTAL`; tests go lower, never to the
/// 4 KiB the library's wording depends on).
fn splice(
    old_text: &str,
    (mut old, mut spans): (Parse, Spans),
    new_text: &str,
    target: Target,
    shortest: usize,
) -> Result<(Parse, Spans), ()> {
    if old_text.len().min(new_text.len()) < shortest
        || old.omitted > 0
        || old.diagnostics.len() > MAX_DIAGNOSTICS
        || may_be_quoted(old_text)
        || may_be_quoted(new_text)
    {
        return Err(());
    }
    let (old_b, new_b) = (old_text.as_bytes(), new_text.as_bytes());
    let prefix = old_b.iter().zip(new_b).take_while(|(a, b)| a == b).count();
    let room = old_b.len().min(new_b.len()) - prefix;
    let suffix = old_b
        .iter()
        .rev()
        .zip(new_b.iter().rev())
        .take(room)
        .take_while(|(a, b)| a == b)
        .count();
    if prefix == old_b.len() && prefix == new_b.len() {
        return Ok((old, spans)); // the same text
    }
    // The edit: old[prefix..old_end] became new[prefix..new_end].
    let new_end = new_b.len() - suffix;
    let core_start = back(new_b, prefix, MARGIN);
    let core_end = forward(new_b, new_end, MARGIN);
    // The same place in the old text: the suffix is shared.
    let old_core_end = core_end + old_b.len() - new_b.len();
    let window_start =
        back(new_b, core_start, MARGIN).min(back(new_b, core_start.saturating_sub(CONTEXT), 1));
    let window_end = forward(new_b, core_end, MARGIN).max(forward(
        new_b,
        (core_end + CONTEXT).min(new_b.len()),
        1,
    ));
    if window_start == 0 && window_end == new_b.len() {
        return Err(()); // the window is the whole text
    }
    let window_text = &new_text[window_start..window_end];
    if may_be_quoted(window_text) {
        return Err(()); // read whole as a quoted template, where the text is not
    }
    let window = rotlang::parse(window_text, target);
    if window.omitted > 0 {
        return Err(());
    }
    // At the end of the text the core takes what starts there too (nothing comes after).
    let at_end = core_end == new_b.len();
    let in_core = |span: Span| span.start >= core_start && (span.start < core_end || at_end);
    let moved = |span: Span| Span::new(span.start + window_start, span.end + window_start);
    // The change in length, in two's complement: what comes after the core moves by it.
    let change = new_b.len().wrapping_sub(old_b.len());
    let delta = |span: Span| {
        Span::new(
            span.start.wrapping_add(change),
            span.end.wrapping_add(change),
        )
    };

    // Diagnostics: before the core, the core's (from the window), after the core (moved).
    let mut diagnostics = Vec::new();
    let mut after = Vec::new();
    for d in old.diagnostics.drain(..) {
        let start = d.primary_span().start;
        if start < core_start {
            diagnostics.push(d);
        } else if start >= old_core_end && !at_end {
            after.push(d);
        }
    }
    for mut d in window.diagnostics {
        shift_diagnostic(&mut d, moved);
        if in_core(d.primary_span()) {
            diagnostics.push(d);
        }
    }
    for mut d in after {
        shift_diagnostic(&mut d, delta);
        diagnostics.push(d);
    }
    if diagnostics.len() > MAX_DIAGNOSTICS {
        return Err(()); // which the library keeps depends on every one
    }

    // Instructions: the old ones before and after the core stay (those after moved), the
    // core's come from the window.
    let first = spans.first_starting_at(core_start);
    let past = if at_end {
        spans.len()
    } else {
        spans.first_starting_at(old_core_end)
    };
    let core = window
        .template
        .instructions
        .iter()
        .map(|i| moved(i.span))
        .filter(|&s| in_core(s));
    spans.splice(first..past, core, change);

    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    Ok((
        Parse {
            warnings: diagnostics.len() - errors,
            errors,
            omitted: 0,
            diagnostics,
            template: old.template,
        },
        spans,
    ))
}

fn is_separator(b: u8) -> bool {
    matches!(b, b',' | b' ' | b'\t' | b'\r' | b'\n')
}

/// Whether the library may read `text` as a quoted template: its first character past the
/// separators opens a quote (the closing one is at the other end: a whole-text matter).
fn may_be_quoted(text: &str) -> bool {
    text.trim_start_matches([',', ' ', '\t', '\r', '\n'])
        .starts_with(OPENING_QUOTES)
}

/// The start of the `chunks`-th chunk (a run of non-separators) that starts before `at`,
/// counting the one `at` is in; 0 when the text starts first.
fn back(text: &[u8], at: usize, chunks: usize) -> usize {
    let mut i = at.min(text.len());
    for _ in 0..chunks {
        while i > 0 && is_separator(text[i - 1]) {
            i -= 1;
        }
        while i > 0 && !is_separator(text[i - 1]) {
            i -= 1;
        }
        if i == 0 {
            return 0;
        }
    }
    i
}

/// The end of the `chunks`-th chunk that ends after `at`, counting the one `at` is in; the
/// text's end when it ends first.
fn forward(text: &[u8], at: usize, chunks: usize) -> usize {
    let mut i = at.min(text.len());
    for _ in 0..chunks {
        while i < text.len() && is_separator(text[i]) {
            i += 1;
        }
        while i < text.len() && !is_separator(text[i]) {
            i += 1;
        }
        if i == text.len() {
            return i;
        }
    }
    i
}

/// Every span of a diagnostic (its labels and its fix), moved by `f`.
fn shift_diagnostic(d: &mut Diagnostic, f: impl Fn(Span) -> Span) {
    for l in &mut d.labels {
        l.span = f(l.span);
    }
    if let Some(fix) = &mut d.fix {
        fix.span = f(fix.span);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Pieces of templates, valid and not: every kind of instruction, the mistakes whose
    /// diagnostics look at neighbours (`+30/ 5cm`, `+30/50 %`, `1,5mm`, `45 deg`, `+30 /5`),
    /// separators of every kind, quotes, a byte-order mark, letters outside ASCII.
    const PIECES: &[&str] = &[
        "0", "90", "+30", "-45", "+10L25%", "-10l25%", "B!", "#14", "+15R", "+30/5cm", "+30/",
        "5cm", "%", "50", "1", "5mm", "*", "*3", "X", "deg", "/", "/5", "+5*2*", "T", "S", "\"",
        "«", "»", "'", "\u{feff}", "é°", "1:4", ", ", ",", " ", ",,", "\n", "\r\n", "\t", ", , ",
        "+30 /", "/ 5", " 5", "5 ", "+30/ ", "1,", ",5mm", "45 ", " deg", "50 %", " / ", " 5cm",
    ];

    fn piece() -> impl Strategy<Value = String> {
        prop::collection::vec(prop::sample::select(PIECES), 0..6).prop_map(|p| p.concat())
    }

    /// A template of about 20 KB: a valid pattern with a few pieces sprinkled in (a
    /// template with more than 100 diagnostics is parsed whole, and not what is tested).
    fn template() -> impl Strategy<Value = String> {
        prop::collection::vec((0usize..20_000, piece()), 0..8).prop_map(|inserts| {
            let mut text = "+10L25%, -10l25%, 0, 90, +30/5cm\n".repeat(600);
            for (at, p) in inserts {
                text.insert_str(boundary(&text, at), &p);
            }
            text
        })
    }

    fn boundary(text: &str, at: usize) -> usize {
        let mut at = at.min(text.len());
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        at
    }

    /// An edit: where, how many bytes it removes, what it inserts. Edits land near each
    /// other (as typing does) or anywhere.
    fn edits() -> impl Strategy<Value = Vec<(usize, usize, String)>> {
        prop::collection::vec((0usize..21_000, 0usize..12, piece()), 1..24)
    }

    /// The incremental result is the full parse's: the same diagnostics and counts, the
    /// same instruction spans, and the instructions read again from them are the same.
    fn same(
        a: &(Parse, Spans),
        b: &Parse,
        text: &str,
        target: Target,
    ) -> Result<(), TestCaseError> {
        let (a, spans) = a;
        let full: Vec<Span> = b.template.instructions.iter().map(|i| i.span).collect();
        prop_assert_eq!(spans.iter().collect::<Vec<_>>(), full);
        prop_assert_eq!(
            &spans.get(text, target, 0..spans.len()),
            &b.template.instructions
        );
        prop_assert_eq!(&a.diagnostics, &b.diagnostics);
        prop_assert_eq!(
            (a.errors, a.warnings, a.omitted),
            (b.errors, b.warnings, b.omitted)
        );
        Ok(())
    }

    /// A full parse as the server keeps it: spans, no IR.
    fn compact(mut parse: Parse) -> (Parse, Spans) {
        let spans = Spans::of_parse(&mut parse);
        (parse, spans)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

        /// Incremental and full parses agree on every version of a random edit sequence.
        #[test]
        fn matches_a_full_parse(text in template(), edits in edits(), solid in any::<bool>()) {
            let target = if solid { Target::Solid } else { Target::Sparse };
            let mut text = text;
            let mut parse = rotlang::parse(&text, target);
            let mut last = 0;
            for (i, (at, remove, insert)) in edits.iter().enumerate() {
                // Every other edit near the one before it: typing.
                let at = if i % 3 != 0 { (last + at % 24).saturating_sub(12) } else { *at };
                let start = boundary(&text, at);
                let end = boundary(&text, start + remove);
                let mut next = text.clone();
                next.replace_range(start..end, insert);
                last = start + insert.len();
                let full = rotlang::parse(&next, target);
                // (Whether edits are spliced at all, rather than parsed whole:
                // `an_edit_in_a_long_template_is_spliced`.)
                if let Ok(incremental) = splice(&text, compact(parse), &next, target, 5000) {
                    same(&incremental, &full, &next, target)?;
                }
                text = next;
                parse = full;
            }
        }
    }

    #[test]
    fn an_edit_in_a_long_template_is_spliced() {
        let text = "+10L25%, -10l25%, 0, 90, ".repeat(4000);
        let old = rotlang::parse(&text, Target::Sparse);
        let mut next = text.clone();
        next.replace_range(50_000..50_002, "+30/ 5cm,,X");
        let full = rotlang::parse(&next, Target::Sparse);
        let (incremental, spans) =
            splice(&text, compact(old), &next, Target::Sparse, MIN_INCREMENTAL)
                .expect("spliced, not parsed whole");
        assert!(incremental.errors > 0);
        assert_eq!(
            spans.get(&next, Target::Sparse, 0..spans.len()),
            full.template.instructions
        );
        assert_eq!(incremental.diagnostics, full.diagnostics);
        assert_eq!(
            (incremental.errors, incremental.warnings),
            (full.errors, full.warnings)
        );
    }
}
