//! Handles: what C holds is an id, never an address of Rust memory.
//!
//! Every live handle is in one registry, keyed by an id that is never reused. A call looks
//! its handle up (a short lock), clones the `Arc` and works on that clone with the lock
//! released. So a handle freed twice, a pointer that was never a handle, a template passed
//! where an evaluator is expected, or a handle used after its free are all
//! `ROTLANG_STATUS_INVALID_HANDLE` and never touch freed memory; and a free while another
//! thread is still evaluating the same template only drops the registry's reference: the
//! evaluation finishes on its own.

use std::any::Any;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, MutexGuard};

use crate::status::{Failure, RotlangStatus};

/// An opaque parsed template (see `rotlang_parse`). Immutable: any number of threads may
/// evaluate one template at the same time.
pub struct RotlangTemplate {
    _private: [u8; 0],
}

/// An opaque layer-by-layer evaluator (see `rotlang_evaluator_new`). It holds a cursor,
/// so calls on one evaluator are serialised (safe from any thread, but not parallel):
/// give each thread its own.
pub struct RotlangEvaluator {
    _private: [u8; 0],
}

/// A kind of handle: the C type that stands for it and the name of the kind in messages.
/// The registry holds any `Send + Sync` value, so it needs nothing of the modules that
/// define them (`template`, `evaluator` import this one; this one imports neither, which
/// keeps the module graph acyclic).
pub(crate) trait Kind {
    const NAME: &'static str;
}

impl Kind for RotlangTemplate {
    const NAME: &'static str = "template";
}

impl Kind for RotlangEvaluator {
    const NAME: &'static str = "evaluator";
}

type Entry = Arc<dyn Any + Send + Sync>;

struct Registry {
    /// The next id to hand out. Ids are multiples of 16 from 0x1000, so a handle never
    /// looks like NULL or a small integer, and never repeats.
    next: usize,
    live: BTreeMap<usize, Entry>,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    next: 0x1000,
    live: BTreeMap::new(),
});

/// The registry, even after a panic elsewhere poisoned its lock: every change to it is a
/// single insert or remove, so it is never left half-updated.
fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The number of live handles (templates and evaluators).
pub(crate) fn live() -> usize {
    registry().live.len()
}

/// A new handle of kind `H` holding `value`. Each kind of handle holds values of one
/// type only (a template handle a `TemplateData`, an evaluator handle a
/// `Mutex<EvaluatorState>`), so the type of the value tells the kind apart.
pub(crate) fn new<H: Kind, T: Any + Send + Sync>(value: T) -> *mut H {
    let mut registry = registry();
    let id = registry.next;
    registry.next += 16;
    registry.live.insert(id, Arc::new(value));
    std::ptr::without_provenance_mut(id)
}

fn null_or(ptr: usize) -> Result<usize, Failure> {
    if ptr == 0 {
        Err(RotlangStatus::NullPointer.into())
    } else {
        Ok(ptr)
    }
}

fn invalid<H: Kind>() -> Failure {
    Failure::with(
        RotlangStatus::InvalidHandle,
        format!("not a live {} handle", H::NAME),
    )
}

/// The value of a live handle of kind `H` holding a `T`.
pub(crate) fn get<H: Kind, T: Any + Send + Sync>(handle: *const H) -> Result<Arc<T>, Failure> {
    let id = null_or(handle.addr())?;
    let entry = registry().live.get(&id).map(Arc::clone);
    entry
        .and_then(|entry| entry.downcast::<T>().ok())
        .ok_or_else(invalid::<H>)
}

/// Removes a handle of kind `H` holding a `T`. The value is dropped outside the lock
/// (and later, if another thread is still using it).
pub(crate) fn free<H: Kind, T: Any + Send + Sync>(handle: *const H) -> Result<(), Failure> {
    let id = null_or(handle.addr())?;
    let removed = {
        let mut registry = registry();
        match registry.live.get(&id) {
            Some(entry) if entry.is::<T>() => registry.live.remove(&id),
            _ => None,
        }
    };
    removed.map(drop).ok_or_else(invalid::<H>)
}
