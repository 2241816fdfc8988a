//! Working buffers kept per thread from one layer to the next: a layer of a small region
//! (a star's, an L's) is a few thousand instructions, of which each allocation and free
//! of a working list is a few hundred. A buffer is taken (empty, with the capacity it
//! grew to), used, and given back cleared; a nested or concurrent use finds none and
//! allocates its own, so nothing depends on what the pool holds. Buffers past
//! `LARGEST` elements are freed, not kept (a huge layer's lists are not held on to).

use std::cell::Cell;
use std::thread::LocalKey;

/// The most elements a buffer kept may hold room for: a small layer's lists (where an
/// allocation is a noticeable part of the work) are kept, a large one's are not held on
/// to (at most a few hundred kB a thread in all).
const LARGEST: usize = 1 << 12;

/// A pool of one buffer per thread.
pub(crate) type Pool<T> = LocalKey<Cell<Vec<T>>>;

/// The pool's buffer (empty), or a new one.
#[inline]
pub(crate) fn take<T: 'static>(pool: &'static Pool<T>) -> Vec<T> {
    pool.try_with(Cell::take).unwrap_or_default()
}

/// Gives `buffer` back to the pool, cleared (freed instead when larger than `LARGEST`).
#[inline]
pub(crate) fn give<T: 'static>(pool: &'static Pool<T>, mut buffer: Vec<T>) {
    if buffer.capacity() == 0 || buffer.capacity() > LARGEST {
        return;
    }
    buffer.clear();
    // During the thread's teardown the pool may be gone: the buffer is freed.
    let _ = pool.try_with(|cell| cell.set(buffer));
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        static POOL: Cell<Vec<u32>> = const { Cell::new(Vec::new()) };
    }

    /// A buffer given back is handed out again empty with its room; a second taker
    /// while it is out gets a new one; a huge one is not kept.
    #[test]
    fn buffers_come_back_empty_with_their_room() {
        let mut a = take(&POOL);
        assert_eq!(a.capacity(), 0);
        a.extend(0..100);
        let nested = take(&POOL);
        assert_eq!(nested.capacity(), 0);
        give(&POOL, a);
        let b = take(&POOL);
        assert!(b.is_empty() && b.capacity() >= 100);
        give(&POOL, Vec::with_capacity(LARGEST + 1));
        assert_eq!(take(&POOL).capacity(), 0);
        give(&POOL, b);
    }
}
