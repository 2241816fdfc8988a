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

// ── large documents ─────────────────────────────────────────────────────────────────────

const MIB: usize = 1 << 20;

/// Resident memory of a process (kB), from /proc; `None` where there is no /proc.
fn rss_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// A valid template of `len` bytes or just over.
fn big_template(len: usize) -> String {
    "+10L25%, -10l25%, 0, 90, ".repeat(len / 25 + 1)
}

#[test]
fn documents_over_the_limit_get_one_diagnostic_and_nothing_else() {
    let mut lsp = Lsp::start();
    let text = format!("{}X", big_template(4 * MIB));
    let published = lsp.open(ROT, "rotlang", &text);
    assert_eq!(published.len(), 1, "{published:?}");
    let d = &published[0];
    assert_eq!(d["code"], "rotlang-lsp::document-too-large");
    assert_eq!(d["range"]["start"], json!({"line": 0, "character": 0}));
    assert!(
        d["message"]
            .as_str()
            .unwrap()
            .contains("rotlang.maxDocumentBytes"),
        "{d}"
    );
    assert!(format(&mut lsp, ROT).is_null());
    let hover = lsp.result(
        "textDocument/hover",
        json!({"textDocument": {"uri": ROT}, "position": {"line": 0, "character": 1}}),
    );
    assert!(hover.is_null());
    // Shrunk below the limit, it is checked again.
    lsp.change(ROT, 2, "+30X5");
    assert_eq!(
        errors(&lsp.diagnostics(ROT, Some(2))),
        ["rotlang::unknown-sign"]
    );
    lsp.shutdown();
}

#[test]
fn a_setting_raises_the_limit() {
    let (mut lsp, _) =
        Lsp::start_with(json!({}), json!({"rotlang": {"maxDocumentBytes": 8 * MIB}}));
    let text = format!("{}X", big_template(4 * MIB));
    let published = lsp.open(ROT, "rotlang", &text);
    assert_eq!(errors(&published), ["rotlang::unknown-sign"]);
    lsp.shutdown();
}

#[test]
fn memory_returns_to_idle_after_closing_a_large_document() {
    let mut lsp = Lsp::start();
    lsp.open(
        JSON,
        "json",
        "{\"sparse_infill_rotate_template\": \"0, 90\"}",
    );
    let Some(idle) = rss_kb(lsp.pid()) else {
        eprintln!("no /proc: RSS not measured");
        return;
    };
    // Just under the limit: parsed, diagnosed, held.
    let text = big_template(4 * MIB - 64);
    let text = &text[..text[..4 * MIB - 64].rfind(',').unwrap()];
    assert!(lsp.open(ROT, "rotlang", text).is_empty());
    let open = rss_kb(lsp.pid()).unwrap();
    lsp.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": ROT}}),
    );
    assert!(lsp.diagnostics(ROT, None).is_empty());
    // A round trip, so the close has been handled.
    let _ = format(&mut lsp, JSON);
    let closed = rss_kb(lsp.pid()).unwrap();
    eprintln!("RSS idle {idle} kB, with 4 MiB open {open} kB, after close {closed} kB");
    assert!(
        closed < idle + 16 * 1024,
        "RSS after close {closed} kB, idle {idle} kB (open: {open} kB)"
    );
    lsp.shutdown();
}
