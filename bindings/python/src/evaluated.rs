//! What an evaluation hands back, in either dialect, before it becomes Python objects
//! (a leaf: `lib.rs` and `dialect.rs` both build it).

use pyo3::prelude::*;

/// A defect of OrcaSlicer's reading found by the OrcaSlicer dialect.
#[pyclass(frozen, get_all, skip_from_py_object, module = "rotlang")]
#[derive(Clone)]
pub struct Finding {
    /// `orcaslicer::hangs`, `orcaslicer::undefined` or `orcaslicer::nan`.
    pub code: String,
    pub message: String,
    pub first_layer: usize,
    pub layers: usize,
}

#[pymethods]
impl Finding {
    fn __repr__(&self) -> String {
        format!(
            "Finding({:?}, first_layer={}, layers={})",
            self.code, self.first_layer, self.layers
        )
    }
}

/// What one evaluation computes, before it becomes Python objects.
pub struct Evaluated {
    pub angles: Vec<f64>,
    pub fills: Vec<&'static str>,
    pub findings: Vec<Finding>,
}
