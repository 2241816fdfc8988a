//! The fuzz targets' corpora, replayed on stable (see `fuzz/README.md`): every file of
//! `fuzz/corpus/<target>/` runs through the target's body. Targets that need the language
//! server are replayed by `lsp/tests/fuzz_replay.rs`.

#[path = "../../../fuzz/bodies/dialect.rs"]
mod dialect;
#[path = "../../../fuzz/bodies/eval.rs"]
mod eval;
#[path = "../../../fuzz/bodies/fmt.rs"]
mod fmt;
#[path = "../../../fuzz/bodies/parse.rs"]
mod parse;
#[path = "../../../fuzz/bodies/profile.rs"]
mod profile;
#[path = "../../../fuzz/bodies/replay.rs"]
mod replay;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Replayed here.
const HERE: &[&str] = &["dialect", "eval", "fmt", "parse", "profile"];
/// Replayed by `lsp/tests/fuzz_replay.rs`.
const LSP: &[&str] = &["lsp_framing", "lsp_json", "lsp_profiles"];
/// Replayed by `capi/tests/fuzz_replay.rs`.
const CAPI: &[&str] = &["capi"];

#[test]
fn parse_corpus() {
    replay::replay(DIR, "parse", parse::run);
}

#[test]
fn eval_corpus() {
    replay::replay(DIR, "eval", eval::run);
}

#[test]
fn dialect_corpus() {
    replay::replay(DIR, "dialect", dialect::run);
}

#[test]
fn profile_corpus() {
    replay::replay(DIR, "profile", profile::run);
}

#[test]
fn fmt_corpus() {
    replay::replay(DIR, "fmt", fmt::run);
}

/// A new target must be added to one of the replay lists (and get a corpus).
#[test]
fn every_target_is_replayed() {
    let mut listed: Vec<&str> = HERE.iter().chain(LSP).chain(CAPI).copied().collect();
    listed.sort();
    assert_eq!(replay::targets(DIR), listed);
}
