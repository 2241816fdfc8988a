//! The OrcaSlicer compat lint in diagnostics: on by default for JSON and `.ini` profiles
//! (on their own model), on request (`compat: "orcaslicer"`) for `.rot` files, off with
//! `compat: "off"`; a change of the setting republishes open documents.

mod common;

use common::*;
use serde_json::json;
use std::time::Duration;

fn codes(diags: &[serde_json::Value]) -> Vec<String> {
    let mut c: Vec<String> = diags
        .iter()
        .map(|d| d["code"].as_str().unwrap_or("").to_owned())
        .collect();
    c.sort();
    c
}

/// What `rotlang check` reports for a profile's text with no file behind it: the parse of
/// each template and the library's compat lint on the profile's model, codes sorted.
fn library_codes(name: &str, text: &str) -> Vec<String> {
    let profile =
        rotlang_profile::profile::parse(std::path::Path::new(name), text.as_bytes()).unwrap();
    let mut out = Vec::new();
    for found in &profile.templates {
        let pm = profile.model(
            found.target,
            None,
            rotlang_profile::profile::DEFAULT_OBJECT_HEIGHT,
        );
        let parse = rotlang::parse(&found.text, found.target);
        out.extend(parse.diagnostics.iter().map(|d| d.code.to_owned()));
        out.extend(
            pm.compat(&found.text, found.target)
                .iter()
                .map(|d| d.code.to_owned()),
        );
    }
    out.sort();
    out
}

#[test]
fn profiles_get_compat_findings_by_default() {
    let mut lsp = Lsp::start();
    let doc = "{\n  \"layer_height\": \"0.2\",\n  \"sparse_infill_rotate_template\": \"0 90\"\n}\n";
    let diags = lsp.open("file:///tmp/p.json", "json", doc);
    // No direction set: OrcaSlicer's default 45° is rotlang's base, but a default the
    // profile never chose is nothing to act on (the angles are compared without it).
    assert_eq!(
        codes(&diags),
        ["orcaslicer::differs", "orcaslicer::space-separated-list"],
        "{diags:#?}"
    );
    // A direction the profile sets: the findings are the library's for the profile (what
    // `rotlang check` reports), with the direction applied as the library decides.
    let set = doc.replace(
        "\"0.2\",",
        "\"0.2\",\n  \"sparse_infill_direction\": \"30\",",
    );
    let with_direction = lsp.open("file:///tmp/q.json", "json", &set);
    assert_eq!(
        codes(&with_direction),
        library_codes("q.json", &set),
        "{with_direction:#?}"
    );
    let space = diags
        .iter()
        .find(|d| d["code"] == "orcaslicer::space-separated-list")
        .unwrap();
    assert_eq!(space["range"], range(2, 37, 2, 38));
    assert_eq!(space["severity"], 2);
    // A hang is an error.
    let diags = lsp.open(
        "file:///tmp/h.ini",
        "ini",
        "sparse_infill_rotate_template = 10!, 5*\n",
    );
    let hang = diags
        .iter()
        .find(|d| d["code"] == "orcaslicer::hangs")
        .expect("a hang");
    assert_eq!(hang["severity"], 1);
    // A .rot file: rotlang's own reading only, unless asked.
    let diags = lsp.open("file:///tmp/a.rot", "rotlang", "0 90");
    assert!(diags.is_empty(), "{diags:#?}");
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {"compat": "orcaslicer"}}}),
    );
    let republished = lsp.diagnostics("file:///tmp/a.rot", None);
    assert_eq!(
        codes(&republished),
        ["orcaslicer::differs", "orcaslicer::space-separated-list"]
    );
    lsp.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"rotlang": {"compat": "off"}}}),
    );
    let published = lsp.drain(Duration::from_millis(300));
    let json_now = published
        .iter()
        .rfind(|m| m["params"]["uri"] == "file:///tmp/p.json")
        .expect("p.json republished");
    assert_eq!(json_now["params"]["diagnostics"], json!([]));
}

/// A profile on disk that `inherits` a parent beside it: the server reads the parent's
/// model keys as `rotlang check` does, so the findings are the same in both.
#[test]
fn inherited_settings_are_read_beside_the_file() {
    let dir = std::env::temp_dir().join(format!("rotlang-lsp-inherits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("parent.json"),
        r#"{"name": "parent", "sparse_infill_direction": "30", "layer_height": "0.1", "bottom_shell_layers": "3", "top_shell_layers": "4", "initial_layer_print_height": "0.1"}"#,
    )
    .unwrap();
    let child = dir.join("child.json");
    let text = "{\"inherits\": \"parent\", \"sparse_infill_rotate_template\": \"0, +10/1mm\"}";
    std::fs::write(&child, text).unwrap();
    let mut lsp = Lsp::start();
    let diags = lsp.open(&format!("file://{}", child.display()), "json", text);
    let from_server = codes(&diags);
    // The hover reads the template on the parent's layers too (0.1 mm, 200 of them).
    let at = text.find("0, +10").unwrap() as u32;
    let h = hover_text(&mut lsp, &format!("file://{}", child.display()), 0, at);
    assert!(h.contains("Model: 200 layers × 0.1 mm"), "{h}");
    // What `rotlang check --compat orcaslicer child.json` reports.
    let profile = rotlang_profile::profile::read(&child).unwrap();
    let found = &profile.templates[0];
    let pm = profile.model(
        found.target,
        None,
        rotlang_profile::profile::DEFAULT_OBJECT_HEIGHT,
    );
    assert_eq!(pm.model.layer_height(), 0.1);
    let mut from_cli: Vec<String> = pm
        .compat(&found.text, found.target)
        .iter()
        .map(|d| d.code.to_owned())
        .collect();
    from_cli.sort();
    assert_eq!(from_server, from_cli);
    // The message of the model finding names the same layer (0.1 mm layers, not 0.2).
    let differs = |d: &serde_json::Value| d["code"] == "orcaslicer::differs";
    if let Some(d) = diags.iter().find(|d| differs(d)) {
        let lib = pm.compat(&found.text, found.target);
        let lib = lib
            .iter()
            .find(|d| d.code == "orcaslicer::differs")
            .unwrap();
        assert_eq!(d["message"], lib.message);
    }
    // An unsaved buffer (no file behind it) keeps OrcaSlicer's defaults: no parent.
    let diags = lsp.open("untitled:Untitled-1", "json", text);
    assert_eq!(
        codes(&diags),
        library_codes("untitled.json", text),
        "{diags:#?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// An `.ini` export whose template has an error gets the OrcaSlicer findings `rotlang check`
/// reports for the same file (issue 17), beside the error.
#[test]
fn an_ini_with_errors_gets_the_findings_check_reports() {
    let mut lsp = Lsp::start();
    let text = "layer_height = 0.2\nsparse_infill_rotate_template = 1:4, +30X\n";
    let diags = lsp.open("file:///tmp/errors.ini", "ini", text);
    let from_server = codes(&diags);
    assert!(
        from_server.contains(&"rotlang::unknown-sign".to_owned()),
        "{diags:#?}"
    );
    assert!(
        from_server.iter().any(|c| c.starts_with("orcaslicer::")),
        "OrcaSlicer findings on a template with errors: {diags:#?}"
    );
    assert_eq!(from_server, library_codes("errors.ini", text));
}

/// Every compat finding with a fix has its code action, in `.rot` (when asked for), JSON
/// and `.ini` (issue 17): "separate the angles with commas" turns `0 90` into `0, 90`.
#[test]
fn compat_fixes_are_code_actions() {
    let (mut lsp, _) = Lsp::start_with(json!({}), json!({"rotlang": {"compat": "orcaslicer"}}));
    let cases = [
        ("file:///tmp/fix.rot", "rotlang", "0 90".to_owned(), 0),
        (
            "file:///tmp/fix.json",
            "json",
            "{\n  \"sparse_infill_rotate_template\": \"0 90\"\n}\n".to_owned(),
            1,
        ),
        (
            "file:///tmp/fix.ini",
            "ini",
            "sparse_infill_rotate_template = 0 90\n".to_owned(),
            0,
        ),
    ];
    for (uri, language, text, line) in cases {
        let diags = lsp.open(uri, language, &text);
        let finding = diags
            .iter()
            .find(|d| d["code"] == "orcaslicer::space-separated-list")
            .unwrap_or_else(|| panic!("{uri}: {diags:#?}"));
        let actions = lsp.result(
            "textDocument/codeAction",
            json!({"textDocument": {"uri": uri}, "range": finding["range"],
                   "context": {"diagnostics": [finding]}}),
        );
        let action = actions
            .as_array()
            .unwrap()
            .iter()
            .find(|a| a["diagnostics"][0]["code"] == "orcaslicer::space-separated-list")
            .unwrap_or_else(|| panic!("{uri}: no action for the finding: {actions:#}"));
        assert_eq!(action["kind"], "quickfix");
        assert_eq!(action["title"], "separate the angles with commas");
        let edits = &action["edit"]["changes"][uri];
        // Applied to the line, the edit gives `0, 90`.
        let mut fixed = text.lines().nth(line).unwrap().to_owned();
        for edit in edits.as_array().unwrap().iter().rev() {
            assert_eq!(edit["range"]["start"]["line"], line as u64);
            let (a, b) = (
                edit["range"]["start"]["character"].as_u64().unwrap() as usize,
                edit["range"]["end"]["character"].as_u64().unwrap() as usize,
            );
            fixed.replace_range(a..b, edit["newText"].as_str().unwrap());
        }
        assert!(fixed.contains("0, 90"), "{uri}: {fixed}");
    }
}
