//! Evaluator benchmarks (divan): `cargo bench --bench eval`.
//!
//! Targets: parse + expand 10,000 layers under 200 µs; under 20 ns per layer at 100k and
//! 1M layers, with 1M costing at most 12× 100k (no super-linear work); the first layer of
//! any template on 1e8 layers in under 1 ms (`first_layer_of_1e8`).

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang::Target;
use rotlang::eval::{self, Evaluator, Model, Options};

fn main() {
    divan::main();
}

const TEMPLATE: &str = "5, 10!, +20, +10L25%, -10l25%";

/// Consumes every layer so that nothing is optimised away.
fn checksum(layers: impl Iterator<Item = eval::Layer>) -> f64 {
    layers.fold(0.0, |acc, l| acc + l.angle)
}

/// The whole job of a slicer for one object: parse, then expand 10,000 layers.
#[divan::bench]
fn parse_and_expand_10k(bencher: Bencher) {
    let model = Model::uniform(10_000, 0.2, None).expect("model");
    let _ = model.object_height(); // a property of the model, computed once per model
    bencher.counter(ItemsCount::new(10_000usize)).bench(|| {
        let parse = rotlang::parse(black_box(TEMPLATE), Target::Sparse);
        checksum(eval::layers(&parse.template, &model, Options::default()))
    });
}

/// Streaming cost per layer on large uniform models.
#[divan::bench(args = [100_000, 1_000_000])]
fn stream(bencher: Bencher, layers: usize) {
    let model = Model::uniform(layers, 0.2, Some(0.3)).expect("model");
    let template = rotlang::parse(TEMPLATE, Target::Sparse).template;
    let _ = model.object_height();
    bencher.counter(ItemsCount::new(layers)).bench(|| {
        checksum(eval::layers(
            black_box(&template),
            &model,
            Options::default(),
        ))
    });
}

/// The slicer's access pattern: `Evaluator::layer(i)` for i = 0, 1, 2, ...
#[divan::bench(args = [100_000, 1_000_000])]
fn random_access_increasing(bencher: Bencher, layers: usize) {
    let model = Model::uniform(layers, 0.2, Some(0.3)).expect("model");
    let template = rotlang::parse(TEMPLATE, Target::Sparse).template;
    let _ = model.object_height();
    bencher.counter(ItemsCount::new(layers)).bench(|| {
        let mut evaluator = Evaluator::new(black_box(&template), &model, Options::default());
        (0..layers)
            .filter_map(|i| evaluator.layer(i))
            .fold(0.0, |acc, l| acc + l.angle)
    });
}

/// A model given as a list of heights (adaptive layer heights).
#[divan::bench(args = [100_000])]
fn stream_listed_heights(bencher: Bencher, layers: usize) {
    let heights: Vec<f64> = (0..layers).map(|i| 0.1 + 0.02 * (i % 8) as f64).collect();
    let model = Model::from_heights(heights, 0.2).expect("model");
    let template = rotlang::parse(TEMPLATE, Target::Sparse).template;
    bencher.counter(ItemsCount::new(layers)).bench(|| {
        checksum(eval::layers(
            black_box(&template),
            &model,
            Options::default(),
        ))
    });
}

/// Walks over dummies (SEMANTICS.md section 4) on 100k layers: short walks (a dummy or
/// two between set-ups), one-time dummies spent as the model rises, and a long run of
/// dummies crossed on every other layer (the walk is remembered, not walked again).
#[divan::bench(args = [
    "+5, 10*, +20, -3*, +1*, 30",
    "+1!, 0*0, +2!, 5*, +3",
    "+1, +1*, +1*, +1*, +1*, +1*, +1*, +1*, +1*, +1*, +1*, -1*!, 5",
])]
fn stream_walks(bencher: Bencher, template: &str) {
    let layers = 100_000;
    let model = Model::uniform(layers, 0.2, Some(0.3)).expect("model");
    let template = rotlang::parse(template, Target::Sparse).template;
    bencher.counter(ItemsCount::new(layers)).bench(|| {
        checksum(eval::layers(
            black_box(&template),
            &model,
            Options::default(),
        ))
    });
}

/// The memory bench's `dummies` input (`+1!, 0*0, ` repeated, 20,000 instructions) on
/// 100k layers: every one-time instruction spent, then walks over the dummies left.
#[divan::bench]
fn stream_spent_dummies(bencher: Bencher) {
    let layers = 100_000;
    let model = Model::uniform(layers, 0.2, Some(0.3)).expect("model");
    let text = "+1!, 0*0, ".repeat(10_000);
    let template = rotlang::parse(&text, Target::Sparse).template;
    bencher.counter(ItemsCount::new(layers)).bench(|| {
        checksum(eval::layers(
            black_box(&template),
            &model,
            Options::default(),
        ))
    });
}

/// Time to the first layer on the largest model (1e8 uniform layers) and on 1e6 listed
/// heights, with ranges that reach the top: target under 1 ms (range ends come from
/// arithmetic on the running sums, not from walking the layers).
#[divan::bench(args = ["+10L99999999", "+10/50%", "+10/1:2", "+10T, +5L1e9", "0, +5*3/1e6#"])]
fn first_layer_of_1e8(template: &str) -> Option<f64> {
    let model = Model::uniform(eval::MAX_LAYERS, 0.2, Some(0.3)).expect("model");
    let template = rotlang::parse(black_box(template), Target::Sparse).template;
    eval::layers(&template, &model, Options::default())
        .next()
        .map(|l| l.angle)
}

#[divan::bench(args = ["+10L99999999", "+10/50%"])]
fn first_layer_of_listed_1e6(bencher: Bencher, template: &str) {
    let heights: Vec<f64> = (0..1_000_000)
        .map(|i| 0.1 + 0.02 * (i % 8) as f64)
        .collect();
    let model = Model::from_heights(heights, 0.2).expect("model");
    bencher.bench(|| {
        let template = rotlang::parse(black_box(template), Target::Sparse).template;
        eval::layers(&template, &model, Options::default())
            .next()
            .map(|l| l.angle)
    });
}
