//! Comparing OrcaSlicer's readings of two texts, and the helpers every comparison of the
//! lint shares. A leaf of the lint: the parser asks it about a rewrite
//! ([`orcaslicer_change`]) without reaching the lint, which parses.

use crate::dialect::Finding;
use crate::dialect::orcaslicer;
use crate::eval::{Model, Options};

/// Equal directions: modulo 360 within 1e-4°, relatively within 1e-9 above 1e9 (the
/// conformance README's comparison).
pub(super) fn same_angle(a: f64, b: f64) -> bool {
    if a.abs().max(b.abs()) > 1e9 {
        return (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    }
    let diff = (a - b).rem_euclid(360.0);
    diff <= 1e-4 || diff >= 360.0 - 1e-4
}

/// Angles without float noise: `47.25°`, `33.333333°`.
pub(super) fn degrees(d: f64) -> String {
    let rounded = (d * 1e6).round() / 1e6;
    format!("{}°", rounded + 0.0)
}

/// The models a rewrite or a fix is checked on: the cube, a thicker first layer, fine
/// layers.
pub(super) fn reference_models() -> [Model; 3] {
    let uniform = |n, h, first| Model::uniform(n, h, first).expect("valid reference model");
    [
        Model::cube20(),
        uniform(75, 0.2, Some(0.3)).with_shells(4, 5),
        uniform(167, 0.12, None).with_shells(2, 3),
    ]
}

/// What OrcaSlicer does differently after `text` becomes `changed` (on reference models),
/// or `None` when it reads both alike. The formatter asks before rewriting a template.
pub fn orcaslicer_change(text: &str, changed: &str) -> Option<String> {
    // Formatting changes separators only: most texts keep OrcaSlicer's tokens exactly.
    if orcaslicer::same_reading(text, changed) {
        return None;
    }
    for model in reference_models() {
        let options = Options::default();
        let mut a = orcaslicer::layers(text, &model, options);
        let mut b = orcaslicer::layers(changed, &model, options);
        for (x, y) in a.by_ref().zip(b.by_ref()) {
            if x.angle.to_bits() != y.angle.to_bits() && !same_angle(x.angle, y.angle) {
                return Some(format!(
                    "OrcaSlicer would turn layer {} to {} instead of {}",
                    x.index,
                    degrees(y.angle),
                    degrees(x.angle)
                ));
            }
        }
        let codes = |f: &[Finding]| f.iter().map(|f| f.code).collect::<Vec<_>>();
        if codes(a.findings()) != codes(b.findings()) {
            return Some("OrcaSlicer would hang, crash or compute NaN angles differently".into());
        }
    }
    None
}
