//! The C ABI against the Rust API (divan): `cargo bench -p rotlang-capi --bench capi`.
//!
//! The same work on both sides: evaluate every layer of a model into an array of angles.
//! `rust_*` calls `rotlang::eval` (or the OrcaSlicer dialect) directly; `c_abi_*` calls the
//! exported `rotlang_expand` (the very function C links to; the registry lookup, model
//! validation and status handling included). Target: the C ABI within 10% of Rust.
//! With a list of heights both sides build the model from the caller's slice each call,
//! since that is what a C caller hands over. `orcaslicer_table_10k` is the Rust side of the
//! drop-in benchmark (capi/benches/dropin.sh runs the C++ side).

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang::dialect::orcaslicer;
use rotlang::eval::{self, Model, Options};
use rotlang_capi::*;

fn main() {
    divan::main();
}

const TEMPLATE: &str = "5, 10!, +20, +10L25%, -10l25%";
const LAYERS: usize = 100_000;

fn heights() -> Vec<f64> {
    (0..LAYERS)
        .map(|i| if i == 0 { 0.3 } else { 0.2 })
        .collect()
}

fn template() -> *mut RotlangTemplate {
    let mut t = std::ptr::null_mut();
    // SAFETY: the text and out-pointer are valid.
    let status = unsafe { rotlang_parse(TEMPLATE.as_ptr().cast(), TEMPLATE.len(), 0, &mut t) };
    assert_eq!(status, RotlangStatus::Ok);
    t
}

fn rust_fill(out: &mut [f64], layers: impl Iterator<Item = eval::Layer>) {
    out.iter_mut()
        .zip(layers)
        .for_each(|(slot, layer)| *slot = layer.angle);
}

#[divan::bench]
fn rust_uniform(bencher: Bencher) {
    let template = rotlang::parse(TEMPLATE, rotlang::Target::Sparse).template;
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        let model = Model::uniform(LAYERS, 0.2, Some(0.3)).unwrap();
        rust_fill(
            &mut out,
            eval::layers(black_box(&template), &model, Options::default()),
        );
        black_box(&out);
    });
}

#[divan::bench]
fn c_abi_uniform(bencher: Bencher) {
    let t = template();
    let model = rotlang_model_uniform(LAYERS, 0.2, 0.3);
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        // SAFETY: every pointer is valid; `out` holds LAYERS doubles.
        let status = unsafe {
            rotlang_expand(
                black_box(t),
                &model,
                std::ptr::null(),
                0,
                ROTLANG_TO_TOP,
                out.as_mut_ptr(),
                std::ptr::null_mut(),
                out.len(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(status, RotlangStatus::Ok);
        black_box(&out);
    });
    rotlang_template_free(t);
}

#[divan::bench]
fn rust_heights(bencher: Bencher) {
    let template = rotlang::parse(TEMPLATE, rotlang::Target::Sparse).template;
    let heights = heights();
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        let model = Model::from_heights(heights.to_vec(), 0.2).unwrap();
        rust_fill(
            &mut out,
            eval::layers(black_box(&template), &model, Options::default()),
        );
        black_box(&out);
    });
}

#[divan::bench]
fn c_abi_heights(bencher: Bencher) {
    let t = template();
    let heights = heights();
    let model = rotlang_model_heights(heights.as_ptr(), heights.len(), 0.2);
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        // SAFETY: every pointer is valid; `out` holds LAYERS doubles.
        let status = unsafe {
            rotlang_expand(
                black_box(t),
                &model,
                std::ptr::null(),
                0,
                ROTLANG_TO_TOP,
                out.as_mut_ptr(),
                std::ptr::null_mut(),
                out.len(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(status, RotlangStatus::Ok);
        black_box(&out);
    });
    rotlang_template_free(t);
}

#[divan::bench]
fn rust_orcaslicer_uniform(bencher: Bencher) {
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        let model = Model::uniform(LAYERS, 0.2, Some(0.3)).unwrap();
        rust_fill(
            &mut out,
            orcaslicer::layers(black_box(TEMPLATE), &model, Options::default()),
        );
        black_box(&out);
    });
}

#[divan::bench]
fn c_abi_orcaslicer_uniform(bencher: Bencher) {
    let t = template();
    let model = rotlang_model_uniform(LAYERS, 0.2, 0.3);
    let options = RotlangOptions {
        base: 0.0,
        seed: 0,
        dialect: RotlangDialect::Orcaslicer as u32,
    };
    let mut out = vec![0.0; LAYERS];
    bencher.counter(ItemsCount::new(LAYERS)).bench_local(|| {
        // SAFETY: every pointer is valid; `out` holds LAYERS doubles.
        let status = unsafe {
            rotlang_expand(
                black_box(t),
                &model,
                &options,
                0,
                ROTLANG_TO_TOP,
                out.as_mut_ptr(),
                std::ptr::null_mut(),
                out.len(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(status, RotlangStatus::Ok);
        black_box(&out);
    });
    rotlang_template_free(t);
}

/// The drop-in's work for one object, done in Rust: 10,000 layers' tops to heights, the
/// OrcaSlicer dialect, degrees to radians in a table (what rotation_angle.cpp caches).
#[divan::bench]
fn orcaslicer_table_10k(bencher: Bencher) {
    let tops: Vec<f64> = (1..=10_000).map(|i| i as f64 * 0.2).collect();
    bencher
        .counter(ItemsCount::new(10_000usize))
        .bench_local(|| {
            let mut below = 0.0;
            let heights: Vec<f64> = tops
                .iter()
                .map(|&t| {
                    let h = t - below;
                    below = t;
                    h
                })
                .collect();
            let model = Model::from_heights(heights, 0.2).unwrap().with_shells(3, 4);
            let table: Vec<f64> =
                orcaslicer::layers(black_box(TEMPLATE), &model, Options::default())
                    .map(|l| std::f64::consts::PI * l.angle / 180.0)
                    .collect();
            black_box(table)
        });
}

/// Issue 16 item 6: a megabyte of digits (one number, OrcaSlicer's list reading) parsed
/// and expanded on the 100-layer cube in the OrcaSlicer dialect. It took 3-5 s when each
/// layer read the megabyte again and `rotlang_parse` parsed it in rotlang's grammar too;
/// the CLI (`rotlang expand --dialect orcaslicer`) does the same work in about 10 ms.
#[divan::bench(args = ["digits", "list"])]
fn c_abi_orcaslicer_megabyte(bencher: Bencher, kind: &str) {
    let text: String = match kind {
        "digits" => (0..1 << 20)
            .map(|i| char::from(b'0' + (i % 10) as u8))
            .collect(),
        _ => "0, 90, ".repeat((1 << 20) / 7),
    };
    let model = rotlang_model_uniform(100, 0.2, 0.0);
    let orca = RotlangOptions {
        base: 0.0,
        seed: 0,
        dialect: RotlangDialect::Orcaslicer as u32,
    };
    let mut out = vec![0.0; 100];
    bencher.bench_local(|| {
        let mut t = std::ptr::null_mut();
        // SAFETY: every pointer is valid; `out` holds 100 doubles.
        unsafe {
            assert_eq!(
                rotlang_parse(text.as_ptr().cast(), text.len(), 0, &mut t),
                RotlangStatus::Ok
            );
            let status = rotlang_expand(
                t,
                &model,
                &orca,
                0,
                ROTLANG_TO_TOP,
                out.as_mut_ptr(),
                std::ptr::null_mut(),
                out.len(),
                std::ptr::null_mut(),
            );
            assert_eq!(status, RotlangStatus::Ok);
            rotlang_template_free(t);
        }
        black_box(&out);
    });
}
