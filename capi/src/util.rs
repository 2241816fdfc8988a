//! Turning C pointers into Rust references, with NULL and alignment checked first.

use crate::status::{Failure, RotlangStatus};

fn check<T>(ptr: *const T, what: &str) -> Result<(), Failure> {
    if ptr.is_null() {
        return Err(Failure::with(RotlangStatus::NullPointer, what.to_string()));
    }
    if !ptr.is_aligned() {
        return Err(Failure::with(
            RotlangStatus::InvalidArgument,
            format!("{what} is not aligned for its type"),
        ));
    }
    Ok(())
}

/// `*ptr` as a mutable reference to write a result into.
///
/// # Safety
/// `ptr` is NULL or points to a writable `T`.
pub(crate) unsafe fn out<'a, T>(ptr: *mut T) -> Result<&'a mut T, Failure> {
    check(ptr, "the output pointer")?;
    // SAFETY: not NULL, aligned; writable by the caller's contract. Only plain-old-data
    // types are written through it (no drop of the old value matters).
    Ok(unsafe { &mut *ptr })
}

/// `*ptr` as a shared reference to an input.
///
/// # Safety
/// `ptr` is NULL or points to a readable `T`.
pub(crate) unsafe fn input<'a, T>(ptr: *const T, what: &str) -> Result<&'a T, Failure> {
    check(ptr, what)?;
    // SAFETY: not NULL, aligned; readable by the caller's contract.
    Ok(unsafe { &*ptr })
}

/// `len` bytes at `ptr`; NULL is allowed when `len` is 0.
///
/// # Safety
/// `ptr` points to `len` readable bytes (or is NULL with `len == 0`).
pub(crate) unsafe fn bytes<'a>(ptr: *const u8, len: usize) -> Result<&'a [u8], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    check(ptr, "the text pointer")?;
    fits::<u8>(len, "the text")?;
    // SAFETY: the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// `len` elements at `ptr`, which must not be NULL.
///
/// # Safety
/// `ptr` points to `len` readable `T`s.
pub(crate) unsafe fn slice<'a, T>(
    ptr: *const T,
    len: usize,
    what: &str,
) -> Result<&'a [T], Failure> {
    check(ptr, what)?;
    fits::<T>(len, what)?;
    // SAFETY: the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// `len` writable elements at `ptr`, which must not be NULL.
///
/// # Safety
/// `ptr` points to `len` writable `T`s.
pub(crate) unsafe fn slice_mut<'a, T>(
    ptr: *mut T,
    len: usize,
    what: &str,
) -> Result<&'a mut [T], Failure> {
    check(ptr, what)?;
    fits::<T>(len, what)?;
    // SAFETY: the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, len) })
}

/// No Rust slice may span more than `isize::MAX` bytes; a larger length cannot describe
/// real memory, so it is refused before a slice is formed.
fn fits<T>(len: usize, what: &str) -> Result<(), Failure> {
    let max = isize::MAX as usize / std::mem::size_of::<T>().max(1);
    if len > max {
        return Err(Failure::with(
            RotlangStatus::InvalidArgument,
            format!("{what} has length {len}, more than any buffer can hold"),
        ));
    }
    Ok(())
}
