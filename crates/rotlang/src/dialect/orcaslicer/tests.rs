//! The consequences section 10 lists, each on the smallest model that shows it. The
//! conformance corpus (`tests/dialect.rs`) checks thousands more.

use super::*;
use crate::dialect::{HANGS, NAN, UNDEFINED};

fn angles(text: &str, model: &Model) -> Vec<f64> {
    layers(text, model, Options::default())
        .map(|l| l.angle)
        .collect()
}

fn cube(n: usize) -> Model {
    Model::uniform(n, 0.2, None).unwrap()
}

fn first_layer(n: usize) -> Model {
    Model::uniform(n, 0.2, Some(0.3)).unwrap()
}

fn close(got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-9, "{got:?} vs {want:?}");
    }
}

#[test]
fn list_reading() {
    assert_eq!(angles("0 90", &cube(3)), [0.0; 3]);
    assert_eq!(angles("1:4", &cube(2)), [1.0; 2]);
    assert_eq!(angles("10!, 20", &cube(4)), [10.0, 20.0, 10.0, 20.0]);
    assert_eq!(angles("0, 90,", &cube(3)), [0.0, 90.0, 0.0]);
    assert_eq!(angles("0, 90, ", &cube(3)), [0.0, 90.0, 0.0]);
    assert_eq!(angles("10,,20", &cube(3)), [10.0, 0.0, 20.0]);
    assert_eq!(angles("45°, 1e", &cube(2)), [45.0, 0.0]);
    assert_eq!(angles("", &cube(2)), [0.0; 2]);
    let base = Options {
        base: 45.0,
        seed: 0,
    };
    let with_base: Vec<f64> = layers("0, 90", &cube(2), base).map(|l| l.angle).collect();
    assert_eq!(with_base, [45.0, 135.0]);
    assert!(is_list("0 90") && is_list("10!, 20B") && !is_list("+5") && !is_list("5mm"));
}

#[test]
fn spans_name_the_governing_piece_or_token() {
    let spans: Vec<_> = layers(" 0 , 90", &cube(2), Options::default())
        .map(|l| l.instruction)
        .collect();
    assert_eq!(spans, [Some(Span::new(1, 2)), Some(Span::new(5, 7))]);
    let spans: Vec<_> = layers("+5, 𝕏+10", &cube(2), Options::default())
        .map(|l| l.instruction)
        .collect();
    assert_eq!(spans, [Some(Span::new(0, 2)), Some(Span::new(4, 11))]);
}

#[test]
fn metalanguage_consequences() {
    // `+30-5` turns 150 over 5 layers, flipped: 150 × (5 - 1 - i) / 5.
    close(&angles("+30-5", &cube(5)), &[120.0, 90.0, 60.0, 30.0, 0.0]);
    // `+30/5*2` skips `/5`: one layer, run twice.
    close(&angles("+30/5*2", &cube(4)), &[30.0, 30.0, 60.0, 60.0]);
    // `*4294967296` is a dummy (low 32 bits: 0): the walk wraps and the layer shows 10.
    close(&angles("+10*4294967296", &cube(3)), &[10.0, 20.0, 30.0]);
    // Runs re-measured by the previous run's height on a 0.3 mm first layer.
    let runs = angles("+10*3", &first_layer(3));
    close(&runs, &[10.0, 10.0 * 0.2 / 0.3, 10.0 * (0.2 + 0.2) / 0.3]);
    // A range ending inside a layer (2 mm, in layer 9 of 0.3 + 0.2 mm): progress past 1,
    // then the next ramp starts from 45 at the bottom of layer 10.
    let ramp = angles("+45/10#", &first_layer(11));
    close(&ramp[9..], &[47.25, 45.0 + 45.0 * 0.2 / 2.0]);
    // Solid signs, `/B` and everything after `!` are ignored.
    close(&angles("+30M3", &cube(2)), &[30.0, 60.0]);
    close(&angles("+7!B, +1", &cube(3)), &[7.0, 8.0, 9.0]);
    // `c` anywhere after a count is centimetres: `+90/1cx` is a 10 mm ramp.
    close(&angles("+90/1cx", &cube(2)), &[1.8, 3.6]);
}

#[test]
fn hang_is_reported_and_holds() {
    let model = cube(5);
    let mut stream = layers("10!, 5*", &model, Options::default());
    let got: Vec<f64> = stream.by_ref().map(|l| l.angle).collect();
    assert_eq!(got, [10.0; 5]);
    let f = &stream.findings()[0];
    assert_eq!((f.code, f.first_layer, f.layers), (HANGS, 1, 4));
}

#[test]
fn undefined_is_reported_and_holds() {
    let model = cube(4);
    for text in ["+30/1e10", "/nan", "+1/inf", "5, +1/3e9"] {
        let mut stream = layers(text, &model, Options::default());
        let got: Vec<f64> = stream.by_ref().map(|l| l.angle).collect();
        assert!(got.iter().all(|a| a.is_finite()), "{text}: {got:?}");
        let codes: Vec<_> = stream.findings().iter().map(|f| f.code).collect();
        assert_eq!(codes, [UNDEFINED], "{text}");
    }
    let mut stream = layers("5, +1/3e9", &model, Options::default());
    let got: Vec<f64> = stream.by_ref().map(|l| l.angle).collect();
    assert_eq!(got, [5.0; 4]);
    assert_eq!(stream.findings()[0].first_layer, 1);
}

#[test]
fn nan_layers_are_counted_and_finite() {
    let model = first_layer(100);
    let mut stream = layers("+22.5$50%", &model, Options::default());
    let got: Vec<f64> = stream.by_ref().map(|l| l.angle).collect();
    assert!(got.iter().all(|a| a.is_finite()));
    let nan = stream.findings().iter().find(|f| f.code == NAN).unwrap();
    assert!(nan.layers >= 1);
    // Infinite in radians although finite in degrees: held at the layer below.
    let model = cube(2);
    let mut stream = layers("1e308", &model, Options::default());
    assert_eq!(
        stream.by_ref().map(|l| l.angle).collect::<Vec<_>>(),
        [0.0; 2]
    );
    assert_eq!(stream.findings()[0].layers, 2);
}

#[test]
fn long_walks_of_dummies_are_remembered_exactly() {
    // 100 dummies `+1*` then `+5`: each layer adds 99 + 1 + 5 = 105.
    let mut text = "+1*, ".repeat(100);
    text.push_str("+5");
    let got = angles(&text, &cube(1000));
    let want: Vec<f64> = (0..1000).map(|i| 105.0 * (i + 1) as f64).collect();
    assert_eq!(got, want);
    // Absolute dummies: a constant start.
    let mut text = "7*, ".repeat(80);
    text.push_str("+5");
    assert_eq!(angles(&text, &cube(50)), [12.0; 50]);
    // Spent dummies are skipped: ten thousand `!` dummies cost one pass.
    let mut text = "+1*!, ".repeat(10_000);
    text.push_str("+5");
    let got = angles(&text, &cube(100_000));
    assert_eq!(got[0], 9_999.0 + 1.0 + 5.0);
    assert_eq!(got[1], 10_005.0 + 5.0);
}

#[test]
fn walks_end_at_the_first_token_and_after_a_range() {
    // `5, 10*, +20` (section 4's example; OrcaSlicer agrees): 5, 30, 5, 30.
    close(&angles("5, 10*, +20", &cube(4)), &[5.0, 30.0, 5.0, 30.0]);
    close(
        &angles("5, 10!, +20", &cube(7)),
        &[5.0, 10.0, 30.0, 5.0, 25.0, 5.0, 25.0],
    );
}

#[test]
fn same_reading_sees_what_orcaslicer_sees() {
    for (a, b, same) in [
        ("", "", true),
        ("", "0", false),
        ("0 90", "0, 90", false),
        ("0 0", "0, 0", false),
        ("10,,20", "10, 20", false),
        ("10, 20,", "10, 20", true),
        ("10 ,20", "10, 20", true),
        ("+10  +20", "+10, +20", true),
        (",+10", "+10", false),
        ("+10,,+20", "+10, +20", true),
        ("1:4", "1:4, 0", false),
        ("+10", "10", false),
    ] {
        assert_eq!(same_reading(a, b), same, "{a:?} vs {b:?}");
        assert_eq!(same_reading(b, a), same, "{b:?} vs {a:?}");
    }
    // Where it says "same", every layer is the same, bit for bit, on two models.
    let mut compared = 0;
    for text in [
        "0 90",
        "10,,20",
        "+10L25%,, -10l25%",
        " 5, 10!, +20",
        "10!, 5*",
        "#14 +15R",
        "1e5 ,2",
    ] {
        let formatted = crate::format::format(text, crate::Target::Sparse)
            .unwrap_or_else(|| panic!("{text:?} has errors"));
        if same_reading(text, &formatted) {
            compared += 1;
            for model in [cube(50), first_layer(50)] {
                let bits = |t: &str| -> Vec<u64> {
                    angles(t, &model).iter().map(|a| a.to_bits()).collect()
                };
                assert_eq!(bits(text), bits(&formatted), "{text:?}");
            }
        }
    }
    assert_eq!(compared, 4, "+10L25%, 10!, #14 and 1e5 keep their reading");
}

/// Issue 16 item 6: a list of few, long pieces (a megabyte of digits) was read again from
/// the text on every layer, a megabyte a layer. Such a list is read once into a table; a
/// long list of short pieces is still read from the text in turn (its pieces cost less
/// than a table), and both give the same angles and spans.
#[test]
fn long_pieces_are_read_once_short_ones_streamed() {
    let table = |text: &str| matches!(super::list_reading(text), Reading::Table { .. });
    let digits: String = (0..1 << 20)
        .map(|i| char::from(b'0' + (i % 10) as u8))
        .collect();
    assert!(table(&digits));
    assert!(table("0, 90"));
    let long_pieces = format!("{digits}, 7, {digits}");
    assert!(table(&long_pieces));
    let short_pieces = "1,".repeat(100_000);
    assert!(!table(&short_pieces));

    let model = cube(7);
    let streamed = |text: &str| {
        let mut reading = layers(text, &model, Options::default());
        reading.reading = Reading::List {
            text: text.into(),
            next: 0,
        };
        reading
            .map(|l| (l.angle.to_bits(), l.instruction))
            .collect::<Vec<_>>()
    };
    let tabled = |text: &str| {
        layers(text, &model, Options::default())
            .map(|l| (l.angle.to_bits(), l.instruction))
            .collect::<Vec<_>>()
    };
    for text in [
        "0, 90",
        "10,,20, ",
        "1e400, 5",
        &long_pieces,
        &short_pieces[..40],
    ] {
        assert_eq!(
            tabled(text),
            streamed(text),
            "{}",
            &text[..text.len().min(20)]
        );
    }
}

/// Issue 19: the list reading's cycle gives every layer exactly what the stream gives;
/// a list with a piece OrcaSlicer cannot turn into a finite angle has none.
#[test]
fn list_cycles_are_the_stream_bitwise() {
    let models = [cube(57), first_layer(31)];
    for text in ["0, 90", "10,,20, ", "45°, 1e, 0 90", "7"] {
        for model in &models {
            for base in [0.0, 45.0] {
                let options = Options { base, seed: 0 };
                let cycle = layers(text, model, options).plain_cycle().unwrap();
                let mut angles = vec![f64::NAN; model.len()];
                cycle.write(0, &mut angles, None);
                let streamed: Vec<u64> = layers(text, model, options)
                    .map(|l| l.angle.to_bits())
                    .collect();
                let cycled: Vec<u64> = angles.iter().map(|a| a.to_bits()).collect();
                assert_eq!(cycled, streamed, "{text:?}");
            }
        }
    }
    for text in ["1e400, 5", "+30", "0 90 +5"] {
        assert!(
            layers(text, &cube(3), Options::default())
                .plain_cycle()
                .is_none(),
            "{text:?}"
        );
    }
}

/// Issue 19: `fold` (the tight in-range loop) gives every layer, findings included,
/// exactly what `next` gives: ranges, joints, random joints, NaN layers, hangs.
#[test]
// `next`, one layer at a time, spelled out: what `fold` must equal.
#[allow(clippy::while_let_on_iterator)]
fn fold_is_next_bitwise() {
    let texts = [
        "+30/50%",
        "5, 10!, +20, +10L25%, -10l25%",
        "+10L25%, -10l25%, -10L25%, +10l25%",
        "+45#3",
        "0, 15, 30, +45/10#, B!, +30",
        "+30~5, -20^4, +10|3",
        "+1e308/5, -1e308N3",
        "10!, 5*",
        "+5-0.5mm, -3$2cm",
        "+0/0, 7",
    ];
    for text in texts {
        for model in [cube(120), first_layer(77)] {
            let options = Options {
                base: 15.0,
                seed: 3,
            };
            let mut stepped = layers(text, &model, options);
            let mut by_next = Vec::new();
            while let Some(l) = stepped.next() {
                by_next.push((l.index, l.angle.to_bits(), l.instruction));
            }
            let mut folded = layers(text, &model, options);
            let by_fold = folded.fold_rest(Vec::new(), |mut v, l| {
                v.push((l.index, l.angle.to_bits(), l.instruction));
                v
            });
            assert_eq!(by_fold, by_next, "{text}");
            assert_eq!(folded.findings(), stepped.findings(), "{text}");
        }
    }
}
