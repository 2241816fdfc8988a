//! Fuzz target `eval`: parse, then evaluate on one of a few models (chosen by the first
//! bytes) and check the stream against random access: every layer finite, bounds
//! increasing, `Evaluator::layer(i)` bitwise equal to the stream's layer `i` for indices
//! in random order, `Model::layer_bounds` equal to the stream's bounds, and as many layers
//! as the model has. Bytes 0..4 choose the model and options; the rest is the template.

use rotlang::Target;
use rotlang::eval::{self, Evaluator, Layer, Model, Options};

/// Layers streamed at most (a 1e8-layer model is only looked at from below).
const STREAMED: usize = 4096;

pub fn run(data: &[u8]) {
    let (head, rest) = data.split_at(data.len().min(4));
    let mut head = [head, &[0; 4]].concat();
    head.truncate(4);
    let text = String::from_utf8_lossy(rest);
    let target = if head[0] & 0x80 == 0 {
        Target::Sparse
    } else {
        Target::Solid
    };
    let parse = rotlang::parse(&text, target);
    let model = model(&head);
    let options = Options {
        base: f64::from(head[3]) * 7.5 - 90.0,
        seed: u64::from(head[3]),
    };
    let template = &parse.template;
    let stream: Vec<Layer> = eval::layers(template, &model, options)
        .take(STREAMED)
        .collect();
    assert_eq!(stream.len(), model.len().min(STREAMED));
    let mut below = 0.0;
    for (i, layer) in stream.iter().enumerate() {
        assert_eq!(layer.index, i);
        assert!(layer.angle.is_finite(), "layer {i}: angle {}", layer.angle);
        assert!(
            layer.bottom == below && layer.top > layer.bottom,
            "layer {i}: bounds"
        );
        below = layer.top;
        if i < 64 || i % 61 == 0 {
            let bounds = model.layer_bounds(i).expect("a layer below len()");
            assert_eq!(
                (bounds.0.to_bits(), bounds.1.to_bits()),
                (layer.bottom.to_bits(), layer.top.to_bits()),
                "layer {i}: layer_bounds"
            );
        }
    }
    // Random access in an order derived from the input.
    let mut evaluator = Evaluator::new(template, &model, options);
    let mut state = data.iter().fold(0x9e37_79b9_7f4a_7c15_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    });
    for _ in 0..24 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let i = (state % stream.len() as u64) as usize;
        let got = evaluator.layer(i).expect("a layer below len()");
        let want = stream[i];
        assert_eq!(
            got.angle.to_bits(),
            want.angle.to_bits(),
            "layer {i}: angle"
        );
        assert_eq!(
            (
                got.bottom.to_bits(),
                got.top.to_bits(),
                got.fill,
                got.instruction
            ),
            (
                want.bottom.to_bits(),
                want.top.to_bits(),
                want.fill,
                want.instruction
            ),
            "layer {i}"
        );
    }
    assert_eq!(evaluator.layer(model.len()), None);
}

fn model(head: &[u8]) -> Model {
    const HEIGHTS: [f64; 8] = [0.2, 0.1, 0.3, 0.05, 0.12, 0.001, 0.28, 1000.0];
    let h = HEIGHTS[usize::from(head[1] % 8)];
    let first = HEIGHTS[usize::from(head[2] % 8)];
    let n = usize::from(head[1]) * 16 + usize::from(head[2] % 16) + 1;
    let model = match head[0] % 5 {
        0 => Ok(Model::cube20()),
        1 => Model::uniform(n, h, Some(first)),
        // Varying heights, from the header bytes.
        2 => Model::from_heights(
            (0..n)
                .map(|i| 0.05 + f64::from(head[(i % 3) + 1].wrapping_mul(i as u8)) / 255.0 * 0.4)
                .collect(),
            h,
        ),
        // The most layers a model may have: only the bottom of it is streamed.
        3 => Model::uniform(rotlang::eval::MAX_LAYERS, h, Some(first)),
        _ => Model::from_total_height(f64::from(head[2]) + 0.5, h.min(1.0), None),
    };
    model
        .expect("the header gives valid models")
        .with_shells(u32::from(head[2] % 7), u32::from(head[1] % 9))
}
