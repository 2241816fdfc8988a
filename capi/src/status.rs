//! Status codes, the per-thread last-error message, and the guard that keeps panics
//! from crossing the boundary.

use std::cell::RefCell;
use std::ffi::c_char;
use std::panic::{AssertUnwindSafe, catch_unwind};

use rotlang::api::{ApiError, ErrorKind};

/// What a call did. Every function that can fail returns one; `ROTLANG_STATUS_OK` is 0,
/// so `if (status) { ... }` reads as "if it failed". The values are stable across releases
/// (new ones are only ever added at the end).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangStatus {
    Ok = 0,
    /// A pointer argument that must not be NULL was NULL.
    NullPointer = 1,
    /// The template text is not valid UTF-8.
    InvalidUtf8 = 2,
    /// The handle is not a live handle of the expected kind: already freed, never
    /// created, or a handle of the other kind.
    InvalidHandle = 3,
    /// An argument has a value the library cannot accept: an unknown enumerated value
    /// (target, dialect), a pointer not aligned for its type, a base direction that is
    /// not finite or beyond ±1e9 degrees, a length larger than any buffer can be.
    /// `rotlang_last_error` says which.
    InvalidArgument = 4,
    /// The model is unusable: no layers, a height that is NaN, zero, negative or out of
    /// range, too many layers. `rotlang_last_error` says which.
    InvalidModel = 5,
    /// The template has errors, so the rotlang dialect cannot evaluate it (read its
    /// diagnostics; the OrcaSlicer dialect evaluates any text).
    TemplateHasErrors = 6,
    /// A layer index or range reaches past the top of the model.
    OutOfRange = 7,
    /// An output buffer is shorter than the layer range asked for.
    BufferTooSmall = 8,
    // Value 9 is unused: it was DIALECT_UNAVAILABLE, which no build ever returned (both
    // dialects are always compiled in); removed before the first release, and the values
    // around it keep their numbers.
    /// An internal error (a bug in rotlang): the call had no effect. Please report it
    /// with `rotlang_last_error`'s message.
    Internal = 10,
}

impl RotlangStatus {
    fn text(self) -> &'static str {
        match self {
            RotlangStatus::Ok => "ok\0",
            RotlangStatus::NullPointer => "a required pointer argument is NULL\0",
            RotlangStatus::InvalidUtf8 => "the template text is not valid UTF-8\0",
            RotlangStatus::InvalidHandle => {
                "not a live handle of this kind (freed twice, never created, or the other kind)\0"
            }
            RotlangStatus::InvalidArgument => "an argument has a value the library cannot accept\0",
            RotlangStatus::InvalidModel => "the model is invalid\0",
            RotlangStatus::TemplateHasErrors => {
                "the template has errors; read its diagnostics (or use the OrcaSlicer dialect)\0"
            }
            RotlangStatus::OutOfRange => "the layer index or range reaches past the model's top\0",
            RotlangStatus::BufferTooSmall => "an output buffer is too small for the layer range\0",
            RotlangStatus::Internal => "internal error in rotlang (please report it)\0",
        }
    }
}

/// A failure: the status and, when there is more to say than the status's own text,
/// the detail (e.g. which layer height is wrong).
#[derive(Debug)]
pub(crate) struct Failure {
    pub status: RotlangStatus,
    pub detail: Option<String>,
}

impl From<RotlangStatus> for Failure {
    fn from(status: RotlangStatus) -> Self {
        Failure {
            status,
            detail: None,
        }
    }
}

impl Failure {
    pub(crate) fn with(status: RotlangStatus, detail: impl Into<String>) -> Self {
        Failure {
            status,
            detail: Some(detail.into()),
        }
    }
}

/// A refusal of the shared API (`rotlang::api`, what every binding checks its input
/// with): options are `INVALID_ARGUMENT`, the model `INVALID_MODEL`.
impl From<ApiError> for Failure {
    fn from(e: ApiError) -> Self {
        let status = match e.kind {
            // The C ABI reads no profile files.
            ErrorKind::Options | ErrorKind::Profile => RotlangStatus::InvalidArgument,
            ErrorKind::Model => RotlangStatus::InvalidModel,
        };
        Failure::with(status, e.message)
    }
}

thread_local! {
    /// The message of the last failed call on this thread.
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

fn remember(message: String) {
    // `try_with`: during thread teardown the slot may be gone; the status still tells.
    let _ = LAST_ERROR.try_with(|slot| *slot.borrow_mut() = message);
}

/// Runs the body of an exported function: a panic becomes `ROTLANG_STATUS_INTERNAL`
/// (never unwinding into C), and a failure's message is kept for `rotlang_last_error`.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> RotlangStatus {
    let outcome = catch_unwind(AssertUnwindSafe(body));
    let failure = match outcome {
        Ok(Ok(())) => return RotlangStatus::Ok,
        Ok(Err(failure)) => failure,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            Failure::with(RotlangStatus::Internal, format!("internal error: {what}"))
        }
    };
    let text = failure.status.text().trim_end_matches('\0');
    remember(match failure.detail {
        Some(detail) => format!("{text}: {detail}"),
        None => text.to_string(),
    });
    failure.status
}

/// A short English description of a status (a static NUL-terminated string; never NULL,
/// also for values outside the enum).
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_status_message(status: u32) -> *const c_char {
    use RotlangStatus::*;
    let known = [
        Ok,
        NullPointer,
        InvalidUtf8,
        InvalidHandle,
        InvalidArgument,
        InvalidModel,
        TemplateHasErrors,
        OutOfRange,
        BufferTooSmall,
        Internal,
    ];
    match known.iter().find(|s| **s as u32 == status) {
        Some(s) => s.text().as_ptr().cast(),
        None => c"unknown status".as_ptr(),
    }
}

/// The message of the last failed call on the calling thread, with its detail (which
/// layer height is wrong, which index is out of range). Copies at most `capacity - 1`
/// bytes and a NUL into `buffer` and returns the message's full length in bytes (without
/// the NUL), as `snprintf` does: call with `buffer = NULL, capacity = 0` to size a buffer.
/// An empty string when no call has failed on this thread.
///
/// # Safety
/// `buffer` is NULL or points to `capacity` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_last_error(buffer: *mut c_char, capacity: usize) -> usize {
    let copy = |message: &String| {
        let bytes = message.as_bytes();
        if !buffer.is_null() && capacity > 0 {
            let n = bytes.len().min(capacity - 1);
            // SAFETY: the caller gives `capacity` writable bytes at `buffer`; n < capacity.
            unsafe {
                std::ptr::copy_nonoverlapping(bytes.as_ptr(), buffer.cast::<u8>(), n);
                *buffer.add(n) = 0;
            }
        }
        bytes.len()
    };
    LAST_ERROR
        .try_with(|slot| copy(&slot.borrow()))
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last_error() -> String {
        // SAFETY: a NULL buffer with capacity 0 only asks for the length; then 256 bytes.
        let mut buffer = [0 as c_char; 256];
        unsafe { rotlang_last_error(buffer.as_mut_ptr(), buffer.len()) };
        // SAFETY: rotlang_last_error NUL-terminates within the buffer.
        unsafe { std::ffi::CStr::from_ptr(buffer.as_ptr()) }
            .to_string_lossy()
            .into_owned()
    }

    #[test]
    fn a_panic_becomes_internal_with_its_message() {
        let status = guard(|| panic!("index 7 out of bounds"));
        assert_eq!(status, RotlangStatus::Internal);
        let message = last_error();
        assert!(
            message.starts_with("internal error in rotlang")
                && message.contains("index 7 out of bounds"),
            "{message}"
        );
        // A formatted (String) payload too.
        let n = 3;
        assert_eq!(
            guard(|| panic!("layer {n} missing")),
            RotlangStatus::Internal
        );
        assert!(last_error().contains("layer 3 missing"));
        // And the next successful call leaves the message of the failure in place.
        assert_eq!(guard(|| Ok(())), RotlangStatus::Ok);
        assert!(last_error().contains("layer 3 missing"));
    }

    #[test]
    fn every_status_has_its_own_text() {
        for status in 0..=10u32 {
            // SAFETY: a static NUL-terminated string.
            let text = unsafe { std::ffi::CStr::from_ptr(rotlang_status_message(status)) };
            let text = text.to_str().unwrap();
            assert_eq!(text == "unknown status", status == 9, "{status}: {text}");
        }
        let failure = Failure::with(
            RotlangStatus::InvalidArgument,
            "the output pointer is not aligned for its type",
        );
        assert_eq!(guard(|| Err(failure)), RotlangStatus::InvalidArgument);
        assert_eq!(
            last_error(),
            "an argument has a value the library cannot accept: the output pointer is not aligned for its type"
        );
    }
}
