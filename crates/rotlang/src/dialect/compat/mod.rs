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

mod codes;
mod readings;
mod rules;

use rules::MAX_FIXED_TEXT;
#[cfg(test)]
mod tests;

use super::orcaslicer;
use super::{HANGS, NAN, UNDEFINED};
use crate::diagnostic::{Diagnostic, Span};
use crate::eval::{self, Layer, Model, Options};
use crate::ir::{Fill, Target};
use readings::{degrees, reference_models, same_angle};
use rules::{instruction_rules, rules, text_rules};

pub use codes::{
    CODES, DIFFERS, EMPTY_INSTRUCTION, FRACTION, IGNORED_IN_LIST, RANDOM, RULES,
    SHELLS_AFTER_JOINT, SOLID_SIGN, SPACE_SEPARATED_LIST, TEXT_AFTER_BANG,
};
pub use readings::orcaslicer_change;

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
