//! Sine and cosine of `π/2 · t`, for the shapes' arguments (`t` in `[0, 4]`).
//!
//! The libm functions reduce arbitrary arguments and cost ~15 ns a call; here the
//! argument comes in quarter turns, so the reduction is exact (a rounding to the nearest
//! quadrant) and what is left is fdlibm's kernel polynomials on `[-π/4, π/4]`, accurate to
//! about an ulp. This halves the cost of a layer on `L`, `l`, `N`, `n`, `Z`, `z` ranges.

use std::f64::consts::FRAC_PI_2;

/// `sin(x)` for `|x| ≤ π/4` (fdlibm `__kernel_sin`).
// The coefficients are fdlibm's, digit for digit, so they can be checked against it.
#[allow(clippy::excessive_precision)]
#[inline]
fn kernel_sin(x: f64) -> f64 {
    const S1: f64 = -1.666_666_666_666_663_243_48e-01;
    const S2: f64 = 8.333_333_333_322_489_461_24e-03;
    const S3: f64 = -1.984_126_982_985_794_931_34e-04;
    const S4: f64 = 2.755_731_370_707_006_767_89e-06;
    const S5: f64 = -2.505_076_025_340_686_341_95e-08;
    const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    x + z * x * (S1 + z * r)
}

/// `cos(x)` for `|x| ≤ π/4` (fdlibm `__kernel_cos`).
#[allow(clippy::excessive_precision)]
#[inline]
fn kernel_cos(x: f64) -> f64 {
    const C1: f64 = 4.166_666_666_666_660_190_37e-02;
    const C2: f64 = -1.388_888_888_887_410_957_49e-03;
    const C3: f64 = 2.480_158_728_947_672_941_78e-05;
    const C4: f64 = -2.755_731_435_139_066_330_35e-07;
    const C5: f64 = 2.087_572_321_298_174_827_90e-09;
    const C6: f64 = -1.135_964_755_778_819_482_65e-11;
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + z * r)
}

/// `sin(π/2 · t)` shifted by `quadrant` quarter turns, for `t ≥ 0`.
#[inline]
fn quarter_turns(t: f64, quadrant: i64) -> f64 {
    if !t.is_finite() {
        return 0.0;
    }
    // The nearest quadrant. A truncating cast rounds half up for `t ≥ 0` in one
    // instruction, where `round()` is a libm call as costly as the kernels.
    let q = (t + 0.5) as i64;
    // `t - q` is exact: both are close and of the same magnitude.
    let x = (t - q as f64) * FRAC_PI_2;
    match q.wrapping_add(quadrant) & 3 {
        0 => kernel_sin(x),
        1 => kernel_cos(x),
        2 => -kernel_sin(x),
        _ => -kernel_cos(x),
    }
}

/// `sin(π/2 · t)`.
#[inline]
pub(crate) fn sin_quarter(t: f64) -> f64 {
    quarter_turns(t, 0)
}

/// `cos(π/2 · t)`.
#[inline]
pub(crate) fn cos_quarter(t: f64) -> f64 {
    quarter_turns(t, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_libm() {
        let mut worst: f64 = 0.0;
        for i in 0..=400_000 {
            let t = f64::from(i) / 100_000.0;
            let x = FRAC_PI_2 * t;
            worst = worst.max((sin_quarter(t) - x.sin()).abs());
            worst = worst.max((cos_quarter(t) - x.cos()).abs());
        }
        assert!(worst < 1e-15, "worst error {worst:e}");
        assert_eq!(sin_quarter(0.0), 0.0);
        assert_eq!(sin_quarter(1.0), 1.0);
        assert_eq!(cos_quarter(0.0), 1.0);
        assert_eq!(sin_quarter(f64::NAN), 0.0);
    }
}
