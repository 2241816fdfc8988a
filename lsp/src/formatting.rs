//! Formatting through the core formatter: one edit replacing the whole document, or
//! nothing when any template has errors (the formatter never guesses at broken text).

use tower_lsp_server::ls_types::TextEdit;

use crate::document::{Document, Kind};
use crate::position::Positions;

/// `None` when a template has errors; an empty list when the document is already
/// formatted; otherwise a single whole-document edit.
pub fn formatting(doc: &Document, pos: &Positions) -> Option<Vec<TextEdit>> {
    let formatted = formatted_text(doc)?;
    if formatted == doc.text {
        return Some(Vec::new());
    }
    let whole = rotlang::Span::new(0, doc.text.len());
    Some(vec![TextEdit::new(pos.range(whole), formatted)])
}

/// The document with every template in canonical form.
pub fn formatted_text(doc: &Document) -> Option<String> {
    match doc.kind {
        Kind::Rot => {
            let region = doc.regions.first()?;
            let body = rotlang::format::format(&region.text, region.target)?;
            // Keep the file's final newline (editors and `git diff` care), and nothing else.
            let newline = if doc.text.ends_with('\n') && !body.is_empty() {
                "\n"
            } else {
                ""
            };
            Some(format!("{body}{newline}"))
        }
        Kind::Json => {
            let mut out = String::with_capacity(doc.text.len());
            let mut copied = 0;
            for region in &doc.regions {
                let body = rotlang::format::format(&region.text, region.target)?;
                out.push_str(doc.text.get(copied..region.contents.start)?);
                if body == region.text {
                    // Unchanged templates keep their original escapes byte for byte.
                    out.push_str(doc.text.get(region.contents.range())?);
                } else {
                    out.push_str(&doc.encode(&body));
                }
                copied = region.contents.end;
            }
            out.push_str(doc.text.get(copied..)?);
            Some(out)
        }
    }
}
