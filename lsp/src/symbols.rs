//! Document symbols: the instructions (under their key in a JSON profile), for outlines
//! and "go to symbol".

use tower_lsp_server::ls_types::{DocumentSymbol, SymbolKind};

use crate::document::{Document, Region};
use crate::hover::describe;
use crate::position::{Cursor, Positions};
use crate::reading::Reading;
use crate::settings::ModelSettings;

/// Symbols per document: an outline of a 1 MB template is no use past this.
pub const MAX_SYMBOLS: usize = 5000;

pub fn symbols(doc: &Document, model: &ModelSettings, pos: &Positions) -> Vec<DocumentSymbol> {
    let mut budget = MAX_SYMBOLS;
    let mut out = Vec::new();
    for region in &doc.regions {
        let children = instructions(region, &region.reading(model), pos, &mut budget);
        match (&region.key, region.key_span) {
            (Some(key), Some(key_span)) => {
                let whole = key_span.cover(region.contents);
                out.push(symbol(
                    key.clone(),
                    Some(region.text.chars().take(80).collect()),
                    SymbolKind::PROPERTY,
                    pos.range(whole),
                    pos.range(key_span),
                    Some(children),
                ));
            }
            _ => out.extend(children),
        }
    }
    out
}

fn instructions(
    region: &Region,
    reading: &Reading,
    pos: &Positions,
    budget: &mut usize,
) -> Vec<DocumentSymbol> {
    let mut out = Vec::new();
    // Instructions come in text order: the cursor keeps a one-line 1 MB template linear.
    let mut cursor = Cursor::new(pos);
    region.each_instruction(0..region.spans.len(), |_, ins| {
        if *budget == 0 || ins.span.is_empty() {
            return false;
        }
        *budget -= 1;
        let span = region.doc_span(ins.span);
        let range = tower_lsp_server::ls_types::Range::new(
            cursor.position(span.start),
            cursor.position(span.end),
        );
        let name = region.text.get(ins.span.range()).unwrap_or("?").to_string();
        out.push(symbol(
            name,
            Some(describe(&ins, reading)),
            SymbolKind::OPERATOR,
            range,
            range,
            None,
        ));
        true
    });
    out
}

#[allow(deprecated)] // `deprecated` is a required field of the struct, deprecated itself
fn symbol(
    name: String,
    detail: Option<String>,
    kind: SymbolKind,
    range: tower_lsp_server::ls_types::Range,
    selection_range: tower_lsp_server::ls_types::Range,
    children: Option<Vec<DocumentSymbol>>,
) -> DocumentSymbol {
    DocumentSymbol {
        // Clients reject empty names.
        name: if name.is_empty() { "\"\"".into() } else { name },
        detail,
        kind,
        tags: None,
        deprecated: None,
        range,
        selection_range,
        children,
    }
}
