//! The model and the evaluation options as C structs, and their checked conversion.

use std::borrow::Cow;

use rotlang::api::{self, ModelSpec, Style};
use rotlang::dialect::Dialect;
use rotlang::eval::limits::{Given, MAX_SEED};
use rotlang::eval::{MAX_LAYERS, Model, Options};

use crate::status::Failure;
use crate::util::slice;

/// How a template is read (the `dialect` field of `RotlangOptions`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangDialect {
    /// rotlang's own semantics: the template must parse without errors.
    Rotlang = 0,
    /// Exactly what OrcaSlicer computes, for any text (valid or not); its defects
    /// (hangs, undefined counts, NaN layers) are reported as findings.
    Orcaslicer = 1,
}

/// The fill of a layer (the `fills` output).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangFill {
    Sparse = 0,
    Dense = 1,
    Solid = 2,
    Concentric = 3,
    Monotonic = 4,
    Rectilinear = 5,
}

impl From<rotlang::Fill> for RotlangFill {
    fn from(fill: rotlang::Fill) -> Self {
        match fill {
            rotlang::Fill::Sparse => RotlangFill::Sparse,
            rotlang::Fill::Dense => RotlangFill::Dense,
            rotlang::Fill::Solid => RotlangFill::Solid,
            rotlang::Fill::Concentric => RotlangFill::Concentric,
            rotlang::Fill::Monotonic => RotlangFill::Monotonic,
            rotlang::Fill::Rectilinear => RotlangFill::Rectilinear,
        }
    }
}

/// The layers of one object. Either a list of heights (`heights` not NULL) or a uniform
/// model (`heights` NULL): `layers` layers of `layer_height`, the first one of
/// `first_layer_height` (0 = the same as `layer_height`). Build one with
/// `rotlang_model_uniform` or `rotlang_model_heights`, then set the shells if needed.
/// The library copies what it needs: the heights may be freed after the call.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RotlangModel {
    /// Height of every layer in mm, bottom to top; NULL for a uniform model.
    pub heights: *const f64,
    /// The number of entries of `heights` (must be at least 1 when `heights` is set).
    pub heights_len: usize,
    /// Uniform model only: the number of layers.
    pub layers: usize,
    /// The standard layer height `h` (mm); also the height of a uniform model's layers.
    pub layer_height: f64,
    /// Uniform model only: the first layer's height (mm); 0 means `layer_height`.
    pub first_layer_height: f64,
    /// `B`, the bottom shell layer count.
    pub bottom_shells: u32,
    /// `T`, the top shell layer count.
    pub top_shells: u32,
}

/// Evaluation options. Passing NULL where a `const RotlangOptions *` is expected means
/// all defaults: base 0, seed 0, the rotlang dialect.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct RotlangOptions {
    /// The base direction in degrees, added to every angle (the profile's infill
    /// direction). OrcaSlicer's own function adds none: keep 0 to match it.
    pub base: f64,
    /// The seed of the random joints `~` and `^`.
    pub seed: u64,
    /// A `RotlangDialect` value.
    pub dialect: u32,
}

/// OrcaSlicer's default shell counts, as in `rotlang::eval::Model`.
const DEFAULT_BOTTOM_SHELLS: u32 = 3;
const DEFAULT_TOP_SHELLS: u32 = 4;

/// A uniform model: `layers` layers of `layer_height` mm, the first of
/// `first_layer_height` (0 = `layer_height`); shells 3 bottom, 4 top. Only fills a
/// struct: the values are checked when the model is used.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_model_uniform(
    layers: usize,
    layer_height: f64,
    first_layer_height: f64,
) -> RotlangModel {
    RotlangModel {
        heights: std::ptr::null(),
        heights_len: 0,
        layers,
        layer_height,
        first_layer_height,
        bottom_shells: DEFAULT_BOTTOM_SHELLS,
        top_shells: DEFAULT_TOP_SHELLS,
    }
}

/// A model from the height of every layer (`count` entries at `heights`, bottom to top)
/// and the standard layer height; shells 3 bottom, 4 top. Only fills a struct: the
/// pointer and values are checked when the model is used.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_model_heights(
    heights: *const f64,
    count: usize,
    layer_height: f64,
) -> RotlangModel {
    RotlangModel {
        heights,
        heights_len: count,
        layers: 0,
        layer_height,
        first_layer_height: 0.0,
        bottom_shells: DEFAULT_BOTTOM_SHELLS,
        top_shells: DEFAULT_TOP_SHELLS,
    }
}

impl RotlangModel {
    /// The Rust model, checked by `rotlang::api` as every binding's is (heights NaN,
    /// negative, zero or absurd, too many layers are refused).
    ///
    /// # Safety
    /// `heights` is NULL or points to `heights_len` readable doubles.
    pub(crate) unsafe fn checked_model(&self) -> Result<Model, Failure> {
        let heights = match self.heights.is_null() {
            true => None,
            // An empty list is the API's "no layers"; a non-empty one is read (the API
            // counts it before copying it).
            false if self.heights_len == 0 => Some(Cow::Borrowed(&[][..])),
            // Too long to be memory, maybe: refused as the model it describes.
            false if self.heights_len > MAX_LAYERS => {
                return Err(api::too_many_layers(self.heights_len).into());
            }
            // SAFETY: the caller's contract.
            false => Some(Cow::Borrowed(unsafe {
                slice(self.heights, self.heights_len, "the heights")
            }?)),
        };
        let uniform = heights.is_none();
        let spec = ModelSpec {
            heights,
            layers: uniform.then_some(Given::Int(self.layers as i128)),
            height: None,
            layer_height: Some(self.layer_height),
            // 0 is "the same as layer_height" in the C struct.
            first_layer_height: (uniform && self.first_layer_height != 0.0)
                .then_some(self.first_layer_height),
            bottom_shells: Some(Given::Int(self.bottom_shells.into())),
            top_shells: Some(Given::Int(self.top_shells.into())),
        };
        spec.build(Style::Snake).map_err(Failure::from)
    }
}

/// Options read from C, with the dialect decoded.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub options: Options,
    pub dialect: RotlangDialect,
}

impl Settings {
    pub(crate) fn from_c(options: Option<&RotlangOptions>) -> Result<Settings, Failure> {
        let o = options.copied().unwrap_or_default();
        let dialect = match api::dialect_number(o.dialect.into()).map_err(Failure::from)? {
            Dialect::OrcaSlicer => RotlangDialect::Orcaslicer,
            _ => RotlangDialect::Rotlang,
        };
        let options = api::options(Some(o.base), Some(Given::Int(o.seed.into())), MAX_SEED)
            .map_err(Failure::from)?;
        Ok(Settings { options, dialect })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::RotlangStatus;

    #[test]
    fn a_list_longer_than_memory_is_an_invalid_model_before_it_is_read() {
        let h = [0.2];
        // (Only a length no buffer can have: a shorter wrong one would be read.)
        let m = rotlang_model_heights(h.as_ptr(), usize::MAX, 0.2);
        // SAFETY: the length is refused before the pointer is read.
        let e = unsafe { m.checked_model() }.unwrap_err();
        assert_eq!(e.status, RotlangStatus::InvalidModel);
        assert_eq!(
            e.detail.as_deref(),
            Some(
                "the model would have 1.8446744073709552e19 layers; at most 100000000 are supported"
            )
        );
    }
}
