//! The evaluator: per-layer angles and fills for a model.
