//! Time of `rotlang check` on files of many templates (divan): `cargo bench --bench
//! profiles`. Issue 22 item 2: 16,000 template keys in one JSON took 12 s (quadratic: a
//! line index of the whole file per template); it must scale linearly, so the time per
//! template stays flat from 2k to 16k keys, and 200,000 `.ini` lines take a second or so.
//!
//! The files are written once to a temporary folder; each run is the command's own code
//! (reading, checking, the report) writing into a sink.

use std::path::PathBuf;

use clap::Parser;
use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang_cli::cli::check::{CheckArgs, run};

fn main() {
    divan::main();
}

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    args: CheckArgs,
}

/// A file in a temporary folder of this run (left for the OS to clean: benches end by
/// exiting, and divan gives no hook after the last run).
fn file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rotlang-bench-profiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write the input");
    path
}

fn check(path: &std::path::Path, format: &str) -> usize {
    let path = path.display().to_string();
    let args = Cli::parse_from(["check", "--format", format, "--color", "never", &path]).args;
    let mut out = Vec::new();
    let _ = run(black_box(&args), &mut out, &mut std::io::sink()).expect("checks");
    out.len()
}

/// `n` template keys in one JSON preset (the same key: each one after the first is a
/// duplicate, warned about), one per line as OrcaSlicer writes presets.
#[divan::bench(args = [2_000, 4_000, 8_000, 16_000], sample_count = 5)]
fn json_keys(bencher: Bencher, n: usize) {
    let lines = vec!["  \"sparse_infill_rotate_template\": \"+10L25%, -10l25%\""; n];
    let path = file(
        &format!("keys-{n}.json"),
        &format!("{{\n{}\n}}\n", lines.join(",\n")),
    );
    bencher
        .counter(ItemsCount::new(n))
        .bench(|| check(&path, "human"));
}

/// The same, as one line (the worst case for columns) with `--format json`.
#[divan::bench(args = [2_000, 4_000, 8_000, 16_000], sample_count = 5)]
fn json_keys_one_line_report(bencher: Bencher, n: usize) {
    let lines = vec!["\"sparse_infill_rotate_template\": \"+10L25%, -10l25%\""; n];
    let path = file(
        &format!("line-{n}.json"),
        &format!("{{{}}}", lines.join(", ")),
    );
    bencher
        .counter(ItemsCount::new(n))
        .bench(|| check(&path, "json"));
}

/// `n` templates of one key, as a per-extruder array: each one is checked.
#[divan::bench(args = [2_000, 4_000, 8_000, 16_000], sample_count = 5)]
fn json_array(bencher: Bencher, n: usize) {
    let values = vec!["\"+10L25%, -10l25%\""; n];
    let path = file(
        &format!("array-{n}.json"),
        &format!(
            "{{\"sparse_infill_rotate_template\": [{}]}}",
            values.join(", ")
        ),
    );
    bencher
        .counter(ItemsCount::new(n))
        .bench(|| check(&path, "human"));
}

/// `.ini` exports of 50k to 200k template lines.
#[divan::bench(args = [50_000, 100_000, 200_000], sample_count = 3)]
fn ini_lines(bencher: Bencher, n: usize) {
    let path = file(
        &format!("lines-{n}.ini"),
        &"sparse_infill_rotate_template = +10L25%, -10l25%\n".repeat(n),
    );
    bencher
        .counter(ItemsCount::new(n))
        .bench(|| check(&path, "human"));
}
