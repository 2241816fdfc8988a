//! The glue on arbitrary input, natively (the same code the wasm runs): no panic, the
//! answer is JSON, UTF-16 offsets name the same text as the byte offsets, and expand's
//! arrays have one entry per layer with indices in range.

use proptest::prelude::*;
use rotlang_wasm::api::{self, Layers};
use rotlang_wasm::json::Value;
use rotlang_wasm::options::{Request, slot};

/// Characters the language uses, and some it does not (multi-byte and astral among them).
fn text() -> impl Strategy<Value = String> {
    proptest::collection::vec(
        prop_oneof![
            Just("+"),
            Just("-"),
            Just("30"),
            Just("5"),
            Just(".5"),
            Just(","),
            Just(" "),
            Just("%"),
            Just("mm"),
            Just("#"),
            Just("/"),
            Just("L"),
            Just("l"),
            Just("~"),
            Just("!"),
            Just("*"),
            Just("S"),
            Just("B"),
            Just("T"),
            Just("X"),
            Just("°"),
            Just("α"),
            Just("𝕏"),
            Just("\n"),
            Just(":"),
            Just("\""),
        ],
        0..40,
    )
    .prop_map(|parts| parts.concat())
}

fn utf16_offset(text: &str, byte: usize) -> usize {
    text[..byte].encode_utf16().count()
}

fn num(v: &Value) -> usize {
    match v {
        Value::Num(x) => *x as usize,
        other => panic!("not a number: {other:?}"),
    }
}

fn field<'a>(v: &'a Value, name: &str) -> &'a Value {
    match v {
        Value::Object(fields) => &fields.iter().find(|(k, _)| *k == name).expect(name).1,
        other => panic!("not an object: {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn check_spans_agree(text in text()) {
        let mut spans = vec![7; 3]; // stale content is replaced
        let answer = api::check(&text, &Request::default(), &mut spans).expect("check never fails");
        let parse = rotlang::parse(&text, rotlang::Target::Sparse);
        prop_assert_eq!(spans.len(), 4 * parse.template.instructions.len());
        for (quad, i) in spans.chunks(4).zip(&parse.template.instructions) {
            let (start, end) = (i.span.start, i.span.end);
            let want = [start, end, utf16_offset(&text, start), utf16_offset(&text, end)];
            prop_assert_eq!(quad.iter().map(|&n| n as usize).collect::<Vec<_>>(), want.to_vec());
        }
        let Value::Array(diagnostics) = field(&answer, "diagnostics") else { panic!() };
        for d in diagnostics {
            let (start, end) = (num(field(d, "start")), num(field(d, "end")));
            prop_assert!(start <= end && end <= text.len());
            prop_assert!(text.is_char_boundary(start) && text.is_char_boundary(end));
            prop_assert_eq!(num(field(d, "startUtf16")), utf16_offset(&text, start));
            prop_assert_eq!(num(field(d, "endUtf16")), utf16_offset(&text, end));
        }
        let mut json = String::new();
        answer.write(&mut json);
        let object = json.starts_with('{') && json.ends_with('}');
        prop_assert!(object, "not an object: {}", json);
    }

    #[test]
    fn expand_fills_every_layer(text in text(), layers in 1usize..300, orca in any::<bool>()) {
        let req = Request::default()
            .with(slot::LAYERS, layers as f64)
            .with(slot::DIALECT, if orca { 1.0 } else { 0.0 });
        let mut out = Layers::default();
        match api::expand(&text, &req, None, &mut out) {
            Ok(answer) => {
                prop_assert_eq!(out.angles.len(), layers);
                prop_assert_eq!(out.fills.len(), layers);
                prop_assert!(out.angles.iter().all(|a| a.is_finite()));
                let Value::Array(spans) = field(&answer, "instructions") else { panic!() };
                prop_assert!(out.instructions.iter().all(|&i| i >= -1 && (i as i64) < spans.len() as i64));
            }
            // Only rotlang's reading refuses a template, and only one with errors.
            Err(f) => prop_assert!(!orca && f.kind == "template", "{}: {}", f.kind, f.message),
        }
    }
}
