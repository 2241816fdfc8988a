//! What evaluation takes and gives: the options and one evaluated layer.

use crate::diagnostic::Span;
use crate::ir::Fill;

/// Evaluation options.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// The base direction (degrees) added to every angle: the profile's infill direction.
    pub base: f64,
    /// The seed of the random joints `~` and `^`.
    pub seed: u64,
}

/// One evaluated layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// The layer's index, 0 for the first layer.
    pub index: usize,
    /// Bottom height of the layer (mm above the object's bottom).
    pub bottom: f64,
    /// Top height of the layer (mm).
    pub top: f64,
    /// The infill angle in degrees, base included, not wrapped (`+90` gives 90, 180,
    /// 270, 360, 450, ...). Always finite.
    pub angle: f64,
    /// The kind of fill of the layer (sparse, or a solid kind).
    pub fill: Fill,
    /// The span of the instruction that governs the layer; `None` when the layer holds
    /// (every instruction spent) or the template is empty.
    pub instruction: Option<Span>,
}
