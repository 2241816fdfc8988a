//! The language server's fuzz targets, replayed on stable over their corpora (see
//! `fuzz/README.md`; the other targets are replayed by the root crate's tests).

#[path = "../../fuzz/bodies/lsp_framing.rs"]
mod lsp_framing;
#[path = "../../fuzz/bodies/lsp_json.rs"]
mod lsp_json;
#[path = "../../fuzz/bodies/lsp_profiles.rs"]
mod lsp_profiles;
#[path = "../../fuzz/bodies/replay.rs"]
#[allow(dead_code)] // `targets` is for the root crate's check
mod replay;

const DIR: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn lsp_json_corpus() {
    replay::replay(DIR, "lsp_json", lsp_json::run);
}

#[test]
fn lsp_framing_corpus() {
    replay::replay(DIR, "lsp_framing", lsp_framing::run);
}

#[test]
fn lsp_profiles_corpus() {
    replay::replay(DIR, "lsp_profiles", lsp_profiles::run);
}

/// The framing target reaches the server: a seed session is answered.
#[test]
fn lsp_framing_reaches_the_handlers() {
    let body = r#"{"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{}}}"#;
    let exit = r#"{"jsonrpc":"2.0","method":"exit"}"#;
    let input = format!(
        "Content-Length: {}\r\n\r\n{body}Content-Length: {}\r\n\r\n{exit}",
        body.len(),
        exit.len()
    );
    let out = String::from_utf8(lsp_framing::session(input.as_bytes())).unwrap();
    assert!(out.contains("\"capabilities\""), "{out}");
    // A whole seed session: hover and formatting are answered, not cancelled.
    let seeds = replay::fuzz_dir(DIR).join("corpus/lsp_framing");
    let mut answered = 0;
    for entry in std::fs::read_dir(seeds).unwrap() {
        let out = lsp_framing::session(&std::fs::read(entry.unwrap().path()).unwrap());
        answered += String::from_utf8_lossy(&out).matches("\"result\"").count();
    }
    assert!(answered >= 10, "{answered} results");
}
