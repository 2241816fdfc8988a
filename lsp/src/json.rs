//! JSON profiles: the scanner lives in the library (`rotlang_profile::profile::json`), shared with
//! the CLI's `rotlang check profile.json`.

pub use rotlang_profile::profile::json::{
    JsonTemplate, OffsetMap, TEMPLATE_KEYS, escape, find_templates, syntax_error,
};
