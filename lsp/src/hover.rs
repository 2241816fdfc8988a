//! Hover: on an instruction, what it does in plain words and the angles of the layers it
//! governs; elsewhere in a template, the first layers and a sparkline of the sequence.
//! The words come from the library's `meaning()`s; the angles from the evaluator.

use rotlang::{Fill, Instruction, Target};
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind};

use crate::document::{Document, Region};
use crate::position::Positions;
use crate::preview::{Preview, Run, SPARKLINE_WIDTH, fmt_deg};
use crate::reading::Reading;
use crate::settings::ModelSettings;
use rotlang::explain::deg_and_lines;

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
    // On a value a later one of the same key replaces: the template that is used.
    let on_duplicate = || {
        let dup = doc.duplicates.iter().find(|d| {
            (d.key_span.start <= offset && offset <= d.key_span.end)
                || (d.contents.start <= offset && offset <= d.contents.end)
        })?;
        let used = doc.regions.iter().find(|r| r.key_span == Some(dup.used))?;
        Some((dup, used))
    };
    if doc.region_at(offset).is_none()
        && on_key().is_none()
        && let Some((dup, used)) = on_duplicate()
    {
        let preview = doc.preview(doc.index_of(used)?, model)?;
        let span = if dup.key_span.start <= offset && offset <= dup.key_span.end {
            dup.key_span
        } else {
            dup.contents
        };
        let markdown = format!("{}\n\n{}", dup.message, template_hover(used, &preview));
        return Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value: markdown,
            }),
            range: Some(pos.range(span)),
        });
    }
    let (region, at) = doc.region_at(offset).or_else(on_key)?;
    let reading = region.reading(model);
    let preview = doc.preview(doc.index_of(region)?, model)?;
    let (markdown, span) = match region.instruction_at(at) {
        Some((i, ins)) => (
            instruction_hover(region, i, &ins, &reading, &preview),
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
    reading: &Reading,
    preview: &Preview,
) -> String {
    let text = quote(region.text.get(ins.span.range()).unwrap_or(""));
    let mut out = format!("`{text}` {}.\n\n", describe(ins, reading));
    match preview.instructions.get(&index) {
        Some(p) if p.layers > 0 => {
            out.push_str(&format!(
                "Governs {} of the {} layers.",
                p.layers, preview.layers
            ));
            let mut budget = crate::preview::FIRST_RUN_BUDGET;
            let run = crate::preview::first_run(
                region.source(),
                index,
                reading,
                &mut budget,
                preview.reach,
                &mut None,
            );
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
                    format!("{layer}: {}{}", deg_and_lines(angle), fill_mark(fill))
                })
                .collect();
            out.push_str(&format!("Layers: {}", list.join(", ")));
            if p.layers > p.sample.len() {
                out.push_str(", …");
            }
            out.push_str(&format!("{}\n", lines_note(preview)));
        }
        _ if ins.is_dummy() => out.push_str("A dummy takes no layer of its own.\n"),
        _ => out.push_str("Governs no layer of this model.\n"),
    }
    out.push_str(&footer(region, preview));
    out
}

/// The whole-template hover as Markdown.
pub fn template_hover(region: &Region, preview: &Preview) -> String {
    let count = region.spans.len();
    let text = quote(&region.text);
    // An empty code span would show as a literal "``".
    let shown = if text.is_empty() {
        "(empty)".to_owned()
    } else {
        format!("`{text}`")
    };
    let mut out = match &region.key {
        Some(key) => format!("**{key}** {shown}"),
        None => format!("**Template** {shown}"),
    };
    out.push_str(&format!(
        " ({} infill): {count} instruction{}.\n\n",
        match region.target {
            Target::Sparse => "sparse",
            Target::Solid => "solid",
        },
        if count == 1 { "" } else { "s" }
    ));
    if count == 0 {
        out.push_str("An empty template: every layer keeps the base direction.\n");
        out.push_str(&footer(region, preview));
        return out;
    }
    let first: Vec<String> = preview
        .first
        .iter()
        .map(|&(a, fill)| format!("{}{}", deg_and_lines(a), fill_mark(fill)))
        .collect();
    out.push_str(&format!(
        "First {} layers: {}",
        first.len(),
        first.join(", ")
    ));
    if preview.layers > first.len() {
        out.push_str(", …");
    }
    out.push_str(&format!(
        "\n\n`{}` first {} layers\n",
        preview.head_sparkline(),
        preview.head.len()
    ));
    if preview.layers > preview.head.len() {
        // Highest and lowest angle per bucket: a mean would draw angles no layer has
        // (`0, 90` would be a flat line at 45°).
        let (high, low) = preview.model_sparklines();
        out.push_str(&format!(
            "\n`{high}` highest and\n`{low}` lowest angle of each group of about {} layers, all {} layers\n",
            (preview.layers + SPARKLINE_WIDTH / 2) / SPARKLINE_WIDTH,
            preview.layers,
        ));
    }
    out.push_str(&format!(
        "\nAngles from {} to {} over all {} layers.{}\n",
        fmt_deg(preview.min),
        fmt_deg(preview.max),
        preview.layers,
        lines_note(preview)
    ));
    out.push_str(&footer(region, preview));
    out
}

/// Said when some angle is outside `[0°, 180°)`, where lists show it with its line
/// direction in brackets (`270° (90°)`).
fn lines_note(preview: &Preview) -> &'static str {
    if preview.min < 0.0 || preview.max >= 180.0 {
        " (In brackets: the direction of the infill lines, wrapped to [0°, 180°).)"
    } else {
        ""
    }
}

fn footer(region: &Region, preview: &Preview) -> String {
    let mut s = format!("\n_Model: {}._", preview.describe);
    if region.parse.has_errors() {
        s.push_str(" _The template has errors: the preview uses the instructions that parse._");
    }
    s
}

/// What an instruction does, in plain words, starting with a verb (the library's words,
/// shared with `rotlang explain`).
pub fn describe(ins: &Instruction, reading: &Reading) -> String {
    rotlang::explain::instruction(ins, &reading.model)
}

/// The turn across a run, as `rotlang explain` words it (`0°→22.5° over 50 layers`, or
/// `15° for 10 layers (a step from 0°)`).
pub fn turn_words(ins: &Instruction, run: &Run) -> String {
    rotlang::explain::turn(ins, run)
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
