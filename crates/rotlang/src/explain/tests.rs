use super::*;
use crate::eval::Model;
use std::collections::BTreeSet;
use std::path::Path;

/// Every `"prefix::code"` string literal in the library's sources (this file and the
/// table of codes aside).
fn emitted_codes() -> BTreeSet<String> {
    fn walk(dir: &Path, found: &mut BTreeSet<String>) {
        for entry in std::fs::read_dir(dir).expect("src is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                if !path.ends_with("explain") {
                    walk(&path, found);
                }
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let text = std::fs::read_to_string(&path).expect("a source file");
            for prefix in [
                "\"rotlang::",
                "\"orcaslicer::",
                "\"rotlang-lsp::",
                "\"profile::",
                "\"slicer::",
            ] {
                for (at, _) in text.match_indices(prefix) {
                    let rest = &text[at + 1..];
                    let end = rest
                        .find(|c: char| !(c.is_ascii_lowercase() || c == '-' || c == ':'))
                        .unwrap_or(rest.len());
                    let code = &rest[..end];
                    if rest[end..].starts_with('"') && !code.ends_with("::") {
                        found.insert(code.to_owned());
                    }
                }
            }
        }
    }
    let mut found = BTreeSet::new();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    // Every crate's sources (the CLI, profile and geometry crates emit codes too).
    for krate in std::fs::read_dir(root.join("crates")).expect("crates/ is readable") {
        walk(&krate.expect("a crate").path().join("src"), &mut found);
    }
    // The language server's own codes (`rotlang-lsp::`) are explained here too.
    walk(&root.join("lsp/src"), &mut found);
    found
}

#[test]
fn every_emitted_code_is_documented_and_no_other() {
    let emitted = emitted_codes();
    assert!(emitted.len() > 30, "the scan found the codes: {emitted:?}");
    let documented: BTreeSet<String> = codes().iter().map(|d| d.code.to_owned()).collect();
    let missing: Vec<_> = emitted.difference(&documented).collect();
    assert!(
        missing.is_empty(),
        "emitted but not documented: {missing:?}"
    );
    let stale: Vec<_> = documented.difference(&emitted).collect();
    assert!(stale.is_empty(), "documented but never emitted: {stale:?}");
    let list: Vec<&str> = codes().iter().map(|d| d.code).collect();
    let mut sorted = list.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(list, sorted, "the table is sorted, one entry per code");
}

#[test]
fn every_example_reports_its_code() {
    for doc in codes() {
        assert!(
            !doc.summary.is_empty() && !doc.explanation.is_empty() && !doc.fix.is_empty(),
            "{}",
            doc.code
        );
        let Some(_) = doc.code.strip_prefix("rotlang::") else {
            continue;
        };
        // A safety net that no known template reaches.
        if doc.code == "rotlang::invalid-instruction" {
            continue;
        }
        let (text, target) = match doc.code {
            // The cap needs more than 100 diagnostics.
            "rotlang::too-many-diagnostics" => ("x ".repeat(101), Target::Sparse),
            "rotlang::solid-sign-in-solid-template" => (doc.example.to_owned(), Target::Solid),
            _ => (doc.example.to_owned(), Target::Sparse),
        };
        let parse = crate::parse(&text, target);
        let found = parse.diagnostics.iter().find(|d| d.code == doc.code);
        let found = found.unwrap_or_else(|| {
            panic!(
                "example {:?} of {} reports {:?}",
                doc.example,
                doc.code,
                parse.diagnostics.iter().map(|d| d.code).collect::<Vec<_>>()
            )
        });
        assert_eq!(found.severity.as_str(), doc.severity, "{}", doc.code);
    }
}

#[test]
fn codes_are_found_with_or_without_prefix() {
    assert_eq!(
        code("unknown-sign").map(|d| d.code),
        Some("rotlang::unknown-sign")
    );
    assert_eq!(
        code(" rotlang::zero-count ").map(|d| d.code),
        Some("rotlang::zero-count")
    );
    assert!(code("rotlang::no-such-code").is_none());
    assert!(code("").is_none());
}

#[test]
fn template_lists_each_instruction_with_its_layers() {
    let text = template("+10L25%, -10l25%", Target::Sparse, &Model::cube20());
    assert!(text.starts_with("`+10L25%, -10l25%` (sparse infill) on 100 layers × 0.2 mm (20 mm tall), shells B = 3, T = 4:"), "{text}");
    assert!(
        text.contains("1. `+10L25%` turns +10° along a quarter circle"),
        "{text}"
    );
    assert!(text.contains("First acts on layers 0–24: 0°→10° over 25 layers. Governs 50 of the 100 layers: 0–24, 50–74."), "{text}");
    assert!(text.contains("2. `-10l25%`"), "{text}");
    assert!(
        text.contains("First acts on layers 25–49: 10°→0° over 25 layers."),
        "{text}"
    );
    assert!(text.contains("Angles from 0° to 10°"), "{text}");
}

#[test]
fn shell_counts_are_counts_not_places() {
    let text = template("+5/50%, B!, +30", Target::Sparse, &Model::cube20());
    // `B!` acts on the three layers where it is reached, not on the bottom shells.
    assert!(
        text.contains("over the next 3 layers (B = 3, the bottom shell layer count)"),
        "{text}"
    );
    assert!(text.contains("layers 50–52"), "{text}");
}

#[test]
fn steps_read_as_steps() {
    let text = template("+15#10", Target::Sparse, &Model::cube20());
    assert!(
        text.contains("all of it on the range's first layer"),
        "{text}"
    );
    assert!(
        text.contains("First acts on layers 0–9: 15° for 10 layers (a step from 0°)."),
        "{text}"
    );
}

#[test]
fn holds_dummies_errors_and_empty() {
    let text = template("30*, +10!", Target::Sparse, &Model::cube20());
    assert!(
        text.contains("Takes no range of its own. Holds 99 of the 100 layers"),
        "{text}"
    );
    assert!(
        text.contains("First acts on layer 0: 40° for 1 layer."),
        "{text}"
    );
    let text = template("+10!", Target::Sparse, &Model::cube20());
    assert!(
        text.contains("From layer 1 on, every instruction is spent: the angle holds at 10°"),
        "{text}"
    );
    let text = template("", Target::Sparse, &Model::cube20());
    assert!(
        text.starts_with("The empty template (sparse infill)"),
        "{text}"
    );
    assert!(text.contains("The template is empty"), "{text}");
    let text = template("+30X5, 90", Target::Sparse, &Model::cube20());
    assert!(text.contains("the template has 1 error"), "{text}");
    assert!(text.contains("1. `90` sets the direction to 90°"), "{text}");
    let text = template("0, 270", Target::Sparse, &Model::cube20());
    assert!(
        text.contains("infill lines (wrapped to [0°, 180°)) from 0° to 90°"),
        "{text}"
    );
}

#[test]
fn numbers_read_well() {
    assert_eq!(num(22.5), "22.5");
    assert_eq!(num(0.451), "0.45");
    assert_eq!(num(-0.001), "0");
    assert_eq!(num(90.0), "90");
    assert_eq!(turn_deg(22.5), "+22.5°");
    assert_eq!(turn_deg(-10.0), "-10°");
    assert_eq!(deg_and_lines(270.0), "270° (90°)");
    assert_eq!(deg_and_lines(-90.0), "-90° (90°)");
    assert_eq!(deg_and_lines(45.0), "45°");
    assert_eq!(deg_and_lines(179.999), "180° (0°)");
}
