//! Handles: what C holds is an id, never an address of Rust memory.
//!
//! Every live handle is in one registry, keyed by an id that is never reused. A call looks
//! its handle up (a short lock), clones the `Arc` and works on that clone with the lock
//! released. So a handle freed twice, a pointer that was never a handle, a template passed
//! where an evaluator is expected, or a handle used after its free are all
//! `ROTLANG_STATUS_INVALID_HANDLE` and never touch freed memory; and a free while another
//! thread is still evaluating the same template only drops the registry's reference: the
//! evaluation finishes on its own.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, MutexGuard};

use crate::evaluator::EvaluatorState;
use crate::status::{Failure, RotlangStatus};
use crate::template::TemplateData;

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

enum Entry {
    Template(Arc<TemplateData>),
    Evaluator(Arc<Mutex<EvaluatorState>>),
}

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

fn insert(entry: Entry) -> usize {
    let mut registry = registry();
    let id = registry.next;
    registry.next += 16;
    registry.live.insert(id, entry);
    id
}

/// The number of live handles (templates and evaluators).
pub(crate) fn live() -> usize {
    registry().live.len()
}

pub(crate) fn new_template(data: TemplateData) -> *mut RotlangTemplate {
    std::ptr::without_provenance_mut(insert(Entry::Template(Arc::new(data))))
}

pub(crate) fn new_evaluator(state: EvaluatorState) -> *mut RotlangEvaluator {
    std::ptr::without_provenance_mut(insert(Entry::Evaluator(Arc::new(Mutex::new(state)))))
}

fn null_or(ptr: usize) -> Result<usize, Failure> {
    if ptr == 0 {
        Err(RotlangStatus::NullPointer.into())
    } else {
        Ok(ptr)
    }
}

fn invalid(what: &str) -> Failure {
    Failure::with(
        RotlangStatus::InvalidHandle,
        format!("not a live {what} handle"),
    )
}

pub(crate) fn template(handle: *const RotlangTemplate) -> Result<Arc<TemplateData>, Failure> {
    let id = null_or(handle.addr())?;
    match registry().live.get(&id) {
        Some(Entry::Template(data)) => Ok(Arc::clone(data)),
        _ => Err(invalid("template")),
    }
}

pub(crate) fn evaluator(
    handle: *const RotlangEvaluator,
) -> Result<Arc<Mutex<EvaluatorState>>, Failure> {
    let id = null_or(handle.addr())?;
    match registry().live.get(&id) {
        Some(Entry::Evaluator(state)) => Ok(Arc::clone(state)),
        _ => Err(invalid("evaluator")),
    }
}

/// Removes a template handle. The data is dropped outside the lock (and later, if another
/// thread is still using it).
pub(crate) fn free_template(handle: *const RotlangTemplate) -> Result<(), Failure> {
    let id = null_or(handle.addr())?;
    let removed = {
        let mut registry = registry();
        match registry.live.get(&id) {
            Some(Entry::Template(_)) => registry.live.remove(&id),
            _ => None,
        }
    };
    removed.map(drop).ok_or_else(|| invalid("template"))
}

pub(crate) fn free_evaluator(handle: *const RotlangEvaluator) -> Result<(), Failure> {
    let id = null_or(handle.addr())?;
    let removed = {
        let mut registry = registry();
        match registry.live.get(&id) {
            Some(Entry::Evaluator(_)) => registry.live.remove(&id),
            _ => None,
        }
    };
    removed.map(drop).ok_or_else(|| invalid("evaluator"))
}
