//! Issue 19's table: parse + whole-model expand through the C ABI (`rotlang_parse`, then
//! `rotlang_expand` of every layer of a uniform 0.2 mm model), in both dialects, at 10k,
//! 100k and 1M layers, against OrcaSlicer's own `calculate_infill_rotation_angle`
//! (g++ -O2, called once per layer as the slicer does, 10,000 layers of 0.2 mm), whose
//! times are the ones recorded in issue 19: the project does not contain OrcaSlicer's
//! code, so they are constants here, not measured again.
//!
//! `cargo bench -p rotlang-capi --bench floor` prints, per template and dialect, the best
//! time of N runs (the machine is shared: the minimum is the figure that means something),
//! ns per layer at each size, and the ratio OrcaSlicer / rotlang at 10k layers (target:
//! at least 10,000). `-- quick` runs fewer repetitions. Valgrind can run it too
//! (`-- once`: one run of each, for callgrind's instruction counts).

use std::hint::black_box;
use std::time::{Duration, Instant};

use rotlang_capi::*;

/// The templates of issue 19 with OrcaSlicer's time for 10,000 layers (ms), as recorded.
const TABLE: [(&str, f64); 6] = [
    ("0, 90", 279.0),
    ("+30/50%", 743.0),
    ("5, 10!, +20, +10L25%, -10l25%", 1460.0),
    ("+10L25%, -10l25%, -10L25%, +10l25%", 1320.0),
    ("+45#3", 2520.0),
    ("0, 15, 30, +45/10#, B!, +30", 1960.0),
];

fn run(text: &str, dialect: RotlangDialect, layers: usize, out: &mut [f64]) {
    let mut t = std::ptr::null_mut();
    let model = rotlang_model_uniform(layers, 0.2, 0.0);
    let options = RotlangOptions {
        base: 0.0,
        seed: 0,
        dialect: dialect as u32,
    };
    // SAFETY: every pointer is valid; `out` holds `layers` doubles.
    unsafe {
        let status = rotlang_parse(black_box(text).as_ptr().cast(), text.len(), 0, &mut t);
        assert_eq!(status, RotlangStatus::Ok);
        let status = rotlang_expand(
            t,
            &model,
            &options,
            0,
            ROTLANG_TO_TOP,
            out.as_mut_ptr(),
            std::ptr::null_mut(),
            layers,
            std::ptr::null_mut(),
        );
        assert_eq!(status, RotlangStatus::Ok, "{text}");
        rotlang_template_free(t);
    }
    black_box(&out);
}

fn best(text: &str, dialect: RotlangDialect, layers: usize, runs: usize) -> Duration {
    let mut out = vec![0.0; layers];
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            run(text, dialect, layers, &mut out);
            start.elapsed()
        })
        .min()
        .unwrap_or_default()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let once = args.iter().any(|a| a == "once");
    let quick = args.iter().any(|a| a == "quick");
    // `-- only=K`: the K-th template of the table alone (for callgrind); `-- size=N`: that
    // model size alone, printed as the only column (instruction counts per size).
    let size: Option<usize> = args
        .iter()
        .find_map(|a| a.strip_prefix("size=").and_then(|k| k.parse().ok()));
    let only: Option<usize> = args
        .iter()
        .find_map(|a| a.strip_prefix("only=").and_then(|k| k.parse().ok()));
    let runs = |layers: usize| match (once, quick, layers) {
        (true, ..) => 1,
        (false, true, _) => 20,
        (false, false, 10_000) => 200,
        (false, false, 100_000) => 100,
        _ => 30,
    };
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "parse + expand through the C ABI, uniform 0.2 mm model; best of {}/{}/{} runs; load average {}",
        runs(10_000),
        runs(100_000),
        runs(1_000_000),
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    println!(
        "| template | dialect | OrcaSlicer 10k | rotlang 10k | ns/layer 10k | 100k | 1M | × at 10k |"
    );
    println!("|---|---|--:|--:|--:|--:|--:|--:|");
    for (k, (text, orca_ms)) in TABLE.into_iter().enumerate() {
        if only.is_some_and(|o| o != k) {
            continue;
        }
        for (name, dialect) in [
            ("rotlang", RotlangDialect::Rotlang),
            ("orcaslicer", RotlangDialect::Orcaslicer),
        ] {
            let per_layer = |layers: usize| {
                best(text, dialect, layers, runs(layers)).as_secs_f64() * 1e9 / layers as f64
            };
            if let Some(n) = size {
                println!(
                    "| `{text}` | {name} | {n} layers: {:.2} ns a layer |",
                    per_layer(n)
                );
                continue;
            }
            let (small, medium, large) =
                (per_layer(10_000), per_layer(100_000), per_layer(1_000_000));
            let total_us = small * 10_000.0 / 1000.0;
            println!(
                "| `{text}` | {name} | {orca_ms} ms | {total_us:.1} µs | {small:.2} | {medium:.2} | {large:.2} | {:.0} |",
                orca_ms * 1000.0 / total_us
            );
        }
    }
}
