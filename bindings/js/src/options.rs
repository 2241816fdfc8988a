//! The request that every call takes: target, dialect, model, base, seed and a layer
//! range, as a flat array of numbers (the JS wrapper checks names and types and fills the
//! slots; the last slot says which are given, so that a NaN the caller gave is told from
//! an absent value). The values are read by `rotlang::api`, as the C and Python bindings
//! read theirs: one check, one message, in every language.

use rotlang::Target;
use rotlang::api::{self, ApiError, ErrorKind, ModelSpec, Style};
use rotlang::dialect::Dialect;
use rotlang::eval::limits::{self, Given};
use rotlang::eval::{Model, Options};

use crate::Failure;

/// Slots of the request array (kept in step with `SLOTS` in rotlang.js).
pub mod slot {
    pub const TARGET: usize = 0;
    pub const DIALECT: usize = 1;
    pub const LAYERS: usize = 2;
    pub const HEIGHT: usize = 3;
    pub const LAYER_HEIGHT: usize = 4;
    pub const FIRST_LAYER_HEIGHT: usize = 5;
    pub const BOTTOM_SHELLS: usize = 6;
    pub const TOP_SHELLS: usize = 7;
    pub const BASE: usize = 8;
    pub const SEED: usize = 9;
    pub const FROM: usize = 10;
    pub const TO: usize = 11;
    /// The preview's layer.
    pub const LAYER: usize = 12;
    /// The preview's sparse density, in (0, 1].
    pub const DENSITY: usize = 13;
    /// The preview's pattern: an index into `PATTERNS`.
    pub const PATTERN: usize = 14;
    /// The preview's outline: an index into `SHAPES`.
    pub const SHAPE: usize = 15;
    /// Picture size in pixels (the plot's width and height; the preview panel's side).
    pub const WIDTH: usize = 16;
    pub const PICTURE_HEIGHT: usize = 17;
    /// Which slots are given: bit `i` for slot `i`. Absent (NaN, or a request from
    /// before this slot): every slot that is not NaN.
    pub const PRESENT: usize = 18;
    pub const COUNT: usize = 19;
}

#[derive(Clone, Debug)]
pub struct Request {
    slots: [f64; slot::COUNT],
    /// Bit `i`: slot `i` is given.
    present: u32,
}

impl Default for Request {
    fn default() -> Self {
        Request {
            slots: [f64::NAN; slot::COUNT],
            present: 0,
        }
    }
}

/// A refusal of the shared API as the JS wrapper's failure (`kind` options or model).
impl From<ApiError> for Failure {
    fn from(e: ApiError) -> Failure {
        match e.kind {
            ErrorKind::Options => Failure::options(e.message),
            ErrorKind::Model => Failure::model(e.message),
            ErrorKind::Profile => Failure {
                kind: "profile",
                message: e.message,
                diagnostics: None,
            },
        }
    }
}

/// Names for messages.
const NAMES: [&str; slot::COUNT] = [
    "target",
    "dialect",
    "layers",
    "height",
    "layerHeight",
    "firstLayerHeight",
    "bottomShells",
    "topShells",
    "base",
    "seed",
    "from",
    "to",
    "layer",
    "density",
    "pattern",
    "shape",
    "width",
    "height",
    "present",
];

impl Request {
    /// From the slots (missing trailing slots are absent).
    pub fn new(values: &[f64]) -> Request {
        let mut r = Request::default();
        for (slot, v) in r.slots.iter_mut().zip(values) {
            *slot = *v;
        }
        let mask = r.slots[slot::PRESENT];
        r.present = if (0.0..=f64::from(u32::MAX)).contains(&mask) && mask.fract() == 0.0 {
            mask as u32
        } else {
            (0..slot::PRESENT)
                .filter(|&i| !r.slots[i].is_nan())
                .fold(0, |m, i| m | 1 << i)
        };
        r
    }

    /// Sets a slot (for Rust callers and tests).
    pub fn with(mut self, slot: usize, value: f64) -> Request {
        self.slots[slot] = value;
        self.present |= 1 << slot;
        self
    }

    /// A slot's value when given (a given NaN included: the check that reads it refuses
    /// it by name).
    fn get(&self, slot: usize) -> Option<f64> {
        (self.present & 1 << slot != 0).then_some(self.slots[slot])
    }

    /// A whole, non-negative number from a slot (`max` inclusive).
    fn whole(&self, slot: usize, max: u64) -> Result<Option<u64>, Failure> {
        self.get(slot)
            .map(|v| limits::whole(NAMES[slot], Given::Float(v), 0, max))
            .transpose()
            .map_err(|e| Failure::options(e.message))
    }

    pub fn target(&self) -> Result<Target, Failure> {
        match self.whole(slot::TARGET, u64::MAX)? {
            Some(i) => Ok(api::target_number(i)?),
            None => Ok(Target::Sparse),
        }
    }

    pub fn dialect(&self) -> Result<Dialect, Failure> {
        match self.whole(slot::DIALECT, u64::MAX)? {
            Some(i) => Ok(api::dialect_number(i)?),
            None => Ok(Dialect::Rotlang),
        }
    }

    /// The base and seed, read by `rotlang::api` as every binding's are; a seed above
    /// 2^53 cannot come exactly through a JS number.
    pub fn eval_options(&self) -> Result<Options, Failure> {
        let seed = self.get(slot::SEED).map(Given::Float);
        Ok(api::options(
            self.get(slot::BASE),
            seed,
            limits::MAX_EXACT_SEED,
        )?)
    }

    /// A number from a slot (absent: None).
    pub fn number(&self, slot: usize) -> Option<f64> {
        self.get(slot)
    }

    /// A whole number from a slot, at most `max`.
    pub fn index(&self, slot: usize, max: usize) -> Result<Option<usize>, Failure> {
        Ok(self
            .whole(slot, max as u64)?
            .map(|v| usize::try_from(v).unwrap_or(max)))
    }

    /// A picture size in pixels from a slot: 16 to 4096, or `default`.
    pub fn pixels(&self, slot: usize, default: f64) -> Result<f64, Failure> {
        match self.get(slot) {
            None => Ok(default),
            Some(v) if (16.0..=4096.0).contains(&v) => Ok(v),
            Some(v) => Err(Failure::options(format!(
                "`{}` must be from 16 to 4096 pixels, not {v}",
                NAMES[slot]
            ))),
        }
    }

    /// The first layer and one past the last layer asked for (absent: None).
    pub fn range(&self) -> Result<(Option<usize>, Option<usize>), Failure> {
        let max = rotlang::eval::MAX_LAYERS;
        let index = |slot| {
            self.whole(slot, max as u64)
                .map(|v| v.map(|v| usize::try_from(v).unwrap_or(max)))
        };
        let (from, to) = (index(slot::FROM)?, index(slot::TO)?);
        Ok((from, to))
    }

    /// The model (`rotlang::api::ModelSpec`): list heights when given, else the uniform
    /// model described, else the documentation's 20 mm cube.
    pub fn model(&self, heights: Option<Vec<f64>>) -> Result<Model, Failure> {
        let whole = |slot| self.get(slot).map(Given::Float);
        let spec = ModelSpec {
            // Moved into the model: the list is not copied again.
            heights: heights.map(Into::into),
            layers: whole(slot::LAYERS),
            height: self.get(slot::HEIGHT),
            layer_height: self.get(slot::LAYER_HEIGHT),
            first_layer_height: self.get(slot::FIRST_LAYER_HEIGHT),
            bottom_shells: whole(slot::BOTTOM_SHELLS),
            top_shells: whole(slot::TOP_SHELLS),
        };
        Ok(spec.build(Style::Camel)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absent_slots_give_the_cube_and_defaults() {
        let r = Request::new(&[]);
        assert_eq!(r.target().unwrap(), Target::Sparse);
        assert_eq!(r.model(None).unwrap().len(), 100);
        assert_eq!(r.range().unwrap(), (None, None));
    }

    #[test]
    fn bad_values_are_refused_with_their_name() {
        let e = Request::default()
            .with(slot::SEED, -1.0)
            .eval_options()
            .unwrap_err();
        assert!(e.message.contains("`seed`"), "{}", e.message);
        let e = Request::default()
            .with(slot::LAYERS, 2.5)
            .model(None)
            .unwrap_err();
        assert_eq!(e.kind, "model");
        let e = Request::default()
            .with(slot::LAYER_HEIGHT, 0.2)
            .model(None)
            .unwrap_err();
        assert!(e.message.contains("needs `layers`"));
        let e = Request::default()
            .with(slot::LAYERS, 10.0)
            .with(slot::TOP_SHELLS, -2.0)
            .model(None)
            .unwrap_err();
        assert!(e.message.contains("`topShells`"), "{}", e.message);
        assert!(Request::default().with(slot::FROM, 1.5).range().is_err());
    }

    #[test]
    fn base_and_seed_have_the_ranges_of_every_binding() {
        for base in [2e300, -2e300, 1e9 + 1.0] {
            let e = Request::default()
                .with(slot::BASE, base)
                .eval_options()
                .unwrap_err();
            assert_eq!(e.kind, "options");
            assert!(e.message.contains("within ±1000000000"), "{}", e.message);
        }
        let ok = Request::default().with(slot::BASE, -1e9).eval_options();
        assert_eq!(ok.map(|o| o.base).ok(), Some(-1e9));
        let e = Request::default()
            .with(slot::SEED, 2f64.powi(53))
            .eval_options()
            .unwrap_err();
        assert_eq!(
            e.message,
            "`seed` must be a whole number from 0 to 9007199254740991, not 9007199254740992"
        );
        let e = Request::default()
            .with(slot::LAYERS, 0.0)
            .model(None)
            .unwrap_err();
        assert_eq!(
            (e.kind, e.message.as_str()),
            (
                "model",
                "`layers` must be a whole number from 1 to 100000000, not 0"
            )
        );
    }
}
