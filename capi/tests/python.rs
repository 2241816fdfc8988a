//! The Python package (`bindings/python`): `scripts/ensure pip maturin pytest`, then
//! `pip install ./bindings/python` into a virtual environment under `target/` (the system
//! site-packages stay clean), then its pytest suite (conformance cases, bad input,
//! threads). Cargo shares the workspace's target directory with the outer build.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::*;

/// The workspace's target directory (this test binary is in `target/<profile>/deps/`).
fn target_dir() -> PathBuf {
    lib_dir().join("../..").canonicalize().expect("target dir")
}

#[test]
fn python_package_builds_installs_and_passes_pytest() {
    if !ensure(&["pip", "maturin", "pytest"]) {
        return;
    }
    let target = target_dir();
    let venv = target.join("python-venv");
    let python = venv.join("bin/python");
    if !python.exists() {
        // System site-packages visible: maturin and pytest come from `scripts/ensure`.
        check(
            Command::new("python3")
                .args(["-m", "venv", "--system-site-packages"])
                .arg(&venv),
        );
    }
    // The documented install, without build isolation so that it uses the maturin
    // `scripts/ensure` installed instead of downloading one per run.
    check(
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
                "--no-build-isolation",
                "--no-deps",
                "--force-reinstall",
            ])
            .arg(root().join("bindings/python"))
            .env("CARGO_TARGET_DIR", &target),
    );
    let out = check(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(root().join("bindings/python/tests"))
            .current_dir(&target),
    );
    eprintln!("{}", String::from_utf8_lossy(&out.stdout));
}
