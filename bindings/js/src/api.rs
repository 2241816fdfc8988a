//! The operations behind the exports, in plain Rust (unit-testable natively): text and a
//! request in, JSON (and for `expand`, typed arrays) out.

use std::collections::HashMap;

use crate::json::Value;
use crate::obj;
use rotlang::dialect::{Dialect, orcaslicer};
use rotlang::eval::{self, Model};
use rotlang::explain;
use rotlang::{Fill, Parse, Span, Target};

use crate::Failure;
use crate::diagnostics;
use crate::options::Request;
// The option slots only the `full` build's preview and chart read.
#[cfg(feature = "full")]
use crate::options::slot;
use crate::utf16::Utf16Map;

/// Most layers one `expand` call returns (13 bytes each: 130 MB). A larger model is read
/// in ranges (`from`/`to`).
pub const MAX_EXPAND: usize = 10_000_000;

/// The per-layer output of `expand`, read by JavaScript straight from wasm memory.
#[derive(Default)]
pub struct Layers {
    pub angles: Vec<f64>,
    pub fills: Vec<u8>,
    /// Index of the governing instruction in the template, or -1 when the layer holds.
    pub instructions: Vec<i32>,
}

pub fn version() -> Value {
    obj!({ "version": env!("CARGO_PKG_VERSION") })
}

/// The diagnostics as JSON; the instructions' spans go to `spans`, four numbers each
/// (`start`, `end` in bytes, `startUtf16`, `endUtf16`), which JavaScript reads straight
/// from wasm memory: a megabyte template has a quarter of a million instructions, and as
/// JSON objects (with their text) they were 20 MB to write and parse, three quarters of
/// the call.
pub fn check(text: &str, req: &Request, spans: &mut Vec<u32>) -> Result<Value, Failure> {
    let target = req.target()?;
    let parse = rotlang::parse(text, target);
    spans.clear();
    let list: Vec<Span> = parse.template.instructions.iter().map(|i| i.span).collect();
    let map = Utf16Map::new(text, list.iter().flat_map(|s| [s.start, s.end]).collect());
    spans.reserve_exact(list.len() * 4);
    let word = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    for s in &list {
        spans.extend([s.start, s.end, map.get(s.start), map.get(s.end)].map(word));
    }
    Ok(obj!({
        "diagnostics": diagnostics::to_json(text, &parse.diagnostics),
        "hasErrors": parse.has_errors(),
        "omitted": parse.omitted,
        "errors": parse.errors,
        "warnings": parse.warnings,
    }))
}

pub fn format(text: &str, req: &Request) -> Result<Value, Failure> {
    let target = req.target()?;
    let parse = parse_clean(text, target)?;
    Ok(obj!({ "text": rotlang::format::canonical(text, &parse.template) }))
}

pub fn expand(
    text: &str,
    req: &Request,
    heights: Option<Vec<f64>>,
    out: &mut Layers,
) -> Result<Value, Failure> {
    let target = req.target()?;
    let dialect = req.dialect()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let (from, to) = range(req, &model)?;
    out.angles.clear();
    out.fills.clear();
    out.instructions.clear();
    let n = to - from;
    out.angles.reserve_exact(n);
    out.fills.reserve_exact(n);
    out.instructions.reserve_exact(n);
    let mut words = Vec::new();
    let (spans, findings) = match dialect {
        Dialect::Rotlang => {
            let parse = parse_clean(text, target)?;
            let spans: Vec<Span> = parse.template.instructions.iter().map(|i| i.span).collect();
            // Each instruction in words (the LSP hover's and `rotlang explain`'s text).
            words = parse
                .template
                .instructions
                .iter()
                .map(|i| explain::instruction(i, &model))
                .collect();
            let stream = eval::layers(&parse.template, &model, options);
            fill_layers(stream, from, to == model.len(), n, &spans, out);
            (spans, Vec::new())
        }
        Dialect::OrcaSlicer => {
            // OrcaSlicer's reader takes any text; its instructions are the spans its layers
            // name. Indices are given in order of first appearance, then renumbered in
            // order of the text.
            let mut stream = orcaslicer::layers(text, &model, options);
            let mut seen: HashMap<Span, i32> = HashMap::new();
            let mut order: Vec<Span> = Vec::new();
            let mut index_of = |span: Span| {
                *seen.entry(span).or_insert_with(|| {
                    order.push(span);
                    i32::try_from(order.len() - 1).unwrap_or(-1)
                })
            };
            if from > 0 {
                stream.nth(from - 1);
            }
            for layer in stream.by_ref().take(n) {
                out.angles.push(layer.angle);
                out.fills.push(fill_code(layer.fill));
                out.instructions
                    .push(layer.instruction.map_or(-1, &mut index_of));
            }
            let mut spans = order.clone();
            spans.sort_unstable();
            let renumber: Vec<i32> = order
                .iter()
                .map(|s| {
                    spans
                        .binary_search(s)
                        .map_or(-1, |i| i32::try_from(i).unwrap_or(-1))
                })
                .collect();
            for i in &mut out.instructions {
                if let Some(&r) = usize::try_from(*i).ok().and_then(|k| renumber.get(k)) {
                    *i = r;
                }
            }
            (spans, stream.findings().to_vec())
        }
    };
    Ok(obj!({
        "layers": model.len(),
        "from": from,
        "to": to,
        "dialect": dialect.name(),
        "instructions": span_list(text, &spans),
        "words": words,
        "findings": findings_json(&findings),
        "model": model_json(&model),
    }))
}

/// Writes layers `from`..`from + n` of `stream` into `out`, each with the index of its
/// instruction in `spans` (sorted by start).
fn fill_layers<I: Iterator<Item = eval::Layer>>(
    mut stream: I,
    from: usize,
    to_top: bool,
    n: usize,
    spans: &[Span],
    out: &mut Layers,
) {
    // Runs of layers share an instruction: the last lookup is remembered.
    let mut last: Option<(Span, i32)> = None;
    let mut push = |layer: eval::Layer| {
        out.angles.push(layer.angle);
        out.fills.push(fill_code(layer.fill));
        out.instructions.push(match layer.instruction {
            Some(span) => match last {
                Some((s, index)) if s == span => index,
                _ => {
                    let index = spans
                        .binary_search_by_key(&span.start, |s| s.start)
                        .map_or(-1, |i| i32::try_from(i).unwrap_or(-1));
                    last = Some((span, index));
                    index
                }
            },
            None => -1,
        });
    };
    if from > 0 {
        stream.nth(from - 1);
    }
    // Up to the top the stream is folded internally (`for_each`), the evaluator's fast
    // path; `take` would step it one `next` at a time.
    if to_top {
        stream.for_each(&mut push);
    } else {
        stream.take(n).for_each(&mut push);
    }
}

/// The template in plain words on the model: each instruction with the layers it governs
/// (what `rotlang explain TEMPLATE` prints).
pub fn explain(text: &str, req: &Request, heights: Option<Vec<f64>>) -> Result<Value, Failure> {
    let target = req.target()?;
    let model = req.model(heights)?;
    Ok(obj!({ "text": explain::template(text, target, &model) }))
}

/// A diagnostic code explained (`rotlang explain CODE`), or null for an unknown code.
pub fn explain_code(code: &str) -> Value {
    match explain::code(code.trim()) {
        Some(d) => obj!({
            "code": d.code,
            "severity": d.severity,
            "summary": d.summary,
            "explanation": d.explanation,
            "example": d.example,
            "fix": d.fix,
        }),
        None => Value::Null,
    }
}

/// The OrcaSlicer compat lint (`orcaslicer::…` codes): where OrcaSlicer reads the
/// template differently, by rule and on the model; fixes where one keeps both readings.
pub fn compat(text: &str, req: &Request, heights: Option<Vec<f64>>) -> Result<Value, Failure> {
    let target = req.target()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let found = rotlang::dialect::compat(text, target, &model, options);
    Ok(obj!({ "diagnostics": diagnostics::to_json(text, &found) }))
}

#[cfg(feature = "full")]
/// The templates and model of a profile file (`name` picks the kind by its extension:
/// `.json`/`.jsonc` presets, `.ini` exports, `.rot` templates), read by
/// `rotlang_profile::api::profile` (what the Python binding's `read_profile` shows too).
pub fn profile(name: &str, bytes: &[u8]) -> Result<Value, Failure> {
    let p = rotlang_profile::api::profile(name, bytes)?;
    let m = &p.model;
    let templates: Vec<Value> = p
        .templates
        .iter()
        .map(|t| {
            obj!({
                "key": t.key,
                "object": t.object,
                "target": match t.target {
                    Target::Sparse => "sparse",
                    Target::Solid => "solid",
                },
                "text": t.text,
                "base": t.base,
            })
        })
        .collect();
    let notes: Vec<Value> = p
        .notes
        .iter()
        .map(|n| obj!({ "message": n.message, "error": n.error }))
        .collect();
    Ok(obj!({
        "kind": p.kind,
        "templates": templates,
        "model": obj!({
            "layers": m.len(),
            "layerHeight": m.layer_height(),
            "firstLayerHeight": p.first_layer_height,
            "bottomShells": m.bottom_shells(),
            "topShells": m.top_shells(),
        }),
        "base": p.base,
        "notes": notes,
        "hasErrors": p.has_errors,
    }))
}

/// The angle chart of the template on the model (`rotlang_geometry::plot::svg`, as `rotlang plot`
/// draws it). In the full module: 20 KB the core's budget has no room for.
#[cfg(feature = "full")]
pub fn plot(text: &str, req: &Request, heights: Option<Vec<f64>>) -> Result<Value, Failure> {
    let target = req.target()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let width = req.pixels(slot::WIDTH, 960.0)?;
    // The title is cut to the picture's width (the chart's own cut is for 960 px; on a
    // phone-wide picture the rest would be clipped mid-letter): about 9 px a character of
    // its 15 px bold, right of a 72 px margin.
    let room = (((width - 96.0) / 9.0) as usize).saturating_sub(10).max(4);
    let plot = rotlang_geometry::plot::PlotOptions {
        width,
        height: req.pixels(slot::PICTURE_HEIGHT, 560.0)?,
        title: Some(format!("template: {}", shorten(text.trim(), room))),
    };
    let parse = parse_clean(text, target)?;
    Ok(obj!({ "svg": rotlang_geometry::plot::svg(&parse.template, &model, options, text, &plot) }))
}

/// At most `max` characters of `text`, with an ellipsis when cut.
#[cfg(feature = "full")]
fn shorten(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_owned();
    }
    let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
    s.push('…');
    s
}

/// The preview's outlines, by the index the JS wrapper sends (`SHAPES` in lib.js): the
/// documentation's 20 mm cube and others of its size.
#[cfg(feature = "full")]
pub const SHAPES: [&str; 5] = ["square", "circle", "ring", "star", "l"];

/// One layer's infill as printed, seen from above (`rotlang_geometry::infill::preview`, as
/// `rotlang preview` draws it).
#[cfg(feature = "full")]
pub fn preview(text: &str, req: &Request, heights: Option<Vec<f64>>) -> Result<Value, Failure> {
    use rotlang_geometry::infill::{Pattern, Settings, preview, shapes};
    let target = req.target()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let layer = req
        .index(slot::LAYER, model.len().saturating_sub(1))?
        .unwrap_or(0);
    let pattern = match req.index(slot::PATTERN, Pattern::ALL.len() - 1)? {
        Some(i) => Pattern::ALL[i],
        None => Pattern::Lines,
    };
    let density = req.number(slot::DENSITY).unwrap_or(0.2);
    let region = match req.index(slot::SHAPE, SHAPES.len() - 1)?.unwrap_or(0) {
        0 => shapes::square(20.0),
        1 => shapes::circle(10.0),
        2 => shapes::ring_shape(10.0, 5.0),
        3 => shapes::star(10.0, 5.0),
        _ => shapes::l_shape(20.0),
    };
    let settings = Settings {
        pattern,
        density,
        ..Settings::default()
    };
    let panel = preview::PreviewOptions {
        panel: req.pixels(slot::WIDTH, 320.0)?,
        columns: 1,
        travel: false,
    };
    let parse = parse_clean(text, target)?;
    let svg = preview::render(
        &parse.template,
        &model,
        options,
        text,
        &region,
        &settings,
        layer..layer + 1,
        &panel,
    )
    .map_err(|e| Failure::options(e.to_string()))?;
    Ok(obj!({ "svg": svg, "layer": layer, "pattern": pattern.name() }))
}

/// How OrcaSlicer's reading differs from rotlang's on this model: the first layer whose
/// direction differs, the solid layers it would lose, and its findings (hang, crash, NaN).
pub fn compare(text: &str, req: &Request, heights: Option<Vec<f64>>) -> Result<Value, Failure> {
    let target = req.target()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let parse = rotlang::parse(text, target);
    let mut orca = orcaslicer::layers(text, &model, options);
    let mut first_difference = Value::Null;
    let mut differing = 0usize;
    let mut solid_lost = 0usize;
    if !parse.has_errors() {
        for (ours, theirs) in eval::layers(&parse.template, &model, options).zip(orca.by_ref()) {
            let diff = (ours.angle - theirs.angle).rem_euclid(360.0);
            if diff > 1e-4 && diff < 360.0 - 1e-4 {
                if differing == 0 {
                    first_difference = obj!({
                        "layer": ours.index,
                        "rotlang": ours.angle,
                        "orcaslicer": theirs.angle,
                    });
                }
                differing += 1;
            }
            if ours.fill != theirs.fill {
                solid_lost += 1;
            }
        }
    } else {
        orca.by_ref().for_each(drop);
    }
    Ok(obj!({
        "rotlangErrors": parse.has_errors(),
        "firstDifference": first_difference,
        "differingLayers": differing,
        "solidLayersLost": solid_lost,
        "layers": model.len(),
        "findings": findings_json(orca.findings()),
    }))
}

fn findings_json(findings: &[rotlang::dialect::Finding]) -> Value {
    findings
        .iter()
        .map(|f| {
            obj!({
                "code": f.code,
                "message": f.message,
                "firstLayer": f.first_layer,
                "layers": f.layers,
            })
        })
        .collect()
}

/// The template's parse, or the failure that carries its errors.
pub(crate) fn parse_clean(text: &str, target: Target) -> Result<Parse, Failure> {
    let parse = rotlang::parse(text, target);
    if parse.has_errors() {
        let errors = parse.errors;
        let first = parse
            .diagnostics
            .iter()
            .find(|d| d.is_error())
            .map_or(String::new(), |d| format!(": {}", d.message));
        return Err(Failure::template(
            format!(
                "the template has {errors} error{}{first}",
                if errors == 1 { "" } else { "s" }
            ),
            diagnostics::to_json(text, &parse.diagnostics),
        ));
    }
    Ok(parse)
}

fn range(req: &Request, model: &Model) -> Result<(usize, usize), Failure> {
    let len = model.len();
    let (from, to) = req.range()?;
    let from = from.unwrap_or(0);
    let to = to.unwrap_or(len).min(len);
    if from > to {
        return Err(Failure::options(format!(
            "the range {from}..{to} is empty or reversed (the model has {len} layers)"
        )));
    }
    if to - from > MAX_EXPAND {
        return Err(Failure::limit(format!(
            "{} layers asked for at once; at most {MAX_EXPAND} per call: ask for a range with `from` and `to`",
            to - from
        )));
    }
    Ok((from, to))
}

/// Each instruction's span, in bytes and UTF-16 units, and its text.
fn span_list(text: &str, spans: &[Span]) -> Value {
    let map = Utf16Map::new(text, spans.iter().flat_map(|s| [s.start, s.end]).collect());
    spans
        .iter()
        .map(|s| {
            obj!({
                "start": s.start,
                "end": s.end,
                "startUtf16": map.get(s.start),
                "endUtf16": map.get(s.end),
                "text": text.get(s.range()).unwrap_or(""),
            })
        })
        .collect()
}

fn model_json(model: &Model) -> Value {
    obj!({
        "layers": model.len(),
        "layerHeight": model.layer_height(),
        "height": rotlang::number::round_height(model.object_height()),
        "bottomShells": model.bottom_shells(),
        "topShells": model.top_shells(),
    })
}

/// The fill as a byte: the index in the JS wrapper's `FILLS`.
pub fn fill_code(fill: Fill) -> u8 {
    match fill {
        Fill::Sparse => 0,
        Fill::Dense => 1,
        Fill::Solid => 2,
        Fill::Concentric => 3,
        Fill::Monotonic => 4,
        Fill::Rectilinear => 5,
    }
}

/// Every sign that may follow an angle, with its kind and meaning (for completion).
pub fn signs() -> Value {
    use rotlang::{Joint, Solid, Unit};
    let mut out = Vec::new();
    for c in "/NnZz$LlUuQq~^|#".chars() {
        if let Some(j) = Joint::from_symbol(c) {
            out.push(obj!({ "sign": c.to_string(), "kind": "joint", "meaning": format!("turn {}", j.meaning()) }));
        }
    }
    for c in "DSOMR".chars() {
        if let Some(s) = Solid::from_symbol(c) {
            out.push(obj!({ "sign": c.to_string(), "kind": "solid", "meaning": format!("the layers are {}", s.meaning()) }));
        }
    }
    for u in ["mm", "cm", "m", "'", "\"", "#", "%"] {
        if let Some(unit) = Unit::from_symbol(u) {
            out.push(obj!({ "sign": u, "kind": "unit", "meaning": unit.meaning() }));
        }
    }
    for (sign, meaning) in [
        ("!", "run once for the whole model (one-time)"),
        ("*", "a dummy: sets the start angle without taking a layer"),
        ("B", "count: the bottom shell layers"),
        ("T", "count: the top shell layers"),
        (
            "-",
            "flip: run the shape from the end angle back to the start",
        ),
    ] {
        out.push(obj!({ "sign": sign, "kind": "mark", "meaning": meaning }));
    }
    Value::Array(out)
}
