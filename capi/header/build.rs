//! Generates the C header of `rotlang-capi` into OUT_DIR (the test in src/lib.rs compares it
//! with the checked-in `include/rotlang.h`).

use std::path::Path;

fn main() {
    let header_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let capi = header_dir.join("..");
    println!("cargo:rerun-if-changed={}", capi.join("src").display());
    println!(
        "cargo:rerun-if-changed={}",
        capi.join("cbindgen.toml").display()
    );
    let config =
        cbindgen::Config::from_file(capi.join("cbindgen.toml")).expect("capi/cbindgen.toml");
    let out = Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("rotlang.h");
    cbindgen::Builder::new()
        .with_crate(&capi)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header from capi/src")
        .write_to_file(out);
}
