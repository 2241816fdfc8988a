//! The OrcaSlicer dialect in the CLI: `rotlang expand --dialect orcaslicer`.

use std::io::{ErrorKind, Write};

use super::UsageError;
use crate::dialect::orcaslicer;
use crate::eval::{Model, Options};

/// Expands `text` as OrcaSlicer reads it (no grammar: any text has a meaning), writing the
/// layers with `write`, then the findings (hang, undefined behaviour, NaN layers) to `err`.
pub(crate) fn expand(
    text: &str,
    model: &Model,
    options: Options,
    err: &mut dyn Write,
    write: impl FnOnce(&mut orcaslicer::Layers<'_>) -> std::io::Result<()>,
) -> Result<i32, UsageError> {
    let mut layers = orcaslicer::layers(text, model, options);
    match write(&mut layers) {
        Ok(()) => {}
        Err(e) if e.kind() == ErrorKind::BrokenPipe => return Ok(0),
        Err(e) => return Err(UsageError(format!("cannot write output: {e}"))),
    }
    for finding in layers.findings() {
        let layers = match finding.layers {
            1 => "1 layer".to_owned(),
            n => format!("{n} layers"),
        };
        writeln!(
            err,
            "warning[{}]: {} ({layers} from layer {}; rotlang shows finite angles there)",
            finding.code, finding.message, finding.first_layer
        )
        .map_err(|e| UsageError(format!("cannot write to stderr: {e}")))?;
    }
    Ok(0)
}

/// A finding as a diagnostic of `--format json` (the object `check` prints for each
/// diagnostic), with the layers it concerns. A hang has no one token at fault: its span is
/// the whole template.
pub(crate) fn finding_json(
    index: &crate::LineIndex<'_>,
    text: &str,
    finding: &crate::dialect::Finding,
) -> serde_json::Value {
    let span = finding.span.unwrap_or(crate::Span::new(0, text.len()));
    let d =
        crate::Diagnostic::warning(finding.code, finding.message.clone()).with_primary(span, "");
    let mut value = super::diagnostic_json(index, &d);
    value["first_layer"] = finding.first_layer.into();
    value["layers"] = finding.layers.into();
    value
}
