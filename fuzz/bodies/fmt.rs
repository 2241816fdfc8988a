//! Fuzz target `fmt`: the formatter round trip. When `format` accepts a template, its
//! output is a fixed point, parses without errors, keeps every non-separator character in
//! order (it never drops text), and gives the same angles and fills on every layer of a
//! few models; when it refuses, the template has an error.

use rotlang::eval::{self, Model, Options};
use rotlang::{Target, Template};

fn is_separator(c: char) -> bool {
    matches!(c, ',' | ' ' | '\t' | '\r' | '\n')
}

pub fn run(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    for target in [Target::Sparse, Target::Solid] {
        let parse = rotlang::parse(&text, target);
        let Some(once) = rotlang::format::format(&text, target) else {
            assert!(parse.has_errors(), "fmt refused a template without errors");
            continue;
        };
        assert!(!parse.has_errors(), "fmt formatted a template with errors");
        assert_eq!(
            rotlang::format::format(&once, target).as_deref(),
            Some(once.as_str()),
            "fmt is not idempotent"
        );
        // A leading byte-order mark is not text: the splitter may skip it.
        let kept = |t: &str| {
            t.strip_prefix('\u{feff}')
                .unwrap_or(t)
                .chars()
                .filter(|&c| !is_separator(c))
                .collect::<String>()
        };
        assert_eq!(kept(&text), kept(&once), "fmt changed or dropped text");
        let after = rotlang::parse(&once, target);
        assert!(!after.has_errors(), "fmt introduced an error");
        assert_eq!(
            parse.template.instructions.len(),
            after.template.instructions.len()
        );
        for model in models() {
            same_layers(&text, &parse.template, &once, &after.template, &model);
        }
    }
}

fn models() -> [Model; 2] {
    [
        Model::cube20(),
        Model::from_heights(
            vec![0.3, 0.2, 0.15, 0.15, 0.2, 0.25, 0.1, 0.1, 0.4, 0.2],
            0.2,
        )
        .expect("a valid model")
        .with_shells(2, 3),
    ]
}

fn same_layers(a_text: &str, a: &Template, b_text: &str, b: &Template, model: &Model) {
    let options = Options {
        base: 15.0,
        seed: 7,
    };
    let a_layers = eval::layers(a, model, options);
    let b_layers = eval::layers(b, model, options);
    for (x, y) in a_layers.zip(b_layers) {
        assert_eq!(
            x.angle.to_bits(),
            y.angle.to_bits(),
            "layer {}: angle",
            x.index
        );
        assert_eq!(x.fill, y.fill, "layer {}: fill", x.index);
        assert_eq!(
            x.instruction.map(|s| &a_text[s.range()]),
            y.instruction.map(|s| &b_text[s.range()]),
            "layer {}: governing instruction",
            x.index
        );
    }
}
