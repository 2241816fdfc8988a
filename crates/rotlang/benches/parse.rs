//! Parser throughput (divan). `cargo bench --bench parse`.
//!
//! A typical template, and megabyte templates of valid instructions, of mistakes and of
//! one long instruction, at three sizes so that linearity shows: MB/s should stay flat.

use divan::counter::BytesCount;
use divan::{Bencher, black_box};
use rotlang::Target;

fn main() {
    divan::main();
}

const TYPICAL: &str = "5, 10!, +20, +10L25%, -10l25%";
const KB: usize = 1 << 10;
const SIZES: [usize; 3] = [64 * KB, 256 * KB, 1024 * KB];

/// `unit` repeated to `len` bytes (cut at a char boundary of the repetition).
fn sized(unit: &str, len: usize) -> String {
    unit.repeat(len.div_ceil(unit.len()))
}

#[divan::bench]
fn typical(bencher: Bencher) {
    bencher
        .counter(BytesCount::of_str(TYPICAL))
        .bench(|| rotlang::parse(black_box(TYPICAL), Target::Sparse));
}

#[divan::bench]
fn typical_fmt(bencher: Bencher) {
    bencher
        .counter(BytesCount::of_str(TYPICAL))
        .bench(|| rotlang::format::format(black_box(TYPICAL), Target::Sparse));
}

fn bench_text(bencher: Bencher, text: &str) {
    bencher
        .counter(BytesCount::of_str(text))
        .bench(|| rotlang::parse(black_box(text), Target::Sparse));
}

/// `+1, ` repeated: 4-byte instructions, the worst case for per-instruction overhead.
#[divan::bench(args = SIZES, sample_count = 10, sample_size = 1)]
fn valid_short_instructions(bencher: Bencher, len: usize) {
    bench_text(bencher, &sized("+1, ", len));
}

/// The documentation's templates repeated.
#[divan::bench(args = SIZES, sample_count = 10, sample_size = 1)]
fn valid_doc_mix(bencher: Bencher, len: usize) {
    bench_text(
        bencher,
        &sized(
            "+10L25%, -10l25%, #14, +15R, B!, 240M3, #25, +30/1cm, ST, ",
            len,
        ),
    );
}

/// `X, ` repeated: an error in every instruction (diagnostics capped at 100).
#[divan::bench(args = SIZES, sample_count = 10, sample_size = 1)]
fn errors_everywhere(bencher: Bencher, len: usize) {
    bench_text(bencher, &sized("X, ", len));
}

/// One instruction: a number `len` digits long.
#[divan::bench(args = SIZES, sample_count = 10, sample_size = 1)]
fn one_long_number(bencher: Bencher, len: usize) {
    bench_text(bencher, &"9".repeat(len));
}
