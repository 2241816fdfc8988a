//! The C side of the C ABI: `examples/c/expand.c` and `tests/c/abi.c` are compiled with
//! the system C compiler against the static library cargo built for this test run, run,
//! and run again under valgrind (zero invalid accesses, zero leaks).

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::*;
use rotlang::eval::{self, Model, Options};

const TOOLS: [&str; 3] = ["apt", "gcc", "valgrind"];

/// Compiles one C file against `include/` and `librotlang_capi.a`.
fn compile(source: &str, name: &str) -> PathBuf {
    let dir = scratch(name);
    let exe = dir.join(name);
    check(
        Command::new("gcc")
            .args([
                "-std=c11",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-pedantic",
                "-g",
                "-O1",
            ])
            .arg("-I")
            .arg(root().join("include"))
            .arg(root().join(source))
            .arg(lib_dir().join("librotlang_capi.a"))
            .args(["-lpthread", "-ldl", "-lm", "-o"])
            .arg(&exe),
    );
    exe
}

#[test]
fn c_example_prints_what_the_rust_api_computes() {
    if !ensure(&TOOLS) {
        return;
    }
    let exe = compile("examples/c/expand.c", "expand");
    let text = "0, +30~5, -15/10%, 45!";
    let out = check(Command::new(&exe).arg(text));
    let template = rotlang::parse(text, rotlang::Target::Sparse).template;
    let expected: String = eval::layers(
        &template,
        &Model::uniform(100, 0.2, None).unwrap(),
        Options::default(),
    )
    .map(|l| format!("{} {:.6}\n", l.index, l.angle))
    .collect();
    assert_eq!(String::from_utf8_lossy(&out.stdout), expected);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // A template with an error: the diagnostic (code and byte span) on stderr, exit 1.
    let bad = run(Command::new(&exe).arg("+30°, X"));
    assert_eq!(bad.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(
        stderr.contains("error[rotlang::")
            && stderr.contains("bytes 3..5")
            && stderr.contains("bytes 7..8"),
        "{stderr}"
    );
    assert!(stderr.contains("the template has errors"), "{stderr}");

    let checked = valgrind(&exe, &[text]);
    assert!(checked.status.success());
    let checked = valgrind(&exe, &["+30°, X"]);
    assert_eq!(checked.status.code(), Some(1));
}

#[test]
fn c_abi_refuses_hostile_input_and_serves_many_threads() {
    if !ensure(&TOOLS) {
        return;
    }
    let exe = compile("capi/tests/c/abi.c", "abi");
    let out = check(&mut Command::new(&exe));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("ok "), "{stdout}");
    // Valgrind runs threads one at a time, fifty times slower: fewer layers and threads.
    let checked = valgrind(&exe, &["300", "3"]);
    assert!(
        checked.status.success(),
        "{}",
        String::from_utf8_lossy(&checked.stderr)
    );
}
