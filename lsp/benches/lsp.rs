//! Diagnostics and hover for a 10 KB OrcaSlicer profile (target: under 10 ms together).
//!
//! Run with `cargo bench -p rotlang-lsp`. Each benchmark starts from the document text,
//! as the server does on every change (full sync): scan, unescape, parse, convert.

use std::str::FromStr;

use rotlang_lsp::document::{Document, Kind};
use rotlang_lsp::position::{Encoding, Positions};
use rotlang_lsp::settings::ModelSettings;
use rotlang_lsp::{diagnostics, hover};
use tower_lsp_server::ls_types::Uri;

fn main() {
    divan::main();
}

/// A process preset of about 10 KB: many ordinary settings, the two templates (one with
/// an escaped degree sign and a mistake, so diagnostics have work to do).
fn profile() -> String {
    let mut fields = vec![
        r#"  "type": "process""#.to_string(),
        r#"  "name": "0.20mm Standard @rotlang \u00b0""#.to_string(),
        r#"  "sparse_infill_rotate_template": "+10L25%, -10l25%, -10L25%, +10l25%, B!, +30/5mm, 45\u00b0""#.to_string(),
        r#"  "solid_infill_rotate_template": "0, 90, +15#10, 30X""#.to_string(),
    ];
    let mut i = 0;
    while fields.iter().map(|f| f.len() + 2).sum::<usize>() < 10_000 {
        fields.push(format!(r#"  "setting_number_{i}": ["0.2", "0.4", "{i}"]"#));
        fields.push(format!(
            r#"  "description_{i}": "a \"quoted\" value with \\ escapes""#
        ));
        i += 1;
    }
    format!("{{\n{}\n}}\n", fields.join(",\n"))
}

#[divan::bench]
fn diagnostics_10kb(bencher: divan::Bencher) {
    let text = profile();
    assert!((10_000..11_000).contains(&text.len()), "{}", text.len());
    let uri = Uri::from_str("file:///tmp/profile.json").expect("uri");
    bencher.bench(|| {
        let doc = Document::new(divan::black_box(text.clone()), Kind::Json, 1, None);
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        let diags = diagnostics::diagnostics(&doc, &uri, &pos);
        assert_eq!(diags.len(), 2);
        diags
    });
}

#[divan::bench]
fn hover_instruction_10kb(bencher: divan::Bencher) {
    let text = profile();
    let at = text.find("-10l25%").expect("instruction") + 2;
    let model = ModelSettings::default();
    bencher.bench(|| {
        let doc = Document::new(divan::black_box(text.clone()), Kind::Json, 1, None);
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        hover::hover(&doc, at, &model, &pos).expect("a hover")
    });
}

#[divan::bench]
fn hover_template_10kb(bencher: divan::Bencher) {
    let text = profile();
    let at = text.find(", B!").expect("separator") + 1;
    let model = ModelSettings::default();
    bencher.bench(|| {
        let doc = Document::new(divan::black_box(text.clone()), Kind::Json, 1, None);
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        hover::hover(&doc, at, &model, &pos).expect("a hover")
    });
}

/// Both, as one keystroke costs: the change (diagnostics) and the hover that follows.
#[divan::bench]
fn diagnostics_and_hover_10kb(bencher: divan::Bencher) {
    let text = profile();
    let at = text.find("-10l25%").expect("instruction") + 2;
    let uri = Uri::from_str("file:///tmp/profile.json").expect("uri");
    let model = ModelSettings::default();
    bencher.bench(|| {
        let doc = Document::new(divan::black_box(text.clone()), Kind::Json, 1, None);
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        let diags = diagnostics::diagnostics(&doc, &uri, &pos);
        let hover = hover::hover(&doc, at, &model, &pos);
        (diags, hover)
    });
}

/// What a hover after the last edit of a storm waits for on a 3 MB `.rot` document: the
/// analysis of the latest text (parse, and the preview hovers read), then the hover
/// itself. Issue 22's target: 100 ms; `cargo bench -p rotlang-lsp -- storm`.
#[divan::bench(sample_count = 5)]
fn storm_analysis_and_hover_3mb(bencher: divan::Bencher) {
    let text = "+10L25%, -10l25%, 0, 90, ".repeat((3 << 20) / 25) + "+7";
    let at = text.len() - 1;
    let model = ModelSettings::default();
    bencher.bench(|| {
        let doc = Document::new(divan::black_box(text.clone()), Kind::Rot, 1, None);
        let _ = doc.preview(0, &model);
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        hover::hover(&doc, at, &model, &pos).expect("a hover")
    });
}

/// The hover alone on an analysed 3 MB document (its preview ready).
#[divan::bench(sample_count = 20)]
fn hover_on_an_analysed_3mb(bencher: divan::Bencher) {
    let text = "+10L25%, -10l25%, 0, 90, ".repeat((3 << 20) / 25) + "+7";
    let at = text.len() - 1;
    let model = ModelSettings::default();
    let doc = Document::new(text, Kind::Rot, 1, None);
    let _ = doc.preview(0, &model);
    bencher.bench(|| {
        let pos = Positions::new(&doc.text, Encoding::Utf16);
        hover::hover(&doc, at, &model, &pos).expect("a hover")
    });
}

/// Issue 22: the hover after the last edit of a storm, as the server answers it. The
/// server analyses the latest text from the analysis of an earlier one (coalescing the
/// edits between), so what the hover waits for is that analysis (`Document::update`: the
/// templates re-read where the edits touched them), the preview hovers read, and the hover
/// itself, on the edited instruction in the middle of the document. The target: 100 ms on
/// any document under the 4 MiB limit. `cargo bench -p rotlang-lsp -- after_storm`.
#[divan::bench(args = [256 << 10, 1 << 20, 3 << 20, (4 << 20) - 4096], sample_count = 5)]
fn hover_after_storm(bencher: divan::Bencher, len: usize) {
    let base = "+10L25%, -10l25%, 0, 90, ".repeat(len / 25);
    let middle = base.len() / 2 / 25 * 25;
    // Versions 1..=500 type `+N, ` in the middle; the analysis in hand is of version 499.
    let version = |v: usize| format!("{}+{v}, {}", &base[..middle], &base[middle..]);
    let (before, after) = (version(499), version(500));
    assert!(after.len() <= 4 << 20);
    let at = middle + 2;
    let model = ModelSettings::default();
    bencher
        .with_inputs(|| {
            let doc = Document::new(before.clone(), Kind::Rot, 499, None);
            (doc, after.clone())
        })
        .bench_values(|(previous, text)| {
            let doc = Document::update(previous, text, Kind::Rot, 500, None);
            let _ = doc.preview(0, &model);
            let pos = Positions::new(&doc.text, Encoding::Utf16);
            let h = hover::hover(&doc, at, &model, &pos).expect("a hover");
            let tower_lsp_server::ls_types::HoverContents::Markup(m) = &h.contents else {
                panic!("markdown")
            };
            assert!(m.value.starts_with("`+500`"), "{}", m.value);
            (doc, h)
        });
}
