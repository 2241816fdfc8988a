//! The OrcaSlicer dialect, and `explain`.

use pyo3::prelude::*;

use rotlang_core::Target;
use rotlang_core::eval::{Model, Options};

use rotlang_core::dialect::orcaslicer;

use crate::evaluated::{Evaluated, Finding};

pub const NAMES: [&str; 2] = rotlang_core::api::DIALECTS;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    Rotlang,
    OrcaSlicer,
}

impl Dialect {
    /// The dialect named `name`; the caller turns a refusal into Python's exception.
    pub fn from_name(name: &str) -> Result<Dialect, rotlang_core::api::ApiError> {
        match rotlang_core::api::dialect(name)? {
            rotlang_core::dialect::Dialect::OrcaSlicer => Ok(Dialect::OrcaSlicer),
            rotlang_core::dialect::Dialect::Rotlang => Ok(Dialect::Rotlang),
        }
    }
}

/// Evaluates `text` in a dialect other than rotlang's (which needs a parse first).
pub fn evaluate(
    py: Python<'_>,
    dialect: Dialect,
    text: &str,
    model: &Model,
    options: Options,
    want_fills: bool,
) -> PyResult<Evaluated> {
    match dialect {
        Dialect::OrcaSlicer => Ok(py.detach(|| {
            let mut layers = orcaslicer::layers(text, model, options);
            let mut angles = Vec::with_capacity(model.len());
            let mut fills = Vec::new();
            for layer in layers.by_ref() {
                angles.push(layer.angle);
                if want_fills {
                    fills.push(layer.fill.name());
                }
            }
            let findings = layers
                .findings()
                .iter()
                .map(|f| Finding {
                    code: f.code.to_string(),
                    message: f.message.clone(),
                    first_layer: f.first_layer,
                    layers: f.layers,
                })
                .collect();
            Evaluated {
                angles,
                fills,
                findings,
            }
        })),
        Dialect::Rotlang => Err(pyo3::exceptions::PyValueError::new_err(
            "the rotlang dialect parses first",
        )),
    }
}

/// The template in words (`rotlang::explain::template`) on `model` (default: the cube).
pub fn explain(py: Python<'_>, text: &str, target: Target, model: Option<&Model>) -> String {
    let cube;
    let model = match model {
        Some(m) => m,
        None => {
            cube = Model::cube20();
            &cube
        }
    };
    // Evaluating the layer ranges can take a while on tall models: let Python run.
    py.detach(|| rotlang_core::explain::template(text, target, model))
}
