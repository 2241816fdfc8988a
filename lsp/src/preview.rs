//! Previews: what the layers of a model get, summarised for hovers and inlay hints.
//!
//! The angles come from the library's evaluator (`rotlang::eval`) through
//! `for_each_layer`, the only function here that knows how evaluation is called.
//! Everything else is a bounded summary of the stream: memory is O(instructions), whatever
//! the number of layers.

use rotlang::eval::{self, Model, Options};
use rotlang::{Fill, Span, Template};

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

/// Evaluate `template` on the model with the library's evaluator, layer by layer, bottom
/// to top, while `f` returns `true`. The only function here that knows how evaluation is
/// called.
pub fn for_each_layer(
    template: &Template,
    model: &ModelSettings,
    mut f: impl FnMut(PreviewLayer) -> bool,
) {
    // Settings are validated with the evaluator's own limits, so this fails only if those
    // change; then there is simply nothing to preview.
    let Ok(m) = Model::uniform(model.layers, model.layer_height, model.first_layer_height) else {
        return;
    };
    let m = m.with_shells(model.bottom_shell_layers, model.top_shell_layers);
    for layer in eval::layers(template, &m, Options::default()) {
        let go_on = f(PreviewLayer {
            index: layer.index,
            angle: layer.angle,
            fill: layer.fill,
            instruction: layer.instruction,
        });
        if !go_on {
            return;
        }
    }
}

/// Layers evaluated in search of first runs, per request: bounds the cost of inlay hints
/// on long templates over tall models.
pub const FIRST_RUN_BUDGET: usize = 2_000_000;

/// The first run of instruction `index`: the layers of its first range(s) before another
/// instruction takes over, and the turn across them.
///
/// Provenance alone cannot tell where one range of an instruction ends and its next range
/// begins (in `B!, +30` every layer after the shells is a new range of `+30`). So the
/// template is evaluated with that instruction made one-time: it then acts exactly once,
/// and the layers it governs are its first run. Evaluation stops at the run's end, and
/// `budget` (layers) bounds the total work; `None` when it runs out or the instruction
/// never acts.
pub fn first_run(
    template: &Template,
    index: usize,
    model: &ModelSettings,
    budget: &mut usize,
) -> Option<Run> {
    let ins = template.instructions.get(index)?;
    if ins.is_dummy() {
        return None;
    }
    // The copy costs one unit per instruction: on a 1 MB template only a few first runs
    // are computed this way, and the rest fall back to the first block.
    *budget = budget.checked_sub(template.instructions.len())?;
    let mut once = template.clone();
    let target = once.instructions.get_mut(index)?;
    if target.one_time.is_none() {
        target.one_time = Some(target.span);
    }
    let span = ins.span;
    let mut run: Option<Run> = None;
    let mut previous = 0.0;
    let mut exhausted = false;
    for_each_layer(&once, model, |layer| {
        if *budget == 0 {
            exhausted = true;
            return false;
        }
        *budget -= 1;
        let angle = if layer.angle.is_finite() {
            layer.angle
        } else {
            0.0
        };
        let mine = layer.instruction == Some(span);
        match (&mut run, mine) {
            (None, true) => {
                run = Some(Run {
                    first_layer: layer.index,
                    layers: 1,
                    from: previous,
                    first: angle,
                    to: angle,
                })
            }
            (Some(r), true) => {
                r.layers += 1;
                r.to = angle;
            }
            (Some(_), false) => return false,
            (None, false) => {}
        }
        previous = angle;
        true
    });
    if exhausted { None } else { run }
}

/// A contiguous block of layers governed by one instruction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    pub first_layer: usize,
    pub layers: usize,
    /// The angle of the layer below the run (0 below the first layer): where a turn starts.
    pub from: f64,
    /// The angle of the run's first layer.
    pub first: f64,
    /// The angle of the run's last layer.
    pub to: f64,
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
    pub model: ModelSettings,
    /// The first layers of the model: (angle, fill).
    pub first: Vec<(f64, Fill)>,
    /// The first `SPARKLINE_WIDTH` layers' angles, one per layer, for the sparkline.
    pub head: Vec<f64>,
    /// The whole model in `SPARKLINE_WIDTH` buckets of consecutive layers, each the mean
    /// angle of its layers. Means, not samples: sampling a `0, 90` alternation every
    /// other-but-one layer draws blocks that are not there.
    pub means: Vec<f64>,
    pub min: f64,
    pub max: f64,
    /// Per instruction, in the template's order.
    pub instructions: Vec<InstructionPreview>,
}

impl Preview {
    pub fn compute(template: &Template, model: &ModelSettings) -> Preview {
        let n = template.instructions.len();
        let mut instructions = vec![InstructionPreview::default(); n];
        let mut first = Vec::new();
        let mut head = Vec::new();
        let mut means = Vec::new();
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        let layers = model.layers.max(1);
        let mut buckets = vec![(0.0, 0usize); SPARKLINE_WIDTH.min(layers)];
        let mut previous: (f64, Option<usize>) = (0.0, None);
        for_each_layer(template, model, |layer| {
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
            if let Some((sum, n)) = buckets.get_mut(bucket) {
                *sum += angle;
                *n += 1;
            }
            min = min.min(angle);
            max = max.max(angle);
            let which = layer.instruction.and_then(|span| index_of(template, span));
            if let Some(i) = which
                && let Some(p) = instructions.get_mut(i)
            {
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
        means.extend(
            buckets
                .iter()
                .filter(|(_, n)| *n > 0)
                .map(|&(sum, n)| sum / n as f64),
        );
        if !min.is_finite() {
            (min, max) = (0.0, 0.0);
        }
        Preview {
            model: *model,
            first,
            head,
            means,
            min,
            max,
            instructions,
        }
    }

    /// The first layers as a Unicode sparkline, one mark per layer, scaled between the
    /// lowest and highest angle of the whole model.
    pub fn head_sparkline(&self) -> String {
        sparkline(&self.head, self.min, self.max)
    }

    /// The whole model, one mark per bucket of consecutive layers (their mean angle).
    pub fn model_sparkline(&self) -> String {
        sparkline(&self.means, self.min, self.max)
    }
}

/// The instruction with exactly this span (instructions are in text order).
fn index_of(template: &Template, span: Span) -> Option<usize> {
    let i = template
        .instructions
        .partition_point(|ins| ins.span.start < span.start);
    (template.instructions.get(i)?.span == span).then_some(i)
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

/// A number for people: at most two decimals, no trailing zeros, no `-0`.
pub fn fmt_num(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let r = (x * 100.0).round() / 100.0;
    let s = format!("{r:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// An angle for people, with the degree sign.
pub fn fmt_deg(x: f64) -> String {
    format!("{}°", fmt_num(x))
}

/// A signed turn for people: `+22.5°`, `-10°`.
pub fn fmt_turn(x: f64) -> String {
    let s = fmt_deg(x);
    if s.starts_with('-') || s == "0°" {
        s
    } else {
        format!("+{s}")
    }
}

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

    #[test]
    fn sparkline_scales() {
        assert_eq!(sparkline(&[0.0, 45.0, 90.0], 0.0, 90.0), "▁▅█");
        assert_eq!(sparkline(&[5.0, 5.0], 5.0, 5.0), "▁▁");
    }
}
