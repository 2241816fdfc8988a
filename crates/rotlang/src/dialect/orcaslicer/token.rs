//! One token of OrcaSlicer's metalanguage reading, decoded from its text (10.6): a leaf
//! that the walk (`mod.rs`) and the compact token store (`store.rs`) both use.

use super::scan;
use crate::diagnostic::Span;
use crate::ir::Joint;

pub(super) fn is_joint(b: u8) -> bool {
    b.is_ascii() && Joint::from_symbol(b as char).is_some()
}

/// What a token's count makes of the range (10.6 step 5), decided by its text alone.
#[derive(Clone, Copy, Debug)]
pub(super) enum Count {
    Bottom,
    Top,
    /// `steps` (the absolute value of the number read; 0 means none).
    Layers(f64),
    /// A count followed by a character other than `!`: `steps` of that unit above the
    /// bottom of the layer.
    Length(f64, Unit),
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Unit {
    Percent,
    StandardLayers,
    Foot,
    Inch,
    Centimetre,
    Millimetre,
    Metre,
    /// Any other character: the limit stays as it is (and the layer's bottom is added).
    Keep,
}

/// One token, decoded once (10.6 on its text): only the range end depends on the layer.
#[derive(Clone, Copy, Debug)]
pub(super) struct Token {
    pub(super) span: Span,
    /// Contains `!`: spent once read.
    pub(super) bang: bool,
    pub(super) absolute: bool,
    /// The number read, `× 3.6` after `%`.
    pub(super) value: f64,
    /// 0 for a dummy.
    pub(super) repeats: i32,
    pub(super) form: Option<Joint>,
    pub(super) negative: bool,
    pub(super) count: Count,
}

impl Token {
    pub(super) fn new(text: &[u8], span: Span) -> Token {
        let s = &text[span.range()];
        let (mut value, mut pos) = scan::strtod(s).unwrap_or((0.0, 0));
        if s.get(pos) == Some(&b'%') {
            value *= 3.6;
            pos += 1;
        }
        let mut repeats = 1;
        if let Some(star) = s.iter().position(|&b| b == b'*') {
            let (r, len) = scan::strtol(&s[star + 1..]);
            repeats = r;
            pos = star + 1 + len;
        }
        let mut form = None;
        let mut negative = false;
        let count = match s.get(pos) {
            Some(b'B') => Count::Bottom,
            Some(b'T') => Count::Top,
            next => {
                if let Some(&b) = next.filter(|&&b| is_joint(b)) {
                    form = Joint::from_symbol(b as char);
                    pos += 1;
                }
                negative = s.get(pos) == Some(&b'-');
                let (number, len) = scan::strtod(&s[pos..]).unwrap_or((0.0, 0));
                let steps = number.abs();
                pos += len;
                match s.get(pos) {
                    Some(&c) if steps != 0.0 && c != b'!' => Count::Length(
                        steps,
                        match c {
                            b'%' => Unit::Percent,
                            b'#' => Unit::StandardLayers,
                            b'\'' => Unit::Foot,
                            b'"' => Unit::Inch,
                            b'c' => Unit::Centimetre,
                            b'm' if s.get(pos + 1) == Some(&b'm') => Unit::Millimetre,
                            b'm' => Unit::Metre,
                            _ => Unit::Keep,
                        },
                    ),
                    _ => Count::Layers(steps),
                }
            }
        };
        Token {
            span,
            bang: s.contains(&b'!'),
            absolute: s.first().is_some_and(u8::is_ascii_digit),
            value,
            repeats,
            form,
            negative,
            count,
        }
    }
}
