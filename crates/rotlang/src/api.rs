//! What every binding (C, JavaScript, Python) is given, read in one place: the target
//! and dialect names, the model (a list of heights, a layer count or an object height,
//! with its layer heights and shell counts) and the evaluation options (base, seed).
//! Each binding turns its own values into these types and raises the [`ApiError`] it
//! gets back as its error (a C status and `rotlang_last_error`, a JavaScript
//! `RotlangError`, a Python `ValueError`), so one input gets one answer, with one
//! wording, in every language; a fix here lands in all of them.
//!
//! ```
//! use rotlang::api::{self, ErrorKind, ModelSpec, Style};
//! use rotlang::eval::limits::Given;
//!
//! let model = ModelSpec { layers: Some(Given::Int(50)), ..ModelSpec::default() };
//! assert_eq!(model.build(Style::Snake).map(|m| m.len()), Ok(50));
//! let bad = ModelSpec { top_shells: Some(Given::Float(-1.0)), ..ModelSpec::default() };
//! let e = bad.build(Style::Camel).unwrap_err();
//! assert_eq!(e.kind, ErrorKind::Model);
//! assert_eq!(e.message, "`topShells` must be a whole number from 0 to 4294967295, not -1");
//! assert_eq!(api::dialect(" OrcaSlicer ").map(|d| d.name()), Ok("orcaslicer"));
//! ```

// The API of every binding: documented in full (issue 21 asks it of the whole crate).
#![warn(missing_docs)]

use std::borrow::Cow;
use std::fmt::{self, Write};

use crate::Target;
use crate::dialect::Dialect;
use crate::eval::limits::{self, Given, LimitError};
use crate::eval::{Model, Options};

/// What kind of input was refused: a binding maps it to its own error (C:
/// `ROTLANG_STATUS_INVALID_ARGUMENT` or `_INVALID_MODEL`; JavaScript: the
/// `RotlangError`'s `kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// A target, dialect, base or seed.
    Options,
    /// The model: its layers, heights or shell counts.
    Model,
    /// A profile file that cannot be read at all (`rotlang_profile::api::profile`).
    Profile,
}

impl ErrorKind {
    /// `"options"` or `"model"`.
    pub fn as_str(self) -> &'static str {
        match self {
            ErrorKind::Options => "options",
            ErrorKind::Model => "model",
            ErrorKind::Profile => "profile",
        }
    }
}

/// A refused input: its kind and the message the binding shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ApiError {
    /// Options or model.
    pub kind: ErrorKind,
    /// One line of English naming the value and what is allowed.
    pub message: String,
}

impl ApiError {
    fn options(e: impl fmt::Display) -> ApiError {
        ApiError {
            kind: ErrorKind::Options,
            message: e.to_string(),
        }
    }

    fn model(e: impl fmt::Display) -> ApiError {
        ApiError {
            kind: ErrorKind::Model,
            message: e.to_string(),
        }
    }
}

impl fmt::Display for ApiError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ApiError {}

/// How the binding spells option names in its messages: `bottom_shells` in C and Python
/// (their field and argument names), `bottomShells` in JavaScript.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// `first_layer_height`.
    Snake,
    /// `firstLayerHeight`.
    Camel,
}

impl Style {
    /// `name` (one of the snake-case option names of this module) in this style. A
    /// table rather than a conversion: the WebAssembly module carries this code.
    pub fn name(self, name: &'static str) -> &'static str {
        match (self, name) {
            (Style::Camel, "bottom_shells") => "bottomShells",
            (Style::Camel, "top_shells") => "topShells",
            (Style::Camel, "layer_height") => "layerHeight",
            (Style::Camel, "first_layer_height") => "firstLayerHeight",
            _ => name,
        }
    }
}

/// The names of the targets, in the order of their numbers (C's `RotlangTarget`).
pub const TARGETS: [&str; 2] = ["sparse", "solid"];
/// The names of the dialects, in the order of their numbers (C's `RotlangDialect`).
pub const DIALECTS: [&str; 2] = ["rotlang", "orcaslicer"];

/// `names` as "`a` or `b`", or with their numbers, "0 (a) or 1 (b)".
fn listed(names: &[&str], numbered: bool) -> String {
    let mut out = String::new();
    for (i, n) in names.iter().enumerate() {
        if i > 0 {
            out.push_str(" or ");
        }
        if numbered {
            let _ = write!(out, "{i} ({n})");
        } else {
            let _ = write!(out, "`{n}`");
        }
    }
    out
}

/// The index of `given` (any case, spaces around ignored) in `names`.
fn choice(what: &str, names: &[&str], given: &str) -> Result<usize, ApiError> {
    names
        .iter()
        .position(|n| n.eq_ignore_ascii_case(given.trim()))
        .ok_or_else(|| {
            ApiError::options(format!(
                "unknown {what} `{given}`; expected {}",
                listed(names, false)
            ))
        })
}

/// The number of a choice, as C passes it: below `names.len()`.
fn numbered(what: &str, names: &[&str], given: u64) -> Result<usize, ApiError> {
    usize::try_from(given)
        .ok()
        .filter(|i| *i < names.len())
        .ok_or_else(|| {
            ApiError::options(format!(
                "`{what}` must be {}, not {given}",
                listed(names, true)
            ))
        })
}

fn target_at(i: usize) -> Target {
    match i {
        1 => Target::Solid,
        _ => Target::Sparse,
    }
}

fn dialect_at(i: usize) -> Dialect {
    match i {
        1 => Dialect::OrcaSlicer,
        _ => Dialect::Rotlang,
    }
}

/// A target by name: `sparse` or `solid` (any case).
pub fn target(name: &str) -> Result<Target, ApiError> {
    choice("target", &TARGETS, name).map(target_at)
}

/// A dialect by name: `rotlang` or `orcaslicer` (any case).
pub fn dialect(name: &str) -> Result<Dialect, ApiError> {
    choice("dialect", &DIALECTS, name).map(dialect_at)
}

/// A target by number: 0 sparse, 1 solid.
pub fn target_number(given: u64) -> Result<Target, ApiError> {
    numbered("target", &TARGETS, given).map(target_at)
}

/// A dialect by number: 0 rotlang, 1 orcaslicer.
pub fn dialect_number(given: u64) -> Result<Dialect, ApiError> {
    numbered("dialect", &DIALECTS, given).map(dialect_at)
}

/// The evaluation options: `base` (degrees, absent: 0) and `seed` (absent: 0) at most
/// `max_seed` ([`limits::MAX_SEED`], or [`limits::MAX_EXACT_SEED`] where numbers are
/// doubles).
pub fn options(base: Option<f64>, seed: Option<Given>, max_seed: u64) -> Result<Options, ApiError> {
    let base = limits::base(base.unwrap_or(0.0)).map_err(ApiError::options)?;
    let seed = match seed {
        Some(seed) => limits::seed("seed", seed, max_seed).map_err(ApiError::options)?,
        None => 0,
    };
    Ok(Options { base, seed })
}

/// The refusal of an integer option the binding could not even turn into a [`Given`]
/// (a Python integer beyond 128 bits): `name` in snake case, `shown` as the caller
/// prints the value.
pub fn out_of_range(name: &'static str, style: Style, shown: &dyn fmt::Display) -> ApiError {
    let (min, max, kind) = match name {
        "seed" => (0, limits::MAX_SEED, ErrorKind::Options),
        "layers" => (1, crate::eval::MAX_LAYERS as u64, ErrorKind::Model),
        _ => (0, limits::MAX_SHELLS, ErrorKind::Model),
    };
    let LimitError { message } = limits::out_of_range(style.name(name), min, max, shown);
    ApiError { kind, message }
}

/// The refusal of a list of `count` layer heights, more than the evaluator takes: for
/// a binding to give before it even reads a list that long (C's `heights_len`).
pub fn too_many_layers(count: usize) -> ApiError {
    ApiError::model(crate::eval::ModelError::TooManyLayers(count as f64))
}

/// A model as a binding describes it. Exactly one of `heights`, `layers` and `height`
/// says how many layers there are (the first of them given wins, in that order); with
/// none of them, the model is the documentation's 20 mm cube.
#[derive(Clone, Debug, Default)]
pub struct ModelSpec<'a> {
    /// The height of every layer, bottom to top (mm): borrowed (copied into the model)
    /// or owned (moved into it, for a binding that made the list anyway).
    pub heights: Option<Cow<'a, [f64]>>,
    /// A uniform model: this many layers.
    pub layers: Option<Given>,
    /// A uniform model: as many layers as an object this tall (mm) needs.
    pub height: Option<f64>,
    /// The standard layer height `h` (mm). Absent: the first of `heights`, or 0.2.
    pub layer_height: Option<f64>,
    /// A uniform model's first layer (mm). Absent: `layer_height`.
    pub first_layer_height: Option<f64>,
    /// `B`. Absent: 3.
    pub bottom_shells: Option<Given>,
    /// `T`. Absent: 4.
    pub top_shells: Option<Given>,
}

/// The layer height of a uniform model when none is given.
const DEFAULT_LAYER_HEIGHT: f64 = 0.2;

impl ModelSpec<'_> {
    /// The model, checked: every refusal is an [`ErrorKind::Model`] error.
    pub fn build(self, style: Style) -> Result<Model, ApiError> {
        let lh = self.layer_height;
        let model = if let Some(heights) = self.heights {
            // Counted before the copy: a list this long is refused without one.
            if heights.len() > crate::eval::MAX_LAYERS {
                return Err(too_many_layers(heights.len()));
            }
            let h = lh
                .or(heights.first().copied())
                .unwrap_or(DEFAULT_LAYER_HEIGHT);
            Model::from_heights(heights.into_owned(), h)
        } else if let Some(n) = self.layers {
            let n = limits::layers(style.name("layers"), n).map_err(ApiError::model)?;
            let h = lh.unwrap_or(DEFAULT_LAYER_HEIGHT);
            Model::uniform(n, h, self.first_layer_height)
        } else if let Some(height) = self.height {
            let h = lh.unwrap_or(DEFAULT_LAYER_HEIGHT);
            Model::from_total_height(height, h, self.first_layer_height)
        } else if lh.is_some() || self.first_layer_height.is_some() {
            return Err(ApiError::model(
                "the model needs `layers`, `height` or a list of layer heights",
            ));
        } else {
            Ok(Model::cube20())
        };
        let model = model.map_err(ApiError::model)?;
        let shells = |name: &'static str, given: Option<Given>, default: u32| match given {
            Some(v) => limits::shells(style.name(name), v).map_err(ApiError::model),
            None => Ok(default),
        };
        let bottom = shells("bottom_shells", self.bottom_shells, model.bottom_shells())?;
        let top = shells("top_shells", self.top_shells, model.top_shells())?;
        Ok(model.with_shells(bottom, top))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> ModelSpec<'static> {
        ModelSpec::default()
    }

    #[test]
    fn names_are_read_in_any_case_and_refused_with_the_choices() {
        assert_eq!(target(" Solid"), Ok(Target::Solid));
        assert_eq!(dialect("rotlang"), Ok(Dialect::Rotlang));
        assert_eq!(
            dialect("cura").unwrap_err().message,
            "unknown dialect `cura`; expected `rotlang` or `orcaslicer`"
        );
        assert_eq!(
            target("top").unwrap_err(),
            ApiError::options("unknown target `top`; expected `sparse` or `solid`")
        );
        assert_eq!(dialect_number(1), Ok(Dialect::OrcaSlicer));
        assert_eq!(target_number(0), Ok(Target::Sparse));
        assert_eq!(
            dialect_number(7).unwrap_err().message,
            "`dialect` must be 0 (rotlang) or 1 (orcaslicer), not 7"
        );
        assert!(target_number(u64::MAX).is_err());
    }

    #[test]
    fn the_model_is_the_first_of_heights_layers_height_else_the_cube() {
        let list = [0.3, 0.2, 0.2];
        let m = ModelSpec {
            heights: Some(Cow::Borrowed(&list)),
            layers: Some(Given::Int(50)),
            ..spec()
        };
        let m = m.build(Style::Snake).unwrap();
        assert_eq!((m.len(), m.layer_height()), (3, 0.3));
        let m = ModelSpec {
            layers: Some(Given::Float(10.0)),
            height: Some(100.0),
            ..spec()
        };
        assert_eq!(m.build(Style::Camel).unwrap().len(), 10);
        let m = ModelSpec {
            height: Some(2.0),
            layer_height: Some(0.25),
            ..spec()
        };
        assert_eq!(m.build(Style::Snake).unwrap().len(), 8);
        let cube = spec().build(Style::Snake).unwrap();
        assert_eq!(
            (cube.len(), cube.bottom_shells(), cube.top_shells()),
            (100, 3, 4)
        );
        let m = ModelSpec {
            layers: Some(Given::Int(5)),
            bottom_shells: Some(Given::Int(0)),
            ..spec()
        };
        let m = m.build(Style::Snake).unwrap();
        assert_eq!((m.bottom_shells(), m.top_shells()), (0, 4));
    }

    #[test]
    fn every_refusal_of_a_model_is_a_model_error_in_the_callers_spelling() {
        let empty: [f64; 0] = [];
        let cases = [
            (
                ModelSpec {
                    heights: Some(Cow::Borrowed(&empty)),
                    ..spec()
                },
                "the model has no layers",
            ),
            (
                ModelSpec {
                    layers: Some(Given::Int(0)),
                    ..spec()
                },
                "`layers` must be a whole number from 1 to 100000000, not 0",
            ),
            (
                ModelSpec {
                    layer_height: Some(0.2),
                    ..spec()
                },
                "the model needs `layers`, `height` or a list of layer heights",
            ),
            (
                ModelSpec {
                    layers: Some(Given::Int(5)),
                    first_layer_height: Some(0.0),
                    ..spec()
                },
                "the first layer height is 0; it must be between 0.001 and 1000 mm",
            ),
            (
                ModelSpec {
                    layers: Some(Given::Int(5)),
                    bottom_shells: Some(Given::Int(1 << 33)),
                    ..spec()
                },
                "`bottomShells` must be a whole number from 0 to 4294967295, not 8589934592",
            ),
        ];
        for (spec, message) in cases {
            let e = spec.build(Style::Camel).unwrap_err();
            assert_eq!((e.kind, e.message.as_str()), (ErrorKind::Model, message));
        }
    }

    #[test]
    fn options_take_the_ranges_of_limits() {
        let o = options(Some(45.0), Some(Given::Int(7)), limits::MAX_SEED).unwrap();
        assert_eq!((o.base, o.seed), (45.0, 7));
        let e = options(Some(f64::NAN), None, limits::MAX_SEED).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Options);
        assert!(
            e.message.starts_with("`base` must be a finite number"),
            "{e}"
        );
        let e = options(
            None,
            Some(Given::Float(2f64.powi(53))),
            limits::MAX_EXACT_SEED,
        );
        assert!(
            e.unwrap_err()
                .message
                .contains("from 0 to 9007199254740991")
        );
        let e = out_of_range("top_shells", Style::Camel, &"1e40");
        assert_eq!(e.kind, ErrorKind::Model);
        assert_eq!(
            e.message,
            "`topShells` must be a whole number from 0 to 4294967295, not 1e40"
        );
        assert_eq!(Style::Camel.name("first_layer_height"), "firstLayerHeight");
    }
}
