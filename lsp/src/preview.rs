//! Previews: what the layers of a model get, summarised for hovers and inlay hints.
//!
//! The angles come from the library's evaluator (`rotlang::eval`) through
//! `for_each_layer`, the only function here that knows how evaluation is called.
//! Everything else is a bounded summary of the stream: memory is O(instructions), whatever
//! the number of layers.

use std::collections::BTreeMap;

use rotlang::eval::{self, Model};
use rotlang::{Fill, Span, Target, Template};

use crate::instructions::Spans;

use crate::reading::Reading;
use crate::settings::ModelSettings;

/// Layers listed in the whole-template hover.
pub const FIRST_LAYERS: usize = 24;
/// Layers listed per instruction in its hover.
pub const INSTRUCTION_SAMPLE: usize = 12;
/// Width of the sparkline, in characters.
pub const SPARKLINE_WIDTH: usize = 48;

/// One evaluated layer, as the server needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewLayer {
    pub index: usize,
    pub angle: f64,
    pub fill: Fill,
    pub instruction: Option<Span>,
}

/// The template a preview reads: its text and target, and its instructions' spans.
#[derive(Clone, Copy)]
pub struct Source<'a> {
    pub text: &'a str,
    pub target: Target,
    pub spans: &'a Spans,
}

impl Source<'_> {
    /// The template of instructions `range` (the library's IR, read again).
    pub fn template(&self, range: std::ops::Range<usize>) -> Template {
        self.spans.template(self.text, self.target, range)
    }
}

/// Evaluate the first `m` instructions of `source` (all of them: `m = len`) in its reading
/// with the library's evaluator, layer by layer, bottom to top, while `f` returns `true`;
/// each layer names the index of its instruction. The only function here that knows how
/// evaluation is called: on the evaluator's compact form of the text
/// (`eval::parse_layers`), never on the IR of half a million instructions. The text from
/// the first instruction to the `m`-th one's end holds exactly those instructions (a
/// template is its chunks, each read on its own; none starts with a quote, so the text is
/// not read as a quoted template), so its layers are those of the first `m` alone.
pub fn for_each_layer(
    source: Source<'_>,
    m: usize,
    reading: &Reading,
    mut f: impl FnMut(PreviewLayer, Option<usize>) -> bool,
) {
    let m = m.min(source.spans.len());
    let (start, end) = match (
        source.spans.span(0),
        m.checked_sub(1).and_then(|l| source.spans.span(l)),
    ) {
        (Some(first), Some(last)) => (first.start, last.end),
        _ => (0, 0),
    };
    let text = source.text.get(start..end).unwrap_or("");
    let (_, layers) = eval::parse_layers(text, source.target, &reading.model, reading.options);
    for layer in layers {
        let instruction = layer.instruction.map(|s| s.shift(start));
        let which = instruction
            .and_then(|span| source.spans.index_of(span))
            .filter(|&i| i < m);
        let go_on = f(
            PreviewLayer {
                index: layer.index,
                angle: layer.angle,
                fill: layer.fill,
                instruction,
            },
            which,
        );
        if !go_on {
            return;
        }
    }
}

/// Layers evaluated in search of first runs, per request: bounds the cost of inlay hints
/// on long templates over tall models.
pub const FIRST_RUN_BUDGET: usize = 2_000_000;

/// The first run of instruction `index` in the reading (see `rotlang::explain::first_run`,
/// which evaluates without a base: the reading's base is added to its angles, as the
/// evaluator adds it to every layer).
///
/// `reach`: the preview's (`Preview::reach`). Where the model's layers provably stay within
/// the first instructions, the run is found on those alone, with the same result and the
/// same charge to the budget (the whole template's length), in time independent of the
/// template's length.
///
/// `cache`: the template evaluated (the first `reach` instructions, or all), read again
/// from the text on the first call and kept by the caller for the next ones.
pub fn first_run(
    source: Source<'_>,
    index: usize,
    reading: &Reading,
    budget: &mut usize,
    reach: Option<usize>,
    cache: &mut Option<Template>,
) -> Option<Run> {
    let n = source.spans.len();
    // As the library: a dummy has no run, and costs nothing.
    if source
        .spans
        .get(source.text, source.target, index..index + 1)
        .first()?
        .is_dummy()
    {
        return None;
    }
    let run = match reach {
        Some(m) if m < n => {
            // The library charges the template's length first: the rest of it here.
            *budget = budget.checked_sub(n - m)?;
            if index >= m {
                // Never set up on this model (every layer is governed before `m - 1`), so
                // marking it once changes nothing and it has no run; the library would
                // still charge the budget for it.
                *budget = budget.checked_sub(m)?;
                *budget = budget.saturating_sub(reading.layers());
                return None;
            }
            let prefix = cache.get_or_insert_with(|| source.template(0..m));
            rotlang::explain::first_run(prefix, index, &reading.model, budget)?
        }
        _ => {
            // The library would refuse before evaluating: refused before reading it all.
            if *budget < n {
                return None;
            }
            let whole = cache.get_or_insert_with(|| source.template(0..n));
            rotlang::explain::first_run(whole, index, &reading.model, budget)?
        }
    };
    let base = reading.options.base;
    Some(Run {
        from: run.from + base,
        first: run.first + base,
        to: run.to + base,
        ..run
    })
}

/// A contiguous block of layers governed by one instruction (the library's).
pub use rotlang::explain::Run;

/// The evaluator's model for the settings. Settings are validated with the evaluator's own
/// limits, so the fallback (the 20 mm cube) is only there should those change.
pub fn model_of(model: &ModelSettings) -> Model {
    Model::uniform(model.layers, model.layer_height, model.first_layer_height)
        .map(|m| m.with_shells(model.bottom_shell_layers, model.top_shell_layers))
        .unwrap_or_else(|_| Model::cube20())
}

// Here rather than in `reading.rs`, beside the model it makes: the reading names no
// preview, the preview names the reading.
impl Reading {
    /// The reading of a `.rot` template (or of a profile the library cannot read): the
    /// settings' model, no base.
    pub fn of_settings(settings: &ModelSettings) -> Reading {
        let model = model_of(settings);
        Reading {
            describe: rotlang::explain::model(&model),
            model,
            options: eval::Options::default(),
        }
    }
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct InstructionPreview {
    /// Layers governed in the whole model.
    pub layers: usize,
    /// The first block of consecutive layers it governs. Several ranges of the same
    /// instruction in a row merge here; `first_run` tells them apart.
    pub first_block: Option<Run>,
    /// The first layers it governs: (layer index, angle, fill).
    pub sample: Vec<(usize, f64, Fill)>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Preview {
    /// The number of layers of the reading's model.
    pub layers: usize,
    /// The reading's model in words.
    pub describe: String,
    /// The first layers of the model: (angle, fill).
    pub first: Vec<(f64, Fill)>,
    /// The first `SPARKLINE_WIDTH` layers' angles, one per layer, for the sparkline.
    pub head: Vec<f64>,
    /// The whole model in `SPARKLINE_WIDTH` buckets of consecutive layers, each the lowest
    /// and highest angle of its layers. Not samples (sampling a `0, 90` alternation every
    /// other-but-one layer draws blocks that are not there) and not means (a `0, 90`
    /// mean is a 45° no layer has).
    pub ranges: Vec<(f64, f64)>,
    pub min: f64,
    pub max: f64,
    /// Per instruction that governs a layer, by its index in the template. (Not a vector
    /// of every instruction: a 3 MB template has half a million, and a hover must not
    /// allocate for all of them when a model's layers reach a few.)
    pub instructions: BTreeMap<usize, InstructionPreview>,
    /// `Some(m)`: the model's layers are all governed by the first `m - 1` instructions,
    /// so what happens on them is what happens on the first `m` alone (the evaluator walks
    /// the instructions in order and looks past the one it stands on only at the end of
    /// the template, to cycle). `None`: the whole template was evaluated.
    pub reach: Option<usize>,
}

/// The first prefix tried (instructions), and how much longer each next one is.
const FIRST_PREFIX: usize = 1024;
const PREFIX_GROWTH: usize = 16;

impl Preview {
    /// The preview of `template` in its reading. On a long template it is computed on its
    /// first instructions where that is provably the same (see `reach`): preparing the
    /// evaluator for half a million instructions takes longer than a hover may.
    pub fn compute(source: Source<'_>, reading: &Reading) -> Preview {
        let n = source.spans.len();
        let mut m = FIRST_PREFIX;
        while m < n {
            let preview = Preview::compute_on(source, m, reading);
            // Every layer governed, each by one of the first `m - 1`: the walk never stood
            // on the last of the prefix, where it would have cycled (or gone on).
            let governed: usize = preview.instructions.values().map(|p| p.layers).sum();
            let last = preview.instructions.keys().next_back().copied();
            if governed == preview.layers && last.is_some_and(|i| i + 2 <= m) {
                return Preview {
                    reach: Some(m),
                    ..preview
                };
            }
            m = m.saturating_mul(PREFIX_GROWTH);
        }
        Preview::compute_on(source, n, reading)
    }

    /// The preview of the first `m` instructions of `source`.
    fn compute_on(source: Source<'_>, m: usize, reading: &Reading) -> Preview {
        let mut instructions: BTreeMap<usize, InstructionPreview> = BTreeMap::new();
        let mut first = Vec::new();
        let mut head = Vec::new();
        let mut ranges = Vec::new();
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        let layers = reading.layers().max(1);
        let mut buckets = vec![(f64::INFINITY, f64::NEG_INFINITY); SPARKLINE_WIDTH.min(layers)];
        let mut previous: (f64, Option<usize>) = (0.0, None);
        for_each_layer(source, m, reading, |layer, which| {
            let angle = if layer.angle.is_finite() {
                layer.angle
            } else {
                0.0
            };
            if first.len() < FIRST_LAYERS {
                first.push((angle, layer.fill));
            }
            if head.len() < SPARKLINE_WIDTH {
                head.push(angle);
            }
            // Sample column c at layer ⌊c × layers / width⌋.
            let bucket = layer.index.saturating_mul(buckets.len()) / layers;
            if let Some((low, high)) = buckets.get_mut(bucket) {
                *low = low.min(angle);
                *high = high.max(angle);
            }
            min = min.min(angle);
            max = max.max(angle);
            if let Some(i) = which {
                let p = instructions.entry(i).or_default();
                p.layers += 1;
                if p.sample.len() < INSTRUCTION_SAMPLE {
                    p.sample.push((layer.index, angle, layer.fill));
                }
                match &mut p.first_block {
                    None => {
                        p.first_block = Some(Run {
                            first_layer: layer.index,
                            layers: 1,
                            from: previous.0,
                            first: angle,
                            to: angle,
                        })
                    }
                    Some(run)
                        if previous.1 == Some(i) && run.first_layer + run.layers == layer.index =>
                    {
                        run.layers += 1;
                        run.to = angle;
                    }
                    Some(_) => {}
                }
            }
            previous = (angle, which);
            true
        });
        ranges.extend(buckets.iter().copied().filter(|(low, _)| low.is_finite()));
        if !min.is_finite() {
            (min, max) = (0.0, 0.0);
        }
        Preview {
            layers: reading.layers(),
            describe: reading.describe.clone(),
            first,
            head,
            ranges,
            min,
            max,
            instructions,
            reach: None,
        }
    }

    /// The first layers as a Unicode sparkline, one mark per layer, scaled between the
    /// lowest and highest angle of the whole model.
    pub fn head_sparkline(&self) -> String {
        sparkline(&self.head, self.min, self.max)
    }

    /// The whole model, one mark per bucket of consecutive layers: (highest, lowest).
    pub fn model_sparklines(&self) -> (String, String) {
        let high: Vec<f64> = self.ranges.iter().map(|r| r.1).collect();
        let low: Vec<f64> = self.ranges.iter().map(|r| r.0).collect();
        (
            sparkline(&high, self.min, self.max),
            sparkline(&low, self.min, self.max),
        )
    }
}

pub fn sparkline(values: &[f64], min: f64, max: f64) -> String {
    const BARS: [char; 8] = ['▁', '▂', '▃', '▄', '▅', '▆', '▇', '█'];
    let range = max - min;
    values
        .iter()
        .map(|v| {
            if range <= 1e-9 {
                return BARS[0];
            }
            let level = ((v - min) / range * 7.0).round().clamp(0.0, 7.0);
            BARS[level as usize]
        })
        .collect()
}

/// Numbers for people, as the library's `explain` writes them (two decimals at most).
pub use rotlang::explain::{deg as fmt_deg, num as fmt_num, turn_deg as fmt_turn};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_well() {
        assert_eq!(fmt_num(22.5), "22.5");
        assert_eq!(fmt_num(0.451), "0.45");
        assert_eq!(fmt_num(-0.001), "0");
        assert_eq!(fmt_num(90.0), "90");
        assert_eq!(fmt_turn(22.5), "+22.5°");
        assert_eq!(fmt_turn(-10.0), "-10°");
    }

    /// On long templates the preview and first runs come from a prefix: the same answers as
    /// the whole template's (dummies, one-time marks, repeats and cycles included), and the
    /// same charge to the budget.
    #[test]
    fn a_prefix_gives_the_whole_templates_answers() {
        let model = ModelSettings::default();
        let reading = Reading::of_settings(&model);
        let mut from_a_prefix = 0;
        for body in [
            "+10L25%, -10l25%, 0, 90, ",
            "45*, +5*, B!, +30/5mm*3, ",
            "0*, 5*, 10*, ",
            "+1!, +2!, +3!, ",
            "0, 90, #14, +15R, ",
        ] {
            for count in [3, 400, 3000] {
                let text = body.repeat(count) + "+7";
                let (_, spans) = Spans::read(&text, Target::Sparse);
                let source = Source {
                    text: &text,
                    target: Target::Sparse,
                    spans: &spans,
                };
                let template = rotlang::parse(&text, Target::Sparse).template;
                let fast = Preview::compute(source, &reading);
                let full = Preview::compute_on(source, spans.len(), &reading);
                from_a_prefix += usize::from(fast.reach.is_some());
                assert_eq!(
                    Preview {
                        reach: None,
                        ..fast.clone()
                    },
                    full,
                    "{body} × {count}"
                );
                let (mut prefix, mut whole) = (None, None);
                for index in [0, 1, 2, 5, 900, template.instructions.len() - 1] {
                    let (mut a, mut b) = (FIRST_RUN_BUDGET, FIRST_RUN_BUDGET);
                    let expected =
                        rotlang::explain::first_run(&template, index, &reading.model, &mut b).map(
                            |run| Run {
                                from: run.from + reading.options.base,
                                first: run.first + reading.options.base,
                                to: run.to + reading.options.base,
                                ..run
                            },
                        );
                    assert_eq!(
                        first_run(source, index, &reading, &mut a, fast.reach, &mut prefix),
                        expected,
                        "{body} × {count}, instruction {index}"
                    );
                    assert_eq!(a, b);
                    let mut c = FIRST_RUN_BUDGET;
                    assert_eq!(
                        first_run(source, index, &reading, &mut c, None, &mut whole),
                        expected,
                    );
                    assert_eq!(c, b);
                }
            }
        }
        assert!(from_a_prefix >= 5, "{from_a_prefix}");
    }

    #[test]
    fn sparkline_scales() {
        assert_eq!(sparkline(&[0.0, 45.0, 90.0], 0.0, 90.0), "▁▅█");
        assert_eq!(sparkline(&[5.0, 5.0], 5.0, 5.0), "▁▁");
    }
}
