//! The shapes of a turn across its range (SEMANTICS.md section 5).

use crate::ir::Joint;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// `shape(p)` for a progress `p` in `[0, 1]` that is already flipped when the range is.
/// `flipped` matters only to `#`, whose whole turn sits at one end; `random` is the
/// layer's number in `[0, 1)`, used only by `~` and `^`.
#[inline]
pub(crate) fn shape(joint: Joint, p: f64, flipped: bool, random: impl FnOnce() -> f64) -> f64 {
    match joint {
        Joint::Linear => p,
        Joint::SineVertical => p - (TAU * p).sin() / TAU,
        Joint::SineVerticalLazy => p - (TAU * p).sin() / (2.0 * TAU),
        Joint::SineHorizontal => p + (TAU * p).sin() / TAU,
        Joint::SineHorizontalLazy => p + (TAU * p).sin() / (2.0 * TAU),
        // The clamp keeps `asin` finite should rounding push `2p - 1` past ±1.
        Joint::Arcsine => (2.0 * p - 1.0).clamp(-1.0, 1.0).asin() / PI + 0.5,
        Joint::QuarterCircleHV => (FRAC_PI_2 * p).sin(),
        Joint::QuarterCircleVH => 1.0 - (FRAC_PI_2 * p).cos(),
        Joint::Square => 1.0 - (1.0 - p) * (1.0 - p),
        Joint::SquareInverse => (1.0 - p) * (1.0 - p),
        Joint::Cubic => 1.0 - (1.0 - p) * (1.0 - p) * (1.0 - p),
        Joint::CubicInverse => (1.0 - p) * (1.0 - p) * (1.0 - p),
        Joint::Random => random(),
        Joint::PseudoRandom => p + random() - 0.5,
        Joint::Middle => 0.5,
        Joint::Step => {
            if flipped {
                0.0
            } else {
                1.0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_and_middles() {
        let at = |j, p| shape(j, p, false, || 0.25);
        for j in [
            Joint::Linear,
            Joint::SineVertical,
            Joint::SineVerticalLazy,
            Joint::SineHorizontal,
            Joint::SineHorizontalLazy,
            Joint::Arcsine,
            Joint::QuarterCircleHV,
            Joint::QuarterCircleVH,
            Joint::Square,
            Joint::Cubic,
        ] {
            assert!(at(j, 0.0).abs() < 1e-12, "{j:?} at 0");
            assert!((at(j, 1.0) - 1.0).abs() < 1e-12, "{j:?} at 1");
        }
        assert_eq!(at(Joint::SquareInverse, 0.0), 1.0);
        assert_eq!(at(Joint::CubicInverse, 1.0), 0.0);
        assert_eq!(at(Joint::Middle, 0.1), 0.5);
        assert_eq!(at(Joint::Step, 0.1), 1.0);
        assert_eq!(shape(Joint::Step, 0.9, true, || 0.0), 0.0);
        assert_eq!(at(Joint::Random, 0.7), 0.25);
        assert_eq!(at(Joint::PseudoRandom, 0.5), 0.25);
        assert!((at(Joint::Arcsine, 0.5) - 0.5).abs() < 1e-12);
        assert!((at(Joint::QuarterCircleHV, 0.5) - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12);
    }
}
