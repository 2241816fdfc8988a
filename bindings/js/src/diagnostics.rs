//! Diagnostics as JSON for JavaScript: byte offsets (as the core has them) and UTF-16
//! offsets (JavaScript string indices, what CodeMirror and Monaco take), line and column.

use crate::json::Value;
use crate::obj;
use rotlang::{Diagnostic, LineIndex, Span};

use crate::utf16::Utf16Map;

/// The JSON array of `diagnostics` on `text`.
pub fn to_json(text: &str, diagnostics: &[Diagnostic]) -> Value {
    let mut offsets = Vec::new();
    for d in diagnostics {
        let p = d.primary_span();
        offsets.extend([p.start, p.end]);
        for l in &d.labels {
            offsets.extend([l.span.start, l.span.end]);
        }
        if let Some(f) = &d.fix {
            offsets.extend([f.span.start, f.span.end]);
        }
    }
    let map = Utf16Map::new(text, offsets);
    let lines = LineIndex::new(text);
    let span = |s: Span| {
        obj!({
            "start": s.start,
            "end": s.end,
            "startUtf16": map.get(s.start),
            "endUtf16": map.get(s.end),
        })
    };
    let with = Value::merged;
    diagnostics
        .iter()
        .map(|d| {
            let primary = d.primary_span();
            let (line, column) = lines.line_col(primary.start);
            with(
                span(primary),
                obj!({
                    "code": d.code,
                    "severity": d.severity.as_str(),
                    "message": d.message,
                    "line": line,
                    "column": column,
                    "help": d.help,
                    "labels": d.labels.iter().map(|l| with(span(l.span), obj!({
                        "message": l.message,
                        "primary": l.primary,
                    }))).collect::<Vec<_>>(),
                    "fix": d.fix.as_ref().map(|f| with(span(f.span), obj!({
                        "title": f.title,
                        "replacement": f.replacement,
                    }))),
                }),
            )
        })
        .collect()
}
