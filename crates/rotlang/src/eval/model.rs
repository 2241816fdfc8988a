//! The model: the layers of one object, the standard layer height and the shell counts.
//!
//! Layer bounds are running sums in double precision (`b[i+1] = t[i] = b[i] + height[i]`),
//! exactly as SEMANTICS.md section 1 defines them. A model given as a list stores those
//! sums; a uniform model stores three numbers and computes the same sums arithmetically
//! ([`running_sum`]), so both kinds give bitwise identical bounds for the same heights, and
//! the top of a 1e8-layer model costs no more than that of a 10-layer one.

use std::fmt;

/// Layers thinner than one micrometre cannot come from a slicer (heights are scaled
/// integers there) and would drown in the evaluator's 1e-6 mm tie tolerance.
pub const MIN_LAYER_HEIGHT: f64 = 0.001;
/// A layer taller than a metre is not a print; the bound keeps every sum finite.
pub const MAX_LAYER_HEIGHT: f64 = 1000.0;
/// A hundred million layers is ten kilometres of 0.1 mm layers: anything above is a typo.
pub const MAX_LAYERS: usize = 100_000_000;

/// Why a model could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// The model has no layers.
    NoLayers,
    /// A layer height is zero, negative, not finite, or outside the sane range.
    LayerHeight {
        /// The layer (0 for the first).
        index: usize,
        /// Its height as given.
        value: f64,
    },
    /// The standard layer height is zero, negative, not finite, or outside the sane range.
    StandardLayerHeight(f64),
    /// The first layer height is zero, negative, not finite, or outside the sane range.
    FirstLayerHeight(f64),
    /// The object height is zero, negative or not finite.
    ObjectHeight(f64),
    /// More layers than [`MAX_LAYERS`].
    TooManyLayers(f64),
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let range = format!("between {MIN_LAYER_HEIGHT} and {MAX_LAYER_HEIGHT} mm");
        match self {
            ModelError::NoLayers => f.write_str("the model has no layers"),
            ModelError::LayerHeight { index, value } => {
                write!(
                    f,
                    "layer {index} has height {}; a layer height must be {range}",
                    short(*value)
                )
            }
            ModelError::StandardLayerHeight(v) => {
                write!(f, "the layer height is {}; it must be {range}", short(*v))
            }
            ModelError::FirstLayerHeight(v) => {
                write!(
                    f,
                    "the first layer height is {}; it must be {range}",
                    short(*v)
                )
            }
            ModelError::ObjectHeight(v) => {
                write!(
                    f,
                    "the object height is {}; it must be a positive number of mm",
                    short(*v)
                )
            }
            ModelError::TooManyLayers(n) => {
                write!(
                    f,
                    "the model would have {} layers; at most {MAX_LAYERS} are supported",
                    short(*n)
                )
            }
        }
    }
}

/// A number as written in messages: plain when near 1, in exponent form when far from it
/// (`1e-320`, not 320 zeros after the point; `1e300`, not 301 digits).
fn short(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-6..1e15).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl std::error::Error for ModelError {}

fn valid_height(h: f64) -> bool {
    (MIN_LAYER_HEIGHT..=MAX_LAYER_HEIGHT).contains(&h)
}

#[derive(Clone, Debug)]
enum Heights {
    /// `tops[i] = t[i]`, the running sums of the given heights.
    List(Vec<f64>),
    /// `layers` layers: the first of height `first`, every other of height `rest`.
    Uniform {
        layers: usize,
        first: f64,
        rest: f64,
    },
}

/// The layers of one object, bottom to top, with the profile values the template refers
/// to: the standard layer height `h` and the bottom/top shell layer counts `B` and `T`.
#[derive(Clone, Debug)]
pub struct Model {
    heights: Heights,
    layer_height: f64,
    bottom_shells: u32,
    top_shells: u32,
}

/// OrcaSlicer's default shell counts, used until [`Model::with_shells`] says otherwise.
const DEFAULT_BOTTOM_SHELLS: u32 = 3;
const DEFAULT_TOP_SHELLS: u32 = 4;

impl Model {
    /// A model from the height of every layer (bottom to top) and the standard layer
    /// height `h`. Shell counts default to 3 bottom and 4 top (OrcaSlicer's defaults).
    pub fn from_heights(layer_heights: Vec<f64>, layer_height: f64) -> Result<Model, ModelError> {
        if !valid_height(layer_height) {
            return Err(ModelError::StandardLayerHeight(layer_height));
        }
        if layer_heights.is_empty() {
            return Err(ModelError::NoLayers);
        }
        if layer_heights.len() > MAX_LAYERS {
            return Err(ModelError::TooManyLayers(layer_heights.len() as f64));
        }
        // Turn the heights into running sums in place: no second buffer.
        let mut tops = layer_heights;
        let mut sum = 0.0;
        for (index, slot) in tops.iter_mut().enumerate() {
            let value = *slot;
            if !valid_height(value) {
                return Err(ModelError::LayerHeight { index, value });
            }
            sum += value;
            *slot = sum;
        }
        Ok(Model {
            heights: Heights::List(tops),
            layer_height,
            bottom_shells: DEFAULT_BOTTOM_SHELLS,
            top_shells: DEFAULT_TOP_SHELLS,
        })
    }

    /// `layers` layers of `layer_height`, the first one of `first_layer_height` if given.
    /// Stores no per-layer data: a million layers take as much memory as ten.
    pub fn uniform(
        layers: usize,
        layer_height: f64,
        first_layer_height: Option<f64>,
    ) -> Result<Model, ModelError> {
        if !valid_height(layer_height) {
            return Err(ModelError::StandardLayerHeight(layer_height));
        }
        let first = first_layer_height.unwrap_or(layer_height);
        if !valid_height(first) {
            return Err(ModelError::FirstLayerHeight(first));
        }
        if layers == 0 {
            return Err(ModelError::NoLayers);
        }
        if layers > MAX_LAYERS {
            return Err(ModelError::TooManyLayers(layers as f64));
        }
        Ok(Model {
            heights: Heights::Uniform {
                layers,
                first,
                rest: layer_height,
            },
            layer_height,
            bottom_shells: DEFAULT_BOTTOM_SHELLS,
            top_shells: DEFAULT_TOP_SHELLS,
        })
    }

    /// A uniform model tall enough for an object of `height` mm: the first layer, then as
    /// many standard layers as it takes to reach `height` (the last one may overshoot;
    /// a shortfall of up to 1e-6 layer is forgiven so that `20 / 0.2` gives 100 layers).
    pub fn from_total_height(
        height: f64,
        layer_height: f64,
        first_layer_height: Option<f64>,
    ) -> Result<Model, ModelError> {
        if !(height.is_finite() && height > 0.0) {
            return Err(ModelError::ObjectHeight(height));
        }
        if !valid_height(layer_height) {
            return Err(ModelError::StandardLayerHeight(layer_height));
        }
        let first = first_layer_height.unwrap_or(layer_height);
        if !valid_height(first) {
            return Err(ModelError::FirstLayerHeight(first));
        }
        let rest = ((height - first) / layer_height - 1e-6).ceil().max(0.0);
        let layers = 1.0 + rest;
        if layers > MAX_LAYERS as f64 {
            return Err(ModelError::TooManyLayers(layers));
        }
        // `layers` is a whole number in 1..=MAX_LAYERS here, so the cast is exact.
        Model::uniform(layers as usize, layer_height, first_layer_height)
    }

    /// The same model with the given bottom (`B`) and top (`T`) shell layer counts.
    pub fn with_shells(self, bottom: u32, top: u32) -> Model {
        Model {
            bottom_shells: bottom,
            top_shells: top,
            ..self
        }
    }

    /// The documentation's reference model (models.json `cube20`): a 20 mm cube of
    /// 100 layers of 0.2 mm, 3 bottom and 4 top shell layers.
    pub fn cube20() -> Model {
        Model {
            heights: Heights::Uniform {
                layers: 100,
                first: 0.2,
                rest: 0.2,
            },
            layer_height: 0.2,
            bottom_shells: 3,
            top_shells: 4,
        }
    }

    /// How many layers the model has (at least one).
    pub fn len(&self) -> usize {
        match &self.heights {
            Heights::List(tops) => tops.len(),
            Heights::Uniform { layers, .. } => *layers,
        }
    }

    /// Always false: a model has at least one layer.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The standard layer height `h` (mm).
    pub fn layer_height(&self) -> f64 {
        self.layer_height
    }

    /// How many bottom shell layers (`B`).
    pub fn bottom_shells(&self) -> u32 {
        self.bottom_shells
    }

    /// How many top shell layers (`T`).
    pub fn top_shells(&self) -> u32 {
        self.top_shells
    }

    /// The object height `H`: the sum of the layer heights rounded to whole micrometres.
    /// O(1).
    pub fn object_height(&self) -> f64 {
        (self.last_top() * 1000.0).round() / 1000.0
    }

    /// The bottom and top of layer `index` (mm), or `None` past the top. O(1): bitwise
    /// the bounds the evaluator streams.
    pub fn layer_bounds(&self, index: usize) -> Option<(f64, f64)> {
        match &self.heights {
            Heights::List(tops) => {
                let top = *tops.get(index)?;
                let bottom = match index.checked_sub(1) {
                    Some(below) => tops.get(below).copied().unwrap_or(0.0),
                    None => 0.0,
                };
                Some((bottom, top))
            }
            Heights::Uniform {
                layers,
                first,
                rest,
            } => {
                if index >= *layers {
                    return None;
                }
                let cursor = Cursor::new(self);
                if index == 0 {
                    return Some((cursor.bottom, cursor.top));
                }
                let bottom = running_sum(cursor.top, *rest, index - 1);
                debug_assert!(index > 1 || bottom == 0.0 + first);
                Some((bottom, bottom + rest))
            }
        }
    }

    /// `t[last]`, the top of the highest layer. O(1).
    pub(crate) fn last_top(&self) -> f64 {
        match &self.heights {
            Heights::List(tops) => tops.last().copied().unwrap_or(0.0),
            Heights::Uniform {
                layers,
                first,
                rest,
            } => running_sum(0.0 + first, *rest, layers - 1),
        }
    }

    /// `t[j]` for a `j` at or above the layer a cursor stands on, bitwise the running sum
    /// the cursor will follow. O(1).
    pub(crate) fn top_at(&self, cursor: &Cursor, j: usize) -> f64 {
        match &self.heights {
            Heights::List(tops) => tops.get(j).copied().unwrap_or_else(|| self.last_top()),
            Heights::Uniform { layers, rest, .. } => {
                if j + 1 >= *layers {
                    return self.last_top();
                }
                running_sum(cursor.top, *rest, j.saturating_sub(cursor.index))
            }
        }
    }
}

/// `start + step + step + …` with `n` additions, each rounded as `t += step` rounds it:
/// bitwise the loop's result, in O(binades) instead of O(n) (for positive `step`).
///
/// Why it works: while `t` and `t + step` stay in one binade `[2^e, 2^(e+1))`, every
/// value is a multiple of that binade's ulp `u`, and `t + step` rounds to `t + k·u` with
/// the same `k` each time; only an exact tie (`step` ending in half an ulp) depends on
/// the parity of `t`, and after one rounding in the binade `t` is even, so from then on
/// the increment is constant too. So: step one at a time until three consecutive values
/// share a binade, then add the (exact) increment as many times as the binade allows
/// at once, and go on stepping across the binade's edge.
pub(crate) fn running_sum(start: f64, step: f64, n: usize) -> f64 {
    let binade = |x: f64| x.to_bits() >> 52;
    let mut t = start;
    let mut left = n;
    if !(step > 0.0 && start >= 0.0 && start.is_finite() && step.is_finite()) {
        // Not a model's heights: the plain loop (validated models never come here).
        for _ in 0..n {
            t += step;
        }
        return t;
    }
    let mut prev = f64::NAN;
    while left > 0 {
        let next = t + step;
        left -= 1;
        if next == t {
            // `step` is below half an ulp of `t`: nothing will ever change `t` again.
            return t;
        }
        if left > 0 && binade(prev) == binade(t) && binade(t) == binade(next) && prev > 0.0 {
            // `next - t` is exact (same binade); the binade ends at the next power of two.
            let d = next - t;
            let end = f64::from_bits((binade(next) + 1) << 52);
            // The exact sum `next + i·d + step` must stay below `end` for every jump; four
            // jumps short of the edge leaves room for the rounding of `room / d`.
            let room = ((end - next - step) / d).floor() - 4.0;
            if room >= 1.0 {
                let k = (room as usize).min(left);
                // `k·d` and `next + k·d` are multiples of the ulp below `end`: both exact.
                t = next + k as f64 * d;
                left -= k;
                prev = t - d;
                continue;
            }
        }
        prev = t;
        t = next;
    }
    t
}

impl Default for Model {
    /// [`Model::cube20`].
    fn default() -> Self {
        Model::cube20()
    }
}

/// Walks the layers of a model bottom to top, keeping the running sums.
#[derive(Clone, Debug)]
pub(crate) struct Cursor {
    pub index: usize,
    pub bottom: f64,
    pub top: f64,
}

impl Cursor {
    /// At layer 0.
    pub fn new(model: &Model) -> Cursor {
        let top = match &model.heights {
            Heights::List(tops) => tops.first().copied().unwrap_or(0.0),
            Heights::Uniform { first, .. } => 0.0 + first,
        };
        Cursor {
            index: 0,
            bottom: 0.0,
            top,
        }
    }

    /// To the next layer. Past the top it keeps adding standard layers, harmlessly.
    #[inline]
    pub fn advance_in(&mut self, model: &Model) {
        self.index += 1;
        self.bottom = self.top;
        self.top = match &model.heights {
            Heights::List(tops) => match tops.get(self.index) {
                Some(&t) => t,
                None => self.bottom + model.layer_height,
            },
            Heights::Uniform { rest, .. } => self.bottom + rest,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn looped(start: f64, step: f64, n: usize) -> f64 {
        let mut t = start;
        for _ in 0..n {
            t += step;
        }
        t
    }

    #[test]
    fn running_sum_is_the_loop_bitwise() {
        // Steps whose last bit is half an ulp of some partial sum (ties: 0.2 from 0.25 up,
        // 0.1, 0.3), tiny and huge layers, and pseudo-random ones.
        let mut steps = vec![0.2, 0.1, 0.3, 0.05, 0.12, 0.001, 0.28, 1000.0, 0.15, 0.075];
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..20 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            steps.push(MIN_LAYER_HEIGHT + (x % 1_000_000) as f64 / 1_000_000.0);
        }
        for &step in &steps {
            for start in [step, 0.3, 0.001, 0.25, 1.0, 1000.0, step * 3.0] {
                let mut t = start;
                for n in 0..5_000 {
                    // Every n up to 5 000 (each crossing of a binade edge), then long ones.
                    assert_eq!(
                        running_sum(start, step, n).to_bits(),
                        t.to_bits(),
                        "start {start}, step {step}, n {n}"
                    );
                    t += step;
                }
                for n in [65_537, 300_007] {
                    assert_eq!(
                        running_sum(start, step, n).to_bits(),
                        looped(start, step, n).to_bits(),
                        "start {start}, step {step}, n {n}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_hundred_million_layers_sum_up_the_same() {
        for (h, h0) in [(0.2, 0.2), (0.1, 0.3), (0.001, 0.001)] {
            let model = Model::uniform(MAX_LAYERS, h, Some(h0)).unwrap();
            assert_eq!(
                model.last_top().to_bits(),
                looped(h0, h, MAX_LAYERS - 1).to_bits(),
                "h {h}, first {h0}"
            );
        }
    }

    #[test]
    fn layer_bounds_are_the_cursor_bounds() {
        let model = Model::uniform(50_000, 0.2, Some(0.3)).unwrap();
        let mut cursor = Cursor::new(&model);
        for i in 0..50_000 {
            let (b, t) = model.layer_bounds(i).unwrap();
            assert_eq!(
                (b.to_bits(), t.to_bits()),
                (cursor.bottom.to_bits(), cursor.top.to_bits())
            );
            if i % 997 == 0 {
                for j in [i, i + 1, i + 77, 49_999, 60_000] {
                    let mut c = cursor.clone();
                    while c.index < j.min(49_999) {
                        c.advance_in(&model);
                    }
                    assert_eq!(
                        model.top_at(&cursor, j).to_bits(),
                        c.top.to_bits(),
                        "i {i} j {j}"
                    );
                }
            }
            cursor.advance_in(&model);
        }
        assert_eq!(model.layer_bounds(50_000), None);
    }
}
