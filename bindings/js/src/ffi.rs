//! The exports. Inputs are (pointer, length) pairs into memory from [`rotlang_alloc`];
//! every call returns 0 on success, 1 on failure, and leaves its JSON answer in the
//! output buffer. Single-threaded (wasm32-unknown-unknown), so the buffers are
//! thread-locals.

use std::alloc::Layout;
use std::cell::RefCell;

use crate::json::Value;

use crate::Failure;
use crate::api::{self, Layers};
use crate::options::Request;

thread_local! {
    static OUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static LAYERS: RefCell<Layers> = RefCell::new(Layers::default());
    /// The last `check`'s instruction spans, four u32 each (`api::check`).
    static SPANS: RefCell<Vec<u32>> = const { RefCell::new(Vec::new()) };
    /// The mesh of the last `rotlang_mesh` (kept so that each template or slider change
    /// slices it again without copying the file in again).
    #[cfg(feature = "full")]
    static MESH: RefCell<Option<crate::part::Kept>> = const { RefCell::new(None) };
}

/// Inputs are aligned for f64 (the request slots and layer heights are f64 arrays, which
/// JavaScript's Float64Array views and Rust's slices both need aligned).
fn layout(len: usize) -> Option<Layout> {
    Layout::from_size_align(len.max(1), 8).ok()
}

/// Memory for JavaScript to write an input into (8-byte aligned); freed with
/// [`rotlang_dealloc`]. Null when it cannot be had.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_alloc(len: usize) -> *mut u8 {
    match layout(len) {
        // SAFETY: the layout has a non-zero size.
        Some(l) => unsafe { std::alloc::alloc(l) },
        None => std::ptr::null_mut(),
    }
}

/// Frees memory from [`rotlang_alloc`] (same length).
///
/// # Safety
/// `ptr` and `len` must come from one call of `rotlang_alloc`, freed once.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_dealloc(ptr: *mut u8, len: usize) {
    if let (false, Some(l)) = (ptr.is_null(), layout(len)) {
        // SAFETY: the caller passes back what rotlang_alloc gave, with its length.
        unsafe { std::alloc::dealloc(ptr, l) }
    }
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_out_ptr() -> *const u8 {
    OUT.with_borrow(|o| o.as_ptr())
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_out_len() -> usize {
    OUT.with_borrow(Vec::len)
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_layers_len() -> usize {
    LAYERS.with_borrow(|l| l.angles.len())
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_angles_ptr() -> *const f64 {
    LAYERS.with_borrow(|l| l.angles.as_ptr())
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_fills_ptr() -> *const u8 {
    LAYERS.with_borrow(|l| l.fills.as_ptr())
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_instructions_ptr() -> *const i32 {
    LAYERS.with_borrow(|l| l.instructions.as_ptr())
}

/// The last `check`'s instruction spans: `rotlang_spans_len` u32s, four per instruction.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_spans_ptr() -> *const u32 {
    SPANS.with_borrow(|s| s.as_ptr())
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_spans_len() -> usize {
    SPANS.with_borrow(Vec::len)
}

/// Frees the last `expand`'s or `check`'s arrays (JavaScript has copied them).
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_release() {
    LAYERS.with_borrow_mut(|l| *l = Layers::default());
    SPANS.with_borrow_mut(|s| *s = Vec::new());
    OUT.with_borrow_mut(|o| *o = Vec::new());
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_version() -> i32 {
    finish(Ok(api::version()))
}

#[unsafe(no_mangle)]
pub extern "C" fn rotlang_signs() -> i32 {
    finish(Ok(api::signs()))
}

/// # Safety
/// `text`/`text_len`: UTF-8 bytes; `req`/`req_len`: the request's f64 slots
/// (`options::slot`). Each must be readable memory (from `rotlang_alloc`), or a length of 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_check(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }
        .and_then(|(t, r)| SPANS.with_borrow_mut(|spans| api::check(t, &r, spans)));
    if result.is_err() {
        SPANS.with_borrow_mut(Vec::clear);
    }
    finish(result)
}

/// # Safety
/// As [`rotlang_check`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_format(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    finish(unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| api::format(t, &r)))
}

/// `heights`/`count`: the layer heights of a list model (`count` f64s), or a count of 0.
///
/// # Safety
/// As [`rotlang_check`]; `heights` must hold `count` f64s when `count` > 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_expand(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        LAYERS.with_borrow_mut(|out| api::expand(t, &r, heights, out))
    });
    if result.is_err() {
        LAYERS.with_borrow_mut(|l| *l = Layers::default());
    }
    finish(result)
}

/// The template in words on a model.
///
/// # Safety
/// As [`rotlang_expand`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_explain(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        api::explain(t, &r, heights)
    });
    finish(result)
}

/// A diagnostic code explained: the code is the text; the request is ignored.
///
/// # Safety
/// As [`rotlang_check`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_explain_code(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    finish(unsafe { inputs(text, text_len, req, req_len) }.map(|(t, _)| api::explain_code(t)))
}

/// As [`rotlang_expand`], for the compat lint.
///
/// # Safety
/// As [`rotlang_expand`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_compat(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        api::compat(t, &r, heights)
    });
    finish(result)
}

#[cfg(feature = "full")]
/// A profile file: its name (UTF-8) and its bytes (any: a file that is not UTF-8 text is
/// reported as such).
///
/// # Safety
/// Each (pointer, length) pair must be readable memory, or a length of 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_profile(
    name: *const u8,
    name_len: usize,
    bytes: *const u8,
    bytes_len: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let name = unsafe { utf8(name, name_len) }.unwrap_or("profile");
    let bytes = if bytes.is_null() || bytes_len == 0 {
        &[][..]
    } else {
        // SAFETY: forwarded from this function's contract.
        unsafe { std::slice::from_raw_parts(bytes, bytes_len) }
    };
    finish(api::profile(name, bytes))
}

#[cfg(feature = "full")]
/// As [`rotlang_expand`], for `plot` (a JSON answer only).
///
/// # Safety
/// As [`rotlang_expand`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_plot(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        api::plot(t, &r, heights)
    });
    finish(result)
}

#[cfg(feature = "full")]
/// As [`rotlang_expand`], for `preview` (a JSON answer only).
///
/// # Safety
/// As [`rotlang_expand`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_preview(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        api::preview(t, &r, heights)
    });
    finish(result)
}

#[cfg(feature = "full")]
/// A mesh file (STL, OBJ, 3MF by its name's extension): read and kept for `rotlang_part`
/// (a file that cannot be read leaves no mesh). The answer: its size and bounds.
///
/// # Safety
/// As [`rotlang_profile`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_mesh(
    name: *const u8,
    name_len: usize,
    bytes: *const u8,
    bytes_len: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let name = unsafe { utf8(name, name_len) }.unwrap_or("mesh");
    let bytes = if bytes.is_null() || bytes_len == 0 {
        &[][..]
    } else {
        // SAFETY: forwarded from this function's contract.
        unsafe { std::slice::from_raw_parts(bytes, bytes_len) }
    };
    MESH.with_borrow_mut(|m| *m = None);
    let result = crate::part::read_mesh(name, bytes).map(|kept| {
        let answer = crate::part::mesh_json(&kept);
        MESH.with_borrow_mut(|m| *m = Some(kept));
        answer
    });
    finish(result)
}

#[cfg(feature = "full")]
/// The kept mesh (all its objects, or the 3MF object `object`) sliced and filled under
/// the template (`rotlang_geometry::slice::Part`): every layer's section, areas and infill
/// paths (or those of `from`..`to`), as `rotlang preview --shape part.stl [--object NAME]
/// --format json`. `walls`: wall loops (NaN: the project's, else 2); `has_solid`: 1 where
/// `solid` is the solid template (`--solid-template`), 2 for none even where a project
/// sets one (`--no-solid-template`), 0 for the project's own; `has_object` likewise for
/// `object`; `settings_only` (1 or 0): the answer without slicing (what the part is filled
/// with).
///
/// # Safety
/// As [`rotlang_check`]; `solid` and `object` as `text`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn rotlang_part(
    text: *const u8,
    text_len: usize,
    solid: *const u8,
    solid_len: usize,
    object: *const u8,
    object_len: usize,
    req: *const f64,
    req_len: usize,
    walls: f64,
    has_solid: f64,
    has_object: f64,
    settings_only: f64,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // 1: the solid template given; 2: none, even a project's; else the file's.
        let solid = if has_solid == 1.0 {
            // SAFETY: as above.
            match unsafe { utf8(solid, solid_len) } {
                Some(s) => crate::part::Solid::Given(s),
                None => return Err(Failure::options("the solid template is not UTF-8")),
            }
        } else if has_solid == 2.0 {
            crate::part::Solid::Off
        } else {
            crate::part::Solid::FromFile
        };
        let object = if has_object == 1.0 {
            // SAFETY: as above.
            match unsafe { utf8(object, object_len) } {
                Some(s) => Some(s),
                None => return Err(Failure::options("the object's name is not UTF-8")),
            }
        } else {
            None
        };
        MESH.with_borrow(|m| match m {
            Some(kept) => {
                crate::part::part(kept, t, solid, &r, (walls, object, settings_only == 1.0))
            }
            None => Err(Failure::options("no mesh: read one with `readMesh` first")),
        })
    });
    finish(result)
}

/// As [`rotlang_expand`], for `compare` (no arrays out).
///
/// # Safety
/// As [`rotlang_expand`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_compare(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
    heights: *const f64,
    count: usize,
) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let result = unsafe { inputs(text, text_len, req, req_len) }.and_then(|(t, r)| {
        // SAFETY: as above.
        let heights = unsafe { f64s(heights, count) };
        api::compare(t, &r, heights)
    });
    finish(result)
}

/// Reads a call's inputs.
///
/// # Safety
/// As [`rotlang_check`].
unsafe fn inputs<'a>(
    text: *const u8,
    text_len: usize,
    req: *const f64,
    req_len: usize,
) -> Result<(&'a str, Request), Failure> {
    // SAFETY: forwarded.
    let text = unsafe { utf8(text, text_len) }
        .ok_or_else(|| Failure::options("the template is not valid UTF-8"))?;
    let slots = if req.is_null() || req_len == 0 {
        &[][..]
    } else {
        // SAFETY: forwarded: `req` holds `req_len` f64s.
        unsafe { std::slice::from_raw_parts(req, req_len) }
    };
    Ok((text, Request::new(slots)))
}

/// The number of a target (`which` 0: `sparse` 0, `solid` 1) or a dialect (`which` 1:
/// `rotlang` 0, `orcaslicer` 1) from its name, read by `rotlang::api` as the C and
/// Python bindings read names (any case); -1, with the failure in the output buffer, for
/// any other name.
///
/// # Safety
/// `name`/`len`: UTF-8 bytes (from `rotlang_alloc`), or a length of 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_choice(which: u32, name: *const u8, len: usize) -> i32 {
    // SAFETY: forwarded from this function's contract.
    let name = unsafe { utf8(name, len) }.unwrap_or("\u{FFFD}");
    let found = match which {
        0 => rotlang::api::target(name).map(|t| i32::from(t == rotlang::Target::Solid)),
        _ => rotlang::api::dialect(name)
            .map(|d| i32::from(d == rotlang::dialect::Dialect::OrcaSlicer)),
    };
    match found {
        Ok(i) => i,
        Err(e) => {
            finish(Err(e.into()));
            -1
        }
    }
}

/// # Safety
/// `ptr` must point to `len` readable bytes, or `len` must be 0.
unsafe fn utf8<'a>(ptr: *const u8, len: usize) -> Option<&'a str> {
    if len == 0 || ptr.is_null() {
        return Some("");
    }
    // SAFETY: guaranteed by the caller.
    std::str::from_utf8(unsafe { std::slice::from_raw_parts(ptr, len) }).ok()
}

/// # Safety
/// `ptr` must point to `count` f64s, or `count` must be 0.
unsafe fn f64s(ptr: *const f64, count: usize) -> Option<Vec<f64>> {
    if count == 0 || ptr.is_null() {
        return None;
    }
    // SAFETY: guaranteed by the caller.
    Some(unsafe { std::slice::from_raw_parts(ptr, count) }.to_vec())
}

/// Writes the answer (or the failure) to the output buffer; 0 = success, 1 = failure.
fn finish(result: Result<Value, Failure>) -> i32 {
    let (code, value) = match result {
        Ok(v) => (0, v),
        Err(f) => (1, f.to_json()),
    };
    OUT.with_borrow_mut(|o| {
        o.clear();
        let mut text = String::new();
        value.write(&mut text);
        *o = text.into_bytes();
    });
    code
}
