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
    node(&dir, &["build.mjs"], &[]);
    // The budget is the core module's; rotlang-full.wasm (the playground's) is larger.
    let size = std::fs::metadata(dir.join("rotlang.wasm")).map_or(0, |m| m.len());
    assert!(
        size > 0 && size < 300 * 1024,
        "rotlang.wasm is {size} bytes; the budget is 300 KB"
    );
    assert!(dir.join("rotlang-full.wasm").is_file());
    let files = test_files(&dir.join("test"));
    assert!(files.len() >= 3, "{files:?}");
    let mut args = vec!["--test"];
    args.extend(files.iter().map(String::as_str));
    let stdout = node(&dir, &args, &[]);
    assert!(stdout.contains("# fail 0"), "no test failed");
}
