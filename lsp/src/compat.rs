//! The OrcaSlicer compat lint in diagnostics (setting `compat`): where OrcaSlicer reads a
//! template differently, hangs or computes NaN angles (`rotlang::dialect::compat`). On by
//! default for JSON and `.ini` profiles (OrcaSlicer's files), evaluated on the profile's own
//! model; on request for `.rot` files, on the model of the settings.

use std::path::Path;

use rotlang::eval::Options;
use tower_lsp_server::ls_types::{Diagnostic, Uri};

use crate::diagnostics::convert;
use crate::document::{Document, Kind};
use crate::position::Positions;
use crate::settings::ModelSettings;

/// Beside the document's own diagnostics (capped at their own limit).
const MAX_FINDINGS: usize = 100;

pub fn diagnostics(
    doc: &Document,
    uri: &Uri,
    pos: &Positions,
    settings: &ModelSettings,
) -> Vec<Diagnostic> {
    if !settings.compat.applies_to(doc.kind) {
        return Vec::new();
    }
    // The profile's own layer heights, shells and direction (a name that says its kind).
    let name = match doc.kind {
        Kind::Rot => None,
        Kind::Json => Some("profile.json"),
        Kind::Jsonc => Some("profile.jsonc"),
        Kind::Ini => Some("profile.ini"),
    };
    let profile = name.and_then(|n| {
        let mut p = rotlang::profile::parse(Path::new(n), doc.text.as_bytes()).ok()?;
        // A file on disk: its `inherits` parents are found beside it, as the CLI finds them.
        if let Some(path) = uri.to_file_path() {
            p.path = path.into_owned();
            p.resolve_inherits();
        }
        Some(p)
    });
    let mut out = Vec::new();
    // A template with errors gets those first: OrcaSlicer's view of text rotlang rejects
    // would only add noise until it is fixed.
    for region in doc.regions.iter().filter(|r| !r.parse.has_errors()) {
        let found = match &profile {
            Some(p) => p
                .model(region.target, None, rotlang::profile::DEFAULT_OBJECT_HEIGHT)
                .compat(&region.text, region.target),
            None => rotlang::dialect::compat(
                &region.text,
                region.target,
                &crate::preview::model_of(settings),
                Options::default(),
            ),
        };
        for d in found {
            if out.len() >= MAX_FINDINGS {
                return out;
            }
            out.push(convert(&d, region, uri, pos));
        }
    }
    out
}
