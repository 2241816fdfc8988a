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
    run(inputs(doc, settings))
}

/// What the lint of one template reads, owned: the lint of a long profile takes seconds,
/// and the document it came from must not be held meanwhile (the next analysis is made
/// from it in place).
pub struct Input {
    index: usize,
    text: Arc<String>,
    target: rotlang::Target,
    profile: Option<rotlang_profile::profile::ProfileModel>,
    reading: crate::reading::Reading,
}

/// The templates to lint (none where the setting leaves the document out).
pub fn inputs(doc: &Document, settings: &ModelSettings) -> Vec<Input> {
    if !settings.compat.applies_to(doc.kind) {
        return Vec::new();
    }
    doc.regions
        .iter()
        .enumerate()
        .map(|(index, region)| Input {
            index,
            text: region.text.clone(),
            target: region.target,
            profile: region.profile.clone(),
            reading: region.reading(settings),
        })
        .collect()
}

/// The bytes of template text to lint.
pub fn size(inputs: &[Input]) -> usize {
    inputs.iter().map(|i| i.text.len()).sum()
}

/// The findings of the templates, with the index of each one's region, in document order.
pub fn run(inputs: Vec<Input>) -> Vec<(usize, Finding)> {
    let mut out = Vec::new();
    for input in inputs {
        let found = match &input.profile {
            // The library's lint on the profile's model, with the options it decides.
            Some(profile) => profile.compat(&input.text, input.target),
            None => rotlang::dialect::compat(
                &input.text,
                input.target,
                &input.reading.model,
                input.reading.options,
            ),
        };
        for d in found {
            if out.len() >= MAX_FINDINGS {
                return out;
            }
            out.push((input.index, d));
        }
    }
    out
}

/// The findings cached for these settings, if computed already.
pub fn cached_only(doc: &Document, settings: &ModelSettings) -> Option<Findings> {
    let cached = doc.compat.lock().unwrap_or_else(|p| p.into_inner()).clone();
    cached
        .filter(|(s, _)| s == settings)
        .map(|(_, found)| found)
}

/// Keep findings computed elsewhere (`run`) for the document and settings.
pub fn store(doc: &Document, settings: &ModelSettings, found: Findings) {
    *doc.compat.lock().unwrap_or_else(|p| p.into_inner()) = Some((*settings, found));
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
