//! Diagnostics: the library's diagnostics, moved to document positions.

use rotlang::Severity;
use tower_lsp_server::ls_types::{
    Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri,
};

use crate::document::{Document, Region};
use crate::position::Positions;

/// At most this many diagnostics per document: a 1 MB paste of garbage must not produce
/// a million-entry notification that freezes the editor. The last one says what was cut.
pub const MAX_DIAGNOSTICS: usize = 200;

pub const SOURCE: &str = "rotlang";

/// The code `rotlang check` gives a profile value it does not use (`profile::value`).
pub const DUPLICATE: &str = "profile::value";

pub fn diagnostics(doc: &Document, uri: &Uri, pos: &Positions) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    if let Some((len, limit)) = doc.too_large {
        out.push(Diagnostic {
            range: pos.range(rotlang::Span::new(0, 0)),
            severity: Some(DiagnosticSeverity::WARNING),
            code: Some(NumberOrString::String(
                "rotlang-lsp::document-too-large".into(),
            )),
            source: Some(SOURCE.into()),
            message: format!(
                "this document is {len} bytes; rotlang checks documents up to {limit} bytes \
                 (setting `rotlang.maxDocumentBytes`)"
            ),
            ..Diagnostic::default()
        });
        return out;
    }
    if let Some((offset, message)) = &doc.json_error {
        let range = pos.range(rotlang::Span::new(*offset, *offset));
        out.push(Diagnostic {
            range,
            severity: Some(DiagnosticSeverity::ERROR),
            code: Some(NumberOrString::String("rotlang-lsp::json-syntax".into())),
            source: Some(SOURCE.into()),
            message: format!("not valid JSON: {message}; templates after this point may be missed"),
            ..Diagnostic::default()
        });
    }
    // A value a later one of the same key replaces: `rotlang check`'s warning, at its key.
    for dup in doc.duplicates.iter().take(MAX_DIAGNOSTICS / 2) {
        out.push(Diagnostic {
            range: pos.range(dup.key_span),
            severity: Some(DiagnosticSeverity::WARNING),
            code: Some(NumberOrString::String(DUPLICATE.into())),
            source: Some(SOURCE.into()),
            message: dup.message.clone(),
            related_information: Some(vec![DiagnosticRelatedInformation {
                location: Location::new(uri.clone(), pos.range(dup.used)),
                message: "the value that is used".into(),
            }]),
            ..Diagnostic::default()
        });
    }
    let total: usize = doc.regions.iter().map(|r| r.parse.diagnostics.len()).sum();
    // Past the cap errors go first: an error must never hide behind warnings (a
    // formatter refuses the document, and the user must see why).
    let all = || {
        doc.regions
            .iter()
            .flat_map(|r| r.parse.diagnostics.iter().map(move |d| (r, d)))
    };
    let ordered: Box<dyn Iterator<Item = _>> = if out.len() + total > MAX_DIAGNOSTICS {
        Box::new(
            all()
                .filter(|(_, d)| d.is_error())
                .chain(all().filter(|(_, d)| !d.is_error())),
        )
    } else {
        Box::new(all())
    };
    for (region, d) in ordered {
        if out.len() >= MAX_DIAGNOSTICS {
            out.push(truncated(total, pos));
            return out;
        }
        out.push(convert(d, region, uri, pos));
    }
    out
}

/// One library diagnostic as an LSP diagnostic. The `message` is the message alone: it is
/// what an editor shows in its one-line echo area or squiggle tooltip. Every label (the
/// primary one at the diagnostic's own range) and the help go to related information,
/// which editors show on demand, each at its place.
pub fn convert(d: &rotlang::Diagnostic, region: &Region, uri: &Uri, pos: &Positions) -> Diagnostic {
    let range = pos.range(region.doc_span(d.primary_span()));
    let at = |span| Location::new(uri.clone(), pos.range(region.doc_span(span)));
    let mut related: Vec<_> = d
        .labels
        .iter()
        .filter(|l| !(l.primary && (l.message.is_empty() || l.message == d.message)))
        .map(|l| DiagnosticRelatedInformation {
            location: at(l.span),
            message: if l.message.is_empty() {
                "related".into()
            } else {
                l.message.clone()
            },
        })
        .collect();
    if let Some(help) = &d.help {
        related.push(DiagnosticRelatedInformation {
            location: at(d.primary_span()),
            message: format!("help: {help}"),
        });
    }
    Diagnostic {
        range,
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
        }),
        code: Some(NumberOrString::String(d.code.to_string())),
        source: Some(SOURCE.into()),
        message: d.message.clone(),
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

fn truncated(total: usize, pos: &Positions) -> Diagnostic {
    Diagnostic {
        range: pos.range(rotlang::Span::new(0, 0)),
        severity: Some(DiagnosticSeverity::INFORMATION),
        code: Some(NumberOrString::String("rotlang-lsp::too-many".into())),
        source: Some(SOURCE.into()),
        message: format!("{total} problems; only the first {MAX_DIAGNOSTICS} are shown"),
        ..Diagnostic::default()
    }
}
