//! Shared by the tests that compile C and C++ against the library cargo just built.

#![allow(dead_code)] // each test binary uses a different part

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Installs the tools through `scripts/ensure`. `false`: they cannot be installed here
/// (not root), and the caller skips; under CI that is a failure.
pub fn ensure(args: &[&str]) -> bool {
    ensure_logged(args).is_some()
}

/// As [`ensure`], returning what `scripts/ensure` said on stderr (it says nothing when
/// everything is present already); `None` when it cannot install here.
pub fn ensure_logged(args: &[&str]) -> Option<String> {
    let output = Command::new(root().join("scripts/ensure"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("run scripts/ensure");
    let said = String::from_utf8_lossy(&output.stderr).into_owned();
    eprint!("{said}");
    if output.status.code() == Some(77) {
        assert!(
            std::env::var_os("CI").is_none(),
            "scripts/ensure {args:?} could not install in CI (see the message above)"
        );
        eprintln!("SKIPPED: scripts/ensure {args:?} cannot install here");
        return None;
    }
    assert!(
        output.status.success(),
        "scripts/ensure {args:?}: {}",
        output.status
    );
    Some(said)
}

/// Where cargo put `librotlang_capi.{a,so}` for this test run: beside the test binary
/// (`target/<profile>/deps/`), built from the current source before any test runs.
pub fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    let dir = exe.parent().expect("deps dir").to_path_buf();
    assert!(
        dir.join("librotlang_capi.a").exists() && dir.join("librotlang_capi.so").exists(),
        "cargo did not build the static and shared library beside {exe:?}"
    );
    dir
}

/// A fresh scratch directory under `target/` for this test binary and test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = lib_dir()
        .join("../capi-tests")
        .join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

pub fn run(command: &mut Command) -> Output {
    // cargo puts `target/<profile>` on LD_LIBRARY_PATH for tests, and an older
    // `librotlang_capi.so` uplifted there by `cargo build` would win over the one beside
    // this test binary: the programs find theirs through their rpath only.
    command
        .env_remove("LD_LIBRARY_PATH")
        .stdin(Stdio::null())
        .output()
        .unwrap_or_else(|e| panic!("run {command:?}: {e}"))
}

pub fn check(command: &mut Command) -> Output {
    let output = run(command);
    assert!(
        output.status.success(),
        "{command:?} failed: {}\nstdout:\n{}\nstderr:\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// Runs `program args` under valgrind's memcheck and fails on any invalid access, use of
/// uninitialised memory, or leak (definite, indirect or possible): exit code 99.
pub fn valgrind(program: &Path, args: &[&str]) -> Output {
    let output = run(Command::new("valgrind")
        .args([
            "--quiet",
            "--error-exitcode=99",
            "--leak-check=full",
            "--show-leak-kinds=definite,indirect,possible",
            "--errors-for-leak-kinds=definite,indirect,possible",
        ])
        .arg(program)
        .args(args));
    assert!(
        output.status.code() != Some(99),
        "valgrind found errors in {program:?} {args:?}:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}
