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
