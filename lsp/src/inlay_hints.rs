//! Inlay hints: after each instruction, the turn it resolves to on the model, such as
//! `0°→22.5° over 50 layers` (its first run, where it first acts).

use rotlang::Span;
use tower_lsp_server::ls_types::{InlayHint, InlayHintKind, InlayHintLabel, InlayHintTooltip};

use crate::document::{Document, Region};
use crate::hover::turn_words;
use crate::position::{Cursor, Positions};
use crate::preview::{FIRST_RUN_BUDGET, first_run};
use crate::settings::ModelSettings;

/// Hints per request: an editor shows a screenful, not a megabyte's worth.
pub const MAX_HINTS: usize = 1000;

/// Hints for the instructions that end inside `range` (document bytes).
pub fn inlay_hints(
    doc: &Document,
    range: Span,
    model: &ModelSettings,
    pos: &Positions,
) -> Vec<InlayHint> {
    let mut hints = Vec::new();
    let mut cursor = Cursor::new(pos);
    let mut budget = FIRST_RUN_BUDGET;
    for (index, region) in doc.regions.iter().enumerate() {
        if region.contents.end < range.start || region.contents.start > range.end {
            continue;
        }
        let reading = region.reading(model);
        let Some(preview) = doc.preview(index, model) else {
            continue;
        };
        // The instructions whose end is in the range (spans are in text order), read
        // again from the text; the template the first runs evaluate is read once.
        let ends = |i: usize| region.spans.span(i).map(|s| region.doc_span(s).end);
        let n = region.spans.len();
        let first = Region::partition(n, |i| ends(i) < Some(range.start));
        let past = Region::partition(n, |i| ends(i) <= Some(range.end));
        let mut evaluated = None;
        let mut full = false;
        region.each_instruction(first..past, |i, ins| {
            let end = region.doc_span(ins.span).end;
            if end < range.start || end > range.end || ins.is_dummy() {
                return true;
            }
            if hints.len() >= MAX_HINTS {
                full = true;
                return false;
            }
            let run = first_run(
                region.source(),
                i,
                &reading,
                &mut budget,
                preview.reach,
                &mut evaluated,
            )
            .or_else(|| preview.instructions.get(&i).and_then(|p| p.first_block));
            let label = match run {
                Some(run) => turn_words(&ins, &run),
                None => "not reached".to_string(),
            };
            hints.push(InlayHint {
                position: cursor.position(end),
                label: InlayHintLabel::String(label),
                kind: Some(InlayHintKind::TYPE),
                text_edits: None,
                tooltip: Some(InlayHintTooltip::String(format!(
                    "first run on {}",
                    reading.describe
                ))),
                padding_left: Some(true),
                padding_right: Some(false),
                data: None,
            });
            true
        });
        if full {
            return hints;
        }
    }
    hints
}
