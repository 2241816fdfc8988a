//! The library API as an embedder sees it: parse, inspect the IR, report with miette.

use rotlang::{CountKind, Joint, Severity, Target, Unit};

#[test]
fn parses_into_a_spanned_ir() {
    let text = "+10L25%, -10l25%, B!, #14 +15R";
    let parse = rotlang::parse(text, Target::Sparse);
    assert!(parse.diagnostics.is_empty(), "{:?}", parse.diagnostics);
    let ins = &parse.template.instructions;
    assert_eq!(ins.len(), 5);
    assert_eq!(&text[ins[0].span.range()], "+10L25%");
    assert_eq!(ins[0].degrees(), 10.0);
    assert_eq!(ins[0].shape(), Joint::QuarterCircleHV);
    assert_eq!(
        ins[0].count.map(|c| c.kind),
        Some(CountKind::Length {
            value: 25.0,
            unit: Unit::PercentOfHeight
        })
    );
    assert_eq!(ins[1].degrees(), -10.0);
    assert_eq!(ins[2].count.map(|c| c.kind), Some(CountKind::Bottom));
    assert!(ins[2].is_one_time() && ins[2].is_relative());
    assert_eq!(ins[3].shape(), Joint::Step);
    assert_eq!(ins[4].fill(), rotlang::Fill::Rectilinear);
}

#[test]
fn one_bad_instruction_does_not_hide_another() {
    let text = "+30X5, 10, +45/10*2, 1:0";
    let parse = rotlang::parse(text, Target::Sparse);
    let codes: Vec<_> = parse.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(
        codes,
        [
            "rotlang::unknown-sign",
            "rotlang::repeat-after-joint",
            "rotlang::zero-denominator"
        ]
    );
    // The good instruction is still in the IR.
    assert_eq!(parse.template.instructions.len(), 1);
    assert_eq!(parse.template.instructions[0].degrees(), 10.0);
}

#[test]
fn spans_are_bytes_with_non_ascii_text() {
    let text = "α°, 𝕏, +30°";
    let parse = rotlang::parse(text, Target::Sparse);
    let spans: Vec<&str> = parse
        .diagnostics
        .iter()
        .map(|d| &text[d.primary_span().range()])
        .collect();
    assert_eq!(spans, ["α", "𝕏", "°"]);
}

#[test]
fn solid_signs_are_errors_in_a_solid_template() {
    let sparse = rotlang::parse("#14, +15R", Target::Sparse);
    assert!(!sparse.has_errors());
    let solid = rotlang::parse("#14, +15R", Target::Solid);
    let d = &solid.diagnostics[0];
    assert_eq!(
        (d.code, d.severity),
        ("rotlang::solid-sign-in-solid-template", Severity::Error)
    );
    assert_eq!(d.primary_span(), rotlang::Span::new(8, 9));
}

#[test]
fn diagnostics_implement_miette() {
    let text = "+30/5cn";
    let parse = rotlang::parse(text, Target::Sparse);
    let d: &dyn miette::Diagnostic = &parse.diagnostics[0];
    assert_eq!(
        d.code().map(|c| c.to_string()).as_deref(),
        Some("rotlang::unknown-unit")
    );
    assert_eq!(d.severity(), Some(miette::Severity::Error));
    let labels: Vec<_> = d.labels().into_iter().flatten().collect();
    assert_eq!(labels.len(), 1);
    assert_eq!((labels[0].offset(), labels[0].len()), (5, 2));
    assert!(labels[0].label().unwrap().contains("`cm`"));
    // A miette handler renders it against the source.
    let report =
        miette::Report::new(parse.diagnostics[0].clone()).with_source_code(text.to_owned());
    let mut out = String::new();
    miette::NarratableReportHandler::new()
        .render_report(&mut out, report.as_ref())
        .unwrap();
    assert!(out.contains("unknown length unit `cn`"), "{out}");
    assert!(out.contains("cn"), "{out}");
}

#[test]
fn empty_template_is_zero_instructions() {
    for text in ["", "  ", "\n,\n"] {
        let parse = rotlang::parse(text, Target::Sparse);
        assert!(!parse.has_errors());
        assert!(parse.template.instructions.is_empty());
    }
}
