//! The Python package (`bindings/python`): `scripts/ensure venv target/python-venv
//! maturin pytest` makes a virtual environment under `target/` with maturin and pytest in
//! it (the system Python is left alone; it may be "externally managed", as on Debian 12),
//! then `pip install ./bindings/python` runs inside it, then its pytest suite (conformance
//! cases, bad input, threads). Cargo shares the workspace's target directory with the
//! outer build.

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
    let target = target_dir();
    let venv = target.join("python-venv");
    let python = venv.join("bin/python");
    if !ensure(&[
        "venv",
        venv.to_str().expect("UTF-8 path"),
        "maturin",
        "pytest",
    ]) {
        return;
    }
    // Nothing of the system Python is visible: maturin and pytest are the venv's own.
    let isolated = check(Command::new(&python).args([
        "-c",
        "import sys, maturin, pytest; print(sys.prefix != sys.base_prefix and maturin.__file__.startswith(sys.prefix) and pytest.__file__.startswith(sys.prefix))",
    ]));
    assert_eq!(String::from_utf8_lossy(&isolated.stdout).trim(), "True");
    // The documented install, without build isolation so that it uses the venv's maturin
    // instead of downloading one per run.
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
