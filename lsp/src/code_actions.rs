//! Code actions: a quick fix for every diagnostic in the range that carries a safe `fix`.

use std::collections::HashMap;

use rotlang::Span;
use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, TextEdit, Uri, WorkspaceEdit,
};

use crate::diagnostics::convert;
use crate::document::Document;
use crate::position::Positions;

/// Quick fixes for the diagnostics whose primary span touches `range` (document bytes).
pub fn code_actions(
    doc: &Document,
    uri: &Uri,
    range: Span,
    pos: &Positions,
) -> Vec<CodeActionOrCommand> {
    let mut actions = Vec::new();
    for region in &doc.regions {
        if region.contents.end < range.start || region.contents.start > range.end {
            continue;
        }
        for d in &region.parse.diagnostics {
            let Some(fix) = &d.fix else { continue };
            let at = region.doc_span(d.primary_span());
            if at.end < range.start || at.start > range.end {
                continue;
            }
            let edit = TextEdit::new(
                pos.range(region.doc_span(fix.span)),
                doc.encode(&fix.replacement),
            );
            actions.push(CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title.clone(),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![convert(d, region, uri, pos)]),
                edit: Some(WorkspaceEdit {
                    changes: Some(HashMap::from([(uri.clone(), vec![edit])])),
                    ..WorkspaceEdit::default()
                }),
                is_preferred: Some(true),
                ..CodeAction::default()
            }));
        }
    }
    actions
}
