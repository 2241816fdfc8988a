//! Instructions and turns in plain words: the one source of the CLI's `rotlang explain`,
//! the language server's hover and its inlay hints.

use crate::eval::Model;
use crate::ir::{CountKind, Instruction, Joint, Unit};

/// A number for people: at most two decimals, no trailing zeros, no `-0`.
pub fn num(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let r = (x * 100.0).round() / 100.0;
    let s = format!("{r:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// An angle for people, with the degree sign: `22.5°`.
pub fn deg(x: f64) -> String {
    format!("{}°", num(x))
}

/// A signed turn for people: `+22.5°`, `-10°`, `0°`.
pub fn turn_deg(x: f64) -> String {
    let s = deg(x);
    if s.starts_with('-') || s == "0°" {
        s
    } else {
        format!("+{s}")
    }
}

/// An angle with the direction of its infill lines when that differs: `270° (90°)`.
/// Lines at θ and θ + 180° are the same lines, so the bracket is the angle wrapped to
/// `[0°, 180°)`.
pub fn deg_and_lines(x: f64) -> String {
    let lines = crate::number::wrap(x, crate::number::Wrap::HalfTurn);
    let (a, b) = (deg(x), deg(lines));
    // `179.999°` rounds to `180°` at two decimals: that is the 0° line.
    let b = if b == "180°" { "0°".to_owned() } else { b };
    if a == b { a } else { format!("{a} ({b})") }
}

/// What an instruction does on `model`, in plain words, starting with a verb:
/// `turns +30° linearly over the next 50% of the object height`.
pub fn instruction(ins: &Instruction, model: &Model) -> String {
    let deg_ = ins.degrees();
    if ins.is_dummy() {
        return if ins.is_relative() {
            format!(
                "adds {} to the next instruction's start angle without taking a layer (a dummy)",
                turn_deg(deg_)
            )
        } else {
            format!(
                "sets the start angle to {} without taking a layer (a dummy)",
                deg(deg_)
            )
        };
    }
    let range = range_words(ins, model);
    let mut s = if !ins.is_relative() {
        format!("sets the direction to {} {range}", deg(deg_))
    } else if deg_ == 0.0 {
        format!("keeps the current direction {range}")
    } else if let Some(n) = per_layer_count(ins, model) {
        format!(
            "turns {} on each of the next {n} layer{} ({} in all)",
            turn_deg(deg_),
            if n == 1 { "" } else { "s" },
            turn_deg(deg_ * n as f64)
        )
    } else if ins.joint.is_none() && ins.count.is_none() {
        // One layer has no shape to speak of.
        format!("turns {} in one layer", turn_deg(deg_))
    } else if matches!(ins.shape(), Joint::Step | Joint::Middle) {
        // Not a ramp: every layer of the range gets the same angle.
        let at = if ins.shape() == Joint::Middle {
            "half of it at once, then holds"
        } else if ins.is_flipped() {
            "none of it until the range ends (flipped step)"
        } else {
            "all of it on the range's first layer, then holds"
        };
        format!("turns {} {range}: {at}", turn_deg(deg_))
    } else {
        format!("turns {} {} {range}", turn_deg(deg_), ins.shape().meaning())
    };
    if ins.is_flipped() && ins.shape() != Joint::Step {
        s.push_str(", flipped (from the end angle back to the start)");
    }
    if let Some(solid) = ins.solid {
        s.push_str(&format!("; its layers are {}", solid.value.meaning()));
    }
    if ins.runs() > 1 {
        s.push_str(&format!("; runs {} times in a row", ins.runs()));
    }
    if ins.is_one_time() {
        s.push_str("; runs once for the whole model (one-time)");
    }
    s
}

/// A relative turn with no joint over a counted range turns α on each layer.
fn per_layer_count(ins: &Instruction, model: &Model) -> Option<u64> {
    if ins.joint.is_some() {
        return None;
    }
    let n = match ins.count?.kind {
        CountKind::Layers(n) if n >= 1.0 => n.floor() as u64,
        CountKind::Bottom => model.bottom_shells().into(),
        CountKind::Top => model.top_shells().into(),
        _ => return None,
    };
    (n >= 1).then_some(n)
}

/// The range an instruction's count covers. `B` and `T` are counts of layers, not places:
/// `B!` after other instructions acts on the B layers where it is reached.
fn range_words(ins: &Instruction, model: &Model) -> String {
    let Some(count) = ins.count else {
        return "for one layer".into();
    };
    let layers = |n: u32, letter: &str, what: &str| {
        format!(
            "over the next {n} layer{} ({letter} = {n}, the {what} shell layer count)",
            if n == 1 { "" } else { "s" }
        )
    };
    match count.kind {
        CountKind::Layers(n) if n >= 1.0 => {
            let n = n.floor();
            format!(
                "over the next {} layer{}",
                num(n),
                if n == 1.0 { "" } else { "s" }
            )
        }
        CountKind::Layers(_) => "for one layer".into(),
        CountKind::Bottom => layers(model.bottom_shells(), "B", "bottom"),
        CountKind::Top => layers(model.top_shells(), "T", "top"),
        CountKind::Length { value, unit } => match unit {
            Unit::PercentOfHeight => {
                format!("over the next {}% of the object height", num(value))
            }
            Unit::StandardLayers => format!(
                "over the next {} standard layers ({} mm)",
                num(value),
                num(value * model.layer_height())
            ),
            Unit::Millimetre => format!("over the next {} mm of height", num(value)),
            _ => {
                let mm = unit.millimetres().unwrap_or(1.0) * value;
                format!(
                    "over the next {}{} ({} mm) of height",
                    num(value),
                    unit.symbol(),
                    num(mm)
                )
            }
        },
        CountKind::HeightFraction { num: a, den } => {
            format!("over the next {}:{} of the object height", num(a), num(den))
        }
    }
}

/// A contiguous block of layers governed by one instruction, with the angles around it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    /// The first layer of the run.
    pub first_layer: usize,
    /// How many layers it has.
    pub layers: usize,
    /// The angle of the layer below the run (0 below the first layer): where a turn starts.
    pub from: f64,
    /// The angle of the run's first layer.
    pub first: f64,
    /// The angle of the run's last layer.
    pub to: f64,
}

impl Run {
    /// `layer 3` or `layers 3–5`.
    pub fn layers_words(&self) -> String {
        if self.layers == 1 {
            format!("layer {}", self.first_layer)
        } else {
            format!(
                "layers {}–{}",
                self.first_layer,
                self.first_layer + self.layers - 1
            )
        }
    }
}

/// The turn across a run: `0°→22.5° over 50 layers` for a ramp (from the angle below the
/// run to its last layer); `15° for 10 layers (a step from 0°)` when every layer of the
/// run has the same angle, as with `#` and `|`; `30° for 1 layer` when nothing moves. A
/// flipped run starts at its end angle, so it is shown from its first layer.
pub fn turn(ins: &Instruction, run: &Run) -> String {
    let layers = run.layers;
    let plural = if layers == 1 { "" } else { "s" };
    let from = if ins.is_flipped() {
        run.first
    } else {
        run.from
    };
    let same = |a: f64, b: f64| (a - b).abs() < 1e-9;
    // Below layer 0 is the start angle, which leading dummies may have set: unknown
    // here, so a one-layer run there shows its angle alone.
    let unknown_start = run.first_layer == 0 && run.layers == 1;
    if !ins.is_relative() || same(run.to, from) || unknown_start {
        format!("{} for {layers} layer{plural}", deg(run.to))
    } else if layers > 1 && same(run.first, run.to) {
        format!(
            "{} for {layers} layers (a step from {})",
            deg(run.to),
            deg(from)
        )
    } else {
        format!("{}→{} over {layers} layer{plural}", deg(from), deg(run.to))
    }
}

/// The model in a few words: `100 layers × 0.2 mm (20 mm tall), shells B = 3, T = 4`.
pub fn model(model: &Model) -> String {
    let h = model.layer_height();
    let mut s = format!("{} layers × {} mm", model.len(), num(h));
    if let Some((bottom, top)) = model.layer_bounds(0)
        && (top - bottom - h).abs() > 1e-9
    {
        s.push_str(&format!(", first layer {} mm", num(top - bottom)));
    }
    s.push_str(&format!(
        " ({} mm tall), shells B = {}, T = {}",
        num(model.object_height()),
        model.bottom_shells(),
        model.top_shells()
    ));
    s
}
