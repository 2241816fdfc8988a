//! The OrcaSlicer dialect next to the main evaluator (divan): `cargo bench --bench dialect`.
//!
//! Same templates, same models, same work timed on both sides: from the raw text to the
//! last layer. `rotlang` times `parse` + `eval::layers`; `orcaslicer` times
//! `dialect::orcaslicer::layers`, which reads the text as it starts. Both are O(1) per layer;
//! 1M layers should cost about 100× 10,000. `dummies` is a template of 1,000 dummies and one
//! range: every walk crosses them all, which a remembered walk makes O(1).

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang::Target;
use rotlang::dialect::orcaslicer;
use rotlang::eval::{self, Layer, Model, Options};

fn main() {
    divan::main();
}

const TEMPLATES: [(&str, &str); 3] = [
    ("doc", "5, 10!, +20, +10L25%, -10l25%"),
    ("ramps", "+30/5, -15$10#, +90N2mm, 25%*3"),
    ("list", "0, 45, 90, 135"),
];

fn checksum(layers: impl Iterator<Item = Layer>) -> f64 {
    layers.fold(0.0, |acc, l| acc + l.angle)
}

fn model(layers: usize) -> Model {
    let model = Model::uniform(layers, 0.2, Some(0.3)).expect("model");
    let _ = model.object_height();
    model
}

fn template(name: &str) -> String {
    if name == "dummies" {
        let mut t = "+1*, ".repeat(1000);
        t.push_str("+5");
        return t;
    }
    TEMPLATES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| (*t).to_owned())
        .expect("template")
}

const ARGS: [&str; 4] = ["doc", "ramps", "list", "dummies"];

#[divan::bench(consts = [10_000, 1_000_000], args = ARGS)]
fn rotlang<const LAYERS: usize>(bencher: Bencher, name: &str) {
    let model = model(LAYERS);
    let text = template(name);
    // The parse is timed too: the dialect's closure reads the text as well.
    bencher.counter(ItemsCount::new(LAYERS)).bench(|| {
        let template = rotlang::parse(black_box(&text), Target::Sparse).template;
        checksum(eval::layers(&template, &model, Options::default()))
    });
}

/// Includes reading the text: the dialect has no separate parse step.
#[divan::bench(consts = [10_000, 1_000_000], args = ARGS)]
fn orcaslicer<const LAYERS: usize>(bencher: Bencher, name: &str) {
    let model = model(LAYERS);
    let text = template(name);
    bencher.counter(ItemsCount::new(LAYERS)).bench(|| {
        checksum(orcaslicer::layers(
            black_box(&text),
            &model,
            Options::default(),
        ))
    });
}
