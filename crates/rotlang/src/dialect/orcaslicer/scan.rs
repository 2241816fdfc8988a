//! Reading numbers the way OrcaSlicer's C library does (SEMANTICS.md 10.3): `strtod` for
//! angles and counts, `strtol` with base 0 for repeat counts, and the list reading's plain
//! decimal prefix (10.2). Everything works on bytes: the text may be any UTF-8, but only
//! ASCII characters mean anything to OrcaSlicer.

/// C's `isspace` in the "C" locale.
pub(crate) fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

fn starts_with_ignore_case(s: &[u8], prefix: &[u8]) -> bool {
    s.len() >= prefix.len() && s[..prefix.len()].eq_ignore_ascii_case(prefix)
}

fn digits(s: &[u8], from: usize, radix: u32) -> usize {
    s[from..]
        .iter()
        .take_while(|b| (**b as char).is_digit(radix))
        .count()
}

/// What C's number readers skip first: leading white space, then one optional sign. The
/// position after them, and whether the sign was `-`.
fn sign(s: &[u8]) -> (usize, bool) {
    let mut i = 0;
    while i < s.len() && is_space(s[i]) {
        i += 1;
    }
    match s.get(i) {
        Some(b'-') => (i + 1, true),
        Some(b'+') => (i + 1, false),
        _ => (i, false),
    }
}

/// `strtod(s)`: the value and the number of bytes read, or `None` when no number can be
/// read (C then returns 0 and leaves the position where it was).
pub(crate) fn strtod(s: &[u8]) -> Option<(f64, usize)> {
    let (i, negative) = sign(s);
    let rest = &s[i..];
    let (magnitude, len) = if starts_with_ignore_case(rest, b"inf") {
        let len = if starts_with_ignore_case(rest, b"infinity") {
            8
        } else {
            3
        };
        (f64::INFINITY, len)
    } else if starts_with_ignore_case(rest, b"nan") {
        // glibc also takes `nan(chars)`, chars being letters, digits and `_`.
        let mut len = 3;
        if rest.get(3) == Some(&b'(') {
            let inner = rest[4..]
                .iter()
                .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
                .count();
            if rest.get(4 + inner) == Some(&b')') {
                len = 5 + inner;
            }
        }
        (f64::NAN, len)
    } else if let Some(hex) = hex_float(rest) {
        hex
    } else {
        decimal(rest)?
    };
    let value = if negative { -magnitude } else { magnitude };
    Some((value, i + len))
}

/// A decimal floating-point number at the start of `s` (no sign): digits with an optional
/// fraction, at least one digit, an optional exponent with digits.
fn decimal(s: &[u8]) -> Option<(f64, usize)> {
    let whole = digits(s, 0, 10);
    let mut len = whole;
    let mut fraction = 0;
    if s.get(len) == Some(&b'.') {
        fraction = digits(s, len + 1, 10);
        if whole + fraction > 0 {
            len += 1 + fraction;
        }
    }
    if whole + fraction == 0 {
        return None;
    }
    len += exponent(s, len, 10);
    // ASCII digits, `.`, `e` and a sign: always UTF-8, and Rust's parser rounds correctly,
    // as glibc's does, whatever the number of digits.
    let text = std::str::from_utf8(&s[..len]).ok()?;
    Some((text.parse().ok()?, len))
}

/// The length of an exponent (`e`/`E` for decimal, `p`/`P` for hexadecimal, optional
/// sign, decimal digits) at `at`, or 0 when there is none with digits.
fn exponent(s: &[u8], at: usize, radix: u32) -> usize {
    let marker = if radix == 10 { b'e' } else { b'p' };
    if !s.get(at).is_some_and(|b| b.eq_ignore_ascii_case(&marker)) {
        return 0;
    }
    let sign = usize::from(matches!(s.get(at + 1), Some(b'+' | b'-')));
    let n = digits(s, at + 1 + sign, 10);
    if n == 0 { 0 } else { 1 + sign + n }
}

/// A hexadecimal float (`0x1.8p3`), correctly rounded to nearest, ties to even, with
/// subnormals, as glibc reads it. `None` when `s` does not start with `0x` and a hex digit.
fn hex_float(s: &[u8]) -> Option<(f64, usize)> {
    if !(s.len() > 2 && s[0] == b'0' && (s[1] | 0x20) == b'x') {
        return None;
    }
    let whole = digits(s, 2, 16);
    let mut len = 2 + whole;
    let mut fraction = 0;
    if s.get(len) == Some(&b'.') {
        fraction = digits(s, len + 1, 16);
        if whole + fraction > 0 {
            len += 1 + fraction;
        }
    }
    if whole + fraction == 0 {
        return None;
    }
    let exp_len = exponent(s, len, 16);
    let mut exp2: i64 = 0;
    if exp_len > 0 {
        let text = &s[len + 1..len + exp_len];
        let (negative, body) = match text[0] {
            b'-' => (true, &text[1..]),
            b'+' => (false, &text[1..]),
            _ => (false, text),
        };
        // Saturate far beyond any finite result: the sign of the overflow is all that matters.
        let mut e: i64 = 0;
        for b in body {
            e = (e * 10 + i64::from(b - b'0')).min(1 << 40);
        }
        exp2 = if negative { -e } else { e };
    }
    len += exp_len;
    // Mantissa: the first 16 significant hex digits exactly, the rest as a sticky bit.
    let integer = &s[2..2 + whole];
    let fractional = if fraction > 0 {
        &s[3 + whole..3 + whole + fraction]
    } else {
        &[][..]
    };
    let mut mantissa: u64 = 0;
    let mut kept = 0;
    let mut sticky = false;
    let mut position = 0i64; // fraction digits taken into the mantissa (or skipped zeros)
    let tagged = integer
        .iter()
        .map(|b| (b, false))
        .chain(fractional.iter().map(|b| (b, true)));
    for (&b, in_fraction) in tagged {
        let d = u64::from((b as char).to_digit(16).unwrap_or(0));
        if kept < 16 {
            if mantissa != 0 || d != 0 {
                mantissa = mantissa << 4 | d;
                kept += 1;
            }
            if in_fraction {
                position += 1;
            }
        } else {
            sticky |= d != 0;
            if !in_fraction {
                exp2 += 4;
            }
        }
    }
    exp2 -= 4 * position;
    Some((round_binary(mantissa, sticky, exp2), len))
}

/// `(mantissa + a sticky fraction below its last bit) × 2^exp2`, rounded to a double.
fn round_binary(mantissa: u64, sticky: bool, exp2: i64) -> f64 {
    if mantissa == 0 {
        return 0.0;
    }
    let shift_in = mantissa.leading_zeros();
    let m = mantissa << shift_in;
    let e2 = exp2 - i64::from(shift_in);
    // The value lies in [2^top, 2^(top+1)).
    let top = e2 + 63;
    if top > 1023 {
        return f64::INFINITY;
    }
    let keep = if top >= -1022 { 53 } else { 53 - (-1022 - top) };
    if keep < 0 {
        return 0.0;
    }
    let drop = (64 - keep) as u32;
    let wide = u128::from(m);
    let mut q = wide >> drop;
    let rem = wide & ((1u128 << drop) - 1);
    let half = 1u128 << (drop - 1);
    if rem > half || (rem == half && (sticky || q & 1 == 1)) {
        q += 1;
    }
    ldexp(q as f64, e2 + i64::from(drop))
}

/// `x × 2^k`, exact whenever the result is representable (steps of at most 2^±1000 keep
/// every intermediate product normal).
fn ldexp(mut x: f64, mut k: i64) -> f64 {
    let pow2 = |k: i64| f64::from_bits(((k + 1023) as u64) << 52);
    while k > 1000 {
        x *= pow2(1000);
        k -= 1000;
        if x.is_infinite() {
            return x;
        }
    }
    while k < -1000 {
        x *= pow2(-1000);
        k += 1000;
        if x == 0.0 {
            return x;
        }
    }
    x * pow2(k)
}

/// `strtol(s, &end, 0)` converted to a 32-bit `int`: the value and the bytes read (0 when
/// no digits were read: C then leaves the position where it was). Beyond 64 bits the value
/// saturates to `LONG_MAX`/`LONG_MIN`; the conversion to `int` keeps the low 32 bits.
pub(crate) fn strtol(s: &[u8]) -> (i32, usize) {
    let (mut i, negative) = sign(s);
    let hex_digit = |at: usize| s.get(at).is_some_and(u8::is_ascii_hexdigit);
    let radix =
        if s.get(i) == Some(&b'0') && matches!(s.get(i + 1), Some(b'x' | b'X')) && hex_digit(i + 2)
        {
            i += 2;
            16
        } else if s.get(i) == Some(&b'0') {
            8
        } else {
            10
        };
    let n = digits(s, i, radix);
    if n == 0 {
        return (0, 0);
    }
    // Accumulate the magnitude, saturating: LONG_MAX, or LONG_MIN for a negative number.
    let mut magnitude: u64 = 0;
    let mut overflow = false;
    for &b in &s[i..i + n] {
        let d = u64::from((b as char).to_digit(radix).unwrap_or(0));
        match magnitude
            .checked_mul(u64::from(radix))
            .and_then(|m| m.checked_add(d))
        {
            Some(m) => magnitude = m,
            None => overflow = true,
        }
    }
    let value: i64 = if negative {
        if overflow || magnitude > 1 << 63 {
            i64::MIN
        } else {
            (magnitude as i64).wrapping_neg()
        }
    } else if overflow || magnitude > i64::MAX as u64 {
        i64::MAX
    } else {
        magnitude as i64
    };
    (value as i32, i + n)
}

/// The list reading's number (10.2): the longest decimal prefix (no sign, no hex, no
/// `inf`), 0 when there is none or when it ends in an exponent without digits (`1e`).
pub(crate) fn list_number(s: &[u8]) -> f64 {
    let whole = digits(s, 0, 10);
    let mut len = whole;
    let mut fraction = 0;
    if s.get(len) == Some(&b'.') {
        fraction = digits(s, len + 1, 10);
        len += 1 + fraction;
    }
    if whole + fraction == 0 {
        return 0.0;
    }
    if s.get(len).is_some_and(|b| b.eq_ignore_ascii_case(&b'e')) {
        let sign = usize::from(matches!(s.get(len + 1), Some(b'+' | b'-')));
        let n = digits(s, len + 1 + sign, 10);
        if n == 0 {
            return 0.0;
        }
        len += 1 + sign + n;
    }
    std::str::from_utf8(&s[..len])
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(s: &str) -> Option<(f64, usize)> {
        strtod(s.as_bytes())
    }

    #[test]
    fn strtod_like_c() {
        assert_eq!(d("45"), Some((45.0, 2)));
        assert_eq!(d("+22.5$"), Some((22.5, 5)));
        assert_eq!(d("-.5x"), Some((-0.5, 3)));
        assert_eq!(d("5."), Some((5.0, 2)));
        assert_eq!(d("1e5"), Some((1e5, 3)));
        assert_eq!(d("1e"), Some((1.0, 1)));
        assert_eq!(d("1e+"), Some((1.0, 1)));
        assert_eq!(d("1E-2mm"), Some((0.01, 4)));
        assert_eq!(d("."), None);
        assert_eq!(d("-"), None);
        assert_eq!(d("/5"), None);
        assert_eq!(d("inf"), Some((f64::INFINITY, 3)));
        assert_eq!(d("-Infinity!"), Some((f64::NEG_INFINITY, 9)));
        assert_eq!(d("infinit"), Some((f64::INFINITY, 3)));
        assert!(d("nan").is_some_and(|(v, n)| v.is_nan() && n == 3));
        assert!(d("NaN(x_1)z").is_some_and(|(v, n)| v.is_nan() && n == 8));
        assert!(d("nan(x").is_some_and(|(v, n)| v.is_nan() && n == 3));
        assert_eq!(d("1e400"), Some((f64::INFINITY, 5)));
        assert_eq!(d("1e-400"), Some((0.0, 6)));
    }

    #[test]
    fn hexadecimal_floats() {
        assert_eq!(d("0x10"), Some((16.0, 4)));
        assert_eq!(d("0x1p-2"), Some((0.25, 6)));
        assert_eq!(d("0x1.8P1"), Some((3.0, 7)));
        assert_eq!(d("0x.8"), Some((0.5, 4)));
        assert_eq!(d("0x1p"), Some((1.0, 3)));
        assert_eq!(d("0xg"), Some((0.0, 1)));
        assert_eq!(d("0x"), Some((0.0, 1)));
        assert_eq!(d("-0x1p1024"), Some((f64::NEG_INFINITY, 9)));
        assert_eq!(d("0x1p-1074"), Some((f64::from_bits(1), 9)));
        assert_eq!(d("0x1p-1075"), Some((0.0, 9)));
        assert_eq!(d("0x1.8p-1074"), Some((f64::from_bits(2), 11)));
        assert_eq!(d("0x1.fffffffffffff8p0"), Some((2.0, 20)));
        assert_eq!(
            d("0x1.fffffffffffff7ffffp0").map(|v| v.0),
            Some(f64::from_bits(0x3fff_ffff_ffff_ffff))
        );
        assert_eq!(d("0x1.00000000000008p0").map(|v| v.0), Some(1.0));
        assert_eq!(
            d("0x1.000000000000080001p0").map(|v| v.0),
            Some(f64::from_bits(0x3ff0_0000_0000_0001))
        );
        assert_eq!(
            d("0x123456789abcdef12p0").map(|v| v.0),
            Some(0x1_2345_6789_abcd_ef12_u128 as f64)
        );
    }

    #[test]
    fn strtol_base_zero() {
        let l = |s: &str| strtol(s.as_bytes());
        assert_eq!(l("3/5"), (3, 1));
        assert_eq!(l("0x10"), (16, 4));
        assert_eq!(l("0xZ"), (0, 1));
        assert_eq!(l("08"), (0, 1));
        assert_eq!(l("017"), (15, 3));
        assert_eq!(l("-2"), (-2, 2));
        assert_eq!(l("x"), (0, 0));
        assert_eq!(l("+"), (0, 0));
        assert_eq!(l("4294967296"), (0, 10));
        assert_eq!(l("4294967297"), (1, 10));
        assert_eq!(l("2147483648"), (i32::MIN, 10));
        assert_eq!(l("99999999999999999999999"), (-1, 23));
        assert_eq!(l("-99999999999999999999999"), (0, 24));
        assert_eq!(l("-9223372036854775808"), (0, 20));
    }

    #[test]
    fn list_numbers() {
        let n = |s: &str| list_number(s.as_bytes());
        assert_eq!(n("45°"), 45.0);
        assert_eq!(n("1:4"), 1.0);
        assert_eq!(n(".5"), 0.5);
        assert_eq!(n("1e"), 0.0);
        assert_eq!(n("1E3x"), 1000.0);
        assert_eq!(n("x5"), 0.0);
        assert_eq!(n(""), 0.0);
        assert_eq!(n("0x10"), 0.0);
    }
}
