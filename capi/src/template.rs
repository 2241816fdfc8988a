//! Parsing into a template handle, and reading its diagnostics.

use std::ffi::{CString, c_char};
use std::sync::{Arc, OnceLock};

use rotlang::{Parse, Target};

use crate::handle::{self, RotlangTemplate};
use crate::status::{Failure, RotlangStatus, guard};
use crate::util::{self, bytes};

/// Which setting a template belongs to (the `target` argument of `rotlang_parse`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangTarget {
    /// `sparse_infill_rotate_template`.
    Sparse = 0,
    /// `solid_infill_rotate_template`: solid signs are errors there.
    Solid = 1,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangSeverity {
    Warning = 0,
    Error = 1,
}

/// One diagnostic of a template. The strings are NUL-terminated UTF-8 owned by the
/// template handle: valid until it is freed.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RotlangDiagnostic {
    /// Stable code, e.g. `rotlang::unknown-sign`.
    pub code: *const c_char,
    pub severity: RotlangSeverity,
    /// One line of English.
    pub message: *const c_char,
    /// Help text, or NULL when there is none.
    pub help: *const c_char,
    /// Byte offsets (not characters) of the primary span in the text given to
    /// `rotlang_parse`: `text[start..end)`.
    pub start: usize,
    pub end: usize,
}

/// A diagnostic in C form: the strings it points to live in the `CString`s beside it.
struct Stored {
    code: CString,
    message: CString,
    help: Option<CString>,
    severity: RotlangSeverity,
    start: usize,
    end: usize,
}

/// What a template handle holds; immutable once built, shared by every thread. rotlang's
/// own parse (the rotlang dialect's template and the diagnostics) is made on first use:
/// a slicer that evaluates only in the OrcaSlicer dialect, which reads the raw text,
/// never pays for it (a megabyte template parses in about half a second; the OrcaSlicer
/// dialect reads it in milliseconds).
pub(crate) struct TemplateData {
    pub text: String,
    target: Target,
    /// For text made by `lossy` from bytes that are not UTF-8: those bytes, to map the
    /// diagnostics' spans back to offsets in what the caller gave.
    raw: Option<Box<[u8]>>,
    parsed: OnceLock<Parsed>,
    /// Parsed by `rotlang_parse_bytes` from text that is not UTF-8: the offset of the
    /// first invalid byte. Only the OrcaSlicer dialect evaluates such a template.
    pub invalid_utf8: Option<usize>,
}

/// rotlang's parse of a template, and its diagnostics in C form.
pub(crate) struct Parsed {
    pub parse: Parse,
    diagnostics: Vec<Stored>,
}

/// `bytes` as text for a reader of bytes (OrcaSlicer's): valid UTF-8 stays as it is, each
/// byte that is not part of it becomes one U+FFFD. OrcaSlicer treats every byte above
/// 0x7F alike (none is a digit, sign, separator or letter it knows), and so does its
/// dialect with the bytes of U+FFFD, so the angles are the same as on the raw bytes.
/// Also returns, for every byte offset of the text (and its end), the offset in `bytes`.
fn lossy(bytes: &[u8]) -> (String, Vec<usize>) {
    let mut text = String::with_capacity(bytes.len());
    let mut origin = Vec::with_capacity(bytes.len() + 1);
    let mut at = 0;
    for chunk in bytes.utf8_chunks() {
        text.push_str(chunk.valid());
        origin.extend(at..at + chunk.valid().len());
        at += chunk.valid().len();
        for _ in chunk.invalid() {
            text.push(char::REPLACEMENT_CHARACTER);
            origin.extend([at; 3]);
            at += 1;
        }
    }
    origin.push(at);
    (text, origin)
}

/// A string without interior NULs (rotlang's messages have none; replace any as a guard).
fn c_string(s: &str) -> CString {
    CString::new(s.replace('\0', "\u{FFFD}")).unwrap_or_default()
}

/// The data of a live template handle.
pub(crate) fn data(handle: *const RotlangTemplate) -> Result<Arc<TemplateData>, Failure> {
    handle::get(handle)
}

impl TemplateData {
    pub(crate) fn new(text: String, target: Target) -> TemplateData {
        TemplateData {
            text,
            target,
            raw: None,
            parsed: OnceLock::new(),
            invalid_utf8: None,
        }
    }

    /// rotlang's parse and diagnostics, made on the first call.
    pub(crate) fn parsed(&self) -> &Parsed {
        self.parsed.get_or_init(|| self.parse_now())
    }

    fn parse_now(&self) -> Parsed {
        let origin = self.raw.as_deref().map(|raw| lossy(raw).1);
        let to_caller = |offset: usize| {
            origin
                .as_deref()
                .and_then(|o| o.get(offset).copied())
                .unwrap_or(offset)
        };
        let parse = rotlang::parse(&self.text, self.target);
        let diagnostics = parse
            .diagnostics
            .iter()
            .map(|d| {
                let span = d.primary_span();
                Stored {
                    code: c_string(d.code),
                    message: c_string(&d.message),
                    help: d.help.as_deref().map(c_string),
                    severity: match d.severity {
                        rotlang::Severity::Warning => RotlangSeverity::Warning,
                        rotlang::Severity::Error => RotlangSeverity::Error,
                    },
                    start: to_caller(span.start),
                    end: to_caller(span.end),
                }
            })
            .collect();
        Parsed { parse, diagnostics }
    }
}

/// Parses `length` bytes of UTF-8 at `text` (no NUL needed; NUL bytes inside are just
/// characters) for `target` (a `RotlangTarget`). On success `*out` is a new handle, also
/// when the template has errors: read them with `rotlang_template_diagnostic`. Free it
/// with `rotlang_template_free`. `text` may be NULL when `length` is 0 (the empty template).
///
/// Errors: `NULL_POINTER` (`out`, or `text` with `length > 0`), `INVALID_UTF8`,
/// `INVALID_ARGUMENT` (unknown target). On error `*out` is set to NULL.
///
/// # Safety
/// `text` points to `length` readable bytes; `out` to one writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_parse(
    text: *const c_char,
    length: usize,
    target: u32,
    out: *mut *mut RotlangTemplate,
) -> RotlangStatus {
    // SAFETY: the caller's contract, passed on.
    unsafe { parse(text, length, target, out, false) }
}

/// `rotlang_parse` (`keep_bytes` false: text that is not UTF-8 is refused) and
/// `rotlang_parse_bytes` (true: any bytes are kept).
///
/// # Safety
/// As `rotlang_parse`.
unsafe fn parse(
    text: *const c_char,
    length: usize,
    target: u32,
    out: *mut *mut RotlangTemplate,
    keep_bytes: bool,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract on `out`.
        let out = unsafe { util::out::<*mut RotlangTemplate>(out) }?;
        *out = std::ptr::null_mut();
        let target = decode_target(target)?;
        // SAFETY: the caller's contract on `text`.
        let bytes = unsafe { bytes(text.cast(), length) }?;
        let data = match std::str::from_utf8(bytes) {
            Ok(text) => TemplateData::new(text.to_owned(), target),
            Err(e) if !keep_bytes => {
                return Err(Failure::with(
                    RotlangStatus::InvalidUtf8,
                    format!("invalid byte at offset {}", e.valid_up_to()),
                ));
            }
            Err(e) => {
                let mut data = TemplateData::new(lossy(bytes).0, target);
                data.raw = Some(bytes.into());
                data.invalid_utf8 = Some(e.valid_up_to());
                data
            }
        };
        *out = handle::new::<RotlangTemplate, _>(data);
        Ok(())
    })
}

fn decode_target(target: u32) -> Result<Target, Failure> {
    Ok(rotlang::api::target_number(target.into())?)
}

/// As `rotlang_parse`, but any bytes are accepted, as OrcaSlicer reads its template:
/// byte by byte, whatever the encoding. Text that is valid UTF-8 gives the same template
/// as `rotlang_parse`. Otherwise each byte that is not part of valid UTF-8 is kept as one
/// unknown character (U+FFFD, which the diagnostics report as an error with the span of
/// that byte), and the template then evaluates in the OrcaSlicer dialect only, with the
/// angles OrcaSlicer computes on those bytes: `"+30\xb0"` gives what `"+30\xc2\xb0"`
/// gives. The rotlang dialect refuses it with `INVALID_UTF8`. Spans are byte offsets in
/// the bytes given.
///
/// Errors: `NULL_POINTER` (`out`, or `text` with `length > 0`), `INVALID_ARGUMENT`
/// (unknown target). On error `*out` is set to NULL.
///
/// # Safety
/// `text` points to `length` readable bytes; `out` to one writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_parse_bytes(
    text: *const c_char,
    length: usize,
    target: u32,
    out: *mut *mut RotlangTemplate,
) -> RotlangStatus {
    // SAFETY: the caller's contract, passed on.
    unsafe { parse(text, length, target, out, true) }
}

/// Frees a template. Freeing NULL is `NULL_POINTER`; freeing a handle twice (or a pointer
/// that is not a template handle) is `INVALID_HANDLE` and has no other effect. Evaluators
/// made from the template keep working: they hold their own reference.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_template_free(template: *mut RotlangTemplate) -> RotlangStatus {
    guard(|| handle::free::<_, TemplateData>(template))
}

/// The number of diagnostics (errors and warnings) of a template.
///
/// # Safety
/// `out` points to one writable `size_t`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_template_diagnostic_count(
    template: *const RotlangTemplate,
    out: *mut usize,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract on `out`.
        let out = unsafe { util::out::<usize>(out) }?;
        *out = data(template)?.parsed().diagnostics.len();
        Ok(())
    })
}

/// Whether the template has errors (`*out` = 1) or not (0). Warnings do not count.
///
/// # Safety
/// `out` points to one writable `int`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_template_has_errors(
    template: *const RotlangTemplate,
    out: *mut i32,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract on `out`.
        let out = unsafe { util::out::<i32>(out) }?;
        *out = i32::from(data(template)?.parsed().parse.has_errors());
        Ok(())
    })
}

/// Diagnostic number `index` (from 0, in text order). `OUT_OF_RANGE` past the count.
///
/// # Safety
/// `out` points to one writable `RotlangDiagnostic`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_template_diagnostic(
    template: *const RotlangTemplate,
    index: usize,
    out: *mut RotlangDiagnostic,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract on `out`.
        let out = unsafe { util::out::<RotlangDiagnostic>(out) }?;
        let data = data(template)?;
        let parsed = data.parsed();
        let d = parsed.diagnostics.get(index).ok_or_else(|| {
            Failure::with(
                RotlangStatus::OutOfRange,
                format!(
                    "diagnostic {index} of a template with {}",
                    parsed.diagnostics.len()
                ),
            )
        })?;
        // The pointers stay valid after `data` (this Arc clone) drops: the registry or
        // another user holds the data until the template is freed.
        *out = RotlangDiagnostic {
            code: d.code.as_ptr(),
            severity: d.severity,
            message: d.message.as_ptr(),
            help: d.help.as_ref().map_or(std::ptr::null(), |h| h.as_ptr()),
            start: d.start,
            end: d.end,
        };
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lossy_keeps_each_invalid_byte_as_one_character_and_maps_offsets_back() {
        let (text, origin) = lossy(b"+30\xb0, \xe2\x82X\xff");
        assert_eq!(text, "+30\u{FFFD}, \u{FFFD}\u{FFFD}X\u{FFFD}");
        assert_eq!(origin.len(), text.len() + 1);
        // `X` is byte 8 of the input (after `+30`, 0xb0, `, `, 0xe2, 0x82).
        assert_eq!(origin[text.find('X').unwrap()], 8);
        assert_eq!(*origin.last().unwrap(), 10);
        let (same, origin) = lossy("+30°".as_bytes());
        assert_eq!((same.as_str(), origin), ("+30°", vec![0, 1, 2, 3, 4, 5]));
    }
}
