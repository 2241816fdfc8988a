//! Replays a target's corpus through its body on stable Rust: used by the regular test
//! suite (`crates/rotlang-profile/tests/fuzz_replay.rs`, `lsp/tests/fuzz_replay.rs`), so CI needs no nightly.

use std::path::{Path, PathBuf};

/// The `fuzz/` directory, from a crate's manifest directory.
pub fn fuzz_dir(manifest_dir: &str) -> PathBuf {
    let here = Path::new(manifest_dir);
    let root = if here.join("fuzz").is_dir() {
        here.to_path_buf()
    } else {
        here.join("..")
    };
    root.join("fuzz")
}

/// Runs `run` on every file of `fuzz/corpus/<target>/` (and of `fuzz/regressions/<target>/`,
/// the crash inputs of fixed findings), naming the file when one fails. Returns how many
/// files ran; a target with no corpus fails.
pub fn replay(manifest_dir: &str, target: &str, run: fn(&[u8])) -> usize {
    let fuzz = fuzz_dir(manifest_dir);
    let mut files = Vec::new();
    for dir in [
        fuzz.join("corpus").join(target),
        fuzz.join("regressions").join(target),
    ] {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        files.extend(
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.is_file()),
        );
    }
    files.sort();
    assert!(
        !files.is_empty(),
        "no corpus for fuzz target {target} in {}",
        fuzz.display()
    );
    for path in &files {
        let data = std::fs::read(path).expect("a readable corpus file");
        if std::panic::catch_unwind(|| run(&data)).is_err() {
            panic!("fuzz target {target} fails on {}", path.display());
        }
    }
    files.len()
}

/// The names of the targets in `fuzz/fuzz_targets/`.
pub fn targets(manifest_dir: &str) -> Vec<String> {
    let dir = fuzz_dir(manifest_dir).join("fuzz_targets");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("fuzz/fuzz_targets exists")
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            e.file_name()
                .to_str()?
                .strip_suffix(".rs")
                .map(str::to_owned)
        })
        .collect();
    names.sort();
    names
}
