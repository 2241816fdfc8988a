//! The conformance corpus (`../shared/conformance/`): every case must pass.
//!
//! Exact cases compare every layer's angle modulo 360 within 1e-4° and every fill; random
//! cases check the bounds, determinism under one seed and change under another. Every case
//! also checks that random access (in increasing and in shuffled order) equals the stream.

use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};

use rotlang::eval::{self, Evaluator, Layer, Model, Options};
use rotlang::{Fill, Target, Template};
use serde::Deserialize;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/conformance/");
const TOLERANCE: f64 = 1e-4;

/// Random cases where some layer is random (min < max), so another seed must change it.
static SEED_CHECKED: AtomicUsize = AtomicUsize::new(0);

#[derive(Deserialize)]
struct ModelSpec {
    layer_heights: Vec<f64>,
    layer_height: f64,
    bottom_shell_layers: u32,
    top_shell_layers: u32,
}

#[derive(Deserialize)]
struct Case {
    template: String,
    model: String,
    #[serde(default)]
    degrees: Vec<f64>,
    #[serde(default)]
    fills: Option<Vec<String>>,
    #[serde(default)]
    min_degrees: Vec<f64>,
    #[serde(default)]
    max_degrees: Vec<f64>,
}

fn read(name: &str) -> String {
    let path = format!("{DIR}{name}");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {path}: {e}"))
}

fn models() -> HashMap<String, Model> {
    let specs: HashMap<String, ModelSpec> =
        serde_json::from_str(&read("models.json")).expect("models.json");
    specs
        .into_iter()
        .map(|(name, s)| {
            let model = Model::from_heights(s.layer_heights, s.layer_height)
                .unwrap_or_else(|e| panic!("model {name}: {e}"))
                .with_shells(s.bottom_shell_layers, s.top_shell_layers);
            (name, model)
        })
        .collect()
}

fn cases(name: &str) -> Vec<Case> {
    read(name)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .enumerate()
        .map(|(i, l)| serde_json::from_str(l).unwrap_or_else(|e| panic!("{name}:{}: {e}", i + 1)))
        .collect()
}

fn parse(text: &str) -> Result<Template, String> {
    let parse = rotlang::parse(text, Target::Sparse);
    if parse.has_errors() {
        let messages: Vec<String> = parse
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| format!("{}: {}", d.code, d.message))
            .collect();
        return Err(format!("parse errors: {}", messages.join("; ")));
    }
    Ok(parse.template)
}

/// Equal modulo 360 within the tolerance.
fn same_direction(got: f64, expected: f64) -> bool {
    let diff = (got - expected).rem_euclid(360.0);
    diff <= TOLERANCE || diff >= 360.0 - TOLERANCE
}

/// Inside `[min, max]` (modulo 360, within the tolerance).
fn within(got: f64, min: f64, max: f64) -> bool {
    let shifted = got - 360.0 * ((got - min + TOLERANCE) / 360.0).floor();
    shifted <= max + TOLERANCE || same_direction(got, min) || same_direction(got, max)
}

/// A deterministic shuffle (xorshift), so a failure reproduces.
fn shuffled(len: usize, mut state: u64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..len).collect();
    for i in (1..len).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        order.swap(i, (state % (i as u64 + 1)) as usize);
    }
    order
}

/// Internal iteration, and random access in increasing and in shuffled order, must equal
/// the stream, bitwise.
fn check_random_access(
    template: &Template,
    model: &Model,
    options: Options,
    stream: &[Layer],
) -> Result<(), String> {
    let same = |a: &Layer, b: &Layer| a == b && a.angle.to_bits() == b.angle.to_bits();
    // Internal iteration (`fold`, behind `sum`, `for_each`, `last`) has its own loop.
    let folded = eval::layers(template, model, options).fold(Vec::new(), |mut all, layer| {
        all.push(layer);
        all
    });
    if folded.len() != stream.len() || folded.iter().zip(stream).any(|(a, b)| !same(a, b)) {
        return Err("fold differs from next".into());
    }
    let mut evaluator = Evaluator::new(template, model, options);
    for expected in stream {
        match evaluator.layer(expected.index) {
            Some(got) if same(&got, expected) => {}
            got => {
                return Err(format!(
                    "increasing random access at layer {}: {got:?} != stream {expected:?}",
                    expected.index
                ));
            }
        }
    }
    if evaluator.layer(stream.len()).is_some() {
        return Err("random access past the top yields a layer".into());
    }
    let mut evaluator = Evaluator::new(template, model, options);
    for index in shuffled(stream.len(), 0x9e37_79b9_7f4a_7c15 ^ stream.len() as u64) {
        let expected = &stream[index];
        match evaluator.layer(index) {
            Some(got) if same(&got, expected) => {}
            got => {
                return Err(format!(
                    "shuffled random access at layer {index}: {got:?} != stream {expected:?}"
                ));
            }
        }
    }
    Ok(())
}

fn run_exact(case: &Case, model: &Model) -> Result<(), String> {
    let template = parse(&case.template)?;
    let stream: Vec<Layer> = eval::layers(&template, model, Options::default()).collect();
    if stream.len() != case.degrees.len() {
        return Err(format!(
            "{} layers, expected {}",
            stream.len(),
            case.degrees.len()
        ));
    }
    for (layer, &expected) in stream.iter().zip(&case.degrees) {
        if !same_direction(layer.angle, expected) {
            return Err(format!(
                "layer {}: expected {expected}, got {}",
                layer.index, layer.angle
            ));
        }
        let fill = match &case.fills {
            Some(fills) => fills
                .get(layer.index)
                .map(String::as_str)
                .unwrap_or("<missing>"),
            None => Fill::Sparse.name(),
        };
        if layer.fill.name() != fill {
            return Err(format!(
                "layer {}: expected fill {fill}, got {}",
                layer.index,
                layer.fill.name()
            ));
        }
    }
    if case.model == "cube20" {
        // The same model built without a list of heights must give bitwise the same layers.
        let uniform: Vec<Layer> =
            eval::layers(&template, &Model::cube20(), Options::default()).collect();
        if let Some((a, b)) = stream
            .iter()
            .zip(&uniform)
            .find(|(a, b)| a != b || a.angle.to_bits() != b.angle.to_bits())
        {
            return Err(format!(
                "Model::cube20() differs from the listed cube20: {b:?} != {a:?}"
            ));
        }
    }
    check_random_access(&template, model, Options::default(), &stream)
}

fn run_random(case: &Case, model: &Model) -> Result<(), String> {
    let template = parse(&case.template)?;
    let angles = |seed| -> Vec<f64> {
        eval::layers(&template, model, Options { base: 0.0, seed })
            .map(|l| l.angle)
            .collect()
    };
    let first = angles(0);
    if first.len() != case.min_degrees.len() || first.len() != case.max_degrees.len() {
        return Err(format!(
            "{} layers, expected {}",
            first.len(),
            case.min_degrees.len()
        ));
    }
    for (index, ((&got, &min), &max)) in first
        .iter()
        .zip(&case.min_degrees)
        .zip(&case.max_degrees)
        .enumerate()
    {
        if !within(got, min, max) {
            return Err(format!(
                "layer {index}: expected within [{min}, {max}], got {got}"
            ));
        }
    }
    let again = angles(0);
    if first
        .iter()
        .zip(&again)
        .any(|(a, b)| a.to_bits() != b.to_bits())
    {
        return Err("two evaluations with the same seed differ".into());
    }
    let random_layers: Vec<usize> = (0..first.len())
        .filter(|&i| case.max_degrees[i] - case.min_degrees[i] > TOLERANCE)
        .collect();
    if !random_layers.is_empty() {
        let other = angles(0x5eed);
        if random_layers
            .iter()
            .all(|&i| first[i].to_bits() == other[i].to_bits())
        {
            return Err("another seed changes no random layer".into());
        }
        SEED_CHECKED.fetch_add(1, Ordering::Relaxed);
    }
    for seed in [0, 0x5eed] {
        let options = Options { base: 0.0, seed };
        let stream: Vec<Layer> = eval::layers(&template, model, options).collect();
        check_random_access(&template, model, options, &stream)?;
    }
    Ok(())
}

fn run_all(file: &str, expected_count: usize, run: fn(&Case, &Model) -> Result<(), String>) {
    let models = models();
    let cases = cases(file);
    assert_eq!(
        cases.len(),
        expected_count,
        "{file}: wrong number of cases read"
    );
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            let result = match models.get(&case.model) {
                Some(model) => run(case, model),
                None => Err("unknown model".into()),
            };
            result
                .err()
                .map(|e| format!("{:?} on {}: {e}", case.template, case.model))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} cases in {file} fail:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn exact_cases() {
    run_all("cases.jsonl", 1572, run_exact);
}

#[test]
fn random_cases() {
    run_all("cases-random.jsonl", 176, run_random);
    // 72 cases turn only absolute angles with a random joint (constant): no layer to vary.
    assert_eq!(
        SEED_CHECKED.load(Ordering::Relaxed),
        104,
        "cases whose random layers were seed-checked"
    );
}
