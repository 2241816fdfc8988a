//! The `rotlang` command's library: its subcommands, reports and file handling
//! ([`cli`]), run by `main.rs` and by the tests and benches.

// The CLI was part of the `rotlang` crate and names the language, the slicer files and the
// geometry as `crate::…`: the three crates stand in for the crate root here (privately).
#[allow(unused_imports)]
use rotlang::*;
#[allow(unused_imports)]
use rotlang_geometry::*;
#[allow(unused_imports)]
use rotlang_profile::*;

#[doc(hidden)]
pub mod cli;
