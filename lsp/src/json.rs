//! JSON profiles: the scanner lives in the library (`rotlang::profile::json`), shared with
//! the CLI's `rotlang check profile.json`.

pub use rotlang::profile::json::{
    JsonTemplate, OffsetMap, TEMPLATE_KEYS, escape, find_templates, syntax_error,
};
