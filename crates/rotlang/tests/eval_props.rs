//! Property tests of the evaluator on generated template strings: every template ends on
//! every model (one layer per model layer), angles stay finite, evaluation is
//! deterministic, and random access equals the stream bitwise.

use proptest::prelude::*;
use rotlang::Target;
use rotlang::eval::{self, Evaluator, Layer, Model, Options};

/// A number as a template writes it: whole or with a fractional part, up to `huge` (the
/// parser's bounds are 1e9 for counts and 1e9° for angles).
fn number(huge: &'static str) -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (0u32..400).prop_map(|n| n.to_string()),
        3 => (0u32..400, 1u32..100).prop_map(|(a, b)| format!("{a}.{b:02}")),
        1 => Just(huge.to_string()),
        1 => Just("0".to_string()),
    ]
}

fn positive() -> impl Strategy<Value = String> {
    prop_oneof![
        (1u32..50).prop_map(|n| n.to_string()),
        Just("1000000000".to_string())
    ]
}

fn angle() -> impl Strategy<Value = String> {
    let sign = prop_oneof![Just(""), Just("+"), Just("-")];
    let value = prop_oneof![
        4 => number("1000000"),
        2 => number("100000").prop_map(|n| format!("{n}%")),
        1 => (number("1000"), positive()).prop_map(|(a, b)| format!("{a}:{b}")),
    ];
    (sign, value).prop_map(|(s, v)| format!("{s}{v}"))
}

/// `[solid][joint][-][count][unit]`: the range part, never starting with a digit so that
/// it cannot merge with the angle's digits.
fn range() -> impl Strategy<Value = String> {
    let solid =
        prop_oneof![4 => Just(""), 1 => prop::sample::select(vec!["D", "S", "O", "M", "R"])];
    let joint = prop::sample::select(vec![
        "/", "N", "n", "Z", "z", "$", "L", "l", "U", "u", "Q", "q", "~", "^", "|", "#",
    ]);
    let flip = prop_oneof![3 => Just(""), 1 => Just("-")];
    let unit = prop_oneof![
        3 => Just("".to_string()),
        1 => prop::sample::select(vec!["mm", "cm", "m", "'", "\"", "#", "%"]).prop_map(str::to_string),
    ];
    let count = prop_oneof![
        4 => (number("1000000000"), unit).prop_map(|(n, u)| format!("{n}{u}")),
        1 => Just("B".to_string()),
        1 => Just("T".to_string()),
        1 => (number("1000000000"), positive()).prop_map(|(a, b)| format!("{a}:{b}")),
    ];
    (solid, joint, flip, count).prop_map(|(s, j, f, c)| format!("{s}{j}{f}{c}"))
}

fn instruction() -> impl Strategy<Value = String> {
    let runtime = prop_oneof![
        6 => Just("".to_string()),
        1 => Just("!".to_string()),
        1 => (1u32..5).prop_map(|n| format!("*{n}")),
        1 => Just("*1000000000".to_string()),
    ];
    let trailing = prop_oneof![6 => Just(""), 1 => Just("!"), 1 => Just("*")];
    prop_oneof![
        // An angle, a runtime part and a range; a trailing `*` would make a repeated
        // instruction a dummy too, which is an error.
        6 => (angle(), runtime, prop::option::of(range()), trailing).prop_map(|(a, r, g, t)| {
            let t = if r.starts_with('*') && t == "*" { "" } else { t };
            format!("{a}{r}{}{t}", g.unwrap_or_default())
        }),
        // Dummies.
        2 => (angle(), prop_oneof![Just("*"), Just("*0"), Just("*!")]).prop_map(|(a, d)| format!("{a}{d}")),
        // Forms without an angle.
        1 => prop::sample::select(vec!["B!", "T", "#14", "M3", "DT", "S/", "B", "T!", "#1000000000"]).prop_map(str::to_string),
    ]
}

fn template() -> impl Strategy<Value = String> {
    let separator = prop::sample::select(vec![", ", ",", " ", " , ", ",  "]);
    prop::collection::vec((instruction(), separator), 0..7).prop_map(|parts| {
        parts
            .into_iter()
            .enumerate()
            .fold(String::new(), |mut text, (i, (instruction, sep))| {
                if i > 0 {
                    text.push_str(sep);
                }
                text.push_str(&instruction);
                text
            })
    })
}

fn model() -> impl Strategy<Value = Model> {
    let shells = (0u32..8, 0u32..8);
    let uniform = (
        1usize..400,
        prop::sample::select(vec![0.1, 0.12, 0.2, 0.3]),
        prop::option::of(0.1f64..0.4),
    )
        .prop_map(|(n, h, first)| Model::uniform(n, h, first).expect("valid uniform model"));
    let listed = (prop::collection::vec(0.05f64..0.4, 1..300), 0.05f64..0.4)
        .prop_map(|(heights, h)| Model::from_heights(heights, h).expect("valid listed model"));
    (prop_oneof![uniform, listed], shells).prop_map(|(m, (b, t))| m.with_shells(b, t))
}

fn same(a: &Layer, b: &Layer) -> bool {
    a == b && a.angle.to_bits() == b.angle.to_bits()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn evaluation_ends_stays_finite_and_is_consistent(
        text in template(),
        model in model(),
        seed in any::<u64>(),
        base in prop_oneof![Just(0.0), -720.0f64..720.0],
        order_seed in any::<u64>(),
    ) {
        let parse = rotlang::parse(&text, Target::Sparse);
        prop_assert!(!parse.has_errors(), "{:?}: {:?}", text, parse.diagnostics);
        let template = parse.template;
        let options = Options { base, seed };
        let stream: Vec<Layer> = eval::layers(&template, &model, options).collect();
        prop_assert_eq!(stream.len(), model.len());
        for (i, layer) in stream.iter().enumerate() {
            prop_assert_eq!(layer.index, i);
            prop_assert!(layer.angle.is_finite(), "{:?} layer {}: {:?}", text, i, layer);
            if let Some(span) = layer.instruction {
                prop_assert!(span.start <= span.end && span.end <= text.len());
            }
        }
        let again: Vec<Layer> = eval::layers(&template, &model, options).collect();
        prop_assert!(stream.iter().zip(&again).all(|(a, b)| same(a, b)), "not deterministic");

        let mut evaluator = Evaluator::new(&template, &model, options);
        for expected in &stream {
            let got = evaluator.layer(expected.index);
            prop_assert!(got.is_some_and(|g| same(&g, expected)), "increasing: {:?} != {:?}", got, expected);
        }
        // A shuffled order (Fisher–Yates driven by xorshift from the generated seed).
        let mut order: Vec<usize> = (0..stream.len()).collect();
        let mut state = order_seed | 1;
        for i in (1..order.len()).rev() {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            order.swap(i, (state % (i as u64 + 1)) as usize);
        }
        let mut evaluator = Evaluator::new(&template, &model, options);
        for index in order {
            let got = evaluator.layer(index);
            prop_assert!(got.is_some_and(|g| same(&g, &stream[index])), "shuffled at {}: {:?}", index, got);
        }
        prop_assert!(evaluator.layer(model.len()).is_none());
    }
}

/// The generator writes the language, not noise: every template it makes parses cleanly,
/// so the property above exercises the evaluator on meaningful input.
#[test]
fn generated_templates_are_well_formed() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = template();
    let mut errors = Vec::new();
    for _ in 0..500 {
        let text = strategy
            .new_tree(&mut runner)
            .expect("a template")
            .current();
        let parse = rotlang::parse(&text, Target::Sparse);
        if parse.has_errors() {
            errors.push((
                text,
                parse
                    .diagnostics
                    .into_iter()
                    .find(|d| d.is_error())
                    .map(|d| d.message),
            ));
        }
    }
    assert!(
        errors.is_empty(),
        "{} of 500 generated templates do not parse: {:#?}",
        errors.len(),
        &errors[..errors.len().min(20)]
    );
}
