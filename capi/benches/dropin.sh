#!/usr/bin/env bash
# Times the OrcaSlicer drop-in (examples/orcaslicer/rotation_angle.cpp, on the mock
# PrintObject) against the release library: best of 50 runs. The Rust side of the same
# work: `cargo bench -p rotlang-capi --bench capi -- orcaslicer_table_10k`.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}
cargo build --release -p rotlang-capi --manifest-path "$root/Cargo.toml" >&2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
g++ -std=c++17 -O2 -pthread -I "$root/include" -I "$root/capi/tests/orcaslicer/mock" \
    "$root/examples/orcaslicer/rotation_angle.cpp" "$root/capi/benches/dropin_bench.cpp" \
    "$target/release/librotlang_capi.a" -ldl -lm -o "$out/dropin_bench"
"$out/dropin_bench"
