//! Hover: on an instruction, what it does in plain words and the angles of the layers it
//! governs; elsewhere in a template, the first layers and a sparkline of the sequence.
//! The words come from the library's `meaning()`s; the angles from the evaluator.

use rotlang::{CountKind, Fill, Instruction, Target, Unit};
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind};

use crate::document::{Document, Region};
use crate::position::Positions;
use crate::preview::{Preview, Run, SPARKLINE_WIDTH, fmt_deg, fmt_num, fmt_turn};
use crate::settings::ModelSettings;

/// Longest template or instruction text quoted in a hover.
const MAX_QUOTE: usize = 60;

pub fn hover(
    doc: &Document,
    offset: usize,
    model: &ModelSettings,
    pos: &Positions,
) -> Option<Hover> {
    // On a template key in a profile, the hover is about its template.
    let on_key = || {
        doc.regions
            .iter()
            .find(|r| {
                r.key_span
                    .is_some_and(|k| k.start <= offset && offset <= k.end)
            })
            .map(|r| (r, usize::MAX))
    };
    let (region, at) = doc.region_at(offset).or_else(on_key)?;
    let preview = Preview::compute(&region.parse.template, model);
    let (markdown, span) = match region.instruction_at(at) {
        Some((i, ins)) => (
            instruction_hover(region, i, ins, &preview),
            region.doc_span(ins.span),
        ),
        None => (template_hover(region, &preview), region.contents),
    };
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: markdown,
        }),
        range: Some(pos.range(span)),
    })
}

/// The instruction hover as Markdown (public for the benchmark and tests).
pub fn instruction_hover(
    region: &Region,
    index: usize,
    ins: &Instruction,
    preview: &Preview,
) -> String {
    let model = &preview.model;
    let text = quote(region.text.get(ins.span.range()).unwrap_or(""));
    let mut out = format!("`{text}` {}.\n\n", describe(ins, model));
    match preview.instructions.get(index) {
        Some(p) if p.layers > 0 => {
            out.push_str(&format!(
                "Governs {} of the {} layers.",
                p.layers, model.layers
            ));
            let mut budget = crate::preview::FIRST_RUN_BUDGET;
            let run = crate::preview::first_run(&region.parse.template, index, model, &mut budget);
            if let Some(run) = run.or(p.first_block) {
                let last = run.first_layer + run.layers - 1;
                let layers = if run.layers == 1 {
                    format!("layer {}", run.first_layer)
                } else {
                    format!("layers {}–{last}", run.first_layer)
                };
                out.push_str(&format!(" First: {layers}, {}.", turn_words(ins, &run)));
            }
            out.push_str("\n\n");
            let list: Vec<String> = p
                .sample
                .iter()
                .map(|&(layer, angle, fill)| {
                    format!("{layer}: {}{}", fmt_deg(angle), fill_mark(fill))
                })
                .collect();
            out.push_str(&format!("Layers: {}", list.join(", ")));
            if p.layers > p.sample.len() {
                out.push_str(", …");
            }
            out.push('\n');
        }
        _ if ins.is_dummy() => out.push_str("A dummy takes no layer of its own.\n"),
        _ => out.push_str("Governs no layer of this model.\n"),
    }
    out.push_str(&footer(region, preview));
    out
}

/// The whole-template hover as Markdown.
pub fn template_hover(region: &Region, preview: &Preview) -> String {
    let model = &preview.model;
    let count = region.parse.template.instructions.len();
    let text = quote(&region.text);
    let mut out = match &region.key {
        Some(key) => format!("**{key}** `{text}`"),
        None => format!("**Template** `{text}`"),
    };
    out.push_str(&format!(
        " ({} infill): {count} instruction{}.\n\n",
        match region.target {
            Target::Sparse => "sparse",
            Target::Solid => "solid",
        },
        if count == 1 { "" } else { "s" }
    ));
    let first: Vec<String> = preview
        .first
        .iter()
        .map(|&(a, fill)| format!("{}{}", fmt_deg(a), fill_mark(fill)))
        .collect();
    out.push_str(&format!(
        "First {} layers: {}",
        first.len(),
        first.join(", ")
    ));
    if model.layers > first.len() {
        out.push_str(", …");
    }
    out.push_str(&format!(
        "\n\n`{}` first {} layers\n",
        preview.head_sparkline(),
        preview.head.len()
    ));
    if model.layers > preview.head.len() {
        out.push_str(&format!(
            "\n`{}` all {} layers, each mark the mean of about {} layers\n",
            preview.model_sparkline(),
            model.layers,
            (model.layers + SPARKLINE_WIDTH / 2) / SPARKLINE_WIDTH
        ));
    }
    out.push_str(&format!(
        "\nAngles from {} to {} over all {} layers.\n",
        fmt_deg(preview.min),
        fmt_deg(preview.max),
        model.layers
    ));
    out.push_str(&footer(region, preview));
    out
}

fn footer(region: &Region, preview: &Preview) -> String {
    let mut s = format!("\n_Model: {}._", preview.model.describe());
    if region.parse.has_errors() {
        s.push_str(" _The template has errors: the preview uses the instructions that parse._");
    }
    s
}

/// What an instruction does, in plain words, starting with a verb.
pub fn describe(ins: &Instruction, model: &ModelSettings) -> String {
    let deg = ins.degrees();
    if ins.is_dummy() {
        return if ins.is_relative() {
            format!(
                "adds {} to the next instruction's start angle without taking a layer (a dummy)",
                fmt_turn(deg)
            )
        } else {
            format!(
                "sets the start angle to {} without taking a layer (a dummy)",
                fmt_deg(deg)
            )
        };
    }
    let range = range_words(ins, model);
    let mut s = if !ins.is_relative() {
        format!("sets the direction to {} {range}", fmt_deg(deg))
    } else if deg == 0.0 {
        format!("keeps the current direction {range}")
    } else if let Some(n) = per_layer_count(ins, model) {
        format!(
            "turns {} on each of the next {n} layer{} ({} in all)",
            fmt_turn(deg),
            if n == 1 { "" } else { "s" },
            fmt_turn(deg * n as f64)
        )
    } else if ins.joint.is_none() && ins.count.is_none() {
        // One layer has no shape to speak of.
        format!("turns {} in one layer", fmt_turn(deg))
    } else {
        format!("turns {} {} {range}", fmt_turn(deg), ins.shape().meaning())
    };
    if ins.is_flipped() {
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
fn per_layer_count(ins: &Instruction, model: &ModelSettings) -> Option<u64> {
    if ins.joint.is_some() {
        return None;
    }
    let n = match ins.count?.kind {
        CountKind::Layers(n) if n >= 1.0 => n.floor() as u64,
        CountKind::Bottom => model.bottom_shell_layers.into(),
        CountKind::Top => model.top_shell_layers.into(),
        _ => return None,
    };
    (n >= 1).then_some(n)
}

fn range_words(ins: &Instruction, model: &ModelSettings) -> String {
    let Some(count) = ins.count else {
        return "for one layer".into();
    };
    match count.kind {
        CountKind::Layers(n) if n >= 1.0 => {
            let n = n.floor();
            format!(
                "over the next {} layer{}",
                fmt_num(n),
                if n == 1.0 { "" } else { "s" }
            )
        }
        CountKind::Layers(_) => "for one layer".into(),
        CountKind::Bottom => format!(
            "over the next B = {} bottom shell layers",
            model.bottom_shell_layers
        ),
        CountKind::Top => format!(
            "over the next T = {} top shell layers",
            model.top_shell_layers
        ),
        CountKind::Length { value, unit } => match unit {
            Unit::PercentOfHeight => {
                format!("over the next {}% of the object height", fmt_num(value))
            }
            Unit::StandardLayers => format!(
                "over the next {} standard layers ({} mm)",
                fmt_num(value),
                fmt_num(value * model.layer_height)
            ),
            _ => {
                let mm = unit.millimetres().unwrap_or(1.0) * value;
                if unit == Unit::Millimetre {
                    format!("over the next {} mm of height", fmt_num(value))
                } else {
                    format!(
                        "over the next {}{} ({} mm) of height",
                        fmt_num(value),
                        unit.symbol(),
                        fmt_num(mm)
                    )
                }
            }
        },
        CountKind::HeightFraction { num, den } => format!(
            "over the next {}:{} of the object height",
            fmt_num(num),
            fmt_num(den)
        ),
    }
}

/// `0°→22.5° over 50 layers` (from the angle below the run to its last layer), or
/// `30° for 1 layer` when the angle does not move. A flipped run starts at its end angle,
/// so it is shown from its first layer: `27°→0° over 10 layers`.
pub fn turn_words(ins: &Instruction, run: &Run) -> String {
    let layers = run.layers;
    let plural = if layers == 1 { "" } else { "s" };
    let from = if ins.is_flipped() {
        run.first
    } else {
        run.from
    };
    if !ins.is_relative() || (run.to - from).abs() < 1e-9 {
        format!("{} for {layers} layer{plural}", fmt_deg(run.to))
    } else {
        format!(
            "{}→{} over {layers} layer{plural}",
            fmt_deg(from),
            fmt_deg(run.to)
        )
    }
}

fn fill_mark(fill: Fill) -> String {
    match fill {
        Fill::Sparse => String::new(),
        other => format!(" ({})", other.name()),
    }
}

/// Text for a Markdown code span: shortened, and without backticks that would end it.
fn quote(text: &str) -> String {
    // Take the head first: a hover on a 1 MB template must not copy all of it.
    let head: String = text.trim().chars().take(MAX_QUOTE + 1).collect();
    let mut q = head.replace('`', "'").replace(['\n', '\r', '\t'], " ");
    if head.chars().count() > MAX_QUOTE {
        q = q.chars().take(MAX_QUOTE).collect();
        q.push('…');
    }
    q
}
