//! The findings that hold on every model: constructs OrcaSlicer reads differently.

use super::codes::{
    EMPTY_INSTRUCTION, FRACTION, IGNORED_IN_LIST, RANDOM, SHELLS_AFTER_JOINT, SOLID_SIGN,
    SPACE_SEPARATED_LIST, TEXT_AFTER_BANG,
};
use super::readings::{degrees, reference_models};
use crate::diagnostic::{Diagnostic, Span};
use crate::dialect::orcaslicer::is_list;
use crate::eval::{self, Options};
use crate::ir::{AngleValue, CountKind, Instruction, Joint, Sign, Target};

/// Whether `fixed` means what `text` means for rotlang: no errors, and the same angles and
/// fills on reference models (the cube, a thicker first layer, fine layers).
pub(super) fn keeps_meaning(text: &str, fixed: &str, target: Target) -> bool {
    let (a, b) = (crate::parse(text, target), crate::parse(fixed, target));
    if a.has_errors() || b.has_errors() {
        return false;
    }
    reference_models().iter().all(|model| {
        let options = Options::default();
        eval::layers(&a.template, model, options)
            .zip(eval::layers(&b.template, model, options))
            .all(|(x, y)| {
                x.fill == y.fill && (x.angle - y.angle).abs() <= 1e-9 * x.angle.abs().max(1.0)
            })
    })
}

fn splice(text: &str, span: Span, with: &str) -> String {
    format!("{}{with}{}", &text[..span.start], &text[span.end..])
}

/// Adds `fix` to `d` when applying it keeps rotlang's meaning.
fn with_checked_fix(
    d: Diagnostic,
    text: &str,
    fixable: bool,
    target: Target,
    title: &str,
    span: Span,
    replacement: String,
) -> Diagnostic {
    // Each check parses and evaluates the whole template: only for template-sized texts.
    if fixable
        && text.len() <= MAX_FIXED_TEXT
        && keeps_meaning(text, &splice(text, span, &replacement), target)
    {
        d.with_fix(title, span, replacement)
    } else {
        d
    }
}

fn is_separator(b: u8) -> bool {
    b == b',' || b.is_ascii_whitespace() || b == 0x0b
}

pub(super) fn rules(
    text: &str,
    instructions: &[Instruction],
    fixable: bool,
    target: Target,
    out: &mut Vec<Diagnostic>,
) {
    let list = text_rules(text, fixable, target, out);
    for ins in instructions {
        instruction_rules(text, ins, list, fixable, target, out);
    }
    out.truncate(MAX_RULE_FINDINGS);
}

/// The rules read from the text alone (a plain list's pieces, a leading separator), run
/// before [`instruction_rules`]: whether OrcaSlicer reads `text` as a plain list.
pub(super) fn text_rules(
    text: &str,
    fixable: bool,
    target: Target,
    out: &mut Vec<Diagnostic>,
) -> bool {
    let list = !text.is_empty() && is_list(text);
    if list {
        list_rules(text, fixable, target, out);
    } else if let Some(run) = text
        .bytes()
        .position(|b| !is_separator(b))
        .filter(|&n| n > 0)
    {
        // The metalanguage reading: a leading separator yields an empty first token.
        let span = Span::new(0, run);
        let d = Diagnostic::warning(
            EMPTY_INSTRUCTION,
            "OrcaSlicer reads the separator at the start as an empty instruction: one layer at the angle so far",
        )
        .with_primary(span, "an empty instruction for OrcaSlicer")
        .with_help("rotlang ignores it; remove it so that both read the same");
        out.push(with_checked_fix(
            d,
            text,
            fixable,
            target,
            "remove the leading separator",
            span,
            String::new(),
        ));
    }
    list
}

/// A pasted megabyte of `+7!B` must not become a million findings (or fix checks).
pub(super) const MAX_RULE_FINDINGS: usize = 100;
/// Fixes are checked by evaluating the fixed text: templates are lines, not megabytes.
pub(super) const MAX_FIXED_TEXT: usize = 4096;

/// The list reading (no `+ - % * @ ' " c m` and no joint sign): pieces between commas.
fn list_rules(text: &str, fixable: bool, target: Target, out: &mut Vec<Diagnostic>) {
    let bytes = text.as_bytes();
    let mut start = 0;
    while out.len() < MAX_RULE_FINDINGS {
        let end = bytes[start..]
            .iter()
            .position(|&b| b == b',')
            .map_or(bytes.len(), |p| start + p);
        let (mut a, mut b) = (start, end);
        while a < b && is_separator(bytes[a]) {
            a += 1;
        }
        while b > a && is_separator(bytes[b - 1]) {
            b -= 1;
        }
        // The empty piece after a trailing comma is the one OrcaSlicer drops.
        let dropped = end == bytes.len() && start == end && start > 0;
        if dropped {
            // Nothing to say: OrcaSlicer drops it, rotlang ignores it.
        } else if a == b {
            // An empty piece: OrcaSlicer reads 0 for it. Remove it with one comma.
            let span = if start > 0 {
                Span::new(start - 1, end)
            } else {
                Span::new(0, (end + 1).min(bytes.len()))
            };
            let d = Diagnostic::warning(
                EMPTY_INSTRUCTION,
                "OrcaSlicer reads an empty instruction here as 0°",
            )
            .with_primary(span, "an empty instruction for OrcaSlicer")
            .with_help("rotlang ignores it; remove it so that both read the same");
            out.push(with_checked_fix(
                d,
                text,
                fixable,
                target,
                "remove the empty instruction",
                span,
                String::new(),
            ));
        } else if let Some(gap) = bytes[a..b].iter().position(|&c| is_separator(c)) {
            let piece = &text[a..b];
            // The angles of the piece, without a vector of them: a pasted megabyte of
            // `0 90 …` is one piece.
            let parts = || {
                piece
                    .split(|c: char| c.is_ascii_whitespace() || c == '\u{b}')
                    .filter(|p| !p.is_empty())
            };
            let joined = |before: &str, after: &str| {
                let mut all = String::with_capacity(piece.len() * 2 + before.len() + after.len());
                all.push_str(before);
                for (i, p) in parts().enumerate() {
                    if i > 0 {
                        all.push_str(", ");
                    }
                    all.push_str(p);
                }
                all.push_str(after);
                all
            };
            let gap_end = a
                + gap
                + bytes[a + gap..b]
                    .iter()
                    .take_while(|&&c| is_separator(c))
                    .count();
            let d = Diagnostic::warning(
                SPACE_SEPARATED_LIST,
                format!(
                    "OrcaSlicer reads only `{}` here: in a plain list it separates angles at commas, not spaces",
                    parts().next().unwrap_or_default()
                ),
            )
            .with_primary(Span::new(a + gap, gap_end), "a space between angles")
            .with_help(joined("write `", "`"));
            // The fixed text is built only where a fix is checked.
            let d = if fixable && text.len() <= MAX_FIXED_TEXT {
                with_checked_fix(
                    d,
                    text,
                    fixable,
                    target,
                    "separate the angles with commas",
                    Span::new(a, b),
                    joined("", ""),
                )
            } else {
                d
            };
            out.push(d);
        }
        if end == bytes.len() {
            break;
        }
        start = end + 1;
    }
}

/// The rules of one instruction, in the template's order; nothing once
/// [`MAX_RULE_FINDINGS`] are found.
pub(super) fn instruction_rules(
    text: &str,
    ins: &Instruction,
    list: bool,
    fixable: bool,
    target: Target,
    out: &mut Vec<Diagnostic>,
) {
    if out.len() >= MAX_RULE_FINDINGS {
        return;
    }
    let fix = |d, title: &str, span, replacement: String| {
        with_checked_fix(d, text, fixable, target, title, span, replacement)
    };
    if let Some(angle) = &ins.angle
        && let AngleValue::Fraction(a, b) = angle.value
    {
        let percent = a / b * 100.0;
        let theirs = if angle.sign == Some(Sign::Minus) {
            -a
        } else {
            a
        };
        let d = Diagnostic::warning(
            FRACTION,
            format!(
                "OrcaSlicer has no `α:β` angles: it reads `{}` as {}",
                &text[angle.span.range()],
                degrees(theirs)
            ),
        )
        .with_primary(angle.span, format!("rotlang: {}", degrees(angle.degrees())))
        .with_help("write the angle in degrees or as a percentage of 360°");
        let sign = &text[angle.span.start..angle.span.start + usize::from(angle.sign.is_some())];
        let d = match short_decimal(percent) {
            Some(p) => fix(
                d,
                "write it as a percentage",
                angle.span,
                format!("{sign}{p}%"),
            ),
            None => d,
        };
        out.push(d);
    }
    if let Some(count) = ins.count
        && let CountKind::HeightFraction { num, den } = count.kind
    {
        let d = Diagnostic::warning(
            FRACTION,
            format!(
                "OrcaSlicer has no `ℍ:ℕ` heights: it reads `{}` as {} followed by text it ignores",
                &text[count.span.range()],
                short_decimal(num).unwrap_or_else(|| num.to_string())
            ),
        )
        .with_primary(count.span, "the fraction of the object height")
        .with_help("write the height as a percentage of the object height (`25%`)");
        let d = match short_decimal(num / den * 100.0) {
            Some(p) => fix(
                d,
                "write it as a percentage of the height",
                count.span,
                format!("{p}%"),
            ),
            None => d,
        };
        out.push(d);
    }
    if let Some(solid) = ins.solid {
        out.push(
            Diagnostic::warning(
                SOLID_SIGN,
                match target {
                    Target::Sparse => format!("OrcaSlicer has no solid signs: it ignores `{}` and what follows it in the instruction, and fills these layers as sparse infill", solid.value.symbol()),
                    // A solid template's layers are solid anyway: only the pattern is lost.
                    Target::Solid => format!("OrcaSlicer has no solid signs: it ignores `{}` and what follows it in the instruction, and fills these layers with its own solid pattern", solid.value.symbol()),
                },
            )
            .with_primary(solid.span, "rotlang: solid layers")
            .with_help(match target {
                Target::Sparse => "OrcaSlicer prints sparse infill here; only rotlang-based slicers make these layers solid",
                Target::Solid => "OrcaSlicer prints its solid_infill_pattern here; only rotlang-based slicers follow the sign's pattern",
            }),
        );
    }
    if let (Some(joint), Some(count)) = (ins.joint, ins.count)
        && matches!(count.kind, CountKind::Bottom | CountKind::Top)
    {
        out.push(
            Diagnostic::warning(
                SHELLS_AFTER_JOINT,
                format!(
                    "OrcaSlicer does not read `{}` after a joint: the range is one layer",
                    &text[count.span.range()]
                ),
            )
            .with_primary(count.span, "rotlang: the shell layer count")
            .with_secondary(joint.span, "after this joint")
            .with_help("write the number of layers (`+10/3`) for the same range in both"),
        );
    }
    if let Some(joint) = ins.joint
        && matches!(joint.value, Joint::Random | Joint::PseudoRandom)
    {
        out.push(
            Diagnostic::warning(
                RANDOM,
                format!("OrcaSlicer's `{}` uses C's rand(): its angles differ from run to run and from rotlang's seeded ones", joint.value.symbol()),
            )
            .with_primary(joint.span, "random")
            .with_help("rotlang's random joints are reproducible (seeded); OrcaSlicer's are not"),
        );
    }
    if list {
        // `!`, `B`, `T` mean nothing in OrcaSlicer's plain list.
        let ignored = ins.one_time.map(|s| (s, "`!`")).into_iter().chain(
            ins.count
                .filter(|c| matches!(c.kind, CountKind::Bottom | CountKind::Top))
                .map(|c| (c.span, "the shell count")),
        );
        for (span, what) in ignored {
            out.push(
                Diagnostic::warning(
                    IGNORED_IN_LIST,
                    format!("OrcaSlicer reads this template as a plain list of angles and ignores {what}"),
                )
                .with_primary(span, "ignored by OrcaSlicer")
                .with_help("a template without `+ - % * ' \" c m` or a joint sign is a plain list for OrcaSlicer: each instruction is one layer at its angle"),
            );
        }
    } else if let (Some(angle), Some(bang)) = (&ins.angle, ins.one_time)
        && bang.start == angle.span.end
        && bang.end < ins.span.end
    {
        let rest = Span::new(bang.end, ins.span.end);
        let d = Diagnostic::warning(
            TEXT_AFTER_BANG,
            format!("OrcaSlicer ignores `{}` after the `!`", &text[rest.range()]),
        )
        .with_primary(rest, "ignored by OrcaSlicer")
        .with_secondary(bang, "OrcaSlicer stops reading here")
        .with_help("put the `!` at the end of the instruction");
        let moved = format!("{}!", &text[rest.range()]);
        out.push(fix(
            d,
            "move the `!` to the end",
            Span::new(bang.start, ins.span.end),
            moved,
        ));
    }
}

/// `x` with at most six decimals, exactly (`25`, `12.5`), or `None`.
fn short_decimal(x: f64) -> Option<String> {
    if !x.is_finite() {
        return None;
    }
    let rounded = (x * 1e6).round() / 1e6;
    ((rounded - x).abs() <= 1e-12 * x.abs().max(1.0)).then(|| format!("{}", rounded + 0.0))
}
