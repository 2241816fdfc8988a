//! The evaluator: the angle and fill of every layer of a model (SEMANTICS.md).
//!
//! Parse a template once, then evaluate it on as many models as you like. Evaluation
//! streams: [`layers`] yields one [`Layer`] at a time in O(instructions) memory, and
//! [`Evaluator`] answers for any layer index, cheaply when indices increase (as a slicer
//! asks, layer after layer).
//!
//! ```
//! use rotlang::eval::{self, Evaluator, Model, Options};
//!
//! let parse = rotlang::parse("5, 10!, +20", rotlang::Target::Sparse);
//! assert!(!parse.has_errors());
//! let template = parse.template;
//!
//! // The documentation's 20 mm cube, then a tall part with a thicker first layer.
//! let cube = Model::cube20();
//! let angles: Vec<f64> = eval::layers(&template, &cube, Options::default())
//!     .map(|layer| layer.angle)
//!     .take(7)
//!     .collect();
//! assert_eq!(angles, [5.0, 10.0, 30.0, 5.0, 25.0, 5.0, 25.0]);
//!
//! let tall = Model::uniform(1_000_000, 0.2, Some(0.3))?.with_shells(4, 5);
//! let mut slicer = Evaluator::new(&template, &tall, Options { base: 45.0, seed: 0 });
//! for index in 0..tall.len() {
//!     let layer = slicer.layer(index).expect("every index below len() has a layer");
//!     assert!(layer.angle.is_finite());
//! }
//! assert_eq!(slicer.layer(4).map(|l| l.angle), Some(45.0 + 25.0));
//!
//! // Adaptive layer heights, as the slicer computed them.
//! let adaptive = Model::from_heights(vec![0.3, 0.2, 0.15, 0.15, 0.2, 0.25], 0.2)?;
//! let last = eval::layers(&template, &adaptive, Options::default()).last();
//! assert_eq!(last.map(|l| (l.index, l.angle)), Some((5, 5.0)));
//! # Ok::<(), rotlang::eval::ModelError>(())
//! ```

mod cycle;
mod engine;
mod layer;
pub mod limits;
mod model;
mod random;
mod shape;

pub use crate::dialect::Dialect;
// What the evaluator gives (in layer.rs, so that the engine does not name this module).
pub use cycle::Cycle;
pub use layer::{Layer, Options};
pub use model::{MAX_LAYER_HEIGHT, MAX_LAYERS, MIN_LAYER_HEIGHT, Model, ModelError};
// The OrcaSlicer reader (`crate::dialect`) walks the same layers with the same randomness.
pub(crate) use model::Cursor;
pub(crate) use random::unit as random_unit;

use crate::ir::Template;
use engine::Engine;

/// The layers of `model` under `template`, bottom to top.
pub fn layers<'a>(template: &'a Template, model: &'a Model, options: Options) -> Layers<'a> {
    Layers {
        model,
        engine: Engine::new(template, model, options),
        at: Cursor::new(model),
    }
}

/// Parses `text` and streams its layers on `model`, without keeping the IR: what stays
/// is the evaluator's prepared form of the template (24 bytes per instruction, 56 per
/// distinct one), so a template of
/// megabytes costs a small multiple of its size. The layers are bitwise those of
/// [`layers`] on `crate::parse(text, target).template`; the returned `Parse` has every
/// diagnostic and an empty `template`.
pub fn parse_layers<'a>(
    text: &str,
    target: crate::Target,
    model: &'a Model,
    options: Options,
) -> (crate::Parse, Layers<'a>) {
    parse_layers_with(text, target, model, options, |_| {})
}

/// [`parse_layers`], showing each instruction to `inspect` as it is parsed (the compat
/// lint's rules read them in the same pass, without keeping them).
pub(crate) fn parse_layers_with<'a>(
    text: &str,
    target: crate::Target,
    model: &'a Model,
    options: Options,
    mut inspect: impl FnMut(&crate::Instruction),
) -> (crate::Parse, Layers<'a>) {
    // An exact upper bound on the instructions: the steps are allocated once, not grown.
    let chunks = crate::syntax::count_chunks(text);
    let mut program = engine::ProgramBuilder::with_capacity(chunks);
    let collected = crate::syntax::parse_each(text, target, |ins| {
        inspect(&ins);
        program.push(engine::Step::new(&ins, model));
    });
    let layers = Layers {
        model,
        engine: Engine::from_program(program.finish(), options),
        at: Cursor::new(model),
    };
    (collected.into_parse(crate::Template::default()), layers)
}

/// The stream of layers returned by [`layers`]. Cloning it is cheap (O(instructions)).
#[derive(Clone, Debug)]
pub struct Layers<'a> {
    model: &'a Model,
    engine: Engine,
    at: Cursor,
}

impl Layers<'_> {
    /// `Some` when every layer's angle and fill is an entry of a fixed cycle (a plain
    /// list of absolute angles, `0, 90`): then [`Cycle::write`] gives the same layers as
    /// this stream, far faster. The layers' `instruction` spans are not in the cycle.
    pub fn plain_cycle(&self) -> Option<Cycle> {
        self.engine.plain_cycle().map(|entries| Cycle { entries })
    }

    /// The index of the layer the next call to `next` yields.
    pub fn position(&self) -> usize {
        self.at.index
    }
}

impl Iterator for Layers<'_> {
    type Item = Layer;

    #[inline]
    fn next(&mut self) -> Option<Layer> {
        if self.at.index >= self.model.len() {
            return None;
        }
        let layer = self.engine.layer(&self.at, self.model);
        self.at.advance_in(self.model);
        Some(layer)
    }

    /// Internal iteration (`sum`, `for_each`, `last`, `count`, ...): the engine and the
    /// cursor are moved into locals, so the compiler keeps them in registers across
    /// layers instead of going through `self` on every call.
    #[inline]
    fn fold<B, F: FnMut(B, Layer) -> B>(self, init: B, mut f: F) -> B {
        let Layers {
            model,
            mut engine,
            mut at,
        } = self;
        let len = model.len();
        let mut acc = init;
        while at.index < len {
            let layer = engine.layer(&at, model);
            at.advance_in(model);
            acc = f(acc, layer);
        }
        acc
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.model.len().saturating_sub(self.at.index);
        (left, Some(left))
    }
}

impl ExactSizeIterator for Layers<'_> {}
impl std::iter::FusedIterator for Layers<'_> {}

/// Random access to the layers of one model, bitwise equal to the stream of [`layers`].
///
/// Costs: asking for increasing indices is amortised O(1) per layer (the stream just moves
/// on). A layer below the last one asked for restarts from the nearest checkpoint: the
/// evaluator keeps a snapshot every `max(1024, 128 × instructions)` layers as it passes,
/// so going back costs at most that many layers, and the snapshots take about one
/// byte per layer.
#[derive(Clone, Debug)]
pub struct Evaluator<'a> {
    stream: Layers<'a>,
    last: Option<Layer>,
    checkpoints: Vec<Layers<'a>>,
    spacing: usize,
}

impl<'a> Evaluator<'a> {
    /// An evaluator of `template` on `model`, at its first layer.
    pub fn new(template: &'a Template, model: &'a Model, options: Options) -> Self {
        Evaluator {
            stream: layers(template, model, options),
            last: None,
            checkpoints: Vec::new(),
            spacing: template.instructions.len().saturating_mul(128).max(1024),
        }
    }

    /// The layer at `index`, or `None` past the top of the model.
    #[inline]
    pub fn layer(&mut self, index: usize) -> Option<Layer> {
        if index >= self.stream.model.len() {
            return None;
        }
        if let Some(last) = self.last.filter(|l| l.index == index) {
            return Some(last);
        }
        if index < self.stream.position() {
            // Checkpoints are recorded in order as the stream passes them, so every one at
            // or below a layer already passed exists.
            let checkpoint = self.checkpoints.get(index / self.spacing)?;
            self.stream = checkpoint.clone();
        }
        while self.stream.position() < index {
            self.record_checkpoint();
            self.stream.next();
        }
        self.record_checkpoint();
        self.last = self.stream.next();
        self.last
    }

    /// Snapshots the stream if it stands on the next checkpoint not yet recorded.
    #[inline]
    fn record_checkpoint(&mut self) {
        // `checkpoints.len() * spacing` is the next position due: no division per layer.
        if self.stream.position() == self.checkpoints.len().saturating_mul(self.spacing) {
            self.checkpoints.push(self.stream.clone());
        }
    }
}

#[cfg(test)]
mod tests;
