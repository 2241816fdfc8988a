//! Handing freed memory back to the system.
//!
//! Documents are analysed on worker threads, and glibc gives each thread its own malloc
//! arena; the memory a closed document's parse used stays in those arenas, free but
//! resident, until something trims them. A server that ran a 4 MiB template for a while
//! should return to its idle size when the document is closed.

/// Return the free memory of every malloc arena to the system (glibc's `malloc_trim`);
/// nothing elsewhere, where the allocator does not keep per-thread arenas this way.
pub fn release() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        unsafe extern "C" {
            fn malloc_trim(pad: usize) -> std::ffi::c_int;
        }
        // SAFETY: `malloc_trim` takes no pointers and only releases memory that is free;
        // glibc documents it as safe to call at any time, from any thread.
        unsafe {
            malloc_trim(0);
        }
    }
}
