//! Over the wire: an error past the 100-diagnostic cap is published and blocks formatting
//! (issue 7).

mod common;

use common::Lsp;
use serde_json::{Value, json};

const ROT: &str = "file:///tmp/reliability.rot";
const JSON: &str = "file:///tmp/reliability.json";

fn format(lsp: &mut Lsp, uri: &str) -> Value {
    lsp.result(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true}}),
    )
}

fn errors(diagnostics: &[Value]) -> Vec<String> {
    diagnostics
        .iter()
        .filter(|d| d["severity"] == 1)
        .map(|d| d["code"].as_str().unwrap_or("").to_owned())
        .collect()
}

#[test]
fn an_error_past_the_cap_is_published_and_blocks_formatting() {
    let mut lsp = Lsp::start();
    let cases = [
        (
            ROT,
            "rotlang",
            format!("{}X", "0,,".repeat(100)),
            "rotlang::unknown-sign",
        ),
        (
            ROT,
            "rotlang",
            format!("{}+5*2*", "0/5 ".repeat(100)),
            "rotlang::dummy-and-repeat",
        ),
        (
            JSON,
            "json",
            format!(
                "{{\"solid_infill_rotate_template\": \"{}S\"}}",
                "0,,".repeat(100)
            ),
            "rotlang::solid-sign-in-solid-template",
        ),
    ];
    for (i, (uri, language, text, code)) in cases.into_iter().enumerate() {
        let published = if i == 0 || uri == JSON {
            lsp.open(uri, language, &text)
        } else {
            let version = i as i64 + 1;
            lsp.change(uri, version, &text);
            lsp.diagnostics(uri, Some(version))
        };
        assert_eq!(errors(&published), [code], "{text}");
        assert!(format(&mut lsp, uri).is_null(), "formatted {text}");
    }
    // Many templates in one document, more diagnostics than the server publishes: the
    // errors of the last template are still among them.
    let many = format!(
        "{{\"sparse_infill_rotate_template\": \"{}\", \"solid_infill_rotate_template\": \"{}S\"}}",
        "400 ".repeat(150),
        "0,,".repeat(150),
    );
    lsp.change(JSON, 2, &many);
    let published = lsp.diagnostics(JSON, Some(2));
    assert_eq!(
        errors(&published),
        ["rotlang::solid-sign-in-solid-template"]
    );
    assert!(format(&mut lsp, JSON).is_null());
    lsp.shutdown();
}
