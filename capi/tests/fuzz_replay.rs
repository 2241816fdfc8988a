//! The C ABI's fuzz target (`fuzz/bodies/capi.rs`), replayed on stable over its corpus
//! (`fuzz/corpus/capi/`; see `fuzz/bodies/replay.rs`).

#[path = "../../fuzz/bodies/capi.rs"]
mod capi;
#[path = "../../fuzz/bodies/replay.rs"]
#[allow(dead_code)] // `targets` is for the root crate's check
mod replay;

#[test]
fn capi_corpus() {
    let files = replay::replay(env!("CARGO_MANIFEST_DIR"), "capi", capi::run);
    assert!(files >= 20, "only {files} corpus files");
}
