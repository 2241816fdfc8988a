//! The OrcaSlicer compat lint in diagnostics (setting `compat`): where OrcaSlicer reads a
//! template differently, hangs or computes NaN angles (`rotlang::dialect::compat`). On by
//! default for JSON and `.ini` profiles (OrcaSlicer's files), on request for `.rot` files.
//! Each template is linted in its one reading (`Region::reading`): the profile's model and
//! base in a profile, the settings' model in a `.rot` file; hover and inlay hints use the
//! same.

use std::sync::Arc;

use rotlang::Diagnostic as Finding;
use tower_lsp_server::ls_types::{Diagnostic, Uri};

use crate::diagnostics::convert;
use crate::document::{Document, Findings};
use crate::position::Positions;
use crate::settings::ModelSettings;

/// Beside the document's own diagnostics (capped at their own limit).
pub const MAX_FINDINGS: usize = 100;

/// The findings of every template, with the index of its region, in document order. As
/// `rotlang check` reports them: a template with syntax errors gets them too (the library
/// then reports only OrcaSlicer's own problems and the rules, which hold whatever rotlang
/// makes of the text).
pub fn findings(doc: &Document, settings: &ModelSettings) -> Vec<(usize, Finding)> {
    if !settings.compat.applies_to(doc.kind) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (index, region) in doc.regions.iter().enumerate() {
        let found = match &region.profile {
            // The library's lint on the profile's model, with the options it decides.
            Some(profile) => profile.compat(&region.text, region.target),
            None => {
                let reading = region.reading(settings);
                rotlang::dialect::compat(
                    &region.text,
                    region.target,
                    &reading.model,
                    reading.options,
                )
            }
        };
        for d in found {
            if out.len() >= MAX_FINDINGS {
                return out;
            }
            out.push((index, d));
        }
    }
    out
}

/// The findings of `findings`, computed once per document and settings: the diagnostics
/// published and the code actions asked for later are the same findings.
pub fn cached(doc: &Document, settings: &ModelSettings) -> Findings {
    let lock = |doc: &Document| doc.compat.lock().unwrap_or_else(|p| p.into_inner()).clone();
    if let Some((for_settings, found)) = lock(doc)
        && for_settings == *settings
    {
        return found;
    }
    let found = Arc::new(findings(doc, settings));
    *doc.compat.lock().unwrap_or_else(|p| p.into_inner()) = Some((*settings, found.clone()));
    found
}

pub fn diagnostics(
    doc: &Document,
    findings: &[(usize, Finding)],
    uri: &Uri,
    pos: &Positions,
) -> Vec<Diagnostic> {
    findings
        .iter()
        .filter_map(|(i, d)| Some(convert(d, doc.regions.get(*i)?, uri, pos)))
        .collect()
}
