//! Hostile input: megabyte templates, NUL bytes, characters outside ASCII and outside the
//! BMP, absurd numbers. Whatever the input: no panic, at most 101 diagnostics (100 and one
//! "N more not shown"), every span within the text and on char boundaries, and a report
//! whose size does not grow with the input. No timing here (benches/ measures speed).
//!
//! A megabyte of short instructions (`+1, ` × 262 144) takes seconds to parse in a debug
//! build, so those inputs are parsed once (sparse target) and each has its own test to
//! run in parallel; single-instruction megabytes are fast and get both targets.

use rotlang::cli::{Input, render_human};
use rotlang::{Parse, Span, Target};

const MB: usize = 1 << 20;
/// `MAX_DIAGNOSTICS` (100) plus the one that counts the rest.
const CAP: usize = 101;

fn span_ok(text: &str, s: Span) -> bool {
    s.start <= s.end
        && s.end <= text.len()
        && text.is_char_boundary(s.start)
        && text.is_char_boundary(s.end)
}

/// Parses for both targets and checks the invariants; returns the sparse parse.
fn survive(name: &str, text: &str) -> Parse {
    survive_for(name, text, &[Target::Sparse, Target::Solid])
}

/// Parses once, for the sparse target: for inputs with many instructions.
fn survive_once(name: &str, text: &str) -> Parse {
    survive_for(name, text, &[Target::Sparse])
}

fn survive_for(name: &str, text: &str, targets: &[Target]) -> Parse {
    let mut sparse = None;
    for &target in targets {
        let parse = rotlang::parse(text, target);
        assert!(
            parse.diagnostics.len() <= CAP,
            "{name}: {} diagnostics",
            parse.diagnostics.len()
        );
        for d in &parse.diagnostics {
            for s in d
                .labels
                .iter()
                .map(|l| l.span)
                .chain(d.fix.iter().map(|f| f.span))
            {
                assert!(
                    span_ok(text, s),
                    "{name}: {} has span {s:?} (text is {} bytes)",
                    d.code,
                    text.len()
                );
            }
        }
        for ins in &parse.template.instructions {
            assert!(
                span_ok(text, ins.span),
                "{name}: instruction span {:?}",
                ins.span
            );
        }
        sparse.get_or_insert(parse);
    }
    sparse.unwrap()
}

/// Like `survive`, and the template must have an error with a non-empty primary span.
fn rejected(name: &str, text: &str) -> Parse {
    has_error(name, survive(name, text))
}

fn rejected_once(name: &str, text: &str) -> Parse {
    has_error(name, survive_once(name, text))
}

fn has_error(name: &str, parse: Parse) -> Parse {
    let first = parse.diagnostics.iter().find(|d| d.is_error());
    let first = first.unwrap_or_else(|| panic!("{name}: no error"));
    assert!(
        !first.primary_span().is_empty(),
        "{name}: empty primary span for {}",
        first.code
    );
    parse
}

fn codes(parse: &Parse) -> Vec<&'static str> {
    let mut c: Vec<_> = parse.diagnostics.iter().map(|d| d.code).collect();
    c.dedup();
    c
}

/// `s` repeated to at least `len` bytes.
fn repeat_to(s: &str, len: usize) -> String {
    s.repeat(len.div_ceil(s.len()))
}

/// Deterministic pseudo-random bytes (no dependency; the same every run).
fn noise(len: usize, mut seed: u64) -> Vec<u8> {
    (0..len)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 56) as u8
        })
        .collect()
}

// ── one megabyte ────────────────────────────────────────────────────────────────────────

#[test]
fn megabyte_of_valid_instructions() {
    let text = repeat_to("+1, ", MB);
    let parse = survive_once("+1, ×1M", &text);
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
    assert_eq!(parse.template.instructions.len(), text.len() / 4);
    let formatted = rotlang::format::canonical(&text, &parse.template);
    assert_eq!(
        formatted.len(),
        text.len() - 2,
        "only the trailing `, ` goes"
    );
}

#[test]
fn megabyte_of_mixed_valid_instructions() {
    let text = repeat_to("+10L25%, -10l25%\n#14 +15R\tB!, 240M3, +30/1cm, ST, ", MB);
    let parse = survive_once("doc mix ×1M", &text);
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
}

#[test]
fn megabyte_of_random_bytes() {
    let text = String::from_utf8_lossy(&noise(MB, 1)).into_owned();
    survive_once("noise", &text);
}

#[test]
fn megabyte_of_language_characters_in_random_order() {
    let alphabet = b"0123456789.+-*!:%/NnZz$LlUuQq~^|#DSOMRBTmc'\"e ,";
    let text: String = noise(MB, 7)
        .iter()
        .map(|b| alphabet[*b as usize % alphabet.len()] as char)
        .collect();
    survive_once("soup", &text);
}

#[test]
fn one_megabyte_number() {
    let digits = "9".repeat(MB);
    let parse = rejected("1 MB angle", &digits);
    assert!(
        codes(&parse)
            .iter()
            .any(|c| c.starts_with("rotlang::number")),
        "{:?}",
        codes(&parse)
    );
    rejected("1 MB count", &format!("+30/{digits}"));
    rejected("1 MB repeat", &format!("+30*{digits}"));
    rejected("1 MB length", &format!("+30/{digits}mm"));
    rejected("1 MB fraction", &format!("{digits}:{digits}"));
    // A long fraction part is an ordinary number.
    let parse = survive("0.999…", &format!("0.{digits}"));
    assert!(!parse.has_errors(), "{:?}", codes(&parse));
}

#[test]
fn megabyte_of_one_letter() {
    // (`!` and `*` are in `megabyte_of_repeated_marks`.)
    for c in [
        "X", "B", "M", "m", "e", "/", "#", "%", "-", "+", ".", ":", "'",
    ] {
        survive(c, &c.repeat(MB));
    }
    rejected("X×1M", &"X".repeat(MB));
}

#[test]
fn megabyte_of_separators() {
    for sep in [",", " ", "\n", "\r\n", ", ", "\t,"] {
        let parse = survive_once(sep, &repeat_to(sep, MB));
        assert!(!parse.has_errors(), "{sep:?}: {:?}", codes(&parse));
        assert!(parse.template.instructions.is_empty());
    }
}

#[test]
fn megabyte_of_errors_is_capped() {
    let parse = rejected_once("X, ×1M", &repeat_to("X, ", MB));
    assert_eq!(parse.diagnostics.len(), CAP);
    assert_eq!(
        parse.diagnostics.last().unwrap().code,
        "rotlang::too-many-diagnostics"
    );
}

#[test]
fn megabyte_of_warnings_is_capped() {
    let parse = survive_once("400, ×1M", &repeat_to("400, ", MB));
    assert_eq!(parse.diagnostics.len(), CAP, "warnings are capped too");
    assert!(!parse.has_errors());
}

#[test]
fn megabyte_single_instructions() {
    rejected("+30/5/5/5…", &format!("+30{}", repeat_to("/5", MB)));
}

#[test]
fn megabyte_of_repeated_marks() {
    // One instruction with a million `!` (or `*`): a million duplicate-mark warnings, capped.
    let parse = survive_once("+30!!!…", &format!("+30{}", "!".repeat(MB)));
    assert_eq!(parse.diagnostics.len(), CAP);
    survive_once("+30***…", &format!("+30{}", "*".repeat(MB)));
    rejected("+30*2*2*2…", &format!("+30{}", repeat_to("*2", MB)));
    rejected("+30/5mmmm…", &format!("+30/5{}", "m".repeat(MB)));
    rejected("-----…30", &format!("{}30", "-".repeat(MB)));
}

/// The terminal report shows a window of a long line, not the whole line under each
/// diagnostic.
fn report_stays_small(name: &str, text: &str) {
    let parse = survive_once(name, text);
    let input = Input {
        name: name.into(),
        text: text.to_owned(),
        path: None,
    };
    let report = render_human(&[(&input, &parse.diagnostics)], false);
    assert!(
        report.len() < 256 * 1024,
        "{name}: a {} byte report",
        report.len()
    );
}

#[test]
fn megabyte_report_of_many_errors_stays_small() {
    report_stays_small("X, ×1M", &repeat_to("X, ", MB));
}

#[test]
fn megabyte_report_of_noise_stays_small() {
    report_stays_small("noise", &String::from_utf8_lossy(&noise(MB, 9)));
}

#[test]
fn megabyte_report_of_one_long_span_stays_small() {
    report_stays_small("1 MB number", &"9".repeat(MB));
}

// ── characters ──────────────────────────────────────────────────────────────────────────

#[test]
fn nul_bytes() {
    rejected("NUL", "\0");
    rejected("+30 NUL", "+30\0, 90");
    rejected("NUL in unit", "+30/5m\0m");
    rejected("NUL×1M", &"\0".repeat(MB));
}

#[test]
fn megabyte_of_nul_instructions() {
    rejected_once("NUL, ×1M", &repeat_to("\0, ", MB));
}

#[test]
fn characters_outside_ascii() {
    for c in [
        "°", "ℕ", "α", "𝕏", "\u{feff}", "\u{200b}", "\u{fffd}", "é", "\u{301}", "🙂",
    ] {
        if c == "\u{feff}" {
            // A byte-order mark at the start of a file is skipped (editors write one);
            // anywhere else it is an error.
            assert!(!survive(c, c).has_errors());
            assert!(!survive(c, &format!("{c}, +10")).has_errors());
            rejected("+10, {c}", &format!("+10, {c}"));
        } else {
            rejected(c, c);
            rejected(&format!("{c}, +10"), &format!("{c}, +10"));
        }
        rejected(&format!("+30{c}"), &format!("+30{c}"));
        rejected(&format!("+30/{c}5"), &format!("+30/{c}5"));
        rejected(&format!("+10/5{c}%"), &format!("+10/5{c}%"));
        rejected(&format!("{c}×1M"), &c.repeat(MB / c.len()));
        rejected(
            &format!("+30/{c}×1M"),
            &format!("+30/{}", c.repeat(MB / c.len())),
        );
    }
    let parse = rejected("mixed", "+30°, ℕ, α1, 𝕏 +10/5𝕏");
    let first = parse.diagnostics[0].primary_span();
    assert_eq!(&"+30°, ℕ, α1, 𝕏 +10/5𝕏"[first.range()], "°");
}

#[test]
fn megabyte_of_two_byte_instructions() {
    rejected_once("α, ×1M", &repeat_to("α, ", MB));
}

#[test]
fn megabyte_of_astral_instructions() {
    rejected_once("𝕏1, ×1M", &repeat_to("𝕏1, ", MB));
}

#[test]
fn characters_that_look_like_the_language() {
    // Full-width digits and signs, the Unicode minus, superscripts: errors, not angles.
    for t in ["３０", "＋30", "+30/−5", "+³⁰", "+30⁄5", "٣٠"] {
        rejected(t, t);
    }
}

// ── numbers ─────────────────────────────────────────────────────────────────────────────

#[test]
fn huge_numbers_and_counts() {
    let big = "9".repeat(400);
    let zeros = "0".repeat(400);
    for t in [
        "1e999".to_owned(),
        "+1e999".to_owned(),
        "+30/1e999".to_owned(),
        "+30/1e999mm".to_owned(),
        "1e999%".to_owned(),
        "1:1e999".to_owned(),
        "1e999:1".to_owned(),
        big.clone(),
        format!("+{big}"),
        format!("+30/{big}"),
        format!("+30*{big}"),
        format!("+30/{big}:{big}"),
        format!("{big}:{big}"),
        format!("1:{zeros}"),
        format!("+30/1:{zeros}"),
        "+30*1000000001".to_owned(),
        "+30/1000000001".to_owned(),
        "+1/1e10".to_owned(),
        "+30*99999999999999999999999".to_owned(),
        "+inf".to_owned(),
        "+30/NaN".to_owned(),
    ] {
        rejected(&t, &t);
    }
    // At the limit: accepted, whatever the evaluator makes of it.
    for t in [
        "+30*1000000000",
        "+1/1e9",
        "*1000000000",
        "+30/1000000000mm",
        &format!("0.{zeros}1"),
    ] {
        let parse = survive(t, t);
        assert!(!parse.has_errors(), "{t}: {:?}", codes(&parse));
    }
}
