//! The C++ side: `include/rotlang.hpp` and the OrcaSlicer drop-in
//! (`examples/orcaslicer/rotation_angle.cpp`) compiled with the system C++ compiler
//! against the shared library cargo built for this test run. The drop-in is checked on
//! every layer of the conformance corpus's OrcaSlicer angles, from several threads; both
//! programs run again under valgrind.

mod common;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::*;
use serde_json::Value;

const TOOLS: [&str; 4] = ["apt", "g++", "valgrind", "gcc"];
const CORPUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/conformance/");

/// Compiles C++ sources against `include/`, the mock OrcaSlicer headers and
/// `librotlang_capi.so` (found at run time through an rpath).
fn compile(sources: &[&str], name: &str, defines: &[&str]) -> PathBuf {
    let dir = scratch(name);
    let exe = dir.join(name);
    let libs = lib_dir();
    let mut command = Command::new("g++");
    command
        .args([
            "-std=c++17",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
            "-g",
            "-O2",
            "-pthread",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .arg("-I")
        .arg(root().join("capi/tests/orcaslicer/mock"))
        .args(defines);
    for source in sources {
        command.arg(root().join(source));
    }
    command
        .arg("-L")
        .arg(&libs)
        .arg(format!("-Wl,--disable-new-dtags,-rpath,{}", libs.display()))
        .args(["-lrotlang_capi", "-o"])
        .arg(&exe);
    check(&mut command);
    exe
}

/// The corpus in the line format dropin_test.cpp reads (see its header comment).
fn write_corpus(path: &Path) -> usize {
    let read = |name: &str| {
        std::fs::read_to_string(format!("{CORPUS}{name}"))
            .unwrap_or_else(|e| panic!("read {CORPUS}{name}: {e}"))
    };
    let models: BTreeMap<String, Value> = serde_json::from_str(&read("models.json")).unwrap();
    let mut out = String::new();
    for (name, m) in &models {
        let heights: Vec<String> = m["layer_heights"]
            .as_array()
            .unwrap()
            .iter()
            .map(|h| format!("{:?}", h.as_f64().unwrap()))
            .collect();
        writeln!(
            out,
            "model {name} {:?} {} {} {} {}",
            m["layer_height"].as_f64().unwrap(),
            m["bottom_shell_layers"],
            m["top_shell_layers"],
            heights.len(),
            heights.join(" ")
        )
        .unwrap();
    }
    let mut cases = 0;
    for line in read("cases.jsonl").lines().filter(|l| !l.trim().is_empty()) {
        let case: Value = serde_json::from_str(line).unwrap();
        let orca = &case["orcaslicer"];
        let status = orca["status"]
            .as_str()
            .expect("every exact case has an orcaslicer status");
        let degrees = match status {
            "same" => &case["degrees"],
            _ => &orca["degrees"],
        };
        let degrees: Vec<String> = degrees
            .as_array()
            .unwrap_or_else(|| panic!("degrees of {line}"))
            .iter()
            .map(|d| d.as_f64().map_or("nan".to_string(), |d| format!("{d:?}")))
            .collect();
        let text = case["template"].as_str().unwrap();
        let hex: String = if text.is_empty() {
            "-".into()
        } else {
            text.bytes().map(|b| format!("{b:02x}")).collect()
        };
        writeln!(
            out,
            "case {} {status} {hex} {} {}",
            case["model"].as_str().unwrap(),
            degrees.len(),
            degrees.join(" ")
        )
        .unwrap();
        cases += 1;
    }
    std::fs::write(path, out).unwrap();
    cases
}

#[test]
fn cpp_header_wraps_the_c_abi() {
    if !ensure(&TOOLS) {
        return;
    }
    let exe = compile(&["capi/tests/orcaslicer/hpp_test.cpp"], "hpp_test", &[]);
    let out = check(&mut Command::new(&exe));
    assert_eq!(String::from_utf8_lossy(&out.stdout), "ok\n");
    assert!(valgrind(&exe, &[]).status.success());
}

#[test]
fn orcaslicer_drop_in_matches_the_corpus_from_many_threads() {
    if !ensure(&TOOLS) {
        return;
    }
    let dir = scratch("corpus");
    let corpus = dir.join("corpus.txt");
    assert!(
        write_corpus(&corpus) > 1500,
        "the corpus has its 1,572 exact cases"
    );
    let corpus = corpus.to_str().unwrap();
    let exe = compile(
        &[
            "examples/orcaslicer/rotation_angle.cpp",
            "capi/tests/orcaslicer/dropin_test.cpp",
        ],
        "dropin_test",
        &[],
    );
    let out = check(Command::new(&exe).args([corpus, "4", "1"]));
    let stdout = String::from_utf8_lossy(&out.stdout);
    eprintln!("{stdout}");
    assert!(
        stdout.contains("of 1572 cases on 4 threads: 0 failed"),
        "{stdout}"
    );
    // Valgrind runs threads one at a time: a sample of the cases, two threads.
    let checked = valgrind(&exe, &[corpus, "2", "40"]);
    assert!(
        checked.status.success(),
        "{}",
        String::from_utf8_lossy(&checked.stderr)
    );
}
