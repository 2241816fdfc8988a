//! Checks on the IR: errors that depend on the target, and warnings for templates that
//! are legal but most likely not what was meant.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::*;
use crate::syntax::split::Chunk;

/// The checks on one instruction of the IR, run as soon as it is lowered: the caller adds
/// them to its diagnostics in source order (which is what lets it keep the first error).
pub(crate) fn instruction(text: &str, ins: &Instruction, target: Target) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let out = &mut found;
    if target == Target::Solid
        && let Some(s) = ins.solid
    {
        out.push(
                Diagnostic::error("rotlang::solid-sign-in-solid-template", format!("the solid sign `{}` has no meaning in a solid infill template", s.value.symbol()))
                    .with_primary(s.span, "a solid sign")
                    .with_fix("remove the solid sign", s.span, "")
                    .with_help("solid signs (`D S O M R`) put solid layers into sparse infill; use them in `sparse_infill_rotate_template`"),
            );
    }
    angle_range(ins, out);
    zero_count(ins, out);
    dummy(text, ins, out);
    // A joint or flip shapes a turn; an absolute angle has none to shape.
    let shape = ins
        .joint
        .map(|j| (j.span, format!("the joint `{}`", j.value.symbol())))
        .or(ins.flip.map(|f| (f, "the flip `-`".to_owned())));
    if let (Some((span, what)), Some(a)) = (shape, &ins.angle)
        && a.sign.is_none()
        && ins.dummy.is_none()
    {
        out.push(
            Diagnostic::warning(
                "rotlang::joint-on-absolute-angle",
                format!("{what} has no effect on an absolute angle"),
            )
            .with_primary(span, "this shape is never used")
            .with_secondary(a.span, "an absolute angle stays constant over its range")
            .with_help(format!(
                "to turn by {} over the range, write `+{}`",
                fmt_deg(a.degrees()),
                &text[a.span.range()]
            )),
        );
    }
    found
}

/// Warnings about separators (`+30/ 50%`, `+30 /50%`), on chunks as they stream by: a
/// pair of neighbours is looked at once the chunk after them is known. Each chunk comes
/// with whether it was read as a valid instruction.
#[derive(Default)]
pub(crate) struct Spacing<'a> {
    window: [Option<(Chunk<'a>, bool)>; 2],
}

impl<'a> Spacing<'a> {
    pub fn push(&mut self, chunk: Chunk<'a>, valid: bool, out: &mut Vec<Diagnostic>) {
        if let [Some(prev), Some(next)] = self.window {
            space_after_joint(prev, next, out);
            pair(prev.0, next.0, Some(chunk), out);
        }
        self.window = [self.window[1], Some((chunk, valid))];
    }

    pub fn finish(self, out: &mut Vec<Diagnostic>) {
        if let [Some(prev), Some(next)] = self.window {
            space_after_joint(prev, next, out);
            pair(prev.0, next.0, None, out);
        }
    }
}

/// `+30 /50%`: a space splits what looks like one instruction into two. `after` is the
/// chunk after `next`, if any.
fn pair(prev: Chunk<'_>, next: Chunk<'_>, after: Option<Chunk<'_>>, out: &mut Vec<Diagnostic>) {
    // A joint (`+30 /50%`), a lone `#` unit (`+30/5 #`) or a repeat count
    // (`+45/10 *2`) cut off by a space; `#14` on its own is a documented form.
    let cut_off = next
        .text
        .starts_with(|c: char| Joint::from_symbol(c).is_some() && c != '#')
        || next.text == "#"
        || (next.text.starts_with('*') && next.text[1..].starts_with(|c: char| c.is_ascii_digit()));
    if next.after_space_only
        && prev
            .text
            .ends_with(|c: char| c.is_ascii_digit() || c == '%')
        && cut_off
    {
        // `+30 / 50%`: a lone joint with its count cut off too: join all three.
        let count = after.filter(|c| {
            next.text.len() == 1
                && next.text != "#"
                && c.after_space_only
                && c.text
                    .starts_with(|ch: char| ch.is_ascii_digit() || matches!(ch, '-' | 'B' | 'T'))
        });
        let end = count.map_or(next.span.start, |c| c.span.start);
        let gap = Span::new(prev.span.end, end);
        let joined = match count {
            Some(c) => format!("{}{}{}", prev.text, next.text, c.text),
            None => format!("{}{}", prev.text, next.text),
        };
        let mut d = Diagnostic::warning(
            "rotlang::space-splits-instruction",
            format!("`{}` starts a new instruction", next.text),
        )
        .with_primary(
            next.span,
            "read as an instruction of its own (a turn of 0°)",
        )
        .with_secondary(
            Span::new(prev.span.end, next.span.start),
            "because of this space",
        );
        if let Some(c) = count {
            d = d.with_secondary(c.span, "and this one too").with_fix(
                "join the three",
                gap,
                next.text,
            );
        } else {
            d = d.with_fix("join the two", gap, "");
        }
        out.push(d.with_help(format!(
            "did you mean `{joined}`? Otherwise separate them with a comma"
        )));
    }
}

/// `+30/ 50%`, `+30# 10`, `+10L 25%`: a space after a joint splits the instruction from
/// its count, and both halves are legal: a one-layer turn, then an instruction of its own
/// (`50%` is the absolute direction 180°). Only pairs of valid instructions are warned
/// about; a second half that cannot stand alone is an error of the parser.
fn space_after_joint(
    (prev, prev_valid): (Chunk<'_>, bool),
    (next, next_valid): (Chunk<'_>, bool),
    out: &mut Vec<Diagnostic>,
) {
    // `+30 / 50%`: the lone `/` is itself cut off; the check below joins all three.
    let lone_joint = prev.after_space_only
        && prev
            .text
            .starts_with(|c: char| Joint::from_symbol(c).is_some());
    if lone_joint || !(crate::syntax::split::after_joint(&prev, &next) && prev_valid && next_valid)
    {
        return;
    }
    let gap = Span::new(prev.span.end, next.span.start);
    out.push(
        Diagnostic::warning(
            "rotlang::space-splits-instruction",
            format!("`{}` starts a new instruction", next.text),
        )
        .with_primary(
            next.span,
            "read as an instruction of its own, not as the count of the joint",
        )
        .with_secondary(gap, "because of this space")
        .with_fix("remove the space", gap, "")
        .with_help(format!(
            "did you mean `{}{}`? Otherwise separate them with a comma",
            prev.text, next.text
        )),
    );
}

fn fmt_deg(d: f64) -> String {
    format!("{}°", (d * 1e6).round() / 1e6)
}

fn angle_range(ins: &Instruction, out: &mut Vec<Diagnostic>) {
    let Some(a) = &ins.angle else { return };
    let d = a.degrees();
    if a.sign.is_none() && !(0.0..=360.0).contains(&d) {
        let wrapped = d.rem_euclid(360.0);
        out.push(
            Diagnostic::warning(
                "rotlang::angle-out-of-range",
                format!("the absolute angle {} is outside 0–360°", fmt_deg(d)),
            )
            .with_primary(
                a.span,
                format!("the same direction as {}", fmt_deg(wrapped)),
            )
            .with_help(
                "absolute angles are directions from 0 to 360; for a turn, write a sign (`+`)",
            ),
        );
    }
}

fn zero_count(ins: &Instruction, out: &mut Vec<Diagnostic>) {
    let Some(c) = ins.count else { return };
    let zero = match c.kind {
        CountKind::Layers(n) => n < 1.0,
        CountKind::Length { value, .. } => value == 0.0,
        CountKind::HeightFraction { num, .. } => num == 0.0,
        CountKind::Bottom | CountKind::Top => false,
    };
    if zero && ins.dummy.is_none() {
        out.push(
            Diagnostic::warning("rotlang::zero-count", "a count below one layer covers just one layer")
                .with_primary(c.span, "this range is a single layer")
                .with_help("write the number of layers (or the length) the turn should take, or leave the count out"),
        );
    }
}

fn dummy(text: &str, ins: &Instruction, out: &mut Vec<Diagnostic>) {
    let Some(star) = ins.dummy else { return };
    if let Some(r) = ins.repeat {
        out.push(
            Diagnostic::error("rotlang::dummy-and-repeat", "an instruction cannot be both a dummy and repeated")
                .with_primary(star, "a dummy mark")
                .with_secondary(r.span, "a repeat count")
                .with_help("a dummy (`*`) sets an angle without taking layers; `*ℤ` runs the instruction ℤ times: keep one"),
        );
        return;
    }
    // The parts a dummy ignores: everything after its `*`, and, for a trailing `*`, the
    // shape and count too (a dummy takes no layers).
    let ignored: Vec<Span> = [
        ins.solid.map(|s| s.span),
        ins.joint.map(|j| j.span),
        ins.flip,
        ins.count.map(|c| c.span),
    ]
    .into_iter()
    .flatten()
    .collect();
    if let (Some(first), Some(last)) = (ignored.first(), ignored.last()) {
        let span = first.cover(*last);
        out.push(
            Diagnostic::warning(
                "rotlang::dummy-ignores-range",
                "a dummy takes no layers: its shape and count are ignored",
            )
            .with_primary(span, format!("`{}` is ignored", &text[span.range()]))
            .with_secondary(star, "this makes the instruction a dummy")
            .with_help("remove the `*` to turn over the range, or remove the range"),
        );
    } else if ins.is_relative() && ins.degrees() == 0.0 {
        out.push(
            Diagnostic::warning(
                "rotlang::dummy-without-effect",
                "this dummy never changes the angle",
            )
            .with_primary(ins.span, "a turn of 0° that takes no layers")
            .with_help("a dummy sets an angle (`30*`) or a turn (`+30*`) for the next instruction"),
        );
    }
}
