//! Output benchmarks (divan): `cargo bench --bench expand_output`.
//!
//! Target: `rotlang expand` writes 1,000,000 layers as CSV in under 0.3 s (issue 9: number
//! formatting dominated at about 0.6 s). The run is the command's own code, writing into
//! a sink, with the model and the template given as on the command line.

use clap::Parser;
use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use rotlang_cli::cli::expand::{ExpandArgs, run};

fn main() {
    divan::main();
}

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    args: ExpandArgs,
}

fn args(format: &str, layers: usize) -> ExpandArgs {
    let layers = layers.to_string();
    Cli::parse_from([
        "expand",
        "5, 10!, +20, +10L25%, -10l25%",
        "--layers",
        &layers,
        "--layer-height",
        "0.1",
        "--first-layer-height",
        "0.3",
        "--wrap",
        "360",
        "--format",
        format,
    ])
    .args
}

/// Every byte is written into a sink that counts them, so nothing is optimised away.
fn expand(args: &ExpandArgs) -> usize {
    struct Count(usize);
    impl std::io::Write for Count {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0 += b.len();
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mut out = Count(0);
    let code = run(black_box(args), &mut out, &mut std::io::sink()).expect("expands");
    assert_eq!(code, 0);
    out.0
}

#[divan::bench(args = ["csv", "json", "table"], sample_count = 5)]
fn million_layers(bencher: Bencher, format: &str) {
    let args = args(format, 1_000_000);
    bencher
        .counter(ItemsCount::new(1_000_000usize))
        .bench(|| expand(&args));
}
