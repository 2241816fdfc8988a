//! Numbers for people and files: angles and heights printed without floating-point noise.
//!
//! Evaluated angles and running sums of layer heights carry the last bits of binary
//! arithmetic (`0.6000000000000001`, `3.3306690738754696e-15`, `-0.0`). Every front end
//! (the CLI, the JS and Python bindings, the language server) prints them through these
//! helpers, so they all show the same digits:
//!
//! - heights are rounded to micrometres ([`HEIGHT_DECIMALS`]), angles to 1e-9 degree
//!   ([`ANGLE_DECIMALS`]), then printed in the shortest form that reads back as the
//!   rounded value (no exponent, no trailing zeros, `30` rather than `30.0`);
//! - a wrapped angle is in `[0, 360)` or `[0, 180)` *after* rounding (never `360` or
//!   `179.99999999999994`);
//! - there is no negative zero.
//!
//! ```
//! use rotlang::number::{self, Wrap};
//!
//! assert_eq!(number::height(0.1 + 0.2 + 0.3).as_str(), "0.6");
//! assert_eq!(number::angle(3.3306690738754696e-15).as_str(), "0");
//! assert_eq!(number::angle(-1e-12).as_str(), "0");
//! assert_eq!(number::angle(22.5).as_str(), "22.5");
//! assert_eq!(number::wrap(-5.6e-14, Wrap::HalfTurn), 0.0);
//! assert_eq!(number::wrap(370.1, Wrap::Turn), 10.1);
//! assert_eq!(number::angle(number::wrap(360.0, Wrap::Turn)).to_string(), "0");
//! ```

use std::fmt;

/// Decimals kept of an angle in degrees.
pub const ANGLE_DECIMALS: u32 = 9;
/// Decimals kept of a height in millimetres: 3, micrometres (slicers keep no finer).
pub const HEIGHT_DECIMALS: u32 = 3;

const POW10: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// How angles are wrapped for printing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// As evaluated: `+90` gives 90, 180, 270, 360, 450, …
    #[default]
    None,
    /// Into `[0, 360)`: the direction.
    Turn,
    /// Into `[0, 180)`: the infill lines (lines at θ and θ + 180° are the same lines).
    HalfTurn,
}

impl Wrap {
    /// The modulus, if any: 360 or 180.
    pub fn modulus(self) -> Option<f64> {
        match self {
            Wrap::None => None,
            Wrap::Turn => Some(360.0),
            Wrap::HalfTurn => Some(180.0),
        }
    }
}

/// `x` rounded to `decimals` decimals, without negative zero. Values too large for the
/// rounding to mean anything (beyond 2^53 units) are returned as they are.
fn round_to(x: f64, decimals: u32) -> f64 {
    if !x.is_finite() {
        return x;
    }
    let scale = POW10[decimals as usize] as f64;
    let scaled = x * scale;
    if scaled.abs() >= 9_007_199_254_740_992.0 {
        return x + 0.0;
    }
    // An integer divided by a power of ten (both exact) is the double nearest to the
    // decimal, whose shortest form is that decimal. `+ 0.0` turns `-0.0` into `0.0`.
    scaled.round() / scale + 0.0
}

/// An angle rounded to [`ANGLE_DECIMALS`] decimals.
pub fn round_angle(degrees: f64) -> f64 {
    round_to(degrees, ANGLE_DECIMALS)
}

/// A height rounded to [`HEIGHT_DECIMALS`] decimals (micrometres).
pub fn round_height(mm: f64) -> f64 {
    round_to(mm, HEIGHT_DECIMALS)
}

/// An angle rounded and wrapped: in `[0, 360)` or `[0, 180)` after rounding.
pub fn wrap(degrees: f64, wrap: Wrap) -> f64 {
    let rounded = round_angle(degrees);
    let Some(m) = wrap.modulus() else {
        return rounded;
    };
    if !rounded.is_finite() || (0.0..m).contains(&rounded) {
        // Already in range (the common case): no remainder to take.
        return rounded;
    }
    // `rem_euclid` leaves noise (`370.1 % 360 = 10.100000000000023`) and can round up to
    // the modulus itself: round again and fold that onto 0.
    let w = round_angle(rounded.rem_euclid(m));
    if w >= m { 0.0 } else { w }
}

/// A number as text, held inline (no allocation): what [`angle`] and [`height`] return.
#[derive(Clone, Copy)]
pub struct Decimal {
    buf: [u8; 40],
    len: u8,
}

impl Decimal {
    /// The text.
    pub fn as_str(&self) -> &str {
        // Only ASCII digits, signs, `.`, `e` and the words of non-finite values are written.
        std::str::from_utf8(&self.buf[..self.len as usize]).unwrap_or("NaN")
    }

    fn push(&mut self, bytes: &[u8]) {
        let start = self.len as usize;
        let end = (start + bytes.len()).min(self.buf.len());
        self.buf[start..end].copy_from_slice(&bytes[..end - start]);
        self.len = end as u8;
    }
}

impl fmt::Display for Decimal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.as_str())
    }
}

impl fmt::Debug for Decimal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)
    }
}

impl fmt::Write for Decimal {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.push(s.as_bytes());
        Ok(())
    }
}

/// An angle in degrees as text: rounded to 1e-9°, shortest form (`22.5`, `30`, `0`).
pub fn angle(degrees: f64) -> Decimal {
    decimal(degrees, ANGLE_DECIMALS)
}

/// A height in millimetres as text: rounded to the micrometre, shortest form (`0.6`).
pub fn height(mm: f64) -> Decimal {
    decimal(mm, HEIGHT_DECIMALS)
}

/// Below this magnitude, the fixed-point digits are the shortest round-trip form: the
/// double spacing is finer than the last decimal kept (so no shorter decimal reads back
/// as the same value), and `value × 10^decimals` stays below 2^51, where the product is
/// within a quarter of the integer it came from (so the integer is recovered exactly).
fn fast_limit(decimals: u32) -> f64 {
    match decimals {
        ANGLE_DECIMALS => 2_097_152.0,          // 2^21
        HEIGHT_DECIMALS => 2_199_023_255_552.0, // 2^41
        _ => 0.0,
    }
}

fn decimal(x: f64, decimals: u32) -> Decimal {
    let mut out = Decimal {
        buf: [0; 40],
        len: 0,
    };
    let r = round_to(x, decimals);
    if r.is_finite() && r.abs() < fast_limit(decimals) {
        // Fixed point: an integer count of 10^-decimals, printed as digits.
        let scale = POW10[decimals as usize];
        let n = (r.abs() * scale as f64).round() as u64;
        if r < 0.0 && n > 0 {
            out.push(b"-");
        }
        write_u64(&mut out, n / scale);
        let mut frac = n % scale;
        if frac > 0 {
            let mut digits = decimals as usize;
            while frac.is_multiple_of(1000) {
                frac /= 1000;
                digits -= 3;
            }
            while frac.is_multiple_of(10) {
                frac /= 10;
                digits -= 1;
            }
            out.push(b".");
            // Leading zeros of the fraction, then its digits.
            let width = frac.ilog10() as usize + 1;
            out.push(&[b'0'; 9][..digits - width]);
            write_u64(&mut out, frac);
        }
    } else if r.is_finite() && r.abs() < 1e21 {
        // Plain digits (Rust's `Display` is the shortest round-trip form, no exponent).
        let _ = fmt::write(&mut out, format_args!("{r}"));
    } else {
        // Huge values in exponent form (at most 24 bytes), and `NaN`/`inf`.
        let _ = fmt::write(&mut out, format_args!("{r:e}"));
    }
    out
}

/// Two decimal digits per step.
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Writes the decimal digits of `n`.
fn write_u64(out: &mut Decimal, mut n: u64) {
    let mut tmp = [0u8; 20];
    let mut i = tmp.len();
    while n >= 100 {
        let pair = (n % 100) as usize * 2;
        n /= 100;
        i -= 2;
        tmp[i..i + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    }
    if n >= 10 {
        let pair = n as usize * 2;
        i -= 2;
        tmp[i..i + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    } else {
        i -= 1;
        tmp[i] = b'0' + n as u8;
    }
    out.push(&tmp[i..]);
}

/// The decimal digits of an integer, for writers that print many of them (CSV, JSON).
pub fn integer(n: u64) -> Decimal {
    let mut out = Decimal {
        buf: [0; 40],
        len: 0,
    };
    write_u64(&mut out, n);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn noise_is_gone() {
        assert_eq!(height(0.6000000000000001).as_str(), "0.6");
        // Micrometres: a running sum over a million layers keeps no nanometre noise.
        assert_eq!(height(199999.800003).as_str(), "199999.8");
        assert_eq!(height(0.0125).as_str(), "0.013");
        assert_eq!(height(0.0004).as_str(), "0");
        assert_eq!(height(1e12 + 0.25).as_str(), "1000000000000.25");
        assert_eq!(angle(3.3306690738754696e-15).as_str(), "0");
        assert_eq!(angle(-0.0).as_str(), "0");
        assert_eq!(angle(-0.00001).as_str(), "-0.00001");
        assert_eq!(angle(-30.0).as_str(), "-30");
        assert_eq!(angle(1e-9).as_str(), "0.000000001");
        assert_eq!(angle(4e-10).as_str(), "0");
        assert_eq!(angle(12345678.5).as_str(), "12345678.5");
        assert_eq!(angle(1e300).as_str(), "1e300");
        assert_eq!(angle(f64::NAN).as_str(), "NaN");
        assert_eq!(integer(0).as_str(), "0");
        assert_eq!(integer(u64::MAX).as_str(), u64::MAX.to_string());
        assert_eq!(format!("{:>6}|", angle(1.5)), "   1.5|");
    }

    #[test]
    fn wrapping_is_after_rounding() {
        assert_eq!(wrap(-5.684341886080802e-14, Wrap::HalfTurn), 0.0);
        assert_eq!(wrap(-5.684341886080802e-14, Wrap::Turn), 0.0);
        assert_eq!(wrap(359.9999999999999, Wrap::Turn), 0.0);
        assert_eq!(wrap(180.0, Wrap::HalfTurn), 0.0);
        assert_eq!(wrap(360.0, Wrap::Turn), 0.0);
        assert_eq!(wrap(-90.0, Wrap::Turn), 270.0);
        assert_eq!(wrap(-90.0, Wrap::HalfTurn), 90.0);
        assert_eq!(wrap(-0.0, Wrap::None).to_bits(), 0.0f64.to_bits());
        assert_eq!(wrap(450.25, Wrap::None), 450.25);
    }

    proptest! {
        /// The fast fixed-point digits are exactly the shortest round-trip form of the
        /// rounded value (what `Display` prints).
        #[test]
        fn fast_path_is_shortest_round_trip(x in -2e7f64..2e7, small in -10.0f64..10.0, edge in 2_000_000f64..2_200_000.0, huge in 2.1e12f64..2.3e12) {
            for v in [x, small, x / 1e3, small / 1e6, edge, -edge, edge * 1e3] {
                prop_assert_eq!(angle(v).to_string(), format!("{}", round_angle(v)));
                prop_assert_eq!(height(v).to_string(), format!("{}", round_height(v)));
                let back: f64 = angle(v).as_str().parse().unwrap();
                prop_assert_eq!(back, round_angle(v));
            }
            // Heights around the fast path's limit (2^41 mm).
            for v in [huge, -huge, huge / 1e3 + small] {
                prop_assert_eq!(height(v).to_string(), format!("{}", round_height(v)));
            }
        }

        #[test]
        fn wrapped_angles_stay_in_range(x in -1e9f64..1e9, tiny in -1e-6f64..1e-6) {
            for v in [x, tiny, x + tiny] {
                let t = wrap(v, Wrap::Turn);
                let h = wrap(v, Wrap::HalfTurn);
                prop_assert!((0.0..360.0).contains(&t), "{} -> {}", v, t);
                prop_assert!((0.0..180.0).contains(&h), "{} -> {}", v, h);
                prop_assert!(!angle(t).to_string().starts_with('-'));
                prop_assert_ne!(angle(t).to_string(), "360");
                prop_assert_ne!(angle(h).to_string(), "180");
            }
        }
    }
}
