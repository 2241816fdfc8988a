//! Code actions: a quick fix for every diagnostic in the range that carries a safe `fix`,
//! the library's own and the compat lint's alike (`.rot`, JSON and `.ini`).

use std::collections::HashMap;

use rotlang::Span;
use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, TextEdit, Uri, WorkspaceEdit,
};

use crate::diagnostics::convert;
use crate::document::{Document, Region};
use crate::position::Positions;

/// Quick fixes for the diagnostics whose primary span touches `range` (document bytes):
/// the templates' own, then the compat findings published beside them (`compat`, with
/// the index of their region).
pub fn code_actions(
    doc: &Document,
    uri: &Uri,
    range: Span,
    pos: &Positions,
    compat: &[(usize, rotlang::Diagnostic)],
) -> Vec<CodeActionOrCommand> {
    let own = doc
        .regions
        .iter()
        .flat_map(|r| r.parse.diagnostics.iter().map(move |d| (r, d)));
    let linted = compat
        .iter()
        .filter_map(|(i, d)| Some((doc.regions.get(*i)?, d)));
    own.chain(linted)
        .filter(|(region, _)| {
            region.contents.end >= range.start && region.contents.start <= range.end
        })
        .filter_map(|(region, d)| action(doc, uri, range, pos, region, d))
        .collect()
}

fn action(
    doc: &Document,
    uri: &Uri,
    range: Span,
    pos: &Positions,
    region: &Region,
    d: &rotlang::Diagnostic,
) -> Option<CodeActionOrCommand> {
    let fix = d.fix.as_ref()?;
    let at = region.doc_span(d.primary_span());
    if at.end < range.start || at.start > range.end {
        return None;
    }
    let edit = TextEdit::new(
        pos.range(region.doc_span(fix.span)),
        doc.encode(&fix.replacement),
    );
    Some(CodeActionOrCommand::CodeAction(CodeAction {
        title: fix.title.clone(),
        kind: Some(CodeActionKind::QUICKFIX),
        diagnostics: Some(vec![convert(d, region, uri, pos)]),
        edit: Some(WorkspaceEdit {
            changes: Some(HashMap::from([(uri.clone(), vec![edit])])),
            ..WorkspaceEdit::default()
        }),
        is_preferred: Some(true),
        ..CodeAction::default()
    }))
}
