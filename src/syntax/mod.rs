//! Text → syntax tree → IR. The only code that sees pest.

mod errors;
mod grammar;
mod lower;
pub(crate) mod split;

use pest::Parser;
use pest::error::{ErrorVariant, InputLocation};

use crate::diagnostic::{Diagnostic, Span};
use crate::{Parse, Target, Template};
use grammar::{RotParser, Rule};
use split::Chunk;

/// At most this many diagnostics are kept per template; a 1 MB file of garbage must not
/// produce a million reports.
pub const MAX_DIAGNOSTICS: usize = 100;

pub(crate) fn parse(text: &str, target: Target) -> Parse {
    let split = split::split(text);
    let mut diagnostics = Vec::new();
    let mut instructions = Vec::with_capacity(split.chunks.len());
    for span in &split.empties {
        diagnostics.push(
            Diagnostic::warning(
                "rotlang::empty-instruction",
                "an empty instruction is ignored",
            )
            .with_primary(*span, "nothing between these separators")
            .with_fix(
                "remove the extra separator",
                *span,
                if instructions_before(&split.chunks, *span) {
                    ", "
                } else {
                    ""
                },
            )
            .with_help("OrcaSlicer reads an empty instruction as `0`; rotlang ignores it"),
        );
    }
    let mut previous: Option<Chunk<'_>> = None;
    for chunk in &split.chunks {
        match RotParser::parse(Rule::instruction, chunk.text) {
            Ok(mut pairs) => {
                if let Some(pair) = pairs.next() {
                    let mut lowerer = lower::Lowerer {
                        offset: chunk.span.start,
                        diagnostics: &mut diagnostics,
                    };
                    if let Some(ins) = lowerer.instruction(pair) {
                        instructions.push(ins);
                    }
                }
            }
            Err(err) => diagnostics.push(chunk_error(text, chunk, previous.as_ref(), err)),
        }
        previous = Some(*chunk);
    }
    let template = Template { instructions };
    crate::lint::check(text, &template, &split.chunks, target, &mut diagnostics);
    diagnostics.sort_by_key(|d| (d.primary_span().start, std::cmp::Reverse(d.severity)));
    cap(&mut diagnostics);
    Parse {
        template,
        diagnostics,
    }
}

fn instructions_before(chunks: &[Chunk<'_>], span: Span) -> bool {
    chunks.first().is_some_and(|c| c.span.end <= span.start)
}

/// Keeps the first `MAX_DIAGNOSTICS` and says how many more there were.
fn cap(diagnostics: &mut Vec<Diagnostic>) {
    if diagnostics.len() <= MAX_DIAGNOSTICS {
        return;
    }
    let more = diagnostics.len() - MAX_DIAGNOSTICS;
    let errors = diagnostics.iter().any(Diagnostic::is_error);
    let last = diagnostics[MAX_DIAGNOSTICS - 1].primary_span();
    diagnostics.truncate(MAX_DIAGNOSTICS);
    let d = if errors {
        Diagnostic::error(
            "rotlang::too-many-diagnostics",
            format!("{more} more diagnostics not shown"),
        )
    } else {
        Diagnostic::warning(
            "rotlang::too-many-diagnostics",
            format!("{more} more diagnostics not shown"),
        )
    };
    diagnostics.push(
        d.with_primary(Span::new(last.end, last.end), "and more after this")
            .with_help("fix the ones above first; the rest are often the same mistake"),
    );
}

/// The diagnostic for an instruction the grammar rejects.
fn chunk_error(
    text: &str,
    chunk: &Chunk<'_>,
    previous: Option<&Chunk<'_>>,
    err: pest::error::Error<Rule>,
) -> Diagnostic {
    // `+30/50 %`: a unit split off its count by a space.
    if let Some(prev) = previous.filter(|_| chunk.after_space_only)
        && prev.text.ends_with(|c: char| c.is_ascii_digit())
        && ["%", "mm", "cm", "m", "'", "\""].contains(&chunk.text)
    {
        let gap = Span::new(prev.span.end, chunk.span.start);
        let joined = format!("{}{}", prev.text, chunk.text);
        return Diagnostic::error(
            "rotlang::space-before-unit",
            format!("the unit `{}` is cut off from its number", chunk.text),
        )
        .with_primary(chunk.span, "a unit on its own")
        .with_secondary(gap, "this space separates instructions")
        .with_fix("remove the space", gap, "")
        .with_help(format!(
            "did you mean `{joined}`? A space ends an instruction"
        ));
    }
    let pos = match err.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let expected = match err.variant {
        ErrorVariant::ParsingError { positives, .. } => positives,
        ErrorVariant::CustomError { .. } => Vec::new(),
    };
    let _ = text;
    errors::Failure {
        text: chunk.text,
        offset: chunk.span.start,
        pos,
        expected,
    }
    .diagnose()
}
