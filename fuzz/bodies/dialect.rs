//! Fuzz target `dialect`: OrcaSlicer's reading (`rotlang::dialect::orcaslicer`) of any text
//! on one of a few models: every layer comes out, its angle finite in degrees and radians,
//! findings with known codes on layers of the model (at most one hang or crash); then the
//! compat lint on the same text. Bytes 0..3 choose the model and base; the rest is the text.

use rotlang::Target;
use rotlang::dialect::{HANGS, NAN, UNDEFINED, compat, orcaslicer};
use rotlang::eval::{Model, Options};

/// Layers streamed at most.
const STREAMED: usize = 4096;

pub fn run(data: &[u8]) {
    let (head, rest) = data.split_at(data.len().min(3));
    let mut head = [head, &[0; 3]].concat();
    head.truncate(3);
    let text = String::from_utf8_lossy(rest);
    let model = model(&head);
    let options = Options {
        base: f64::from(head[2]) * 3.0 - 360.0,
        seed: u64::from(head[2]),
    };
    let mut stream = orcaslicer::layers(&text, &model, options);
    let mut count = 0;
    for layer in stream.by_ref().take(STREAMED) {
        assert_eq!(layer.index, count);
        assert!(layer.angle.is_finite(), "layer {count}: {}", layer.angle);
        assert!((std::f64::consts::PI * layer.angle / 180.0).is_finite());
        if let Some(span) = layer.instruction {
            assert!(
                text.get(span.range()).is_some(),
                "layer {count}: span {span:?}"
            );
        }
        count += 1;
    }
    assert_eq!(count, model.len().min(STREAMED));
    let findings = stream.findings();
    assert!(findings.iter().filter(|f| f.code != NAN).count() <= 1);
    for f in findings {
        assert!([HANGS, UNDEFINED, NAN].contains(&f.code), "{f:?}");
        assert!(f.first_layer < count && f.layers >= 1, "{f:?}");
    }
    if text.len() <= 4096 {
        for d in compat(&text, Target::Sparse, &Model::cube20(), Options::default()) {
            assert!(d.code.starts_with("orcaslicer::"), "{d:?}");
            for l in &d.labels {
                assert!(text.get(l.span.range()).is_some(), "{d:?}");
            }
        }
    }
}

fn model(head: &[u8]) -> Model {
    const HEIGHTS: [f64; 6] = [0.2, 0.12, 0.3, 0.05, 0.28, 0.001];
    let h = HEIGHTS[usize::from(head[0] % 6)];
    let first = HEIGHTS[usize::from(head[1] % 6)];
    let n = usize::from(head[1]) * 4 + 1;
    let model = match head[0] % 3 {
        0 => Ok(Model::cube20()),
        1 => Model::uniform(n, h, Some(first)),
        _ => Model::from_heights(
            (0..n)
                .map(|i| 0.05 + f64::from((i as u8).wrapping_mul(head[1])) / 255.0 * 0.3)
                .collect(),
            h,
        ),
    };
    model
        .expect("the header gives valid models")
        .with_shells(u32::from(head[1] % 7), u32::from(head[0] % 9))
}
