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
