//! The transcendental functions of the geometry, the same bits on every target.
//!
//! `f64::sin` and its kin call the platform's C library in a native build and a port of
//! musl's in wasm32, and the two differ in the last bit now and then: a gyroid or a circle
//! drawn by the playground (wasm) would then not be the one `rotlang preview` prints. Every
//! sine, cosine, arc tangent and hypotenuse of this crate goes through here, to `libm` (the
//! same port, compiled for both). Square roots and the basic operations are exact in IEEE
//! 754 on every target and stay as they are.

/// The sine of `x` (radians).
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// The cosine of `x` (radians).
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// The sine and cosine of `x` (radians).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The angle of the point (`x`, `y`), in radians in [-π, π].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// The arc cosine of `x`, in radians in [0, π].
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// The length of (`x`, `y`), without overflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// `x` to the power `y`.
#[inline]
pub fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// The base-10 logarithm of `x`.
#[inline]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// Widens the box `lo..=hi` to hold `c`, by comparisons: `f64::min`/`max` take several
/// instructions each for their NaN rule, and the infill's hot loops build a box per ring,
/// chunk or run (a NaN coordinate is passed over, as `min`/`max` pass it over).
#[inline(always)]
pub(crate) fn widen(lo: &mut geo::Coord, hi: &mut geo::Coord, c: geo::Coord) {
    if c.x < lo.x {
        lo.x = c.x;
    }
    if c.x > hi.x {
        hi.x = c.x;
    }
    if c.y < lo.y {
        lo.y = c.y;
    }
    if c.y > hi.y {
        hi.y = c.y;
    }
}

/// The squared distance from `p` to the segment `a`–`b` (its nearest point by the
/// clamped projection; a point-like segment's is `a`). One expression for the infill's
/// tests that compare it (concentric's spacing tests, the router's distance to an edge),
/// so that they agree to the bit.
#[inline(always)]
pub(crate) fn segment_distance2(p: geo::Coord, a: geo::Coord, b: geo::Coord) -> f64 {
    let e = b - a;
    let len2 = e.x * e.x + e.y * e.y;
    let t = if len2 > 0.0 {
        (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = p - (a + e * t);
    q.x * q.x + q.y * q.y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The functions are the usual ones (to a few ulps of std's): a wrong argument order or
    /// a swapped pair would show here.
    #[test]
    fn they_are_the_usual_functions() {
        for i in -50..50 {
            let x = f64::from(i) * 0.37;
            assert!((sin(x) - x.sin()).abs() < 1e-15);
            assert!((cos(x) - x.cos()).abs() < 1e-15);
            assert_eq!(sin_cos(x), (sin(x), cos(x)));
            assert!((atan2(x, 1.5) - x.atan2(1.5)).abs() < 1e-15);
            assert!((hypot(x, 2.0) - x.hypot(2.0)).abs() < 1e-14);
        }
        assert!((acos(0.5) - 0.5f64.acos()).abs() < 1e-15);
        assert_eq!(powf(10.0, 2.0), 100.0);
        assert_eq!(log10(1000.0), 3.0);
    }
}
