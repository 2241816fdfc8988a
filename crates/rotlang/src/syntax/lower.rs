//! Syntax tree (pest pairs) → IR, with the checks that need the numbers' values.

use pest::iterators::Pair;

use super::grammar::Rule;
use crate::diagnostic::{Diagnostic, Span};
use crate::ir::*;

/// The largest count, repeat or length value accepted: no printer has a billion layers,
/// and the evaluator's cost must not depend on these numbers anyway.
pub(crate) const MAX_COUNT: f64 = 1e9;
/// The largest angle magnitude accepted (degrees); beyond it, f64 loses the fraction of a
/// degree that matters.
pub(crate) const MAX_ANGLE: f64 = 1e9;

pub(crate) struct Lowerer<'d> {
    /// Byte offset of the instruction in the template.
    pub offset: usize,
    pub diagnostics: &'d mut super::Sink,
}

impl Lowerer<'_> {
    fn span(&self, pair: &Pair<'_, Rule>) -> Span {
        let s = pair.as_span();
        Span::new(s.start() + self.offset, s.end() + self.offset)
    }

    /// A number's value, or an error when it is not finite or absurd.
    fn number(&mut self, pair: &Pair<'_, Rule>, max: f64, what: &str) -> Option<f64> {
        let span = self.span(pair);
        let v: f64 = pair.as_str().parse().ok()?;
        if !v.is_finite() {
            self.diagnostics.push(
                Diagnostic::error(
                    "rotlang::number-not-finite",
                    format!("this {what} is too large to represent"),
                )
                .with_primary(span, "beyond any floating-point number")
                .with_help(format!("the largest {what} accepted is {max:e}")),
            );
            return None;
        }
        if v > max {
            self.diagnostics.push(
                Diagnostic::error(
                    "rotlang::number-too-large",
                    format!("this {what} is absurdly large"),
                )
                .with_primary(span, format!("larger than {max:e}"))
                .with_help(format!(
                    "the largest {what} accepted is {max:e}; no printer goes further"
                )),
            );
            return None;
        }
        Some(v)
    }

    /// `a:b` from the numerator's pair and the `:b` tail's, with `b ≠ 0`.
    fn fraction(
        &mut self,
        a: &Pair<'_, Rule>,
        tail: Pair<'_, Rule>,
        what: &str,
    ) -> Option<(f64, f64)> {
        let span = self.span(a).cover(self.span(&tail));
        let b = tail.into_inner().next()?;
        let b_span = self.span(&b);
        let num = self.number(a, MAX_COUNT, what);
        let den = self.number(&b, MAX_COUNT, what);
        let (num, den) = (num?, den?);
        if den == 0.0 {
            self.diagnostics.push(
                Diagnostic::error(
                    "rotlang::zero-denominator",
                    format!("a {what} cannot have 0 below the line"),
                )
                .with_primary(b_span, "this divides by zero")
                .with_secondary(span, format!("in this {what}"))
                .with_help("`a:b` means a/b; `1:4` is a quarter"),
            );
            return None;
        }
        Some((num, den))
    }

    /// Lowers one `instruction` pair. Returns `None` when a value was invalid (its
    /// diagnostic has been pushed).
    pub fn instruction(&mut self, pair: Pair<'_, Rule>) -> Option<Instruction> {
        let span = self.span(&pair);
        let mut ins = Instruction {
            span,
            angle: None,
            repeat: None,
            dummy: None,
            one_time: None,
            solid: None,
            joint: None,
            flip: None,
            count: None,
        };
        let mut ok = true;
        for part in pair.into_inner() {
            let ps = self.span(&part);
            match part.as_rule() {
                Rule::angle => match self.angle(part) {
                    Some(a) => ins.angle = Some(a),
                    None => ok = false,
                },
                Rule::runtime => {
                    for mark in part.into_inner() {
                        ok &= self.mark(&mut ins, mark, false);
                    }
                }
                Rule::trailing => {
                    for mark in part.into_inner() {
                        ok &= self.mark(&mut ins, mark, true);
                    }
                }
                Rule::solid => {
                    let c = part.as_str().chars().next().and_then(Solid::from_symbol);
                    ins.solid = c.map(|s| Spanned::new(s, ps));
                }
                Rule::joint => {
                    let c = part.as_str().chars().next().and_then(Joint::from_symbol);
                    ins.joint = c.map(|j| Spanned::new(j, ps));
                }
                Rule::flip => ins.flip = Some(ps),
                Rule::count => match self.count(part) {
                    Some(c) => ins.count = Some(c),
                    None => ok = false,
                },
                Rule::EOI => {}
                // The grammar puts nothing else directly under `instruction`.
                _ => {}
            }
        }
        ok.then_some(ins)
    }

    fn angle(&mut self, pair: Pair<'_, Rule>) -> Option<Angle> {
        let span = self.span(&pair);
        let mut sign = None;
        let mut number = None;
        let mut value = None;
        for part in pair.into_inner() {
            match part.as_rule() {
                Rule::sign => {
                    sign = Some(if part.as_str() == "-" {
                        Sign::Minus
                    } else {
                        Sign::Plus
                    });
                }
                Rule::number => number = Some(part),
                Rule::percent => {
                    let n = number.take()?;
                    value = Some(AngleValue::Percent(self.number(
                        &n,
                        MAX_ANGLE / 3.6,
                        "angle",
                    )?));
                }
                Rule::turn_fraction => {
                    let n = number.take()?;
                    let (a, b) = self.fraction(&n, part, "fraction of a turn")?;
                    value = Some(AngleValue::Fraction(a, b));
                }
                _ => {}
            }
        }
        let value = match (value, number) {
            (Some(v), _) => v,
            (None, Some(n)) => AngleValue::Degrees(self.number(&n, MAX_ANGLE, "angle")?),
            (None, None) => return None,
        };
        if !value.degrees().is_finite() || value.degrees().abs() > MAX_ANGLE {
            self.diagnostics.push(
                Diagnostic::error("rotlang::number-too-large", "this angle is absurdly large")
                    .with_primary(span, format!("more than {MAX_ANGLE:e} degrees"))
                    .with_help("a fraction `a:b` turns a/b of 360°; keep it within a few turns"),
            );
            return None;
        }
        Some(Angle { span, sign, value })
    }

    /// A `*`, `*ℤ` or `!` mark, right after the angle (`trailing == false`) or at the end.
    fn mark(&mut self, ins: &mut Instruction, pair: Pair<'_, Rule>, trailing: bool) -> bool {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::bang => {
                if let Some(first) = ins.one_time {
                    self.diagnostics.push(
                        Diagnostic::warning(
                            "rotlang::duplicate-mark",
                            "the instruction is already one-time",
                        )
                        .with_primary(span, "a second `!`")
                        .with_secondary(first, "made one-time here")
                        .with_fix("remove the second `!`", span, ""),
                    );
                } else {
                    ins.one_time = Some(span);
                }
                true
            }
            Rule::star => {
                let times = pair.into_inner().next();
                match times {
                    Some(n) if trailing && ins.repeat.is_some() => {
                        // `+30*3*2`: `*3` already repeats it; moving `*2` would not help.
                        let first = ins.repeat.map_or(span, |r| r.span);
                        // The help names both ways out: what the fix does (keep the first
                        // count) and the product, for whoever meant the counts to multiply.
                        let kept = ins.repeat.map_or(1, |r| r.value);
                        let second = n.as_str();
                        let help = match second
                            .parse::<u64>()
                            .ok()
                            .and_then(|m| kept.checked_mul(m))
                        {
                            Some(product) => format!(
                                "keep one repeat count: remove `*{second}` to run the instruction {kept} times \
                                 (the fix), or write the product `*{product}` in place of both to run it \
                                 {product} times"
                            ),
                            None => format!(
                                "keep one repeat count: remove `*{second}` to run the instruction {kept} times"
                            ),
                        };
                        self.diagnostics.push(
                            Diagnostic::error(
                                "rotlang::repeat-after-joint",
                                "an instruction has one repeat count",
                            )
                            .with_primary(span, format!("a second repeat count `{}`", n.as_str()))
                            .with_secondary(first, "the instruction is already repeated here")
                            .with_fix("remove the second repeat count", span, "")
                            .with_help(help),
                        );
                        false
                    }
                    Some(n) if trailing => {
                        let n_text = n.as_str().to_owned();
                        let angle_end = ins.angle.as_ref().map_or(ins.span.start, |a| a.span.end);
                        self.diagnostics.push(
                            Diagnostic::error(
                                "rotlang::repeat-after-joint",
                                "a repeat count `*ℤ` belongs right after the angle",
                            )
                            .with_primary(span, "a repeat count at the end of the instruction")
                            .with_help(format!(
                                "move `*{n_text}` to follow the angle, as in `+45*{n_text}/10`"
                            ))
                            .with_secondary(Span::new(angle_end, angle_end), "it goes here"),
                        );
                        false
                    }
                    Some(n) => {
                        let Some(v) = self.number(&n, MAX_COUNT, "repeat count") else {
                            return false;
                        };
                        if v == 0.0 {
                            ins.dummy = Some(span);
                        } else {
                            ins.repeat = Some(Spanned::new(v as u64, span));
                        }
                        true
                    }
                    None => {
                        if ins.dummy.is_some() {
                            self.diagnostics.push(
                                Diagnostic::warning(
                                    "rotlang::duplicate-mark",
                                    "the instruction is already a dummy",
                                )
                                .with_primary(span, "a second `*`")
                                .with_fix(
                                    "remove the second `*`",
                                    span,
                                    "",
                                ),
                            );
                        }
                        ins.dummy.get_or_insert(span);
                        true
                    }
                }
            }
            _ => true,
        }
    }

    fn count(&mut self, pair: Pair<'_, Rule>) -> Option<Count> {
        let span = self.span(&pair);
        let mut parts = pair.into_inner();
        let first = parts.next()?;
        let kind = match (first.as_rule(), parts.next()) {
            (Rule::shell_count, _) if first.as_str() == "B" => CountKind::Bottom,
            (Rule::shell_count, _) => CountKind::Top,
            (Rule::number, None) => CountKind::Layers(self.number(&first, MAX_COUNT, "count")?),
            (Rule::number, Some(tail)) if tail.as_rule() == Rule::height_fraction => {
                let (num, den) = self.fraction(&first, tail, "fraction of the height")?;
                CountKind::HeightFraction { num, den }
            }
            (Rule::number, Some(unit)) => {
                let value = self.number(&first, MAX_COUNT, "length")?;
                CountKind::Length {
                    value,
                    unit: Unit::from_symbol(unit.as_str())?,
                }
            }
            _ => return None,
        };
        Some(Count { span, kind })
    }
}
