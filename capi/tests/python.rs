//! The Python package (`bindings/python`): `scripts/ensure venv target/python-venv
//! bindings/python/requirements-test.txt` makes a virtual environment under `target/` with
//! the pinned maturin and pytest in it (exact versions and hashes; the system Python is left
//! alone: it may be "externally managed", as on Debian 12), then `pip install
//! ./bindings/python` runs inside it, then its pytest suite (conformance cases, bad input,
//! threads). Cargo shares the workspace's target directory with the outer build.

mod common;

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::*;

/// The workspace's target directory (this test binary is in `target/<profile>/deps/`).
fn target_dir() -> PathBuf {
    lib_dir().join("../..").canonicalize().expect("target dir")
}

/// The pins of the test's tools.
fn requirements() -> PathBuf {
    root().join("bindings/python/requirements-test.txt")
}

/// `PATH` with the venv's `bin` first: maturin's build backend runs the `maturin` command
/// by name, which outside an activated venv is not found (or is another one).
fn venv_path(venv: &Path) -> OsString {
    let rest = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(venv.join("bin")).chain(std::env::split_paths(&rest)))
        .expect("PATH entries without ':'")
}

#[test]
fn python_package_builds_installs_and_passes_pytest() {
    let target = target_dir();
    let venv = target.join("python-venv");
    let python = venv.join("bin/python");
    let reqs = requirements();
    if !ensure(&[
        "venv",
        venv.to_str().expect("UTF-8 path"),
        reqs.to_str().expect("UTF-8 path"),
    ]) {
        return;
    }
    let path = venv_path(&venv);
    // Nothing of the system Python is visible: maturin and pytest are the venv's own.
    let isolated = check(Command::new(&python).args([
        "-c",
        "import sys, maturin, pytest; print(sys.prefix != sys.base_prefix and maturin.__file__.startswith(sys.prefix) and pytest.__file__.startswith(sys.prefix))",
    ]));
    assert_eq!(String::from_utf8_lossy(&isolated.stdout).trim(), "True");
    // Every package in the venv is one of the pins, at its pinned version (but the one
    // this test installs).
    let pins = std::fs::read_to_string(&reqs).expect("requirements-test.txt");
    let pinned = |name_version: &str| {
        pins.lines()
            .any(|l| l.split([' ', ';']).next() == Some(name_version))
    };
    let freeze = check(Command::new(&python).args(["-m", "pip", "freeze", "--exclude", "rotlang"]));
    let freeze = String::from_utf8_lossy(&freeze.stdout).to_lowercase();
    for line in freeze.lines() {
        assert!(
            pinned(&line.replace('_', "-")),
            "`{line}` in the venv is not a pin of {reqs:?}"
        );
    }
    for tool in ["maturin==", "pytest=="] {
        assert!(freeze.contains(tool), "no {tool} in the venv:\n{freeze}");
    }
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
            .env("PATH", &path)
            .env("CARGO_TARGET_DIR", &target),
    );
    let out = check(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(root().join("bindings/python/tests"))
            .env("PATH", &path)
            .current_dir(&target),
    );
    eprintln!("{}", String::from_utf8_lossy(&out.stdout));
}

/// `scripts/ensure venv` installs once, then returns at once while the pins stay, and makes
/// the venv anew when they change (here a requirements file with no packages: no network).
#[test]
fn ensure_venv_is_idempotent_and_follows_the_pins() {
    let dir = scratch("ensure-venv");
    let venv = dir.join("venv");
    let reqs = dir.join("requirements.txt");
    let args = [
        "venv",
        venv.to_str().expect("UTF-8 path"),
        reqs.to_str().expect("UTF-8 path"),
    ];
    std::fs::write(&reqs, "# no packages\n").expect("write requirements");
    let Some(first) = ensure_logged(&args) else {
        return;
    };
    assert!(
        first.contains("python3 -m venv"),
        "the first call made no venv: {first}"
    );
    assert!(venv.join("bin/python").exists());
    // A file left in the venv shows whether the next calls remake it.
    let marker = venv.join("marker");
    std::fs::write(&marker, "").expect("write marker");
    let second = ensure_logged(&args).expect("installed before");
    assert_eq!(
        second, "",
        "a second call with the same pins installed something"
    );
    assert!(
        marker.exists(),
        "a second call with the same pins remade the venv"
    );
    std::fs::write(&reqs, "# no packages, another pin\n").expect("write requirements");
    let third = ensure_logged(&args).expect("installed before");
    assert!(
        third.contains("python3 -m venv"),
        "changed pins did not remake the venv: {third}"
    );
    assert!(!marker.exists(), "the venv of the old pins is still there");
    let _ = std::fs::remove_dir_all(&dir);
}
