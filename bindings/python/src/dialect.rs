//! The parts that depend on library modules landing separately: the OrcaSlicer dialect
//! and `explain`. Until they are in, they raise NotImplementedError.

use pyo3::exceptions::{PyNotImplementedError, PyValueError};
use pyo3::prelude::*;

use rotlang_core::Target;
use rotlang_core::eval::{Model, Options};

use crate::Evaluated;

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

pub fn evaluate(
    _py: Python<'_>,
    _dialect: Dialect,
    _text: &str,
    _model: &Model,
    _options: Options,
    _want_fills: bool,
) -> PyResult<Evaluated> {
    Err(PyNotImplementedError::new_err(
        "the OrcaSlicer dialect is not in this build of rotlang yet",
    ))
}

pub fn explain(_py: Python<'_>, _text: &str, _target: Target, _model: Option<&Model>) -> PyResult<String> {
    Err(PyNotImplementedError::new_err(
        "explain is not in this build of rotlang yet",
    ))
}
