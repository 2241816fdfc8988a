//! An error past the 100-diagnostic cap is never lost (issue 7): the three reproducers at
//! every entry point of the library and the CLI (`check`, `check --format json`, `expand`,
//! `fmt`, `fmt --write`, `fmt --check`). The language server's side is in
//! `lsp/tests/reliability.rs`.

use std::path::PathBuf;
use std::process::{Command, Stdio};

use rotlang::{Severity, Target};

/// 100 warnings, then one error: the shapes that used to lose the error.
fn reproducers() -> [(&'static str, String, Target, &'static str); 3] {
    [
        (
            "unknown_sign",
            format!("{}X", "0,,".repeat(100)),
            Target::Sparse,
            "rotlang::unknown-sign",
        ),
        (
            "solid_sign",
            format!("{}S", "0,,".repeat(100)),
            Target::Solid,
            "rotlang::solid-sign-in-solid-template",
        ),
        (
            "dummy_and_repeat",
            format!("{}+5*2*", "0/5 ".repeat(100)),
            Target::Sparse,
            "rotlang::dummy-and-repeat",
        ),
    ]
}

fn target_arg(t: Target) -> &'static str {
    match t {
        Target::Sparse => "sparse",
        Target::Solid => "solid",
    }
}

#[test]
fn library_keeps_the_error() {
    for (name, text, target, code) in reproducers() {
        let parse = rotlang::parse(&text, target);
        assert!(parse.has_errors(), "{name}");
        assert_eq!(parse.errors, 1, "{name}");
        assert_eq!(parse.warnings, 100, "{name}");
        assert_eq!(parse.omitted, 1, "{name}");
        // The error is listed (it replaced the last warning); the note at the end counts
        // the warning it replaced.
        let errors: Vec<_> = parse.diagnostics.iter().filter(|d| d.is_error()).collect();
        assert_eq!(errors.len(), 1, "{name}: {errors:?}");
        assert_eq!(errors[0].code, code, "{name}");
        let last = parse.diagnostics.last().unwrap();
        assert_eq!(last.code, "rotlang::too-many-diagnostics");
        assert_eq!(
            last.severity,
            Severity::Warning,
            "{name}: only a warning was cut"
        );
        assert_eq!(last.message, "1 more warning not shown");
        assert_eq!(parse.diagnostics.len(), 101);
        assert_eq!(rotlang::format::format(&text, target), None, "{name}");
    }
}

#[test]
fn many_errors_keep_the_first_and_count_all() {
    // 150 warnings, then 150 errors: the list holds errors only, the first of them first.
    // No trailing comma: it would be one more warning.
    let text = format!("{}{}X1", "400, ".repeat(150), "X1, ".repeat(149));
    let parse = rotlang::parse(&text, Target::Sparse);
    assert_eq!((parse.errors, parse.warnings), (150, 150));
    assert_eq!(parse.omitted, 200);
    let first_error = text.find('X').unwrap();
    assert!(parse.diagnostics[..100].iter().all(|d| d.is_error()));
    assert_eq!(parse.diagnostics[0].primary_span().start, first_error);
    let note = &parse.diagnostics[100];
    assert_eq!(note.code, "rotlang::too-many-diagnostics");
    assert!(note.is_error());
    assert_eq!(
        note.message,
        "50 more errors and 150 more warnings not shown"
    );

    // A target error on the first instruction is kept although 200 grammar errors follow.
    let text = format!("S, {}", "X, ".repeat(200));
    let parse = rotlang::parse(&text, Target::Solid);
    assert_eq!(parse.errors, 201);
    assert_eq!(
        parse.diagnostics[0].code,
        "rotlang::solid-sign-in-solid-template"
    );
}

// ── the CLI ─────────────────────────────────────────────────────────────────────────────

fn run(args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_rotlang"))
        .args(args)
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .output()
        .expect("the rotlang binary runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().expect("exits, not killed"),
    )
}

/// The lines of a report worth a snapshot: the error headers and the summary (100 warning
/// reports in full would bury them).
fn gist(report: &str) -> String {
    report
        .lines()
        .filter(|l| {
            l.starts_with("error")
                || l.starts_with("warning[rotlang::too-many")
                || l.starts_with("ok:")
                || l.starts_with("failed:")
                || l.contains("not formatted")
        })
        .map(|l| format!("{l}\n"))
        .collect()
}

struct TempFile(PathBuf);

impl TempFile {
    fn new(tag: &str, text: &str) -> TempFile {
        let path = std::env::temp_dir().join(format!(
            "rotlang-cap-{tag}-{}-{:?}.rot",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::write(&path, text).unwrap();
        TempFile(path)
    }

    fn path(&self) -> &str {
        self.0.to_str().unwrap()
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

#[test]
fn cli_refuses_at_every_entry_point() {
    for (name, text, target, code) in reproducers() {
        let t = target_arg(target);
        let mut golden = String::new();

        let (out, _, exit) = run(&["check", "--target", t, "--", &text]);
        assert_eq!(exit, 1, "check {name}");
        golden.push_str(&format!("$ rotlang check\nexit: {exit}\n{}", gist(&out)));

        let (out, _, exit) = run(&["check", "--format", "json", "--target", t, "--", &text]);
        assert_eq!(exit, 1, "check --format json {name}");
        let json: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
        assert_eq!(json["errors"], 1);
        assert_eq!(json["warnings"], 100);
        assert_eq!(json["omitted"], 1);
        let codes: Vec<&str> = json["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|d| d["severity"] == "error")
            .map(|d| d["code"].as_str().unwrap())
            .collect();
        assert_eq!(codes, [code], "check --format json {name}");

        let (out, err, exit) = run(&["expand", "--target", t, "--", &text]);
        assert_eq!(exit, 1, "expand {name}");
        assert_eq!(out, "", "expand {name} printed layers");
        golden.push_str(&format!("$ rotlang expand\nexit: {exit}\n{}", gist(&err)));

        let (out, err, exit) = run(&["fmt", "--target", t, "--", &text]);
        assert_eq!(exit, 1, "fmt {name}");
        assert_eq!(out, "", "fmt {name} printed a formatted template");
        golden.push_str(&format!("$ rotlang fmt\nexit: {exit}\n{}", gist(&err)));

        let file = TempFile::new(name, &format!("{text}\n"));
        let (_, _, exit) = run(&["fmt", "--target", t, "--write", "--file", file.path()]);
        assert_eq!(exit, 1, "fmt --write {name}");
        assert_eq!(
            std::fs::read_to_string(&file.0).unwrap(),
            format!("{text}\n"),
            "fmt --write changed {name}"
        );
        let (_, _, exit) = run(&["fmt", "--target", t, "--check", "--file", file.path()]);
        assert_eq!(exit, 1, "fmt --check {name}");

        insta::assert_snapshot!(format!("cap_{name}"), golden);
    }
}

#[test]
fn summary_counts_errors_and_warnings_exactly() {
    // No trailing comma: it would be one more warning.
    let text = format!("{}{}X1", "400, ".repeat(150), "X1, ".repeat(149));
    let (out, _, exit) = run(&["check", "--", &text]);
    assert_eq!(exit, 1);
    assert!(
        out.ends_with("failed: 1 template, 150 errors, 150 warnings (200 not shown)\n"),
        "{}",
        &out[out.len().saturating_sub(200)..]
    );
}
