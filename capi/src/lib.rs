//! The C ABI of rotlang: `include/rotlang.h` (generated from this crate by cbindgen) and
//! `include/rotlang.hpp` (a C++17 wrapper) describe it for C and C++.
//!
//! Rules every function follows:
//! - It returns a `RotlangStatus` (0 = ok) and writes results through out-pointers; the
//!   reason of a failure, with its detail, is in `rotlang_last_error` (per thread).
//! - No panic crosses the boundary: a bug becomes `ROTLANG_STATUS_INTERNAL`.
//! - NULL pointers, non-UTF-8 text, empty or NaN/negative heights, unknown enum values,
//!   short buffers, freed or foreign handles are error codes, never undefined behaviour.
//! - Handles are ids checked against a registry (see `handle.rs`): a double free is
//!   `ROTLANG_STATUS_INVALID_HANDLE`.
//! - A template is immutable: evaluate it from as many threads at once as you like.
//!   An evaluator has a cursor: one per thread.
//! - Every allocation has its free: `rotlang_template_free`, `rotlang_evaluator_free`.
//!   Nothing else allocates memory the caller owns.

mod evaluator;
mod expand;
mod handle;
mod model;
mod status;
mod stream;
mod template;
mod util;

use std::ffi::c_char;

pub use evaluator::*;
pub use expand::*;
pub use handle::{RotlangEvaluator, RotlangTemplate};
pub use model::*;
pub use status::{RotlangStatus, rotlang_last_error, rotlang_status_message};
pub use stream::{RotlangFinding, RotlangFindingKind, RotlangFindings, rotlang_finding_code};
pub use template::*;

/// The version of this ABI. It changes only when an existing function, struct or value
/// changes incompatibly; additions keep it. Compare `rotlang_abi_version()` with the
/// header's `ROTLANG_ABI_VERSION` at start-up to catch a header/library mismatch.
pub const ROTLANG_ABI_VERSION: u32 = 1;

/// The ABI version of the loaded library (see `ROTLANG_ABI_VERSION`).
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_abi_version() -> u32 {
    ROTLANG_ABI_VERSION
}

/// The number of handles (templates and evaluators) created and not yet freed, in the
/// whole process. Handles live in a registry the library keeps, so a forgotten `_free` is
/// memory a leak checker (valgrind, LeakSanitizer) reports as "still reachable", which it
/// does not count as a leak: assert that this is 0 at the end of a test run instead.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_live_handles() -> usize {
    handle::live()
}

/// The version of rotlang, e.g. `"0.1.0"`: a static NUL-terminated string.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}
