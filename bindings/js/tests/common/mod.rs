#![allow(dead_code)] // each test binary uses part of it
//! What the Node and browser tests share: installing tools through `scripts/ensure` and
//! building `rotlang.wasm` into the workspace's target dir.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `bindings/js`.
pub fn package() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

pub fn root() -> PathBuf {
    package().join("../..")
}

/// The workspace's target dir (shared: the wasm build reuses what cargo already built).
pub fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target"))
}

/// Runs `scripts/ensure ARGS`; false (after saying why) when it cannot install outside
/// CI. In CI a tool that cannot be installed fails the test.
pub fn ensure(args: &[&str]) -> bool {
    let status = Command::new("bash")
        .arg(root().join("scripts/ensure"))
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

/// The wasm target and binaryen (for wasm-opt); false when they cannot be installed.
pub fn wasm_tools() -> bool {
    ensure(&["rust-target", "wasm32-unknown-unknown"])
        && ensure(&["npm-ci", &package().to_string_lossy()])
}

/// Runs `node ARGS` in `dir`, printing its output; panics unless it succeeds.
pub fn node(dir: &Path, args: &[&str], env: &[(&str, &Path)]) -> String {
    let mut cmd = Command::new("node");
    cmd.args(args)
        .current_dir(dir)
        .env("CARGO_TARGET_DIR", target_dir());
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().expect("node is on the machine (Node 20)");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    println!("{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "node {args:?} failed (output above)");
    stdout
}

/// The `*.test.js` files of a directory, sorted.
pub fn test_files(dir: &Path) -> Vec<String> {
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .expect("a test directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".test.js"))
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    files.sort();
    files
}
