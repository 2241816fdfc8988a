//! `include/rotlang.h` is generated from `rotlang-capi` by cbindgen (build.rs) and checked
//! in; the test below fails when the checked-in copy is stale. To update it after changing
//! the C ABI: `ROTLANG_BLESS=1 cargo test -p rotlang-capi-header`.

/// The header as cbindgen generates it from the current source.
pub const GENERATED: &str = include_str!(concat!(env!("OUT_DIR"), "/rotlang.h"));

#[cfg(test)]
mod tests {
    use std::path::Path;

    #[test]
    fn checked_in_header_is_current() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../include/rotlang.h");
        if std::env::var_os("ROTLANG_BLESS").is_some() {
            std::fs::write(&path, super::GENERATED).expect("write include/rotlang.h");
            return;
        }
        let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            checked_in == super::GENERATED,
            "include/rotlang.h is stale: run `ROTLANG_BLESS=1 cargo test -p rotlang-capi-header` \
             and commit the result"
        );
    }
}
