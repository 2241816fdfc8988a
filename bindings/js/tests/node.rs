//! The npm package through Node: builds `rotlang.wasm` (cargo, `wasm` profile, the shared
//! target dir) and runs its `node --test` suite (conformance, API, hostile input).

use std::path::{Path, PathBuf};
use std::process::Command;

fn package() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// Runs `scripts/ensure ARGS`; false (after saying why) when it cannot install outside CI.
fn ensure(args: &[&str]) -> bool {
    let root = package().join("../..");
    let status = Command::new("bash")
        .arg(root.join("scripts/ensure"))
        .args(args)
        .status()
        .expect("run scripts/ensure");
    if status.code() == Some(77) {
        assert!(
            std::env::var_os("CI").is_none(),
            "scripts/ensure {args:?} cannot install in CI (see above)"
        );
        eprintln!("SKIPPED: scripts/ensure {args:?} cannot install (see above)");
        return false;
    }
    assert!(status.success(), "scripts/ensure {args:?}: {status}");
    true
}

#[test]
fn node_test_suite_passes() {
    if !ensure(&["rust-target", "wasm32-unknown-unknown"]) {
        return;
    }
    let dir = package();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| dir.join("../../target"));
    let status = Command::new("node")
        .arg("build.mjs")
        .current_dir(&dir)
        .env("CARGO_TARGET_DIR", &target)
        .status()
        .expect("node is on the machine (Node 20)");
    assert!(status.success(), "building rotlang.wasm failed: {status}");
    let size = std::fs::metadata(dir.join("rotlang.wasm")).map_or(0, |m| m.len());
    assert!(
        size > 0 && size < 300 * 1024,
        "rotlang.wasm is {size} bytes; the budget is 300 KB"
    );
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir.join("test"))
        .expect("test/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".test.js"))
        .collect();
    files.sort();
    assert!(files.len() >= 3, "{files:?}");
    let out = Command::new("node")
        .arg("--test")
        .args(&files)
        .current_dir(&dir)
        .output()
        .expect("run node --test");
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "node --test failed (output above)");
    assert!(stdout.contains("# fail 0"), "no test failed");
}
