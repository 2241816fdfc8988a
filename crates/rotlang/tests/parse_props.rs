//! Property tests of the parser and the formatter (proptest):
//!
//! - well-formed templates from a generator (every part of an instruction, SEMANTICS.md
//!   section 2) parse with no error, one IR instruction per generated instruction;
//! - any string (arbitrary Unicode, bytes through `from_utf8_lossy`, or a soup of the
//!   language's own characters) parses without a panic, and every span is within the text,
//!   on char boundaries;
//! - `fmt` is idempotent and keeps the IR (compared with spans stripped).

use proptest::prelude::*;
use proptest::test_runner::Config;

use rotlang::{
    AngleValue, CountKind, Diagnostic, Instruction, Joint, Parse, Sign, Solid, Span, Target,
};

/// Cases per property; `PROPTEST_CASES=100000 cargo test --test parse_props` searches longer.
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

// ── a generator of well-formed instructions ──────────────────────────────────────────────

/// A number as the language writes it: digits, an optional fraction, rarely an exponent.
fn number(max_int: u32) -> impl Strategy<Value = String> {
    (
        0..=max_int,
        proptest::option::of(0u32..1000),
        prop::bool::weighted(0.05),
    )
        .prop_map(|(int, frac, exp)| {
            let mut s = int.to_string();
            if let Some(f) = frac {
                s.push_str(&format!(".{f}"));
            }
            if exp {
                s.push_str("e2");
            }
            s
        })
}

/// A number that is not zero (a denominator).
fn nonzero(max_int: u32) -> impl Strategy<Value = String> {
    (1..=max_int, proptest::option::of(0u32..100)).prop_map(|(i, f)| match f {
        Some(f) => format!("{i}.{f}"),
        None => i.to_string(),
    })
}

fn angle() -> impl Strategy<Value = String> {
    let value = prop_oneof![
        3 => number(720),
        1 => number(100).prop_map(|n| format!("{n}%")),
        1 => (number(16), nonzero(16)).prop_map(|(a, b)| format!("{a}:{b}")),
    ];
    (prop_oneof![Just(""), Just("+"), Just("-")], value).prop_map(|(s, v)| format!("{s}{v}"))
}

#[derive(Clone, Debug)]
enum Runtime {
    /// `*` or `*ℤ`
    Star(Option<u32>),
    /// `!`
    Bang,
    /// `*!` or `*ℤ!`
    StarBang(Option<u32>),
}

fn runtime() -> impl Strategy<Value = Runtime> {
    let times = proptest::option::of(0u32..50);
    prop_oneof![
        times.clone().prop_map(Runtime::Star),
        Just(Runtime::Bang),
        times.prop_map(Runtime::StarBang),
    ]
}

#[derive(Clone, Debug)]
enum Count {
    Layers(String),
    Shell(char),
    Length(String, &'static str),
    HeightFraction(String, String),
}

impl Count {
    fn numeric(&self) -> bool {
        !matches!(self, Count::Shell(_))
    }

    fn text(&self) -> String {
        match self {
            Count::Layers(n) => n.clone(),
            Count::Shell(c) => c.to_string(),
            Count::Length(n, u) => format!("{n}{u}"),
            Count::HeightFraction(h, n) => format!("{h}:{n}"),
        }
    }
}

fn count() -> impl Strategy<Value = Count> {
    let unit = prop::sample::select(vec!["mm", "cm", "m", "'", "\"", "#", "%"]);
    prop_oneof![
        number(1000).prop_map(Count::Layers),
        prop::sample::select(vec!['B', 'T']).prop_map(Count::Shell),
        (number(1000), unit).prop_map(|(n, u)| Count::Length(n, u)),
        (number(10), nonzero(10)).prop_map(|(h, n)| Count::HeightFraction(h, n)),
    ]
}

const JOINTS: &str = "/NnZz$LlUuQq~^|#";
const SOLIDS: &str = "DSOMR";

/// The choices for one instruction, before the rules of the language are applied.
#[derive(Clone, Debug)]
struct Parts {
    angle: Option<String>,
    runtime: Option<Runtime>,
    solid: Option<char>,
    joint: Option<char>,
    joint_first: bool,
    flip: bool,
    count: Option<Count>,
    trailing: Option<char>,
}

fn parts() -> impl Strategy<Value = Parts> {
    (
        proptest::option::weighted(0.8, angle()),
        proptest::option::weighted(0.25, runtime()),
        proptest::option::weighted(
            0.2,
            prop::sample::select(SOLIDS.chars().collect::<Vec<_>>()),
        ),
        proptest::option::weighted(
            0.5,
            prop::sample::select(JOINTS.chars().collect::<Vec<_>>()),
        ),
        any::<bool>(),
        prop::bool::weighted(0.2),
        proptest::option::weighted(0.5, count()),
        proptest::option::weighted(0.15, prop::sample::select(vec!['*', '!'])),
    )
        .prop_map(
            |(angle, runtime, solid, joint, joint_first, flip, count, trailing)| Parts {
                angle,
                runtime,
                solid,
                joint,
                joint_first,
                flip,
                count,
                trailing,
            },
        )
}

impl Parts {
    /// The instruction's text, with the choices the language forbids adjusted: a repeat
    /// `*ℤ` never meets a dummy `*`; a flip needs a count and something before it; a
    /// number as count needs a joint, a flip, a solid sign, the angle's `%` or a `!`
    /// before it (otherwise its digits would merge with the angle's); otherwise it
    /// becomes `B`. Never empty.
    fn render(&self) -> String {
        let mut t = self.angle.clone().unwrap_or_default();
        let mut repeats = false;
        match &self.runtime {
            Some(Runtime::Star(n)) => {
                t.push('*');
                if let Some(n) = n {
                    t.push_str(&n.to_string());
                    repeats = *n > 0;
                }
            }
            Some(Runtime::Bang) => t.push('!'),
            Some(Runtime::StarBang(n)) => {
                t.push('*');
                if let Some(n) = n {
                    t.push_str(&n.to_string());
                    repeats = *n > 0;
                }
                t.push('!');
            }
            None => {}
        }
        let signs: Vec<char> = match (self.solid, self.joint, self.joint_first) {
            (Some(s), Some(j), false) => vec![s, j],
            (Some(s), Some(j), true) => vec![j, s],
            (s, j, _) => s.into_iter().chain(j).collect(),
        };
        t.extend(signs);
        if let Some(count) = &self.count {
            if self.flip && !t.is_empty() {
                t.push('-');
            }
            let separated = t
                .ends_with(|c: char| JOINTS.contains(c) || SOLIDS.contains(c) || "-%!".contains(c));
            if count.numeric() && !separated {
                t.push('B');
            } else {
                t.push_str(&count.text());
            }
        }
        match self.trailing {
            Some('*') if repeats => {}
            Some(c) => t.push(c),
            None => {}
        }
        if t.is_empty() {
            t.push('0');
        }
        t
    }
}

fn separator() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![", ", ",", " ", "\n", "\t", " , ", "\r\n", ",\n  "])
}

/// A well-formed template: its text and how many instructions it has.
fn template() -> impl Strategy<Value = (String, usize)> {
    (
        prop::collection::vec((parts(), separator()), 0..8),
        prop::sample::select(vec!["", " ", "\n"]),
        prop::sample::select(vec!["", ",", "\n", " "]),
    )
        .prop_map(|(items, lead, tail)| {
            let n = items.len();
            let mut t = lead.to_owned();
            for (i, (p, sep)) in items.iter().enumerate() {
                if i > 0 {
                    t.push_str(sep);
                }
                t.push_str(&p.render());
            }
            t.push_str(tail);
            (t, n)
        })
}

// ── invariants ──────────────────────────────────────────────────────────────────────────

fn span_ok(text: &str, s: Span) -> bool {
    s.start <= s.end
        && s.end <= text.len()
        && text.is_char_boundary(s.start)
        && text.is_char_boundary(s.end)
}

/// Every span in the diagnostics and the IR lies within the text, on char boundaries, and
/// the diagnostics are capped.
fn check_spans(text: &str, parse: &Parse) -> Result<(), TestCaseError> {
    prop_assert!(
        parse.diagnostics.len() <= 101,
        "{} diagnostics",
        parse.diagnostics.len()
    );
    for d in &parse.diagnostics {
        for s in d
            .labels
            .iter()
            .map(|l| l.span)
            .chain(d.fix.iter().map(|f| f.span))
        {
            prop_assert!(span_ok(text, s), "{}: bad span {s:?} in {text:?}", d.code);
        }
    }
    for ins in &parse.template.instructions {
        prop_assert!(
            span_ok(text, ins.span),
            "instruction span {:?} in {text:?}",
            ins.span
        );
        prop_assert!(!ins.span.is_empty());
    }
    Ok(())
}

/// An instruction with every span dropped: what it means, not where it was written.
#[derive(Debug, PartialEq)]
struct Meaning {
    angle: Option<(Option<Sign>, AngleValue)>,
    repeat: Option<u64>,
    dummy: bool,
    one_time: bool,
    solid: Option<Solid>,
    joint: Option<Joint>,
    flip: bool,
    count: Option<CountKind>,
}

fn meaning(ins: &Instruction) -> Meaning {
    Meaning {
        angle: ins.angle.as_ref().map(|a| (a.sign, a.value)),
        repeat: ins.repeat.map(|r| r.value),
        dummy: ins.dummy.is_some(),
        one_time: ins.one_time.is_some(),
        solid: ins.solid.map(|s| s.value),
        joint: ins.joint.map(|j| j.value),
        flip: ins.flip.is_some(),
        count: ins.count.map(|c| c.kind),
    }
}

fn meanings(parse: &Parse) -> Vec<Meaning> {
    parse.template.instructions.iter().map(meaning).collect()
}

fn error_codes(ds: &[Diagnostic]) -> Vec<&'static str> {
    ds.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

/// `fmt` output (when there is one) is a fixed point and means the same.
fn check_format(text: &str, target: Target) -> Result<(), TestCaseError> {
    let Some(once) = rotlang::format::format(text, target) else {
        prop_assert!(
            rotlang::parse(text, target).has_errors(),
            "fmt refused a template without errors: {text:?}"
        );
        return Ok(());
    };
    let twice = rotlang::format::format(&once, target);
    prop_assert_eq!(
        twice.as_deref(),
        Some(once.as_str()),
        "fmt is not idempotent on {:?}",
        text
    );
    let before = rotlang::parse(text, target);
    let after = rotlang::parse(&once, target);
    prop_assert!(
        !after.has_errors(),
        "fmt introduced errors {:?}: {:?} → {:?}",
        error_codes(&after.diagnostics),
        text,
        once
    );
    prop_assert_eq!(
        meanings(&before),
        meanings(&after),
        "fmt changed the meaning: {:?} → {:?}",
        text,
        once
    );
    let texts = |t: &str, p: &Parse| {
        p.template
            .instructions
            .iter()
            .map(|i| t[i.span.range()].to_owned())
            .collect::<Vec<_>>()
    };
    prop_assert_eq!(texts(text, &before), texts(&once, &after));
    Ok(())
}

/// Strings made of the language's own characters (and a few others): they reach far more
/// of the parser than arbitrary Unicode does.
fn soup() -> impl Strategy<Value = String> {
    let alphabet: Vec<char> =
        "0123456789.+-*!:%/NnZz$LlUuQq~^|#DSOMRBTmc'\"e ,,\t\nXx°α𝕏\u{0}\u{feff}"
            .chars()
            .collect();
    prop::collection::vec(prop::sample::select(alphabet), 0..40)
        .prop_map(|v| v.into_iter().collect())
}

fn any_target() -> impl Strategy<Value = Target> {
    prop_oneof![Just(Target::Sparse), Just(Target::Solid)]
}

proptest! {
    #![proptest_config(Config { cases: cases(), ..Config::default() })]

    #[test]
    fn well_formed_templates_parse_clean((text, n) in template()) {
        let parse = rotlang::parse(&text, Target::Sparse);
        prop_assert!(!parse.has_errors(), "errors {:?} in {:?}", error_codes(&parse.diagnostics), text);
        prop_assert_eq!(parse.template.instructions.len(), n, "instructions of {:?}", text);
        check_spans(&text, &parse)?;
    }

    #[test]
    fn well_formed_templates_format_faithfully((text, _) in template()) {
        check_format(&text, Target::Sparse)?;
    }

    #[test]
    fn arbitrary_unicode_never_panics(text in any::<String>(), target in any_target()) {
        let parse = rotlang::parse(&text, target);
        check_spans(&text, &parse)?;
        check_format(&text, target)?;
    }

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..128), target in any_target()) {
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let parse = rotlang::parse(&text, target);
        check_spans(&text, &parse)?;
        check_format(&text, target)?;
    }

    #[test]
    fn character_soup_never_panics(text in soup(), target in any_target()) {
        let parse = rotlang::parse(&text, target);
        check_spans(&text, &parse)?;
        check_format(&text, target)?;
    }
}

// ── the diagnostic cap never hides an error ─────────────────────────────────────────────

/// One instruction: well-formed, or legal with a warning.
fn clean_piece() -> impl Strategy<Value = String> {
    prop_oneof![
        1 => parts().prop_map(|p| p.render()),
        2 => prop::sample::select(vec!["400", "0/5", "+0*", "0/0", "30/5*"]).prop_map(str::to_owned),
    ]
}

/// One instruction: clean, an error, or a scrap of soup.
fn piece() -> impl Strategy<Value = String> {
    let alphabet: Vec<char> = "0123456789.+-*!:%/NLlDSBTXm'\"°".chars().collect();
    prop_oneof![
        3 => clean_piece(),
        1 => prop::sample::select(vec!["X", "+30X5", "S", "+5*2*", "1:0", "+30/5/5", "5mm", "%"])
            .prop_map(str::to_owned),
        1 => prop::collection::vec(prop::sample::select(alphabet), 1..6)
            .prop_map(|v| v.into_iter().collect()),
    ]
}

fn joined(items: Vec<(String, &'static str)>) -> String {
    items
        .into_iter()
        .map(|(p, sep)| format!("{p}{sep}"))
        .collect()
}

fn separators() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![", ", ",,", " ", ",, ", "\n"])
}

/// Up to a few hundred clean instructions, many with warnings, and empty instructions
/// (`,,`: a warning each), often past the cap of 100 diagnostics; then a few of anything.
fn long_template() -> impl Strategy<Value = String> {
    (
        prop::collection::vec((clean_piece(), separators()), 0..250),
        prop::collection::vec((piece(), separators()), 0..12),
    )
        .prop_map(|(clean, mixed)| joined(clean) + &joined(mixed))
}

/// The instructions (separated as the language separates them) that have an error when
/// parsed on their own: "some instruction failed to parse or validate", with no cap.
fn failing_alone(text: &str, target: Target) -> Vec<Span> {
    let mut out = Vec::new();
    let mut start = 0;
    for part in text.split([',', ' ', '\t', '\r', '\n']) {
        if !part.is_empty() && rotlang::parse(part, target).has_errors() {
            out.push(Span::new(start, start + part.len()));
        }
        start += part.len() + 1;
    }
    out
}

proptest! {
    #![proptest_config(Config { cases: cases(), ..Config::default() })]

    #[test]
    fn has_errors_is_exact_whatever_the_cap(text in long_template(), target in any_target()) {
        let parse = rotlang::parse(&text, target);
        let failing = failing_alone(&text, target);
        prop_assert_eq!(parse.has_errors(), !failing.is_empty(), "{:?}", text);
        prop_assert_eq!(parse.has_errors(), parse.errors > 0);
        prop_assert!(parse.diagnostics.len() <= 101);
        let listed: Vec<&Diagnostic> = parse
            .diagnostics
            .iter()
            .filter(|d| d.code != "rotlang::too-many-diagnostics")
            .collect();
        prop_assert_eq!(parse.errors + parse.warnings, listed.len() + parse.omitted);
        // The first error is listed, whatever came before it.
        if let Some(first) = failing.first() {
            let shown = listed.iter().find(|d| d.is_error());
            prop_assert!(
                shown.is_some_and(|d| d.primary_span().start <= first.end),
                "first failing instruction at {:?}, first error listed {:?}",
                first,
                shown.map(|d| (d.code, d.primary_span()))
            );
        }
        // A formatter never rewrites a template with an error.
        prop_assert_eq!(rotlang::format::format(&text, target).is_none(), parse.has_errors());
    }
}

proptest! {
    #![proptest_config(Config { cases: cases(), ..Config::default() })]

    /// The streaming entry points (`check`, `format`) agree with `parse`.
    #[test]
    fn streaming_entry_points_agree(text in long_template(), target in any_target()) {
        let parse = rotlang::parse(&text, target);
        let checked = rotlang::check(&text, target);
        prop_assert_eq!(&checked.diagnostics, &parse.diagnostics);
        prop_assert_eq!((checked.errors, checked.warnings, checked.omitted), (parse.errors, parse.warnings, parse.omitted));
        prop_assert!(checked.template.instructions.is_empty());
        let formatted = rotlang::format::format(&text, target);
        if parse.has_errors() {
            prop_assert_eq!(formatted, None);
        } else {
            prop_assert_eq!(formatted, Some(rotlang::format::canonical(&text, &parse.template)));
        }
    }
}
