//! Text → syntax tree → IR. The only code that sees pest.

mod errors;
mod grammar;
mod lower;
pub(crate) mod split;

mod sink;

pub(crate) use sink::{Collected, Sink};
pub use sink::{MAX_DIAGNOSTICS, Parse};
pub(crate) use split::after_joint;

use pest::Parser;
use pest::error::{ErrorVariant, InputLocation};

use crate::diagnostic::{Diagnostic, Severity, Span};
use crate::{Instruction, Target, Template};
use grammar::{RotParser, Rule};
use split::{Chunk, Piece, Pieces};

/// The most text parsed in one pest call on the fast path.
const BATCH_BYTES: usize = 16 * 1024;

pub(crate) fn parse(text: &str, target: Target) -> Parse {
    let mut instructions = Vec::new();
    let collected = parse_each(text, target, |ins| instructions.push(ins));
    collected.into_parse(Template { instructions })
}

/// How many instructions `text` has at most (its non-empty chunks), without parsing.
pub(crate) fn count_chunks(text: &str) -> usize {
    Pieces::new(text, 0)
        .filter(|p| matches!(p, Piece::Chunk(_)))
        .count()
}

/// Parses a template, handing each instruction to `emit` in order instead of keeping
/// them: memory is the text, one batch of pest tokens and the capped diagnostics, whatever
/// the template's size (for `check`, `fmt` and the evaluator's own compact form).
pub(crate) fn parse_each(
    text: &str,
    target: Target,
    mut emit: impl FnMut(Instruction),
) -> Collected {
    let mut sink = Sink::default();
    // `"0, 90"`: a template copied with its quotes. One diagnostic for the pair, and the
    // inside is read as the template it surely is.
    let pieces = match quoted(text) {
        Some((open, close)) => {
            let inner = Span::new(open.end, close.start);
            sink.push(
                Diagnostic::error(
                    "rotlang::quoted-template",
                    "a template is written without quotes",
                )
                .with_primary(open, "an opening quote")
                .with_secondary(close, "its closing quote")
                .with_fix(
                    "remove the quotes",
                    open.cover(close),
                    text[inner.range()].to_owned(),
                )
                .with_help("write the template's text alone: `0, 90`, not `\"0, 90\"`"),
            );
            Pieces::new(&text[inner.range()], inner.start)
        }
        None => Pieces::new(text, 0),
    };
    let mut pieces = pieces.peekable();
    let mut previous: Option<Chunk<'_>> = None;
    let mut spacing = crate::lint::Spacing::default();
    let mut batch: Vec<Piece<'_>> = Vec::new();
    // Fast path: valid text parses in one pest call per batch of instructions (per-call
    // set-up dominates the cost of short instructions; batches keep pest's token queue in
    // cache on megabyte templates). A batch's items are exactly its chunks; when a batch
    // fails, each of its chunks is parsed on its own for its own diagnostics.
    loop {
        batch.clear();
        let mut start = None;
        while let Some(piece) = pieces.next_if(|p| match (p, start) {
            (Piece::Chunk(c), Some(s)) => c.span.end - s <= BATCH_BYTES,
            _ => true,
        }) {
            if let (Piece::Chunk(c), None) = (piece, start) {
                start = Some(c.span.start);
            }
            batch.push(piece);
        }
        if batch.is_empty() {
            break;
        }
        let Some(start) = start else {
            // Empty instructions with no chunk after them: at the end (`0, 90,,`, `,`).
            for piece in &batch {
                if let Piece::Empty(span) = piece {
                    sink.push(empty_instruction(text, *span, previous.is_some()));
                }
            }
            continue;
        };
        let last_end = batch
            .iter()
            .rev()
            .find_map(|p| match p {
                Piece::Chunk(c) => Some(c.span.end),
                Piece::Empty(_) => None,
            })
            .unwrap_or(start);
        let batch_text = &text[start..last_end];
        let mut items = RotParser::parse(Rule::template, batch_text)
            .into_iter()
            .flatten()
            .flat_map(|t| t.into_inner())
            .filter(|p| p.as_rule() == Rule::item);
        for piece in &batch {
            let chunk = match piece {
                Piece::Empty(span) => {
                    sink.push(empty_instruction(text, *span, previous.is_some()));
                    continue;
                }
                Piece::Chunk(chunk) => chunk,
            };
            let mut valid = false;
            let parsed = match items.next() {
                Some(item)
                    if Span::new(item.as_span().start(), item.as_span().end()).shift(start)
                        == chunk.span =>
                {
                    Ok((item, start))
                }
                _ => RotParser::parse(Rule::instruction, chunk.text)
                    .map(|mut pairs| (pairs.next(), chunk.span.start))
                    .and_then(|(pair, offset)| {
                        pair.map(|p| (p, offset))
                            .ok_or_else(|| unreachable_error(chunk.text))
                    }),
            };
            match parsed {
                Ok((pair, offset)) => {
                    let errors = sink.errors();
                    let mut lowerer = lower::Lowerer {
                        offset,
                        diagnostics: &mut sink,
                    };
                    match lowerer.instruction(pair) {
                        Some(ins) => {
                            for d in crate::lint::instruction(text, &ins, target) {
                                sink.push(d);
                            }
                            emit(ins);
                            valid = true;
                        }
                        // Every instruction left out of the IR is an error: should lowering
                        // ever drop one without saying why, say it here.
                        None if sink.errors() == errors => sink.push(
                            Diagnostic::error(
                                "rotlang::invalid-instruction",
                                "this instruction cannot be read",
                            )
                            .with_primary(chunk.span, "not a valid instruction"),
                        ),
                        None => {}
                    }
                }
                // When it would not be kept, a failure is only counted: diagnosing it
                // would cost time and memory for a report nobody sees.
                Err(_) if !sink.keeps(Severity::Error) => sink.count(Severity::Error),
                Err(err) => sink.push(chunk_error(text, chunk, previous.as_ref(), err)),
            }
            let mut found = Vec::new();
            spacing.push(*chunk, valid, &mut found);
            found.into_iter().for_each(|d| sink.push(d));
            previous = Some(*chunk);
        }
    }
    let mut found = Vec::new();
    spacing.finish(&mut found);
    found.into_iter().for_each(|d| sink.push(d));
    sink.finish()
}

/// The spans of a pair of quotes around the whole template (separators aside).
fn quoted(text: &str) -> Option<(Span, Span)> {
    let start = text.len() - text.trim_start_matches(split::is_separator).len();
    let end = text.trim_end_matches(split::is_separator).len();
    let body = text.get(start..end)?;
    let open = body.chars().next()?;
    let close = body[open.len_utf8()..].chars().next_back()?;
    let pair = matches!(
        (open, close),
        ('"', '"')
            | ('\'', '\'')
            | ('`', '`')
            | ('\u{201C}', '\u{201D}')
            | ('\u{2018}', '\u{2019}')
            | ('«', '»')
            | ('\u{201E}', '\u{201C}')
    );
    pair.then(|| {
        (
            Span::new(start, start + open.len_utf8()),
            Span::new(end - close.len_utf8(), end),
        )
    })
}

/// pest always returns the rule's pair on success; should it not, the instruction is
/// reported rather than silently dropped.
fn unreachable_error(text: &str) -> pest::error::Error<Rule> {
    pest::error::Error::new_from_pos(
        ErrorVariant::CustomError {
            message: "no instruction read".into(),
        },
        pest::Position::from_start(text),
    )
}

/// `after_instruction`: between two instructions the fix leaves one separator; at either
/// end of the template (`, +10`, `0, 90,,`, `,` alone) it removes the whole run.
fn empty_instruction(text: &str, span: Span, after_instruction: bool) -> Diagnostic {
    // At the end, the span stops at the last comma: what follows is nothing or separators.
    let trailing = text
        .get(span.end..)
        .and_then(|rest| rest.chars().next())
        .is_none_or(split::is_separator);
    // `0, 90,`: one comma after the last instruction, which OrcaSlicer drops too when it
    // ends the text (a space or newline after it is a piece OrcaSlicer reads as 0).
    let one_trailing_comma = trailing && after_instruction && text.get(span.range()) == Some(",");
    let after_instruction = after_instruction && !trailing;
    let warning = Diagnostic::warning(
        "rotlang::empty-instruction",
        "an empty instruction is ignored",
    );
    if one_trailing_comma {
        return warning
            .with_primary(span, "nothing follows this comma")
            .with_fix("remove the trailing comma", span, "")
            .with_help(format!(
                "a comma separates instructions, and no instruction follows the last one; {}",
                orcaslicer_on_empty(text, span, "")
            ));
    }
    let replacement = if after_instruction { ", " } else { "" };
    warning
        .with_primary(span, "nothing between these separators")
        .with_fix("remove the extra separator", span, replacement)
        .with_help(orcaslicer_on_empty(text, span, replacement))
}

/// What OrcaSlicer makes of the empty instruction at `span`, asked of the dialect (a
/// trailing `0 , 90 ,` is dropped, `10,,20` is a 0° layer); for long texts, where each
/// question would read the whole text, the help says less.
fn orcaslicer_on_empty(text: &str, span: Span, replacement: &str) -> &'static str {
    if text.len() > 4096 {
        return "rotlang ignores it (OrcaSlicer may read it as a layer of its own: `rotlang check` says where)";
    }
    let without = format!("{}{replacement}{}", &text[..span.start], &text[span.end..]);
    // Left empty, the text would be a template OrcaSlicer reads as the profile's direction.
    if without.is_empty() || crate::dialect::compat::orcaslicer_change(text, &without).is_some() {
        "OrcaSlicer reads this empty instruction as a layer of its own; rotlang ignores it"
    } else {
        "rotlang ignores it, and so does OrcaSlicer here"
    }
}

/// The diagnostic for an instruction the grammar rejects.
fn chunk_error(
    text: &str,
    chunk: &Chunk<'_>,
    previous: Option<&Chunk<'_>>,
    err: pest::error::Error<Rule>,
) -> Diagnostic {
    // `+30/ 5cm`: a count cut off from its joint by a space.
    if let Some(prev) = previous
        && after_joint(prev, chunk)
    {
        let gap = Span::new(prev.span.end, chunk.span.start);
        return Diagnostic::error(
            "rotlang::space-after-joint",
            format!("`{}` is cut off from its joint by a space", chunk.text),
        )
        .with_primary(chunk.span, "not an instruction on its own")
        .with_secondary(gap, "this space ends the instruction before it")
        .with_fix("remove the space", gap, "")
        .with_help(format!("did you mean `{}{}`?", prev.text, chunk.text));
    }
    // `+30/50 %`, `+30/5,%`: a unit split off its count by a separator.
    if let Some(prev) = previous
        && prev.text.ends_with(|c: char| c.is_ascii_digit())
        && ["%", "mm", "cm", "m", "'", "\""].contains(&chunk.text)
    {
        let gap = Span::new(prev.span.end, chunk.span.start);
        let joined = format!("{}{}", prev.text, chunk.text);
        let what = if chunk.after_space_only {
            "space"
        } else {
            "separator"
        };
        return Diagnostic::error(
            "rotlang::space-before-unit",
            format!("the unit `{}` is cut off from its number", chunk.text),
        )
        .with_primary(chunk.span, "a unit on its own")
        .with_secondary(gap, format!("this {what} ends the instruction"))
        .with_fix(format!("remove the {what}"), gap, "")
        .with_help(format!("did you mean `{joined}`?"));
    }
    // `+30/1,5mm`: a decimal comma, read as a separator.
    if let Some(prev) = previous
        && prev.span.end + 1 == chunk.span.start
        && text.as_bytes().get(prev.span.end) == Some(&b',')
        && prev.text.ends_with(|c: char| c.is_ascii_digit())
        && chunk.text.starts_with(|c: char| c.is_ascii_digit())
        && RotParser::parse(Rule::instruction, &format!("{}.{}", prev.text, chunk.text)).is_ok()
    {
        let comma = Span::new(prev.span.end, chunk.span.start);
        return Diagnostic::error(
            "rotlang::decimal-comma",
            "a comma separates instructions; decimals use a dot",
        )
        .with_primary(
            comma,
            format!("did you mean `{}.{}`?", prev.text, chunk.text),
        )
        .with_secondary(chunk.span, "read as an instruction of its own")
        .with_fix("write a decimal point", comma, ".");
    }
    let pos = match err.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let expected = match err.variant {
        ErrorVariant::ParsingError { positives, .. } => positives,
        ErrorVariant::CustomError { .. } => Vec::new(),
    };
    // `45 deg`: the instruction a unit of angle follows, with the space between.
    let with_previous = previous
        .filter(|p| text[p.span.end..chunk.span.start].trim().is_empty())
        .map(|p| &text[p.span.start..chunk.span.end]);
    errors::Failure {
        text: chunk.text,
        with_previous,
        offset: chunk.span.start,
        pos,
        expected,
    }
    .diagnose()
}
