//! No cycle between the modules of any crate of the repository (issue 21): every folder
//! with a `Cargo.toml` and a `src/` (the workspace's members, bindings/python's own
//! workspace), `target/` and `node_modules/` aside.

use std::path::{Path, PathBuf};

fn crates(dir: &Path, found: &mut Vec<PathBuf>) {
    if dir.join("Cargo.toml").is_file() && dir.join("src").is_dir() {
        found.push(dir.to_path_buf());
    }
    for entry in std::fs::read_dir(dir).expect("a readable folder").flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let skip = [".git", "target", "node_modules", "src", "tests", "benches"];
        if path.is_dir()
            && !skip.iter().any(|s| name == *s)
            && !name.to_string_lossy().starts_with('.')
        {
            crates(&path, found);
        }
    }
}

#[test]
fn no_crate_has_a_module_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut found = Vec::new();
    crates(&root, &mut found);
    let names: Vec<String> = found
        .iter()
        .map(|c| c.strip_prefix(&root).unwrap_or(c).display().to_string())
        .collect();
    for expected in [
        "crates/rotlang",
        "crates/rotlang-cli",
        "lsp",
        "capi",
        "bindings/js",
        "bindings/python",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} not scanned: {names:?}"
        );
    }
    let mut report = Vec::new();
    for (dir, name) in found.iter().zip(&names) {
        let graph =
            rotlang_cycles::crate_graph(&dir.join("src")).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!graph.is_empty(), "{name}: no files read");
        for cycle in rotlang_cycles::cycles(&graph) {
            report.push(format!("{name}/src: {}", cycle.join(" ↔ ")));
        }
    }
    assert!(report.is_empty(), "module cycles:\n{}", report.join("\n"));
}
