//! The ranges of the numbers a binding passes to the evaluator (base direction, seed,
//! layer and shell counts), and one wording of the refusal: the Python and JavaScript
//! bindings both check their arguments here, so that the same bad number gets the same
//! answer, with the allowed range in it, whichever language it came from.
//!
//! ```
//! use rotlang::eval::limits::{self, Given};
//!
//! assert_eq!(limits::base(45.0), Ok(45.0));
//! assert!(limits::base(2e300).unwrap_err().message.contains("within ±1000000000"));
//! let e = limits::seed("seed", Given::Int(-1), limits::MAX_SEED).unwrap_err();
//! assert_eq!(e.message, "`seed` must be a whole number from 0 to 18446744073709551615, not -1");
//! assert_eq!(limits::shells("top_shells", Given::Float(4.0)), Ok(4));
//! ```

use std::fmt;

use super::MAX_LAYERS;

/// The largest base direction, in degrees either way: it keeps `base + angle` far from
/// overflow and from losing the fractions of a degree.
pub const MAX_BASE: f64 = 1e9;
/// The largest seed.
pub const MAX_SEED: u64 = u64::MAX;
/// The largest seed a JavaScript number carries exactly (2^53 - 1): the JavaScript
/// binding's bound, as a larger number there is not the one its caller wrote.
pub const MAX_EXACT_SEED: u64 = (1 << 53) - 1;
/// The most bottom or top shell layers.
pub const MAX_SHELLS: u64 = u32::MAX as u64;

/// A number as a binding received it: a float (JavaScript) or an integer (Python, C).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Given {
    /// A floating-point number (JavaScript numbers).
    Float(f64),
    /// An integer (Python ints, C integers), wide enough for any of them.
    Int(i128),
}

impl fmt::Display for Given {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Given::Float(v) => write!(f, "{}", Shown(*v)),
            // In two u64 halves: the code that prints an i128 is a kilobyte of the wasm
            // module (which never prints one).
            Given::Int(v) => {
                const E19: u128 = 10_000_000_000_000_000_000;
                let sign = if *v < 0 { "-" } else { "" };
                let m = v.unsigned_abs();
                // m <= 2^127, so m / 1e19 < 1.8e19 fits a u64.
                let (hi, lo) = ((m / E19) as u64, (m % E19) as u64);
                if hi == 0 {
                    write!(f, "{sign}{lo}")
                } else {
                    write!(f, "{sign}{hi}{lo:019}")
                }
            }
        }
    }
}

/// A float in a message: `2e300` and `1e-7` in exponent form (Rust's plain form of 2e300
/// has 300 zeros), the rest as usual (`-1`, `0.5`, `NaN`, `inf`).
struct Shown(f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v.is_finite() && v != 0.0 && !(1e-6..1e21).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}

/// Why a number was refused: the binding raises `message` as its error for bad options
/// (Python's `ValueError`, a JavaScript `RotlangError`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LimitError {
    /// What was refused and why, in one sentence.
    pub message: String,
}

impl fmt::Display for LimitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for LimitError {}

/// The base direction (degrees): finite and within ±[`MAX_BASE`].
pub fn base(value: f64) -> Result<f64, LimitError> {
    if value.is_finite() && value.abs() <= MAX_BASE {
        Ok(value)
    } else {
        Err(LimitError {
            message: format!(
                "`base` must be a finite number of degrees within ±{MAX_BASE}, not {}",
                Shown(value)
            ),
        })
    }
}

const TWO_TO_64: f64 = 18_446_744_073_709_551_616.0;

/// A whole number from `min` to `max`; `name` is the argument's name in the caller's
/// language (`bottom_shells`, `bottomShells`).
pub fn whole(name: &str, value: Given, min: u64, max: u64) -> Result<u64, LimitError> {
    let fits = match value {
        Given::Int(v) => u64::try_from(v).ok().filter(|v| (min..=max).contains(v)),
        // Below 2^64 a whole float converts to u64 exactly (the cast would saturate above).
        Given::Float(v) if v.fract() == 0.0 && (0.0..TWO_TO_64).contains(&v) => {
            Some(v as u64).filter(|v| (min..=max).contains(v))
        }
        Given::Float(_) => None,
    };
    fits.ok_or_else(|| out_of_range(name, min, max, &value))
}

/// The refusal of [`whole`], for a value the caller could not even turn into a
/// [`Given`] (a Python integer beyond 128 bits): `shown` as the caller prints it.
pub fn out_of_range(name: &str, min: u64, max: u64, shown: &dyn fmt::Display) -> LimitError {
    LimitError {
        message: format!("`{name}` must be a whole number from {min} to {max}, not {shown}"),
    }
}

/// The seed of the random joints: 0 to `max` ([`MAX_SEED`], or [`MAX_EXACT_SEED`] where
/// numbers are doubles).
pub fn seed(name: &str, value: Given, max: u64) -> Result<u64, LimitError> {
    whole(name, value, 0, max)
}

/// A bottom or top shell count: 0 to [`MAX_SHELLS`].
pub fn shells(name: &str, value: Given) -> Result<u32, LimitError> {
    // In range, so the conversion cannot fail.
    whole(name, value, 0, MAX_SHELLS).map(|v| u32::try_from(v).unwrap_or(u32::MAX))
}

/// A count of layers: 1 to [`MAX_LAYERS`].
pub fn layers(name: &str, value: Given) -> Result<usize, LimitError> {
    whole(name, value, 1, MAX_LAYERS as u64).map(|v| usize::try_from(v).unwrap_or(MAX_LAYERS))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_in_range_pass_in_both_forms() {
        assert_eq!(whole("n", Given::Int(0), 0, 5), Ok(0));
        assert_eq!(whole("n", Given::Float(5.0), 0, 5), Ok(5));
        assert_eq!(
            seed("seed", Given::Int(i128::from(u64::MAX)), MAX_SEED),
            Ok(u64::MAX)
        );
        assert_eq!(
            seed("seed", Given::Float(MAX_EXACT_SEED as f64), MAX_EXACT_SEED),
            Ok(MAX_EXACT_SEED)
        );
        assert_eq!(layers("layers", Given::Int(100_000_000)), Ok(100_000_000));
        assert_eq!(shells("t", Given::Int(i128::from(u32::MAX))), Ok(u32::MAX));
    }

    #[test]
    fn everything_else_is_refused_with_the_range() {
        for (value, max) in [
            (Given::Int(-1), MAX_SEED),
            (Given::Int(1 << 64), MAX_SEED),
            (Given::Float(-1.0), MAX_EXACT_SEED),
            (Given::Float(0.5), MAX_EXACT_SEED),
            (Given::Float(f64::NAN), MAX_EXACT_SEED),
            (Given::Float(f64::INFINITY), MAX_EXACT_SEED),
            (Given::Float(2f64.powi(53)), MAX_EXACT_SEED),
            (Given::Float(2f64.powi(64)), MAX_SEED),
        ] {
            let e = seed("seed", value, max).unwrap_err();
            assert_eq!(
                e.message,
                format!("`seed` must be a whole number from 0 to {max}, not {value}")
            );
        }
        assert!(shells("top_shells", Given::Int(1 << 40)).is_err());
        let e = seed("seed", Given::Int(-(10i128.pow(30))), MAX_SEED).unwrap_err();
        assert!(
            e.message.ends_with(&format!("not -1{}", "0".repeat(30))),
            "{e}"
        );
        assert_eq!(Given::Int(i128::MIN).to_string(), i128::MIN.to_string());
        assert_eq!(Given::Int(i128::MAX).to_string(), i128::MAX.to_string());
        assert_eq!(Given::Int(1 << 64).to_string(), "18446744073709551616");
        assert!(layers("layers", Given::Int(0)).is_err());
        let e = layers("layers", Given::Float(1e9)).unwrap_err();
        assert!(e.message.contains("from 1 to 100000000"), "{e}");
        for bad in [2e300, -1e9 - 1.0, f64::NAN, f64::NEG_INFINITY] {
            assert!(base(bad).is_err(), "{bad}");
        }
        assert_eq!(
            base(2e300).unwrap_err().message,
            "`base` must be a finite number of degrees within ±1000000000, not 2e300"
        );
        assert!(
            base(-1e9 - 0.5)
                .unwrap_err()
                .message
                .ends_with("not -1000000000.5")
        );
        assert_eq!(base(-1e9), Ok(-1e9));
    }
}
