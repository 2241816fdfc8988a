//! The operations behind the exports, in plain Rust (unit-testable natively): text and a
//! request in, JSON (and for `expand`, typed arrays) out.

use rotlang::eval::{self, Model};
use rotlang::{Fill, Parse, Target};
use serde_json::{Value, json};

use crate::Failure;
use crate::diagnostics;
use crate::options::Request;
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
    json!({ "version": env!("CARGO_PKG_VERSION") })
}

pub fn check(text: &str, req: &Request) -> Result<Value, Failure> {
    let target = req.target()?;
    let parse = rotlang::parse(text, target);
    Ok(json!({
        "diagnostics": diagnostics::to_json(text, &parse.diagnostics),
        "hasErrors": parse.has_errors(),
        "omitted": parse.omitted,
        "errors": parse.errors,
        "warnings": parse.warnings,
        "instructions": instruction_spans(text, &parse),
    }))
}

pub fn format(text: &str, req: &Request) -> Result<Value, Failure> {
    let target = req.target()?;
    let parse = parse_clean(text, target)?;
    Ok(json!({ "text": rotlang::format::canonical(text, &parse.template) }))
}

pub fn expand(
    text: &str,
    req: &Request,
    heights: Option<Vec<f64>>,
    out: &mut Layers,
) -> Result<Value, Failure> {
    let target = req.target()?;
    let options = req.eval_options()?;
    let model = req.model(heights)?;
    let (from, to) = range(req, &model)?;
    let parse = parse_clean(text, target)?;
    let spans = instruction_spans(text, &parse);
    out.angles.clear();
    out.fills.clear();
    out.instructions.clear();
    let n = to - from;
    out.angles.reserve_exact(n);
    out.fills.reserve_exact(n);
    out.instructions.reserve_exact(n);
    let starts: Vec<usize> = parse
        .template
        .instructions
        .iter()
        .map(|i| i.span.start)
        .collect();
    // Runs of layers share an instruction: the last lookup is remembered.
    let mut last: Option<(usize, i32)> = None;
    let mut push = |layer: eval::Layer| {
        out.angles.push(layer.angle);
        out.fills.push(fill_code(layer.fill));
        out.instructions.push(match layer.instruction {
            Some(span) => match last {
                Some((start, index)) if start == span.start => index,
                _ => {
                    let index = starts
                        .binary_search(&span.start)
                        .map_or(-1, |i| i32::try_from(i).unwrap_or(-1));
                    last = Some((span.start, index));
                    index
                }
            },
            None => -1,
        });
    };
    // The stream (no checkpoints kept, unlike `Evaluator`), moved on to `from`. Up to the
    // top it is folded internally (`for_each`), the evaluator's fast path; `take` would
    // step it one `next` at a time.
    let mut stream = eval::layers(&parse.template, &model, options);
    if from > 0 {
        stream.nth(from - 1);
    }
    if to == model.len() {
        stream.for_each(&mut push);
    } else {
        stream.take(n).for_each(&mut push);
    }
    Ok(json!({
        "layers": model.len(),
        "from": from,
        "to": to,
        "instructions": spans,
        "model": model_json(&model),
    }))
}

/// The template's parse, or the failure that carries its errors.
fn parse_clean(text: &str, target: Target) -> Result<Parse, Failure> {
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
    let from = req.from.unwrap_or(0);
    let to = req.to.unwrap_or(len).min(len);
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
fn instruction_spans(text: &str, parse: &Parse) -> Value {
    let ins = &parse.template.instructions;
    let map = Utf16Map::new(
        text,
        ins.iter()
            .flat_map(|i| [i.span.start, i.span.end])
            .collect(),
    );
    ins.iter()
        .map(|i| {
            json!({
                "start": i.span.start,
                "end": i.span.end,
                "startUtf16": map.get(i.span.start),
                "endUtf16": map.get(i.span.end),
                "text": &text[i.span.range()],
            })
        })
        .collect()
}

fn model_json(model: &Model) -> Value {
    json!({
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
            out.push(json!({ "sign": c.to_string(), "kind": "joint", "meaning": format!("turn {}", j.meaning()) }));
        }
    }
    for c in "DSOMR".chars() {
        if let Some(s) = Solid::from_symbol(c) {
            out.push(json!({ "sign": c.to_string(), "kind": "solid", "meaning": format!("the layers are {}", s.meaning()) }));
        }
    }
    for u in ["mm", "cm", "m", "'", "\"", "#", "%"] {
        if let Some(unit) = Unit::from_symbol(u) {
            out.push(json!({ "sign": u, "kind": "unit", "meaning": unit.meaning() }));
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
        out.push(json!({ "sign": sign, "kind": "mark", "meaning": meaning }));
    }
    Value::Array(out)
}
