//! The OrcaSlicer dialect, and `explain` (which raises NotImplementedError until
//! `rotlang::explain` is in the library).

use pyo3::exceptions::{PyNotImplementedError, PyValueError};
use pyo3::prelude::*;

use rotlang_core::Target;
use rotlang_core::eval::{Model, Options};

use rotlang_core::dialect::orcaslicer;

use crate::{Evaluated, Finding};

pub const NAMES: [&str; 2] = ["rotlang", "orcaslicer"];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    Rotlang,
    OrcaSlicer,
}

impl Dialect {
    pub fn from_name(name: &str) -> PyResult<Dialect> {
        match name {
            "rotlang" => Ok(Dialect::Rotlang),
            "orcaslicer" => Ok(Dialect::OrcaSlicer),
            other => Err(PyValueError::new_err(format!(
                "dialect must be 'rotlang' or 'orcaslicer', not {other:?}"
            ))),
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
        Dialect::Rotlang => Err(PyValueError::new_err("the rotlang dialect parses first")),
    }
}

pub fn explain(_py: Python<'_>, _text: &str, _target: Target, _model: Option<&Model>) -> PyResult<String> {
    Err(PyNotImplementedError::new_err(
        "explain is not in this build of rotlang yet",
    ))
}
