//! Reading each kind of file from bytes; the fixtures and hostile files are in
//! `tests/profiles.rs`.

use super::*;

fn p(name: &str, bytes: &[u8]) -> Profile {
    parse(Path::new(name), bytes).unwrap_or_else(|e| panic!("{e}"))
}

/// The source text under a template span mapped into the file.
fn in_file<'a>(profile: &'a Profile, found: &Found, span: Span) -> &'a str {
    &profile.sources[found.source].text[found.span_in_source(span).range()]
}

#[test]
fn kinds_by_content_and_extension() {
    let k = |name: &str, bytes: &[u8]| Kind::detect(Path::new(name), bytes);
    assert_eq!(k("a.json", b"{}"), Kind::Json);
    assert_eq!(k("a", b"  {\"x\": 1}"), Kind::Json);
    assert_eq!(k("a.rot", b"0, 90"), Kind::Template);
    assert_eq!(k("a", b"0, 90"), Kind::Template);
    assert_eq!(
        k(
            "a",
            b"layer_height = 0.2\nsparse_infill_rotate_template = 0"
        ),
        Kind::Ini
    );
    assert_eq!(k("a.json", b"PK\x03\x04...."), Kind::ThreeMf);
    assert_eq!(k("x.INI", b""), Kind::Ini);
}

#[test]
fn json_templates_with_escapes_and_settings() {
    let doc = "\u{feff}{\"layer_height\": \"0.12\", \"top_shell_layers\": 6,\r\n \"sparse_infill_rotate_template\": \"+30\\u00b0, 0\", \"bottom_shell_layers\": [\"2\", \"9\"]}";
    let profile = p("a.json", doc.as_bytes());
    assert!(profile.notes.is_empty(), "{:?}", profile.notes);
    let t = &profile.templates[0];
    assert_eq!(t.text, "+30°, 0");
    let deg = t.text.find('°').unwrap();
    assert_eq!(in_file(&profile, t, Span::new(deg, deg + 2)), "\\u00b0");
    let m = profile.model(Target::Sparse, None, 12.0);
    assert_eq!(m.model.layer_height(), 0.12);
    assert_eq!(m.model.top_shells(), 6);
    assert_eq!(m.model.bottom_shells(), 2);
    assert_eq!(m.direction.degrees, 45.0);
    assert!(
        m.notes
            .iter()
            .any(|n| n.contains("initial_layer_print_height")),
        "{:?}",
        m.notes
    );
    assert!(
        m.direction
            .note
            .as_deref()
            .is_some_and(|n| n.contains("sparse_infill_direction"))
    );
}

#[test]
fn jsonc_comments_and_trailing_commas() {
    let doc = "// c \"sparse_infill_rotate_template\": \"no\"\n{ /* \"x\" */ \"sparse_infill_rotate_template\": \"0\", }";
    let profile = p("a.jsonc", doc.as_bytes());
    assert!(profile.notes.is_empty(), "{:?}", profile.notes);
    assert_eq!(profile.templates.len(), 1);
    assert_eq!(profile.templates[0].text, "0");
    assert_eq!(json::strip_jsonc("[1,\n]"), "[1 \n]");
}

#[test]
fn wrong_types_are_notes() {
    let doc = r#"{"sparse_infill_rotate_template": 5, "layer_height": true, "solid_infill_rotate_template": "0"}"#;
    let profile = p("a.json", doc.as_bytes());
    assert_eq!(profile.templates.len(), 1);
    let errors: Vec<_> = profile.notes.iter().filter(|n| n.error).collect();
    assert_eq!(errors.len(), 1, "{:?}", profile.notes);
    assert!(errors[0].message.contains("should be a template"));
    assert_eq!(&doc[errors[0].span.range()], "5");
    assert!(
        profile
            .notes
            .iter()
            .any(|n| !n.error && n.message.contains("layer_height"))
    );
    let invalid = p("b.json", br#"{"sparse_infill_rotate_template": "0" "#);
    assert!(invalid.has_errors());
    assert_eq!(invalid.templates.len(), 1);
}

#[test]
fn bad_setting_values_fall_back_with_notes() {
    let doc = r#"{"layer_height": "abc", "bottom_shell_layers": "-2", "initial_layer_print_height": "0"}"#;
    let m = p("a.json", doc.as_bytes()).model(Target::Sparse, None, 20.0);
    assert_eq!(m.model.layer_height(), 0.2);
    assert_eq!(m.model.bottom_shells(), 3);
    assert!(
        m.notes
            .iter()
            .any(|n| n.contains("`layer_height` = `abc` is not a number")),
        "{:?}",
        m.notes
    );
    assert!(
        m.notes.iter().any(|n| n.contains("no model")),
        "{:?}",
        m.notes
    );
}

#[test]
fn ini_lines_with_crlf_and_bom() {
    let doc =
        "\u{feff}; comment\r\nlayer_height = 0.3\r\nsparse_infill_rotate_template =  +5, +5*  \r\n";
    let profile = p("a.ini", doc.as_bytes());
    let t = &profile.templates[0];
    assert_eq!(t.text, "+5, +5*");
    assert_eq!(in_file(&profile, t, Span::new(4, 7)), "+5*");
    assert_eq!(
        profile
            .model(Target::Sparse, None, 20.0)
            .model
            .layer_height(),
        0.3
    );
}

#[test]
fn rot_files_and_non_utf8() {
    let profile = p("a.rot", "\u{feff}0,\n90\n".as_bytes());
    assert_eq!(profile.templates[0].text, "0,\n90\n");
    assert_eq!(
        in_file(&profile, &profile.templates[0], Span::new(3, 5)),
        "90"
    );
    let err = parse(Path::new("a.json"), b"{\"a\": \"\xff\"}").unwrap_err();
    assert!(
        err.message.contains("not UTF-8") && err.message.contains("offset 7"),
        "{err}"
    );
}

#[cfg(feature = "3mf")]
#[test]
fn xml_attribute_values_map_through_entities() {
    let (text, map) = threemf::unescape_xml("a&amp;b&#x2B;c&bogus;", 10);
    assert_eq!(text, "a&b+c&bogus;");
    assert_eq!(map.span_to_doc(Span::new(3, 4)), Span::new(17, 23));
    assert_eq!(map.to_doc(4), 23);
}
