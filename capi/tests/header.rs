//! `include/rotlang.h` is generated from this crate by cbindgen and checked in: this test
//! regenerates it and fails when the checked-in copy is stale. To update it after changing
//! the C ABI: `ROTLANG_BLESS=1 cargo test -p rotlang-capi --test header`.

use std::path::Path;

#[test]
fn checked_in_header_is_current() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config =
        cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = crate_dir.join("../include/rotlang.h");
    if std::env::var_os("ROTLANG_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/rotlang.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/rotlang.h is stale: run `ROTLANG_BLESS=1 cargo test -p rotlang-capi --test header` \
         and commit the result"
    );
}
