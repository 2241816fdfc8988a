//! Formatting through the core formatter: one edit replacing the whole document, or
//! nothing when any template has errors (the formatter never guesses at broken text).
//! Where OrcaSlicer's reading matters (setting `compat`: JSON and `.ini` profiles by
//! default), a template OrcaSlicer would read differently once formatted (`0,,90` is 0°,
//! 0°, 90° for it) is left as it is, as `rotlang fmt` does without `--force`.

use tower_lsp_server::ls_types::TextEdit;

use crate::document::{Document, Kind};
use crate::position::Positions;

/// `None` when a template has errors; an empty list when the document is already
/// formatted; otherwise a single whole-document edit.
pub fn formatting(doc: &Document, pos: &Positions, keep_orcaslicer: bool) -> Option<Vec<TextEdit>> {
    let formatted = formatted_keeping(doc, keep_orcaslicer)?;
    if formatted == *doc.text {
        return Some(Vec::new());
    }
    let whole = rotlang::Span::new(0, doc.text.len());
    Some(vec![TextEdit::new(pos.range(whole), formatted)])
}

/// Whether OrcaSlicer would read `formatted` differently from `text` (the library's
/// check, shared with `rotlang fmt`).
fn orcaslicer_reads_differently(text: &str, formatted: &str) -> bool {
    let line = |t: &'_ str| -> String {
        let t = t.strip_suffix('\n').unwrap_or(t);
        t.strip_suffix('\r').unwrap_or(t).to_owned()
    };
    let (before, after) = (line(text), line(formatted));
    before != after && rotlang::dialect::compat::orcaslicer_change(&before, &after).is_some()
}

/// The document with every template in canonical form.
pub fn formatted_text(doc: &Document) -> Option<String> {
    formatted_keeping(doc, false)
}

/// [`formatted_text`]; with `keep_orcaslicer`, templates OrcaSlicer would read
/// differently once formatted stay as they are.
pub fn formatted_keeping(doc: &Document, keep_orcaslicer: bool) -> Option<String> {
    match doc.kind {
        Kind::Rot => {
            let region = doc.regions.first()?;
            if region.parse.has_errors() {
                return None;
            }
            let formatted = rot_layout(&region.text, &region.spans);
            if keep_orcaslicer && orcaslicer_reads_differently(&region.text, &formatted) {
                return Some(doc.text.to_string());
            }
            Some(formatted)
        }
        Kind::Json | Kind::Jsonc | Kind::Ini => {
            let mut out = String::with_capacity(doc.text.len());
            let mut copied = 0;
            for region in &doc.regions {
                let body = rotlang::format::format(&region.text, region.target)?;
                out.push_str(doc.text.get(copied..region.contents.start)?);
                if body == *region.text
                    || (keep_orcaslicer && orcaslicer_reads_differently(&region.text, &body))
                {
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

/// A `.rot` file in canonical form that keeps its lines: instructions the file puts on
/// separate lines stay on separate lines (one line break, in the file's own style), those
/// on one line are joined with `, `. The file's final line break is kept, nothing else.
fn rot_layout(text: &str, spans: &crate::instructions::Spans) -> String {
    let newline = match text.find(['\r', '\n']) {
        Some(i) if text[i..].starts_with("\r\n") => "\r\n",
        Some(i) => &text[i..i + 1],
        None => "\n",
    };
    let mut out = String::with_capacity(text.len());
    let mut previous_end = None;
    for span in spans.iter() {
        if let Some(end) = previous_end {
            let gap: &str = &text[end..span.start];
            out.push_str(if gap.contains(['\r', '\n']) {
                newline
            } else {
                ", "
            });
        }
        out.push_str(&text[span.range()]);
        previous_end = Some(span.end);
    }
    if !out.is_empty() && text.ends_with(['\r', '\n']) {
        out.push_str(newline);
    }
    out
}
