//! Turning pest's "expected …" at a position into a diagnostic a person can act on.
//!
//! pest tells where the grammar stopped and which rules it tried there; the character at
//! that place and the text before it tell which mistake it most likely is.

use pest::Parser;

use super::grammar::{RotParser, Rule, rule_name};
use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{Joint, Solid, Unit};

/// Context of a failed instruction.
pub(crate) struct Failure<'a> {
    /// The instruction's text.
    pub text: &'a str,
    /// The previous instruction through this one, when only spaces part them (`45 deg`).
    pub with_previous: Option<&'a str>,
    /// Its byte offset in the template.
    pub offset: usize,
    /// Where the grammar stopped, relative to `text`.
    pub pos: usize,
    /// The rules pest expected there.
    pub expected: Vec<Rule>,
}

const SIGNS_HELP: &str = "after the angle come, in order: a runtime mark (`*`, `*ℤ`, `!`), a solid sign \
(`D S O M R`), a joint sign (`/ N n Z z $ L l U u Q q ~ ^ | #`), a flip `-`, a count (`ℕ`, `B`, `T`), \
a length unit (`mm cm m ' \" # %`) and a trailing `*` or `!`";

fn is_unit_start(rest: &str) -> Option<&'static str> {
    ["mm", "cm", "'", "\"", "m"]
        .into_iter()
        .find(|u| rest.starts_with(u))
}

/// Edit distance ≤ 1 (one substitution, insertion or deletion) between short ASCII words.
fn near(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len().abs_diff(b.len()) > 1 {
        return false;
    }
    let (mut i, mut j, mut edits) = (0, 0, 0);
    while i < a.len() && j < b.len() {
        if a[i] == b[j] {
            i += 1;
            j += 1;
            continue;
        }
        edits += 1;
        match a.len().cmp(&b.len()) {
            std::cmp::Ordering::Less => j += 1,
            std::cmp::Ordering::Greater => i += 1,
            std::cmp::Ordering::Equal => {
                i += 1;
                j += 1;
            }
        }
    }
    edits + (a.len() - i) + (b.len() - j) <= 1
}

/// A unit a misspelt or foreign unit word most likely meant.
fn unit_suggestion(word: &str) -> Option<&'static str> {
    let lower = word.to_ascii_lowercase();
    match lower.as_str() {
        "in" | "inch" | "inches" => return Some("\""),
        "ft" | "foot" | "feet" => return Some("'"),
        "mms" | "mil" => return Some("mm"),
        "l" | "layer" | "layers" => return Some("#"),
        _ => {}
    }
    // An exact match first: `CM` is `cm`, although it is also one edit away from `mm`.
    ["mm", "cm"]
        .into_iter()
        .find(|u| lower == *u)
        .or_else(|| ["mm", "cm"].into_iter().find(|u| near(&lower, u)))
}

/// The ASCII character a typographic or full-width look-alike stands for.
fn look_alike(c: char) -> Option<char> {
    Some(match c {
        '\u{2212}' | '\u{2010}' | '\u{2011}' | '\u{2013}' | '\u{2014}' | '\u{FF0D}' => '-',
        '\u{FF0B}' => '+',
        '\u{FF0C}' | '\u{3001}' => ',',
        '\u{FF0E}' => '.',
        '\u{FF1A}' => ':',
        '\u{FF05}' => '%',
        '\u{FF0F}' | '\u{2215}' | '\u{2044}' => '/',
        '\u{2032}' | '\u{2018}' | '\u{2019}' => '\'',
        '\u{2033}' | '\u{201C}' | '\u{201D}' => '"',
        '\u{00D7}' | '\u{FF0A}' => '*',
        '\u{FF01}' => '!',
        '\u{FF03}' => '#',
        '\u{FF10}'..='\u{FF19}' => char::from(b'0' + (c as u32 - 0xFF10) as u8),
        _ => return None,
    })
}

impl Failure<'_> {
    fn abs(&self, start: usize, end: usize) -> Span {
        Span::new(self.offset + start, self.offset + end)
    }

    fn expected_words(&self) -> String {
        let mut names: Vec<&str> = self.expected.iter().map(|r| rule_name(*r)).collect();
        names.dedup();
        match names.len() {
            0 => "something else".to_owned(),
            1 => names[0].to_owned(),
            n => format!("{} or {}", names[..n - 1].join(", "), names[n - 1]),
        }
    }

    /// The alphabetic run starting at `pos`.
    fn word_at(&self, pos: usize) -> &str {
        let rest = &self.text[pos..];
        let len = rest
            .char_indices()
            .find(|(_, c)| !c.is_ascii_alphabetic())
            .map_or(rest.len(), |(i, _)| i);
        &rest[..len]
    }

    /// The characters before `pos` with their offsets; callers look for an earlier sign
    /// among them (no digit is a sign, so numbers never match).
    fn earlier_signs(&self, pos: usize) -> impl Iterator<Item = (usize, char)> + '_ {
        self.text[..pos].char_indices()
    }

    pub fn diagnose(&self) -> Diagnostic {
        let text = self.text;
        let pos = self.pos.min(text.len());
        let rest = &text[pos..];
        let prev = text[..pos].chars().next_back();
        let prev_digit = prev.is_some_and(|c| c.is_ascii_digit());
        let Some(c) = rest.chars().next() else {
            return self.at_end();
        };
        let here = self.abs(pos, pos + c.len_utf8());

        // `"0, 90"`: a template copied with its quotes.
        if pos == 0
            && matches!(
                c,
                '"' | '\'' | '`' | '\u{201C}' | '\u{201D}' | '\u{2018}' | '\u{2019}' | '«' | '»'
            )
        {
            return Diagnostic::error("rotlang::quoted-template", "a template is written without quotes")
                .with_primary(here, "a quote")
                .with_fix("remove the quote", here, "")
                .with_help("write the template's text alone: `0, 90`, not `\"0, 90\"`; `'` and `\"` are units (feet and inches) after a count");
        }
        // `*2.5`, `*1e3`: a repeat count is a whole number of runs.
        let digits_start = text[..pos]
            .trim_end_matches(|d: char| d.is_ascii_digit())
            .len();
        if prev_digit && matches!(c, '.' | 'e' | 'E') && text[..digits_start].ends_with('*') {
            let len = rest
                .bytes()
                .take_while(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'+' | b'-'))
                .count();
            let len = rest[..len]
                .trim_end_matches(|ch: char| !ch.is_ascii_digit())
                .len()
                .max(1);
            return Diagnostic::error(
                "rotlang::repeat-not-whole",
                "a repeat count `*ℤ` is a whole number",
            )
            .with_primary(self.abs(digits_start, pos + len), "not a whole number")
            .with_secondary(self.abs(digits_start - 1, digits_start), "a repeat count")
            .with_help("`*3` runs the instruction 3 times in a row; write whole digits only");
        }

        let word = self.word_at(pos);
        // `+30/5e`: an exponent with no digits.
        if prev_digit && matches!(c, 'e' | 'E') && word.len() == 1 {
            let len = 1 + usize::from(rest[1..].starts_with(['+', '-']));
            return Diagnostic::error("rotlang::bad-number", "an exponent needs digits")
                .with_primary(self.abs(pos, pos + len), "no digits after the exponent")
                .with_help("write `1e3` for 1000, or leave the exponent out");
        }
        // `[0, 90]`, `(+30/5)`: brackets are not part of the language.
        if matches!(c, '[' | ']' | '(' | ')' | '{' | '}' | '<' | '>') {
            return Diagnostic::error("rotlang::bracket", format!("`{c}` is not part of the language"))
                .with_primary(here, "a bracket")
                .with_fix("remove the bracket", here, "")
                .with_help("a template is instructions separated by commas or spaces, with nothing around them: `0, 90`");
        }
        // Numbers written in ways the language does not read.
        if c == '.' {
            let next_digit = rest[1..].starts_with(|d: char| d.is_ascii_digit());
            if !prev_digit && next_digit {
                return Diagnostic::error("rotlang::leading-dot", "a number cannot start with `.`")
                    .with_primary(here, "write a 0 before the dot")
                    .with_fix("write `0.`", self.abs(pos, pos), "0")
                    .with_help("numbers are written `0.5`, not `.5`");
            }
            if prev_digit && !next_digit {
                return Diagnostic::error("rotlang::trailing-dot", "a number cannot end with `.`")
                    .with_primary(here, "nothing follows the dot")
                    .with_fix("remove the `.`", here, "")
                    .with_help("write `10` or `10.5`, not `10.`");
            }
            return Diagnostic::error("rotlang::bad-number", "a number has at most one `.`")
                .with_primary(here, "a second decimal point")
                .with_help("numbers are digits with an optional fractional part: `22.5`");
        }
        if ["inf", "infinity", "nan"].contains(&word.to_ascii_lowercase().as_str()) {
            return Diagnostic::error(
                "rotlang::number-not-finite",
                format!("`{word}` is not a number rotlang reads"),
            )
            .with_primary(self.abs(pos, pos + word.len()), "not a finite number")
            .with_help("angles, counts and lengths are finite decimal numbers such as `22.5`");
        }

        if ["deg", "degs", "degree", "degrees"].contains(&word.to_ascii_lowercase().as_str()) {
            let span = self.abs(pos, pos + word.len());
            return Diagnostic::error(
                "rotlang::degree-sign",
                format!("angles are written without `{word}`"),
            )
            .with_primary(span, "a unit of angle")
            .with_fix(format!("remove `{word}`"), span, "")
            .with_help(self.degrees_help(pos, word.len()));
        }
        if let Some(unit) = is_unit_start(rest).or(rest.starts_with('%').then_some("%"))
            && let Some(before) = ["mm", "cm", "m", "'", "\"", "%", "#"]
                .into_iter()
                .find(|u| text[..pos].ends_with(u))
            && text[..pos - before.len()].ends_with(|d: char| d.is_ascii_digit())
        {
            let span = self.abs(pos, pos + unit.len());
            return Diagnostic::error("rotlang::two-units", "a count has one length unit")
                .with_primary(span, format!("a second unit after `{before}`"))
                .with_fix("remove the second unit", span, "")
                .with_help("length units: `mm cm m ' \" # %`");
        }
        if let Some(unit) = is_unit_start(rest).filter(|_| prev_digit)
            && !text[..pos].contains(|c: char| {
                Joint::from_symbol(c).is_some() || c == '-' || c == '!' || c == '%' || c == ':'
            })
            // `+30m3` is the monotonic sign in lower case, not metres (handled below).
            && !(unit == "m" && self.parses_with(pos, 1, "M"))
        {
            let span = self.abs(pos, pos + unit.len());
            return Diagnostic::error("rotlang::unit-after-angle", format!("the unit `{unit}` follows an angle, not a count"))
                .with_primary(span, "a length unit right after the angle")
                .with_help(format!("a length needs a joint (or a flip) before its count: `+30/10{unit}` turns 30° over 10{unit}"));
        }
        if c == '-' && pos == 1 && text.starts_with(['+', '-']) {
            return Diagnostic::error("rotlang::two-signs", "an angle has one sign")
                .with_primary(self.abs(0, 2), "two signs")
                .with_help("`+30` turns counter-clockwise, `-30` clockwise");
        }
        // A misspelt unit right after a count's number (`5CM`, `5layers`), checked before
        // the signs: its first letter may also be a sign (`M`, `l`).
        if c.is_ascii_alphabetic() {
            let start = text[..pos]
                .trim_end_matches(|ch: char| ch.is_ascii_alphabetic())
                .len();
            let word = self.word_at(start);
            if text[..start].ends_with(|ch: char| ch.is_ascii_digit())
                && word.len() >= 2
                && let Some(u) = unit_suggestion(word)
                    .filter(|u| *u != word && self.parses_with(start, word.len(), u))
            {
                return self.unknown_unit(start, word, u);
            }
        }

        // `1:2%`, `+30/1:2mm`: a fraction is already a share of a turn or of the height.
        let number_start = text[..pos]
            .trim_end_matches(|d: char| d.is_ascii_digit() || d == '.')
            .len();
        let after_fraction = prev_digit && text[..number_start].ends_with(':');
        let unit_or_percent = if matches!(c, '%' | '#') {
            Some(&rest[..1])
        } else {
            is_unit_start(rest)
        };
        if let Some(unit) = unit_or_percent.filter(|_| after_fraction) {
            let colon = number_start - 1;
            let frac_start = text[..colon]
                .trim_end_matches(|d: char| d.is_ascii_digit() || d == '.')
                .len();
            let span = self.abs(pos, pos + unit.len());
            let fraction = self.abs(frac_start, pos);
            let is_angle = matches!(&text[..frac_start], "" | "+" | "-");
            let d = if is_angle {
                Diagnostic::error(
                    "rotlang::unit-after-fraction",
                    "an angle is written `α:β` or `α%`, not both",
                )
                .with_primary(span, format!("`{unit}` after a fraction of a turn"))
                .with_secondary(fraction, "already a fraction of a full turn")
                .with_help("`1:4` and `25%` are both a quarter turn (90°)")
            } else {
                Diagnostic::error("rotlang::unit-after-fraction", "a fraction of the height `ℍ:ℕ` takes no unit")
                    .with_primary(span, format!("`{unit}` after a fraction of the height"))
                    .with_secondary(fraction, "already a share of the object height")
                    .with_help("`+30/1:2` turns over half the height; for a length write a number and a unit, as in `+30/10mm`")
            };
            return d.with_fix(format!("remove `{unit}`"), span, "");
        }

        // Units in the wrong place.
        // `#` and `%` are units too: after `B`/`T` they are the same mistake as `mm`.
        let unit_here = if matches!(c, '#' | '%') {
            Some(&rest[..1])
        } else {
            is_unit_start(rest)
        };
        if let Some(unit) = unit_here.filter(|_| matches!(prev, Some('B' | 'T'))) {
            let span = self.abs(pos, pos + unit.len());
            return Diagnostic::error("rotlang::unit-after-shell-count", "`B` and `T` count layers and take no unit")
                .with_primary(span, "a unit after a shell count")
                .with_fix("remove the unit", span, "")
                .with_help("`B` is the number of bottom shell layers, `T` of top shell layers; for a length write a number, as in `+30/2mm`");
        }
        if let Some(unit) = is_unit_start(rest).filter(|_| !prev_digit) {
            let span = self.abs(pos, pos + unit.len());
            if matches!(prev, Some('B' | 'T')) {
                return Diagnostic::error("rotlang::unit-after-shell-count", "`B` and `T` count layers and take no unit")
                    .with_primary(span, "a unit after a shell count")
                    .with_fix("remove the unit", span, "")
                    .with_help("`B` is the number of bottom shell layers, `T` of top shell layers; for a length write a number, as in `+30/2mm`");
            }
            return Diagnostic::error(
                "rotlang::unit-without-count",
                format!("the unit `{unit}` needs a number before it"),
            )
            .with_primary(span, "no count before this unit")
            .with_help(format!("write how many, as in `+30/10{unit}`"));
        }
        if c == '%' && !prev_digit {
            return Diagnostic::error(
                "rotlang::unit-without-count",
                "the unit `%` needs a number before it",
            )
            .with_primary(here, "no count before this unit")
            .with_help("write how much of the height, as in `+30/50%`");
        }

        // Signs out of order, or doubled.
        if let Some(j) = Joint::from_symbol(c) {
            let earlier = self
                .earlier_signs(pos)
                .find(|&(_, e)| Joint::from_symbol(e).is_some() && !(e == '#' && prev_digit));
            if let Some((i, first)) = earlier {
                return Diagnostic::error("rotlang::two-joints", "an instruction has at most one joint sign")
                    .with_primary(here, format!("a second joint `{}`", j.symbol()))
                    .with_secondary(self.abs(i, i + first.len_utf8()), "the first joint")
                    .with_help("keep the one shape you want; to chain shapes, write two instructions: `+10/5, +10N5`");
            }
            return Diagnostic::error(
                "rotlang::misplaced-sign",
                format!("the joint sign `{c}` is out of place"),
            )
            .with_primary(here, "a joint here")
            .with_help(format!(
                "the joint comes before the flip and the count, as in `+30{c}5`; {SIGNS_HELP}"
            ));
        }
        if let Some(s) = Solid::from_symbol(c) {
            if let Some((i, first)) = self
                .earlier_signs(pos)
                .find(|&(_, e)| Solid::from_symbol(e).is_some())
            {
                return Diagnostic::error(
                    "rotlang::two-solid-signs",
                    "an instruction has at most one solid sign",
                )
                .with_primary(here, format!("a second solid sign `{}`", s.symbol()))
                .with_secondary(self.abs(i, i + first.len_utf8()), "the first solid sign");
            }
            return Diagnostic::error("rotlang::misplaced-sign", format!("the solid sign `{c}` is out of place"))
                .with_primary(here, "a solid sign here")
                .with_help(format!("the solid sign comes right after the angle (and its runtime mark), as in `+30{c}3`; {SIGNS_HELP}"));
        }
        if matches!(c, 'B' | 'T') {
            // Only a count can stand right before a misplaced `B`/`T` (`30B` is legal).
            let first = if matches!(prev, Some('B' | 'T')) {
                Some(self.abs(pos - 1, pos))
            } else if prev_digit {
                Some(self.abs(digits_start, pos))
            } else {
                None
            };
            if let Some(first) = first {
                return Diagnostic::error("rotlang::two-counts", "an instruction has one count")
                    .with_primary(here, "a second count")
                    .with_secondary(first, "the count")
                    .with_help("`B` and `T` are the numbers of bottom and top shell layers; write either one of them or a number");
            }
            return Diagnostic::error(
                "rotlang::misplaced-sign",
                format!("the count `{c}` is out of place"),
            )
            .with_primary(here, "a count here")
            .with_help(format!(
                "an instruction has one count, before its unit; {SIGNS_HELP}"
            ));
        }
        if c == '+' {
            return Diagnostic::error(
                "rotlang::missing-separator",
                "a `+` can only begin an instruction",
            )
            .with_primary(here, "a new instruction starts here")
            .with_fix(
                "separate the instructions with `, `",
                self.abs(pos, pos),
                ", ",
            )
            .with_help("separate instructions with a comma or a space: `+10, +20`");
        }
        if c == '-' {
            let nothing_after =
                !rest[1..].starts_with(|d: char| d.is_ascii_digit() || d == 'B' || d == 'T');
            if nothing_after {
                return Diagnostic::error("rotlang::flip-without-count", "a flip `-` needs a count after it")
                    .with_primary(here, "nothing to flip over")
                    .with_help("the flip reverses the shape over its count, as in `+22.5u-50%`; remove the `-` or add a count");
            }
            return Diagnostic::error("rotlang::misplaced-sign", "the flip `-` is out of place")
                .with_primary(here, "a flip here")
                .with_help(format!(
                    "the flip comes after the joint and right before the count; {SIGNS_HELP}"
                ));
        }
        if matches!(c, '*' | '!') {
            return Diagnostic::error("rotlang::misplaced-sign", format!("`{c}` is out of place"))
                .with_primary(here, "a runtime mark here")
                .with_help("`*`, `*ℤ` and `!` come right after the angle or at the very end of the instruction");
        }
        if c == ':' && text[..number_start].ends_with(':') && prev_digit {
            let first = number_start - 1;
            return Diagnostic::error("rotlang::bad-fraction", "a fraction has one `:`")
                .with_primary(here, "a second `:`")
                .with_secondary(self.abs(first, first + 1), "the fraction's `:`")
                .with_help("`a:b` is a/b: `1:4` is a quarter turn as an angle, or a quarter of the height as a count");
        }
        if c == ':' {
            return Diagnostic::error(
                "rotlang::bad-fraction",
                "a fraction needs a number on each side of `:`",
            )
            .with_primary(here, "an incomplete fraction")
            .with_help(
                "`1:4` is a quarter turn as an angle, or a quarter of the height as a count",
            );
        }
        if c == ';' {
            return Diagnostic::error(
                "rotlang::unexpected-character",
                "instructions are separated by commas, not `;`",
            )
            .with_primary(here, "a semicolon")
            .with_fix("use a comma", here, ",");
        }
        if c == '\u{feff}' {
            return Diagnostic::error(
                "rotlang::byte-order-mark",
                "an invisible byte-order mark (U+FEFF) is in the template",
            )
            .with_primary(here, "a byte-order mark")
            .with_fix("remove the byte-order mark", here, "")
            .with_help(
                "some editors write it at the start of a file; save the file as UTF-8 without BOM",
            );
        }
        // `°`, and what keyboards and fonts give for it: the masculine ordinal `º` (U+00BA)
        // and the ring above `˚` (U+02DA).
        if matches!(c, '°' | 'º' | '˚') {
            let message = if c == '°' {
                "angles are written without `°`".to_owned()
            } else {
                format!(
                    "angles are written without a degree sign (`{c}` U+{:04X} is one)",
                    u32::from(c)
                )
            };
            return Diagnostic::error("rotlang::degree-sign", message)
                .with_primary(here, "a degree sign")
                .with_fix(format!("remove the `{c}`"), here, "")
                .with_help(self.degrees_help(pos, c.len_utf8()));
        }
        if c.is_ascii_digit() {
            let len = rest
                .bytes()
                .take_while(|b| b.is_ascii_digit() || *b == b'.')
                .count();
            let number = self.abs(pos, pos + len);
            if matches!(prev, Some('B' | 'T')) {
                let shell = self.abs(pos - 1, pos);
                return Diagnostic::error("rotlang::two-counts", "an instruction has one count")
                    .with_primary(number, "a second count")
                    .with_secondary(shell, format!("the count is already `{}`", &text[pos - 1..pos]))
                    .with_help("`B` and `T` are the numbers of bottom and top shell layers; write either one of them or a number");
            }
            let before_unit = ["mm", "cm", "m", "'", "\"", "%", "#"]
                .into_iter()
                .find(|u| {
                    text[..pos].ends_with(u)
                        && text[..pos - u.len()].ends_with(|d: char| d.is_ascii_digit())
                });
            if let Some(unit) = before_unit {
                return Diagnostic::error("rotlang::misplaced-number", format!("a number after the unit `{unit}`"))
                    .with_primary(number, "an extra number")
                    .with_help("a count is a number then its unit (`+30/5mm`); after the unit only a trailing `*` or `!` may follow");
            }
            return Diagnostic::error("rotlang::misplaced-number", "a number is out of place here")
                .with_primary(self.abs(pos, pos + rest.bytes().take_while(|b| b.is_ascii_digit() || *b == b'.').count()), "an extra number")
                .with_help(format!(
                    "a count needs a joint, a flip, the angle's `%` or a `!` before it (`+30/5`); {SIGNS_HELP}"
                ));
        }
        if c.is_ascii_alphabetic() {
            let wspan = self.abs(pos, pos + word.len());
            // A "did you mean" is offered only when the corrected instruction parses.
            let parses = |replacement: &str, len: usize| self.parses_with(pos, len, replacement);
            if prev_digit && let Some(u) = unit_suggestion(word).filter(|u| parses(u, word.len())) {
                return self.unknown_unit(pos, word, u);
            }
            let upper = c.to_ascii_uppercase();
            if c.is_ascii_lowercase() && parses(&upper.to_string(), 1) {
                let what = match Solid::from_symbol(upper) {
                    Some(s) => s.meaning(),
                    None if upper == 'B' => "the bottom shell layer count",
                    None if upper == 'T' => "the top shell layer count",
                    None => "a sign",
                };
                return Diagnostic::error("rotlang::unknown-sign", format!("unknown sign `{c}`"))
                    .with_primary(here, format!("did you mean `{upper}` ({what})?"))
                    .with_fix(format!("write `{upper}`"), here, upper.to_string())
                    .with_help("signs are case-sensitive");
            }
            let span = if word.len() > 1 && word.len() <= 12 {
                wspan
            } else {
                here
            };
            let shown = &self.text[span.start - self.offset..span.end - self.offset];
            return Diagnostic::error("rotlang::unknown-sign", format!("unknown sign `{shown}`"))
                .with_primary(span, "not a sign of the language")
                .with_help(SIGNS_HELP);
        }
        if let Some(ascii) = look_alike(c) {
            return Diagnostic::error(
                "rotlang::look-alike-character",
                format!("`{c}` (U+{:04X}) looks like `{ascii}` but is not", c as u32),
            )
            .with_primary(here, format!("did you mean `{ascii}`?"))
            .with_fix(format!("write `{ascii}`"), here, ascii.to_string())
            .with_help("templates are plain ASCII; word processors and some keyboards substitute look-alike characters");
        }
        let shown = if c.is_control() || c.is_whitespace() {
            format!("U+{:04X}", c as u32)
        } else {
            format!("`{c}` (U+{:04X})", c as u32)
        };
        Diagnostic::error(
            "rotlang::unexpected-character",
            format!("unexpected character {shown}"),
        )
        .with_primary(here, "not part of the language")
        .with_help("templates are digits and the signs `+ - % : * ! / # | $ ~ ^ ' \"`, letters `D S O M R N n Z z L l U u Q q B T m c`, separated by commas or spaces")
    }

    /// "write `45`, not `45deg`": this instruction without its unit of angle.
    fn degrees_help(&self, pos: usize, len: usize) -> String {
        let without = format!("{}{}", &self.text[..pos], &self.text[pos + len..]);
        // `45 deg`: the unit is an instruction of its own; name the angle it follows.
        let (without, written) = match self.with_previous {
            Some(both) if without.trim().is_empty() => (
                both[..both.len() - self.text.len()].trim_end().to_owned(),
                both.to_owned(),
            ),
            _ if without.trim().is_empty() => {
                return format!(
                    "every angle is in degrees already: remove `{}`",
                    self.text.trim()
                );
            }
            _ => (without, self.text.to_owned()),
        };
        format!("every angle is in degrees already: write `{without}`, not `{written}`")
    }

    /// Whether the instruction parses with `len` bytes at `pos` replaced.
    fn parses_with(&self, pos: usize, len: usize, replacement: &str) -> bool {
        let fixed = format!(
            "{}{}{}",
            &self.text[..pos],
            replacement,
            &self.text[pos + len..]
        );
        RotParser::parse(Rule::instruction, &fixed).is_ok()
    }

    fn unknown_unit(&self, pos: usize, word: &str, u: &str) -> Diagnostic {
        let wspan = self.abs(pos, pos + word.len());
        let unit = Unit::from_symbol(u).map_or("", Unit::meaning);
        Diagnostic::error(
            "rotlang::unknown-unit",
            format!("unknown length unit `{word}`"),
        )
        .with_primary(wspan, format!("did you mean `{u}` ({unit})?"))
        .with_fix(format!("write `{u}`"), wspan, u)
        .with_help("length units: `mm cm m ' \" # %`")
    }

    fn at_end(&self) -> Diagnostic {
        let end = self.text.len();
        // `+10/-`, `30-`: a flip with nothing after it (a lone `-` is an unfinished angle).
        if self.text.ends_with('-') && end > 1 {
            return Diagnostic::error("rotlang::flip-without-count", "a flip `-` needs a count after it")
                .with_primary(self.abs(end - 1, end), "nothing to flip over")
                .with_help("the flip reverses the shape over its count, as in `+22.5u-50%`; remove the `-` or add a count");
        }
        let span = self.abs(
            end.saturating_sub(
                self.text[..end]
                    .chars()
                    .next_back()
                    .map_or(0, char::len_utf8),
            ),
            end,
        );
        Diagnostic::error("rotlang::incomplete", "the instruction ends too early").with_primary(
            span,
            format!("expected {} after this", self.expected_words()),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::near;

    #[test]
    fn near_is_one_edit() {
        assert!(near("cn", "cm"));
        assert!(near("mmm", "mm"));
        assert!(near("c", "cm"));
        assert!(!near("xyz", "mm"));
    }
}
