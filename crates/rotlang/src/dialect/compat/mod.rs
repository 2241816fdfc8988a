//! The compat lint: where OrcaSlicer and rotlang part on a template.
//!
//! Two kinds of finding, each with its own stable code:
//!
//! - **on the model**: both readings are evaluated on the model (the default cube or the
//!   profile's own); the first layer where the angles (or fills) differ gets a warning on
//!   the instruction at fault with both values ([`DIFFERS`]); where OrcaSlicer hangs,
//!   crashes or computes NaN angles, an error ([`HANGS`], [`UNDEFINED`], [`NAN`]).
//! - **by rule** ([`RULES`]): constructs OrcaSlicer reads differently on every model: a
//!   plain list separated by spaces, `α:β`/`ℍ:ℕ`, solid signs, `B`/`T` after a joint, text
//!   after a `!`, empty instructions, `!`/`B`/`T` in a plain list, `~`/`^`.
//!
//! Both readings are evaluated with the same `options`: a base is added to every angle in
//! both. A profile's infill direction is the base of an empty template only, in both
//! readings, as OrcaSlicer decides it (`rotlang_profile::profile::ProfileModel::options`), so the
//! two never part on it and every angle a message names is one the slicer prints. (The
//! finding `orcaslicer::direction-ignored`, which reported rotlang adding the direction to
//! every angle, is retired with that reading.)
//!
//! A fix is attached only where it keeps rotlang's meaning (checked by evaluating the fixed
//! text on reference models) and removes what OrcaSlicer misreads.

mod rules;

use rules::MAX_FIXED_TEXT;
#[cfg(test)]
mod tests;

use super::orcaslicer::{self, is_list};
use super::{HANGS, NAN, UNDEFINED};
use crate::diagnostic::{Diagnostic, Span};
use crate::eval::{self, Layer, Model, Options};
use crate::ir::{AngleValue, CountKind, Fill, Instruction, Joint, Sign, Target};
use rules::{instruction_rules, rules, text_rules};

/// OrcaSlicer's angle or fill differs from rotlang's on some layer of the model.
pub const DIFFERS: &str = "orcaslicer::differs";
/// `0 90`: OrcaSlicer reads a plain list only at commas (`0`).
pub const SPACE_SEPARATED_LIST: &str = "orcaslicer::space-separated-list";
/// `α:β` or `ℍ:ℕ`: OrcaSlicer reads the first number only.
pub const FRACTION: &str = "orcaslicer::fraction";
/// `D S O M R`: OrcaSlicer has no solid signs; the layers stay sparse.
pub const SOLID_SIGN: &str = "orcaslicer::solid-sign";
/// `+10/B`: OrcaSlicer reads no count after a joint's `B`/`T`.
pub const SHELLS_AFTER_JOINT: &str = "orcaslicer::shells-after-joint";
/// `+7!B`: OrcaSlicer ignores everything after a `!` that follows the angle.
pub const TEXT_AFTER_BANG: &str = "orcaslicer::text-after-bang";
/// `, +10`, `10,,20`: OrcaSlicer reads an empty instruction as 0°.
pub const EMPTY_INSTRUCTION: &str = "orcaslicer::empty-instruction";
/// `10!, 20`: in a plain list OrcaSlicer ignores `!`, `B` and `T`.
pub const IGNORED_IN_LIST: &str = "orcaslicer::ignored-in-list";
/// `~`, `^`: OrcaSlicer's random numbers differ from run to run.
pub const RANDOM: &str = "orcaslicer::random";
/// The codes of the findings that hold on every model (the rule-based ones).
pub const RULES: [&str; 8] = [
    SPACE_SEPARATED_LIST,
    FRACTION,
    SOLID_SIGN,
    SHELLS_AFTER_JOINT,
    TEXT_AFTER_BANG,
    EMPTY_INSTRUCTION,
    IGNORED_IN_LIST,
    RANDOM,
];

/// Every code the lint can report.
pub const CODES: [&str; 12] = [
    DIFFERS,
    HANGS,
    UNDEFINED,
    NAN,
    SPACE_SEPARATED_LIST,
    FRACTION,
    SOLID_SIGN,
    SHELLS_AFTER_JOINT,
    TEXT_AFTER_BANG,
    EMPTY_INSTRUCTION,
    IGNORED_IN_LIST,
    RANDOM,
];

/// Compares rotlang's reading of `text` with OrcaSlicer's on `model` and by rule, both
/// with `options` (for a profile's template: `rotlang_profile::profile::ProfileModel::compat`).
/// Diagnostics are sorted by position; none of them is a syntax error (run `parse` for
/// those: where the template has errors, only OrcaSlicer's own problems and the rules are
/// reported).
pub fn compat(text: &str, target: Target, model: &Model, options: Options) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    if text.len() <= MAX_FIXED_TEXT {
        // A fix is offered only on a template without errors, which the whole parse tells
        // before the rules run; on a text this short the IR costs nothing.
        let parse = crate::parse(text, target);
        let fixable = !parse.has_errors();
        rules(
            text,
            &parse.template.instructions,
            fixable,
            target,
            &mut out,
        );
        let ours = fixable.then(|| eval::layers(&parse.template, model, options));
        on_model(text, ours, model, options, &mut out);
    } else {
        // No fix is checked on a text this long (`MAX_FIXED_TEXT`), so the rules can read
        // each instruction as it is parsed, and rotlang's layers come from the evaluator's
        // compact form: the IR of a megabyte template, many times its size, is never built.
        let list = text_rules(text, false, target, &mut out);
        let (parse, ours) = eval::parse_layers_with(text, target, model, options, |ins| {
            instruction_rules(text, ins, list, false, target, &mut out);
        });
        out.truncate(rules::MAX_RULE_FINDINGS);
        let ours = (!parse.has_errors()).then_some(ours);
        on_model(text, ours, model, options, &mut out);
    }
    out.sort_by_key(|d| (d.primary_span(), d.code));
    out
}

/// Equal directions: modulo 360 within 1e-4°, relatively within 1e-9 above 1e9 (the
/// conformance README's comparison).
fn same_angle(a: f64, b: f64) -> bool {
    if a.abs().max(b.abs()) > 1e9 {
        return (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    }
    let diff = (a - b).rem_euclid(360.0);
    diff <= 1e-4 || diff >= 360.0 - 1e-4
}

/// Angles without float noise: `47.25°`, `33.333333°`.
fn degrees(d: f64) -> String {
    let rounded = (d * 1e6).round() / 1e6;
    format!("{}°", rounded + 0.0)
}

fn whole(text: &str) -> Span {
    Span::new(0, text.len())
}

/// The findings on the model: `ours` is rotlang's reading, `None` when the template has
/// errors (OrcaSlicer's own problems are reported then, no difference).
fn on_model(
    text: &str,
    mut ours: Option<eval::Layers<'_>>,
    model: &Model,
    options: Options,
    out: &mut Vec<Diagnostic>,
) {
    let mut theirs = orcaslicer::layers(text, model, options);
    let mut first: Option<(Layer, Layer)> = None;
    let mut nan_seen = 0;
    let mut halted = false;
    while let Some(o) = theirs.next() {
        let r = ours.as_mut().and_then(Iterator::next);
        let findings = theirs.findings();
        let nan = findings
            .iter()
            .find(|f| f.code == NAN)
            .map_or(0, |f| f.layers);
        halted |= findings.iter().any(|f| f.code != NAN);
        // NaN layers and layers past a hang or crash are reported as such, not as angles.
        let nan_layer = nan > nan_seen;
        nan_seen = nan;
        if let Some(r) = r
            && first.is_none()
            && !halted
            && !nan_layer
            && (!same_angle(r.angle, o.angle) || r.fill != Fill::Sparse)
        {
            first = Some((r, o));
        }
    }
    for f in theirs.findings() {
        let span = f.span.unwrap_or_else(|| whole(text));
        let (label, help) = match f.code {
            HANGS => (
                "OrcaSlicer loops forever here",
                "only dummies are left alive once the first instruction is spent: \
                 OrcaSlicer freezes while slicing; rotlang holds the angle",
            ),
            UNDEFINED => (
                "a count OrcaSlicer cannot convert to a 32-bit integer",
                "keep counts below 2147483647 layers and finite",
            ),
            _ => (
                "OrcaSlicer computes NaN or infinite angles here",
                "a range that ends inside a layer pushes progress past 1 (`$` then takes \
                 the arcsine of a value above 1); end ranges on layer boundaries or use \
                 another joint",
            ),
        };
        let message = if f.code == NAN && f.layers > 1 {
            format!(
                "OrcaSlicer computes NaN or infinite angles on {} layers, from layer {}",
                f.layers, f.first_layer
            )
        } else {
            f.message.clone()
        };
        out.push(
            Diagnostic::error(f.code, message)
                .with_primary(span, label)
                .with_help(help),
        );
    }
    if let Some((r, o)) = first {
        let span = r
            .instruction
            .or(o.instruction)
            .unwrap_or_else(|| whole(text));
        let message = if r.fill != Fill::Sparse && same_angle(r.angle, o.angle) {
            // `S` is plain "solid"; the other solid signs name their pattern.
            let solid = match r.fill {
                Fill::Solid => "a solid layer".to_owned(),
                other => format!("a {} solid layer", other.name()),
            };
            format!(
                "OrcaSlicer makes layer {} sparse infill, rotlang {solid}",
                r.index
            )
        } else {
            format!(
                "OrcaSlicer turns layer {} to {}, rotlang to {}",
                r.index,
                degrees(o.angle),
                degrees(r.angle)
            )
        };
        let mut d = Diagnostic::warning(DIFFERS, message)
            .with_primary(span, format!("rotlang: layer {} follows this", r.index));
        if let Some(theirs) = o.instruction.filter(|&s| s != span) {
            d = d.with_secondary(theirs, "OrcaSlicer reads this for that layer");
        }
        out.push(d.with_help(
            "the two readings part from this layer on; see the other `orcaslicer::` \
             findings for why, or `rotlang expand --dialect orcaslicer`",
        ));
    }
}

/// Whether `fixed` means what `text` means for rotlang: no errors, and the same angles and
/// fills on reference models (the cube, a thicker first layer, fine layers).
fn keeps_meaning(text: &str, fixed: &str, target: Target) -> bool {
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

fn reference_models() -> [Model; 3] {
    let uniform = |n, h, first| Model::uniform(n, h, first).expect("valid reference model");
    [
        Model::cube20(),
        uniform(75, 0.2, Some(0.3)).with_shells(4, 5),
        uniform(167, 0.12, None).with_shells(2, 3),
    ]
}

/// Whether OrcaSlicer reads `text` as rotlang does: no errors, and on reference models
/// the same angles, sparse fills and no hang, crash or NaN. `check --fix` applies a fix
/// that gets there whatever it changes in OrcaSlicer's reading.
pub fn readings_agree(text: &str, target: Target) -> bool {
    let parse = crate::parse(text, target);
    if parse.has_errors() || text.len() > MAX_FIXED_TEXT {
        return false;
    }
    reference_models().iter().all(|model| {
        let options = Options::default();
        let mut theirs = orcaslicer::layers(text, model, options);
        let agree = eval::layers(&parse.template, model, options)
            .zip(theirs.by_ref())
            .all(|(r, o)| r.fill == Fill::Sparse && same_angle(r.angle, o.angle));
        agree && theirs.findings().is_empty()
    })
}

/// What OrcaSlicer does differently after `text` becomes `changed` (on reference models),
/// or `None` when it reads both alike. The formatter asks before rewriting a template.
pub fn orcaslicer_change(text: &str, changed: &str) -> Option<String> {
    // Formatting changes separators only: most texts keep OrcaSlicer's tokens exactly.
    if orcaslicer::same_reading(text, changed) {
        return None;
    }
    for model in reference_models() {
        let options = Options::default();
        let mut a = orcaslicer::layers(text, &model, options);
        let mut b = orcaslicer::layers(changed, &model, options);
        for (x, y) in a.by_ref().zip(b.by_ref()) {
            if x.angle.to_bits() != y.angle.to_bits() && !same_angle(x.angle, y.angle) {
                return Some(format!(
                    "OrcaSlicer would turn layer {} to {} instead of {}",
                    x.index,
                    degrees(y.angle),
                    degrees(x.angle)
                ));
            }
        }
        let codes = |f: &[super::Finding]| f.iter().map(|f| f.code).collect::<Vec<_>>();
        if codes(a.findings()) != codes(b.findings()) {
            return Some("OrcaSlicer would hang, crash or compute NaN angles differently".into());
        }
    }
    None
}
