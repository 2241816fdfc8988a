//! Semantic tokens (full document) from the IR's spans.
//!
//! The legend uses standard token types, so every theme colours templates without setup,
//! plus one custom modifier per part of an instruction, so a theme can tell them apart:
//!
//! | part          | token type   | modifier  | example        |
//! |---------------|--------------|-----------|----------------|
//! | angle         | `number`     | `angle`   | `22.5`, `25%`, `1:4` |
//! | sign          | `operator`   | `sign`    | `+`, `-` before the angle |
//! | runtime mark  | `keyword`    | `runtime` | `*`, `*3`, `!` |
//! | solid sign    | `enumMember` | `solid`   | `D S O M R`    |
//! | joint         | `function`   | `joint`   | `/ N n Z z $ L l U u Q q ~ ^ \| #` |
//! | flip          | `operator`   | `flip`    | `-` before the count |
//! | count         | `number`     | `count`   | `50`, `1:2`; `B`/`T` are `variable` + `count` |
//! | unit          | `type`       | `unit`    | `mm cm m ' " # %` |

use rotlang::{CountKind, Instruction, Span};
use tower_lsp_server::ls_types::{
    SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokens, SemanticTokensLegend,
};

use crate::document::{Document, Region};
use crate::position::{Cursor, Positions};

/// A 1 MB template has hundreds of thousands of tokens; past this many the rest of the
/// document stays uncoloured rather than sending tens of megabytes.
pub const MAX_TOKENS: usize = 100_000;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    Angle,
    Sign,
    Runtime,
    Solid,
    Joint,
    Flip,
    Count,
    ShellCount,
    Unit,
}

const TYPES: [SemanticTokenType; 7] = [
    SemanticTokenType::NUMBER,
    SemanticTokenType::OPERATOR,
    SemanticTokenType::KEYWORD,
    SemanticTokenType::ENUM_MEMBER,
    SemanticTokenType::FUNCTION,
    SemanticTokenType::VARIABLE,
    SemanticTokenType::TYPE,
];

const MODIFIERS: [&str; 8] = [
    "angle", "sign", "runtime", "solid", "joint", "flip", "count", "unit",
];

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: TYPES.to_vec(),
        token_modifiers: MODIFIERS
            .iter()
            .map(|m| SemanticTokenModifier::new(m))
            .collect(),
    }
}

impl Part {
    /// (index into the token types, modifier bit set).
    fn encode(self) -> (u32, u32) {
        let (ty, modifier) = match self {
            Part::Angle => (0, 0),
            Part::Sign => (1, 1),
            Part::Runtime => (2, 2),
            Part::Solid => (3, 3),
            Part::Joint => (4, 4),
            Part::Flip => (1, 5),
            Part::Count => (0, 6),
            Part::ShellCount => (5, 6),
            Part::Unit => (6, 7),
        };
        (ty, 1 << modifier)
    }
}

/// The parts of one instruction, as template spans.
pub fn parts(text: &str, ins: &Instruction) -> Vec<(Span, Part)> {
    let mut out = Vec::new();
    if let Some(angle) = &ins.angle {
        let mut rest = angle.span;
        if angle.sign.is_some() && !rest.is_empty() {
            out.push((Span::new(rest.start, rest.start + 1), Part::Sign));
            rest.start += 1;
        }
        out.push((rest, Part::Angle));
    }
    if let Some(r) = ins.repeat {
        // Include the `*` when the span holds only the number.
        let mut span = r.span;
        if span.start > 0
            && text.as_bytes().get(span.start - 1) == Some(&b'*')
            && text.as_bytes().get(span.start) != Some(&b'*')
        {
            span.start -= 1;
        }
        out.push((span, Part::Runtime));
    }
    for span in [ins.dummy, ins.one_time].into_iter().flatten() {
        out.push((span, Part::Runtime));
    }
    if let Some(s) = ins.solid {
        out.push((s.span, Part::Solid));
    }
    if let Some(j) = ins.joint {
        out.push((j.span, Part::Joint));
    }
    if let Some(f) = ins.flip {
        out.push((f, Part::Flip));
    }
    if let Some(count) = ins.count {
        match count.kind {
            CountKind::Bottom | CountKind::Top => out.push((count.span, Part::ShellCount)),
            CountKind::Length { unit, .. } => {
                let symbol = unit.symbol();
                let inside = text.get(count.span.range()).unwrap_or("");
                if inside.ends_with(symbol) && inside.len() > symbol.len() {
                    let cut = count.span.end - symbol.len();
                    out.push((Span::new(count.span.start, cut), Part::Count));
                    out.push((Span::new(cut, count.span.end), Part::Unit));
                } else if text
                    .get(count.span.end..)
                    .is_some_and(|t| t.starts_with(symbol))
                {
                    out.push((count.span, Part::Count));
                    out.push((
                        Span::new(count.span.end, count.span.end + symbol.len()),
                        Part::Unit,
                    ));
                } else {
                    out.push((count.span, Part::Count));
                }
            }
            _ => out.push((count.span, Part::Count)),
        }
    }
    out.retain(|(s, _)| !s.is_empty());
    out.sort_by_key(|(s, _)| s.start);
    out
}

/// Every token of the document, delta-encoded as the protocol wants.
pub fn tokens(doc: &Document, pos: &Positions) -> SemanticTokens {
    let mut absolute: Vec<(Span, Part)> = Vec::new();
    'regions: for region in &doc.regions {
        let mut full = false;
        region.each_instruction(0..region.spans.len(), |_, ins| {
            for (span, part) in parts(&region.text, &ins) {
                if absolute.len() >= MAX_TOKENS {
                    full = true;
                    return false;
                }
                absolute.push((region_span(region, span), part));
            }
            true
        });
        if full {
            break 'regions;
        }
    }
    absolute.sort_by_key(|(s, _)| s.start);
    let mut data = Vec::with_capacity(absolute.len());
    let (mut line, mut col, mut end) = (0u32, 0u32, 0usize);
    let mut cursor = Cursor::new(pos);
    for (span, part) in absolute {
        if span.start < end {
            continue; // overlapping tokens are not allowed; keep the first
        }
        let start = cursor.position(span.start);
        let stop = cursor.position(span.end);
        if start.line != stop.line {
            continue; // tokens cannot span lines
        }
        let (ty, modifiers) = part.encode();
        data.push(SemanticToken {
            delta_line: start.line - line,
            delta_start: if start.line == line {
                start.character - col
            } else {
                start.character
            },
            length: stop.character - start.character,
            token_type: ty,
            token_modifiers_bitset: modifiers,
        });
        (line, col, end) = (start.line, start.character, span.end);
    }
    SemanticTokens {
        result_id: None,
        data,
    }
}

fn region_span(region: &Region, span: Span) -> Span {
    region.doc_span(span)
}
