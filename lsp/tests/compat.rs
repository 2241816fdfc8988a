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

#[test]
fn profiles_get_compat_findings_by_default() {
    let mut lsp = Lsp::start();
    let doc = "{\n  \"layer_height\": \"0.2\",\n  \"sparse_infill_rotate_template\": \"0 90\"\n}\n";
    let diags = lsp.open("file:///tmp/p.json", "json", doc);
    // No direction set: OrcaSlicer's default 45°, which it ignores for a template.
    assert_eq!(
        codes(&diags),
        [
            "orcaslicer::differs",
            "orcaslicer::direction-ignored",
            "orcaslicer::space-separated-list"
        ],
        "{diags:#?}"
    );
    let direction = diags
        .iter()
        .find(|d| d["code"] == "orcaslicer::direction-ignored")
        .unwrap();
    assert_eq!(
        direction["message"],
        "OrcaSlicer ignores sparse_infill_direction = 45° when a template is set; rotlang adds it to every angle"
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
