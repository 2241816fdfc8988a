//! The corpus: every file in `corpus/{valid,invalid,warn}/*.rot` is checked here, and its
//! rendered `rotlang check` report is compared with the snapshot beside it
//! (`corpus/invalid/foo.rot` → `corpus/invalid/foo.snap`).
//!
//! Update the snapshots after a deliberate change with
//! `INSTA_UPDATE=always cargo test --test corpus` (or `cargo insta test --review`), and
//! read the diff before committing it.
//!
//! A file holds one template; one trailing newline is not part of it. Files named
//! `*.solid.rot` are checked as `solid_infill_rotate_template` (`--target solid`).

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use rotlang::{Diagnostic, Severity, Target};
use rotlang_cli::cli::{Input, render_human};

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    /// Documentation examples and other legal forms: no errors.
    Valid,
    /// Mistakes: at least one error.
    Invalid,
    /// Legal but likely mistakes: warnings, no errors.
    Warn,
}

struct Case {
    /// `invalid/foo.rot`
    name: String,
    path: PathBuf,
    text: String,
    target: Target,
    kind: Kind,
}

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../corpus")
}

fn cases(kind: Kind) -> Vec<Case> {
    let sub = match kind {
        Kind::Valid => "valid",
        Kind::Invalid => "invalid",
        Kind::Warn => "warn",
    };
    let dir = corpus_dir().join(sub);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "rot"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let bytes = std::fs::read(&path).unwrap();
            // The CLI reads files the same way: bytes that are not UTF-8 become U+FFFD.
            let mut text = String::from_utf8_lossy(&bytes).into_owned();
            if text.ends_with('\n') {
                text.pop();
            }
            let file = path.file_name().unwrap().to_str().unwrap().to_owned();
            let target = if file.ends_with(".solid.rot") {
                Target::Solid
            } else {
                Target::Sparse
            };
            Case {
                name: format!("{sub}/{file}"),
                path,
                text,
                target,
                kind,
            }
        })
        .collect()
}

/// Control characters (NUL, BEL…) shown as their Unicode control pictures, so snapshots
/// stay plain text.
fn visible(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            '\n' => c,
            '\u{0}'..='\u{1f}' => char::from_u32(0x2400 + c as u32).unwrap(),
            '\u{7f}' => '\u{2421}',
            _ => c,
        })
        .collect()
}

/// The report `rotlang check --color never` prints for this file, plus the canonical form
/// of templates without errors.
fn report(case: &Case, diagnostics: &[Diagnostic]) -> String {
    let input = Input {
        name: case.name.clone(),
        text: case.text.clone(),
        path: None,
    };
    let mut out = render_human(&[(&input, diagnostics)], false);
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    let warnings = diagnostics.len() - errors;
    out.push_str(&format!("errors: {errors}, warnings: {warnings}\n"));
    if errors == 0 {
        let formatted =
            rotlang::format::format(&case.text, case.target).expect("no errors, so it formats");
        out.push_str(&format!("fmt: {formatted}\n"));
    }
    visible(&out)
}

/// Every label and fix span lies within the text, on char boundaries.
fn check_spans(case: &Case, diagnostics: &[Diagnostic]) -> Result<(), String> {
    let text = &case.text;
    let ok = |s: rotlang::Span| {
        s.start <= s.end
            && s.end <= text.len()
            && text.is_char_boundary(s.start)
            && text.is_char_boundary(s.end)
    };
    for d in diagnostics {
        let spans = d
            .labels
            .iter()
            .map(|l| l.span)
            .chain(d.fix.iter().map(|f| f.span));
        for s in spans {
            if !ok(s) {
                return Err(format!("{}: {} has a bad span {s:?}", case.name, d.code));
            }
        }
    }
    Ok(())
}

/// The checks that do not depend on snapshots.
fn check_case(case: &Case, diagnostics: &[Diagnostic]) -> Result<(), String> {
    check_spans(case, diagnostics)?;
    let errors: Vec<_> = diagnostics.iter().filter(|d| d.is_error()).collect();
    let warnings = diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Warning)
        .count();
    match case.kind {
        Kind::Valid if !errors.is_empty() => Err(format!(
            "{}: a valid template has errors: {:?}",
            case.name,
            codes(&errors)
        )),
        Kind::Warn if !errors.is_empty() || warnings == 0 => Err(format!(
            "{}: expected warnings and no errors, got {} errors ({:?}) and {warnings} warnings",
            case.name,
            errors.len(),
            codes(&errors)
        )),
        Kind::Invalid => {
            let Some(first) = errors.first() else {
                return Err(format!(
                    "{}: an invalid template checks without errors",
                    case.name
                ));
            };
            let span = first.primary_span();
            if span.is_empty() {
                return Err(format!(
                    "{}: the first error ({}) has an empty primary span",
                    case.name, first.code
                ));
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

fn codes(ds: &[&Diagnostic]) -> Vec<&'static str> {
    ds.iter().map(|d| d.code).collect()
}

/// Compares one snapshot; a mismatch is returned (not raised) so that one run reports every
/// file that changed.
fn snapshot(case: &Case, name: &str, content: &str) -> Result<(), String> {
    let dir = case.path.parent().unwrap().to_path_buf();
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(dir);
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.set_input_file(&case.path);
    settings.set_description(format!("rotlang check: {}", case.name));
    catch_unwind(AssertUnwindSafe(|| {
        settings.bind(|| insta::assert_snapshot!(name.to_owned(), content));
    }))
    .map_err(|_| format!("{}: the report differs from {name}.snap", case.name))
}

fn stem(case: &Case) -> String {
    let file = case.path.file_name().unwrap().to_str().unwrap();
    file.strip_suffix(".rot").unwrap().to_owned()
}

#[test]
fn corpus() {
    let mut failures = Vec::new();
    // First error code of every invalid file.
    let mut first_codes: BTreeMap<&'static str, Vec<String>> = BTreeMap::new();
    let mut counts = BTreeMap::new();
    for kind in [Kind::Valid, Kind::Invalid, Kind::Warn] {
        let cases = cases(kind);
        counts.insert(format!("{kind:?}"), cases.len());
        for case in &cases {
            let parse = rotlang::parse(&case.text, case.target);
            if let Err(e) = check_case(case, &parse.diagnostics) {
                failures.push(e);
            }
            if kind == Kind::Invalid
                && let Some(d) = parse.diagnostics.iter().find(|d| d.is_error())
            {
                first_codes.entry(d.code).or_default().push(stem(case));
            }
            if let Err(e) = snapshot(case, &stem(case), &report(case, &parse.diagnostics)) {
                failures.push(e);
            }
        }
    }
    eprintln!("corpus files: {counts:?}");

    // The mistakes must be told apart, not all reported as "unexpected character".
    let index: String = first_codes
        .iter()
        .map(|(code, files)| format!("{code} ({}): {}\n", files.len(), files.join(", ")))
        .collect();
    eprintln!("first error code of each invalid file:\n{index}");
    let invalid_dir = corpus_dir().join("invalid");
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(&invalid_dir);
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.set_description("the first error code of each invalid file");
    if catch_unwind(AssertUnwindSafe(|| {
        settings.bind(|| insta::assert_snapshot!("_first-error-codes", index))
    }))
    .is_err()
    {
        failures.push("the index of first error codes differs from _first-error-codes.snap".into());
    }
    if counts["Invalid"] < 45 {
        failures.push(format!(
            "only {} invalid files; the corpus keeps at least 45 mistakes",
            counts["Invalid"]
        ));
    }
    if first_codes.len() < 20 {
        failures.push(format!(
            "only {} distinct first error codes across invalid files (want ≥ 20)",
            first_codes.len()
        ));
    }
    assert!(
        failures.is_empty(),
        "{} corpus failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
