//! The native side of "JS expand of 100k layers in Node against native":
//! `cargo bench -p rotlang-wasm --bench expand`. The glue's `expand` (parse, evaluate,
//! fill the typed-array buffers, JSON of the answer) compiled natively, and the bare
//! evaluator for reference. The Node side is `node bindings/js/bench/expand.mjs`, on the
//! same template and model.

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang_wasm::api::{self, Layers};
use rotlang_wasm::options::{Request, slot};

fn main() {
    divan::main();
}

const TEMPLATE: &str = "5, 10!, +20, +10L25%, -10l25%";
const LAYERS: usize = 100_000;

fn request() -> Request {
    Request::default()
        .with(slot::LAYERS, LAYERS as f64)
        .with(slot::LAYER_HEIGHT, 0.2)
        .with(slot::FIRST_LAYER_HEIGHT, 0.3)
}

/// What one JS `expand` call does inside the wasm, natively.
#[divan::bench]
fn glue_expand_100k(bencher: Bencher) {
    let req = request();
    let mut out = Layers::default();
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        api::expand(black_box(TEMPLATE), &req, None, &mut out).expect("expand");
        out.angles.len()
    });
}

/// The bare evaluator on the same model, collecting the angles.
#[divan::bench]
fn evaluator_100k(bencher: Bencher) {
    let model = rotlang::eval::Model::uniform(LAYERS, 0.2, Some(0.3)).expect("model");
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        let parse = rotlang::parse(black_box(TEMPLATE), rotlang::Target::Sparse);
        rotlang::eval::layers(&parse.template, &model, Default::default())
            .map(|l| l.angle)
            .collect::<Vec<f64>>()
    });
}
