//! Unit tests of the evaluator on parsed templates: the documented sequences, the corners
//! of section 9, and the cost and finiteness guarantees.

use super::*;
use crate::diagnostic::Span;
use crate::ir::Fill;
use crate::{Target, parse};

fn template(text: &str) -> Template {
    let parse = parse(text, Target::Sparse);
    assert!(!parse.has_errors(), "{text:?}: {:?}", parse.diagnostics);
    parse.template
}

fn angles_on(text: &str, model: &Model, n: usize) -> Vec<f64> {
    let t = template(text);
    layers(&t, model, Options::default())
        .take(n)
        .map(|l| l.angle)
        .collect()
}

fn angles(text: &str, n: usize) -> Vec<f64> {
    angles_on(text, &Model::cube20(), n)
}

fn close(got: &[f64], expected: &[f64]) -> bool {
    got.len() == expected.len() && got.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-9)
}

#[test]
fn documented_sequences() {
    let cases: &[(&str, &[f64])] = &[
        ("5, 10, +20", &[5.0, 10.0, 30.0, 5.0, 10.0, 30.0]),
        ("5, 10*, +20", &[5.0, 30.0, 5.0, 30.0]),
        ("5, 10!, +20", &[5.0, 10.0, 30.0, 5.0, 25.0, 5.0, 25.0]),
        ("5, 10*!, +20", &[5.0, 30.0, 5.0, 25.0, 5.0, 25.0]),
        (
            "5, 10*3, +20",
            &[5.0, 10.0, 10.0, 10.0, 30.0, 5.0, 10.0, 10.0, 10.0, 30.0],
        ),
        ("+10*3", &[10.0, 10.0, 10.0, 20.0, 20.0, 20.0]),
        ("+10*0", &[10.0, 20.0, 30.0]),
        ("+90", &[90.0, 180.0, 270.0, 360.0, 450.0]),
        ("0, 90", &[0.0, 90.0, 0.0, 90.0]),
        ("B!, +30", &[0.0, 0.0, 0.0, 30.0, 60.0]),
        ("", &[0.0, 0.0, 0.0]),
    ];
    for (text, expected) in cases {
        let got = angles(text, expected.len());
        assert!(close(&got, expected), "{text:?}: {got:?} != {expected:?}");
    }
}

#[test]
fn step_joint_turns_at_the_start_of_its_range() {
    let got = angles("+15#10", 20);
    assert!(
        got[..10].iter().all(|&a| a == 15.0) && got[10..].iter().all(|&a| a == 30.0),
        "{got:?}"
    );
}

#[test]
fn walks_end_where_orcaslicer_hangs() {
    // Only dummies alive and the first instruction spent (section 9).
    assert!(close(&angles("10!, 5*", 4), &[10.0, 5.0, 5.0, 5.0]));
    let t = template("229*!, -62*");
    assert_eq!(
        layers(&t, &Model::cube20(), Options::default()).count(),
        100
    );
}

#[test]
fn a_spent_template_holds_where_its_range_ended() {
    // `u` ends back at the start angle: the hold keeps it instead of jumping to a0 + d.
    let got = angles("+10u5!", 8);
    assert!(
        (got[4] - 0.0).abs() < 1e-9 && got[5..].iter().all(|&a| a.abs() < 1e-9),
        "{got:?}"
    );
    let t = template("+10u5!");
    let held = layers(&t, &Model::cube20(), Options::default())
        .nth(6)
        .unwrap();
    assert_eq!((held.instruction, held.fill), (None, Fill::Sparse));
}

#[test]
fn layers_carry_their_instruction_span_and_fill() {
    let text = "#14, +15R";
    let t = template(text);
    let all: Vec<Layer> = layers(&t, &Model::cube20(), Options::default()).collect();
    let span = |l: &Layer| l.instruction.map(|s| &text[s.range()]);
    assert_eq!(span(&all[0]), Some("#14"));
    assert_eq!(span(&all[14]), Some("+15R"));
    assert_eq!(
        (all[13].fill, all[14].fill, all[15].fill),
        (Fill::Sparse, Fill::Rectilinear, Fill::Sparse)
    );
    assert_eq!(all[14].angle, 15.0);
    assert_eq!(
        layers(&template(""), &Model::cube20(), Options::default())
            .next()
            .unwrap()
            .instruction,
        None
    );
}

#[test]
fn base_is_added_and_bounds_are_running_sums() {
    let t = template("0, 90");
    let model = Model::cube20();
    let options = Options {
        base: 45.0,
        seed: 0,
    };
    let all: Vec<Layer> = layers(&t, &model, options).collect();
    assert_eq!((all[0].angle, all[1].angle), (45.0, 135.0));
    let mut sum = 0.0f64;
    for l in &all {
        assert_eq!(l.bottom.to_bits(), sum.to_bits());
        sum += 0.2;
        assert_eq!(l.top.to_bits(), sum.to_bits());
    }
}

#[test]
fn uniform_and_listed_models_agree_bitwise() {
    let uniform = Model::uniform(300, 0.12, Some(0.2))
        .unwrap()
        .with_shells(6, 7);
    let mut heights = vec![0.12; 300];
    heights[0] = 0.2;
    let listed = Model::from_heights(heights, 0.12)
        .unwrap()
        .with_shells(6, 7);
    assert_eq!(uniform.object_height(), listed.object_height());
    for text in [
        "+30/50%",
        "+10/7, -5L13",
        "+45/1000",
        "+22.5$1cm, 3!, +7*3-2mm",
        "+30*2/5, T, B!",
    ] {
        let t = template(text);
        let a: Vec<Layer> = layers(&t, &uniform, Options::default()).collect();
        let b: Vec<Layer> = layers(&t, &listed, Options::default()).collect();
        assert_eq!(a.len(), 300);
        for (x, y) in a.iter().zip(&b) {
            assert!(
                x == y && x.angle.to_bits() == y.angle.to_bits(),
                "{text:?}: {x:?} != {y:?}"
            );
        }
    }
    for i in [0, 1, 150, 299] {
        assert_eq!(uniform.layer_bounds(i), listed.layer_bounds(i));
    }
    assert_eq!(uniform.layer_bounds(300), None);
}

#[test]
fn huge_counts_cost_nothing_extra_and_stay_finite() {
    let model = Model::uniform(1_000_000, 0.2, None).unwrap();
    let start = std::time::Instant::now();
    for text in [
        "+10*1000000000",
        "+10/1000000000",
        "+10 1000000000",
        "+10/1000000mm",
        "+10/1000000000, 5*1000000000!",
        "+99999999999999999999999999999999999999999999999999/1e9",
        "+1:0.0000000000000000000001/0.00000001%",
    ] {
        let t = parse(text, Target::Sparse).template;
        let mut evaluator = Evaluator::new(&t, &model, Options::default());
        for index in [0, 1, 2, 999_999] {
            let layer = evaluator.layer(index).unwrap();
            assert!(layer.angle.is_finite(), "{text:?} layer {index}: {layer:?}");
        }
    }
    // Generous even for a debug build: a loop over any count would take far longer.
    assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
}

#[test]
fn absurd_numbers_stay_finite() {
    let huge = format!("+{}", "9".repeat(400));
    for text in [huge.as_str(), "+1e308", "-1:0", "+10/1:0", "+10$0", "+10^5"] {
        let t = parse(text, Target::Sparse).template;
        let model = Model::uniform(50, 0.2, Some(0.3)).unwrap();
        for options in [
            Options::default(),
            Options {
                base: f64::INFINITY,
                seed: 1,
            },
            Options {
                base: f64::NAN,
                seed: 2,
            },
        ] {
            for l in layers(&t, &model, options) {
                assert!(l.angle.is_finite(), "{text:?}: {l:?}");
            }
        }
    }
}

#[test]
fn random_joints_are_pure_functions_of_seed_and_layer() {
    let t = template("+360~100%");
    let model = Model::cube20();
    let a: Vec<f64> = layers(&t, &model, Options { base: 0.0, seed: 7 })
        .map(|l| l.angle)
        .collect();
    let b: Vec<f64> = layers(&t, &model, Options { base: 0.0, seed: 7 })
        .map(|l| l.angle)
        .collect();
    let c: Vec<f64> = layers(&t, &model, Options { base: 0.0, seed: 8 })
        .map(|l| l.angle)
        .collect();
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert!(a.iter().all(|&x| (0.0..=360.0).contains(&x)));
}

#[test]
fn random_access_goes_back_through_checkpoints() {
    let t = template("+10/7, -3L11, 5!, +1*3");
    let model = Model::uniform(5000, 0.2, Some(0.3)).unwrap();
    let stream: Vec<Layer> = layers(&t, &model, Options::default()).collect();
    let mut evaluator = Evaluator::new(&t, &model, Options::default());
    for index in [4999, 0, 3000, 1023, 1024, 1025, 2047, 17, 4999, 4998] {
        assert_eq!(evaluator.layer(index), Some(stream[index]));
    }
    assert_eq!(evaluator.layer(5000), None);
}

#[test]
fn model_validation() {
    assert_eq!(
        Model::from_heights(vec![], 0.2).unwrap_err(),
        ModelError::NoLayers
    );
    assert!(matches!(
        Model::from_heights(vec![0.2, 0.0], 0.2),
        Err(ModelError::LayerHeight { index: 1, .. })
    ));
    assert!(matches!(
        Model::from_heights(vec![0.2, f64::NAN], 0.2),
        Err(ModelError::LayerHeight { index: 1, .. })
    ));
    assert!(matches!(
        Model::from_heights(vec![0.2], -1.0),
        Err(ModelError::StandardLayerHeight(_))
    ));
    assert!(matches!(
        Model::uniform(10, 0.2, Some(f64::INFINITY)),
        Err(ModelError::FirstLayerHeight(_))
    ));
    assert!(matches!(
        Model::uniform(usize::MAX, 0.2, None),
        Err(ModelError::TooManyLayers(_))
    ));
    assert!(matches!(
        Model::from_total_height(1e12, 0.2, None),
        Err(ModelError::TooManyLayers(_))
    ));
    assert!(matches!(
        Model::from_total_height(-1.0, 0.2, None),
        Err(ModelError::ObjectHeight(_))
    ));
    assert!(!ModelError::NoLayers.to_string().is_empty());

    assert_eq!(
        Model::from_total_height(20.0, 0.2, None).unwrap().len(),
        100
    );
    assert_eq!(
        Model::from_total_height(15.1, 0.2, Some(0.3))
            .unwrap()
            .len(),
        75
    );
    assert_eq!(Model::from_total_height(0.1, 0.2, None).unwrap().len(), 1);
    let cube = Model::default();
    assert_eq!(
        (
            cube.len(),
            cube.bottom_shells(),
            cube.top_shells(),
            cube.layer_height()
        ),
        (100, 3, 4, 0.2)
    );
    assert_eq!(cube.object_height(), 20.0);
    assert!(!cube.is_empty());
    // One million layers, O(1) memory: only three numbers and a lazily computed top.
    let big = Model::uniform(1_000_000, 0.2, Some(0.3)).unwrap();
    assert_eq!(big.object_height(), 200_000.1);
}

/// IR no parser would produce (infinite, NaN, negative numbers) must still evaluate to
/// finite angles: embedders may build templates by hand.
#[test]
fn hand_built_nonsense_stays_finite() {
    use crate::ir::{Angle, AngleValue, Count, CountKind, Instruction, Joint, Sign, Spanned, Unit};
    let span = Span::new(0, 1);
    let instruction = |value: f64, count: Option<CountKind>, joint: Option<Joint>| Instruction {
        span,
        angle: Some(Angle {
            span,
            sign: Some(Sign::Plus),
            value: AngleValue::Degrees(value),
        }),
        repeat: Some(Spanned::new(u64::MAX, span)),
        dummy: None,
        one_time: None,
        solid: None,
        joint: joint.map(|j| Spanned::new(j, span)),
        flip: None,
        count: count.map(|kind| Count { span, kind }),
    };
    let weird = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -1.0,
        0.0,
        1e308,
        0.5,
    ];
    let mut instructions = Vec::new();
    for &x in &weird {
        for joint in [None, Some(Joint::Arcsine), Some(Joint::PseudoRandom)] {
            instructions.push(instruction(x, Some(CountKind::Layers(x)), joint));
            instructions.push(instruction(
                x,
                Some(CountKind::Length {
                    value: x,
                    unit: Unit::Metre,
                }),
                joint,
            ));
            instructions.push(instruction(
                1e308,
                Some(CountKind::HeightFraction { num: x, den: 0.0 }),
                joint,
            ));
            instructions.push(instruction(x, None, joint));
        }
    }
    let model = Model::uniform(2000, 0.2, Some(0.3)).unwrap();
    for chunk in instructions.chunks(3) {
        let t = Template {
            instructions: chunk.to_vec(),
        };
        let all: Vec<Layer> = layers(&t, &model, Options::default()).collect();
        assert_eq!(all.len(), 2000);
        assert!(all.iter().all(|l| l.angle.is_finite()), "{chunk:?}");
    }
}

/// Sections 3 and 4 transcribed literally for instructions without counts or joints
/// (every range one layer): the oracle for the walk, whose engine version is optimised.
fn naive_walk(template: &Template, layers: usize) -> Vec<f64> {
    let instructions = &template.instructions;
    let n = instructions.len();
    let mut spent = vec![false; n];
    let (mut cursor, mut a0, mut d, mut runs_left) = (0, 0.0, 0.0, 0);
    let mut out = Vec::new();
    for _ in 0..layers {
        if runs_left > 0 {
            runs_left -= 1;
        } else if spent.iter().any(|s| !s) {
            runs_left = 0;
            let mut set_up = vec![false; n];
            let mut last_dummy = false;
            loop {
                if !spent[cursor] {
                    if set_up[cursor] {
                        break;
                    }
                    set_up[cursor] = true;
                    let i = &instructions[cursor];
                    a0 += d;
                    d = 0.0;
                    spent[cursor] = i.is_one_time();
                    if i.is_relative() {
                        d = i.degrees();
                    } else {
                        a0 = i.degrees();
                    }
                    last_dummy = i.is_dummy();
                    if !last_dummy {
                        runs_left = i.runs() - 1;
                    }
                }
                cursor = (cursor + 1) % n;
                if spent.iter().all(|&s| s) || (!spent[cursor] && (!last_dummy || cursor == 0)) {
                    break;
                }
            }
        }
        // Every range is one layer: progress 1, linear.
        out.push(a0 + d);
    }
    out
}

/// Random templates of up to `len` instructions (`+`/`-`/absolute, with one of the
/// `suffixes`) evaluated by the engine and by [`naive_walk`] on 60 layers.
fn walks_match_naive(len: u64, suffixes: &[&str], templates: usize) {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = |m: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % m
    };
    let model = Model::uniform(60, 0.2, None).unwrap();
    for _ in 0..templates {
        let mut text = String::new();
        for k in 0..1 + next(len) {
            if k > 0 {
                text.push_str(", ");
            }
            text.push_str(["", "+", "-"][next(3) as usize]);
            text.push_str(&(next(50) * 5).to_string());
            text.push_str(suffixes[next(suffixes.len() as u64) as usize]);
        }
        let t = template(&text);
        let expected = naive_walk(&t, model.len());
        let got: Vec<f64> = layers(&t, &model, Options::default())
            .map(|l| l.angle)
            .collect();
        assert!(
            got.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-9),
            "{text:?}:\n got {got:?}\n expected {expected:?}"
        );
    }
}

#[test]
fn walks_match_the_literal_rules() {
    walks_match_naive(9, &["", "", "*", "*", "*!", "!", "*2", "*3"], 3000);
}

#[test]
fn long_walks_match_the_literal_rules() {
    // Mostly dummies, some spent as they are crossed: walks long enough to be remembered,
    // remembered walks made stale by a spend, walks that come back to where they began.
    walks_match_naive(40, &["", "!", "*", "*", "*", "*", "*!", "*!", "*2"], 3000);
}

#[test]
fn long_chains_of_dummies_cost_o1_per_layer() {
    // 20,000 dummies between two turns: every other walk crosses all of them.
    let text = format!("+1, {}, -1*!, 5", vec!["+1*"; 20_000].join(", "));
    let t = template(&text);
    let model = Model::uniform(200_000, 0.2, None).unwrap();
    let start = std::time::Instant::now();
    let last = layers(&t, &model, Options::default()).last().unwrap();
    assert!(last.angle.is_finite());
    // A walk per layer over every dummy would be 2e9 set-ups: minutes, not this.
    assert!(start.elapsed().as_secs() < 10, "{:?}", start.elapsed());
}

#[test]
fn parse_layers_is_layers_of_the_parse() {
    let models = [
        Model::cube20(),
        Model::uniform(5_000, 0.1, Some(0.3))
            .unwrap()
            .with_shells(2, 5),
        Model::from_heights(vec![0.3, 0.2, 0.15, 0.15, 0.2, 0.25, 0.1], 0.2).unwrap(),
    ];
    let texts = [
        "5, 10!, +20, +10L25%, -10l25%",
        "0*, +30*, 45!*, +10/5, -5~3, B!, T, #14 +15R",
        "+10L99999999, +5*3/1e6#, 1:4, -1:8/1:2",
        "0,,X, +30X5, 90",
        "\"0, 90\"",
    ];
    for model in &models {
        for text in texts {
            for target in [Target::Sparse, Target::Solid] {
                let options = Options {
                    base: 15.0,
                    seed: 3,
                };
                let parse = parse(text, target);
                let (streamed, layers_of_text) = parse_layers(text, target, model, options);
                assert_eq!(streamed.diagnostics, parse.diagnostics, "{text}");
                assert!(streamed.template.instructions.is_empty());
                let want: Vec<Layer> = layers(&parse.template, model, options).collect();
                let got: Vec<Layer> = layers_of_text.collect();
                assert_eq!(got.len(), want.len());
                for (g, w) in got.iter().zip(&want) {
                    assert_eq!(
                        g.angle.to_bits(),
                        w.angle.to_bits(),
                        "{text} layer {}",
                        g.index
                    );
                    assert_eq!(g, w);
                }
            }
        }
    }
}

/// Issue 19: a plain list's cycle gives every layer exactly (bitwise, fills too) what the
/// stream gives, on uniform and listed models, with a base; anything else has no cycle.
#[test]
fn plain_cycles_are_the_stream_bitwise() {
    let models = [
        Model::cube20(),
        Model::uniform(1000, 0.2, Some(0.3)).unwrap(),
        Model::from_heights(vec![0.001, 1000.0, 0.001, 0.3, 0.07, 999.9], 0.2).unwrap(),
        Model::uniform(3, 0.001, None).unwrap(),
    ];
    let plain = [
        "0, 90",
        "0, 0.0, 0e5",
        "45",
        "0, 15, 30, 45D, 90S",
        "1e9, 999999999.5, 30",
        "10N, 20Z, 30$",
    ];
    for text in plain {
        let t = template(text);
        for model in &models {
            for base in [0.0, -0.0, 45.0, -1e300] {
                let options = Options { base, seed: 7 };
                let cycle = layers(&t, model, options)
                    .plain_cycle()
                    .unwrap_or_else(|| panic!("{text:?} is a plain list"));
                let mut angles = vec![f64::NAN; model.len()];
                let mut fills = vec![Fill::Sparse; model.len()];
                cycle.write(0, &mut angles, Some(&mut fills));
                for (i, layer) in layers(&t, model, options).enumerate() {
                    assert_eq!(
                        angles[i].to_bits(),
                        layer.angle.to_bits(),
                        "{text:?} layer {i}"
                    );
                    assert_eq!(fills[i], layer.fill, "{text:?} layer {i}");
                    assert_eq!(cycle.at(i).0.to_bits(), layer.angle.to_bits());
                }
            }
        }
    }
    for text in [
        "+90", "0, 90!", "0*2, 90", "0#2, 90", "~30", "-30R", "30/1mm",
    ] {
        let t = template(text);
        assert!(
            layers(&t, &Model::cube20(), Options::default())
                .plain_cycle()
                .is_none(),
            "{text:?} is not a plain list"
        );
    }
}
