//! The npm package through Node: builds `rotlang.wasm` (cargo, `wasm` profile, the shared
//! target dir, wasm-opt) and runs its `node --test` suite (conformance, API, hostile input).

mod common;

use common::*;

#[test]
fn node_test_suite_passes() {
    if !wasm_tools() {
        return;
    }
    let dir = package();
    // A cargo warning in the wasm builds (core or full) fails the build here.
    node(&dir, &["build.mjs", "--deny-warnings"], &[]);
    // The budget is the core module's; rotlang-full.wasm (the playground's) is larger.
    let size = std::fs::metadata(dir.join("rotlang.wasm")).map_or(0, |m| m.len());
    assert!(
        size > 0 && size < 320 * 1024,
        "rotlang.wasm is {size} bytes; the budget is 320 KB"
    );
    assert!(dir.join("rotlang-full.wasm").is_file());
    // The README's sizes are the modules just built (build.mjs writes them).
    let readme = std::fs::read_to_string(dir.join("README.md")).expect("README.md");
    for name in ["rotlang.wasm", "rotlang-full.wasm"] {
        let bytes = std::fs::metadata(dir.join(name)).map_or(0, |m| m.len());
        let shown = format!("{} bytes", thousands(bytes));
        assert!(
            readme.contains(&format!("`{name}` is")) && readme.contains(&shown),
            "README.md does not give {name}'s size ({shown})"
        );
    }
    let files = test_files(&dir.join("test"));
    assert!(files.len() >= 3, "{files:?}");
    let mut args = vec!["--test"];
    args.extend(files.iter().map(String::as_str));
    // The workspace's own binaries (built by `cargo test --workspace` before any test
    // runs), for the test that reads one preset through the CLI, the server and JS.
    let bin = target_dir().join("debug");
    let (cli, lsp) = (bin.join("rotlang"), bin.join("rotlang-lsp"));
    assert!(
        cli.is_file() && lsp.is_file(),
        "{} and {} are built by `cargo test --workspace --all-features`",
        cli.display(),
        lsp.display()
    );
    let stdout = node(&dir, &args, &[("ROTLANG_CLI", &cli), ("ROTLANG_LSP", &lsp)]);
    assert!(
        !stdout.contains("# skipped 1") && stdout.contains("# skipped 0"),
        "no test skipped"
    );
    assert!(stdout.contains("# fail 0"), "no test failed");
}

/// `1234567` as `1,234,567`.
fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}
