//! Layer-by-layer evaluation: a handle that owns its model and a cursor.

use std::sync::{Arc, Mutex};

use rotlang::eval::{self, Layer, Model};
use self_cell::self_cell;

use crate::handle::{self, RotlangEvaluator, RotlangTemplate};
use crate::model::{RotlangDialect, RotlangFill, RotlangModel, RotlangOptions, Settings};
use crate::status::{Failure, RotlangStatus, guard};
use crate::stream::{RotlangFinding, RotlangFindings, Stream, report};
use crate::template::TemplateData;
use crate::util::input;

/// One evaluated layer.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RotlangLayer {
    pub index: usize,
    /// Bottom and top of the layer, mm above the object's bottom.
    pub bottom: f64,
    pub top: f64,
    /// Degrees, base included, not wrapped; always finite.
    pub angle: f64,
    pub fill: RotlangFill,
}

impl From<Layer> for RotlangLayer {
    fn from(l: Layer) -> Self {
        RotlangLayer {
            index: l.index,
            bottom: l.bottom,
            top: l.top,
            angle: l.angle,
            fill: l.fill.into(),
        }
    }
}

/// What the cursor borrows: the template (shared with its handle) and the model copy.
pub(crate) struct Owner {
    template: Arc<TemplateData>,
    model: Model,
    settings: Settings,
}

/// The cursor of one dialect.
pub(crate) enum Cursor<'a> {
    /// rotlang's own random access (checkpoints; going back is cheap).
    Rotlang(eval::Evaluator<'a>),
    /// A stream for the other dialects: forward is O(1) per layer, going back restarts
    /// from the bottom.
    Stream {
        stream: Stream<'a>,
        last: Option<Layer>,
        /// The findings of the furthest-reaching stream this cursor dropped when it went
        /// back, and how far it had gone: a stream is deterministic, so those cover
        /// everything below `kept_to`, and the findings of the layers gone through are
        /// the ones of whichever stream went further.
        kept: Vec<RotlangFinding>,
        kept_to: usize,
    },
}

self_cell!(
    struct Cell {
        owner: Owner,
        #[covariant]
        dependent: Cursor,
    }
);

/// What an evaluator handle holds (behind a mutex: the cursor moves).
pub(crate) struct EvaluatorState {
    cell: Cell,
}

impl EvaluatorState {
    fn new(owner: Owner) -> Result<EvaluatorState, Failure> {
        let cell = Cell::try_new(owner, open)?;
        Ok(EvaluatorState { cell })
    }

    fn layer(&mut self, index: usize) -> Result<Layer, Failure> {
        let len = self.cell.borrow_owner().model.len();
        if index >= len {
            return Err(Failure::with(
                RotlangStatus::OutOfRange,
                format!("layer {index} of a model with {len} layers"),
            ));
        }
        self.cell.with_dependent_mut(|owner, cursor| match cursor {
            Cursor::Rotlang(evaluator) => evaluator
                .layer(index)
                .ok_or_else(|| Failure::with(RotlangStatus::Internal, "layer missing")),
            Cursor::Stream {
                stream,
                last,
                kept,
                kept_to,
            } => {
                if let Some(l) = last.filter(|l| l.index == index) {
                    return Ok(l);
                }
                if index < stream.layer_position() {
                    let fresh = Stream::open(&owner.template, &owner.model, owner.settings)?;
                    let old = std::mem::replace(stream, fresh);
                    if old.layer_position() > *kept_to {
                        *kept_to = old.layer_position();
                        *kept = old.findings();
                    }
                }
                stream.seek(index);
                *last = stream.next();
                last.ok_or_else(|| Failure::with(RotlangStatus::Internal, "layer missing"))
            }
        })
    }

    fn findings(&self) -> Vec<RotlangFinding> {
        match self.cell.borrow_dependent() {
            Cursor::Rotlang(_) => Vec::new(),
            Cursor::Stream {
                stream,
                kept,
                kept_to,
                ..
            } => match stream.layer_position() >= *kept_to {
                true => stream.findings(),
                false => kept.clone(),
            },
        }
    }
}

/// The state of a live evaluator handle.
fn state(handle: *const RotlangEvaluator) -> Result<Arc<Mutex<EvaluatorState>>, Failure> {
    handle::get(handle)
}

fn open(owner: &Owner) -> Result<Cursor<'_>, Failure> {
    let stream = Stream::open(&owner.template, &owner.model, owner.settings)?;
    Ok(match owner.settings.dialect {
        // The stream checked the template; the rotlang dialect has a better cursor.
        RotlangDialect::Rotlang => Cursor::Rotlang(eval::Evaluator::new(
            &owner.template.parsed().parse.template,
            &owner.model,
            owner.settings.options,
        )),
        _ => Cursor::Stream {
            stream,
            last: None,
            kept: Vec::new(),
            kept_to: 0,
        },
    })
}

/// A new evaluator for `template` on `model` (copied: the caller's heights may be freed
/// afterwards) with `options` (NULL: defaults). Free it with `rotlang_evaluator_free`; it
/// keeps the template alive on its own, so the template may be freed first.
///
/// Asking for increasing layers costs O(1) per layer. Going back costs at most a few
/// thousand layers in the rotlang dialect (checkpoints), up to the whole way from the
/// bottom in the OrcaSlicer dialect. An evaluator has a cursor, so calls on one evaluator
/// are serialised by a lock: give each thread its own.
///
/// # Safety
/// As `rotlang_expand` for `model` and `options`; `out` points to one writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_evaluator_new(
    template: *const RotlangTemplate,
    model: *const RotlangModel,
    options: *const RotlangOptions,
    out: *mut *mut RotlangEvaluator,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract.
        let out = unsafe { crate::util::out(out) }?;
        *out = std::ptr::null_mut();
        let template = crate::template::data(template)?;
        // SAFETY: the caller's contract.
        let model = unsafe { input(model, "the model")?.checked_model() }?;
        let options = (!options.is_null())
            // SAFETY: the caller's contract.
            .then(|| unsafe { input(options, "the options") })
            .transpose()?;
        let settings = Settings::from_c(options)?;
        let state = EvaluatorState::new(Owner {
            template,
            model,
            settings,
        })?;
        *out = handle::new::<RotlangEvaluator, _>(Mutex::new(state));
        Ok(())
    })
}

/// Layer `index` of the evaluator's model (`OUT_OF_RANGE` at or past the top).
///
/// # Safety
/// `out` points to one writable `RotlangLayer`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_evaluator_layer(
    evaluator: *mut RotlangEvaluator,
    index: usize,
    out: *mut RotlangLayer,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract.
        let out = unsafe { crate::util::out(out) }?;
        let state = state(evaluator)?;
        let mut state = state.lock().unwrap_or_else(|p| p.into_inner());
        *out = state.layer(index)?.into();
        Ok(())
    })
}

/// The OrcaSlicer dialect's findings on the layers this evaluator has gone through (also
/// after it went back to a lower layer, which restarts its stream from the bottom).
///
/// # Safety
/// `findings` points to a valid `RotlangFindings`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_evaluator_findings(
    evaluator: *const RotlangEvaluator,
    findings: *mut RotlangFindings,
) -> RotlangStatus {
    guard(|| {
        if findings.is_null() {
            return Err(Failure::with(RotlangStatus::NullPointer, "findings"));
        }
        let state = state(evaluator)?;
        let found = state.lock().unwrap_or_else(|p| p.into_inner()).findings();
        // SAFETY: the caller's contract.
        unsafe { report(findings, &found) }
    })
}

/// Frees an evaluator. NULL is `NULL_POINTER`; a second free is `INVALID_HANDLE`.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_evaluator_free(evaluator: *mut RotlangEvaluator) -> RotlangStatus {
    guard(|| handle::free::<_, Mutex<EvaluatorState>>(evaluator))
}
