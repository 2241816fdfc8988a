//! One stream of layers for either dialect, and the dialect's findings in C form.

use std::ffi::c_char;

use rotlang::dialect::{self, orcaslicer};
use rotlang::eval::{self, Layer, Model};

use crate::model::{RotlangDialect, Settings};
use crate::status::{Failure, RotlangStatus};
use crate::template::TemplateData;

/// A defect of OrcaSlicer's reading that rotlang's OrcaSlicer dialect found and worked
/// around (SEMANTICS.md section 10).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotlangFindingKind {
    /// OrcaSlicer never finishes slicing from `first_layer` (`orcaslicer::hangs`).
    Hangs = 1,
    /// A count outside the 32-bit range: OrcaSlicer's behaviour is undefined (it
    /// crashes) from `first_layer` (`orcaslicer::undefined`).
    Undefined = 2,
    /// OrcaSlicer's angle is NaN or infinite on `layers` layers from `first_layer`
    /// (`orcaslicer::nan`).
    Nan = 3,
}

/// One finding: its kind, the first layer it concerns and how many layers.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RotlangFinding {
    pub kind: RotlangFindingKind,
    pub first_layer: usize,
    pub layers: usize,
}

/// Where an evaluation reports its findings: the caller's array of `capacity` entries
/// (`items` may be NULL when `capacity` is 0). The library sets `count` to the number of
/// findings, which may exceed `capacity`: then only the first `capacity` were written.
/// The rotlang dialect never has findings (`count` = 0).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RotlangFindings {
    pub items: *mut RotlangFinding,
    pub capacity: usize,
    pub count: usize,
}

/// The stable code of a finding kind (`"orcaslicer::hangs"`, ...), a static
/// NUL-terminated string; `"unknown"` for other values.
#[unsafe(no_mangle)]
pub extern "C" fn rotlang_finding_code(kind: u32) -> *const c_char {
    match kind {
        1 => c"orcaslicer::hangs".as_ptr(),
        2 => c"orcaslicer::undefined".as_ptr(),
        3 => c"orcaslicer::nan".as_ptr(),
        _ => c"unknown".as_ptr(),
    }
}

/// The layers of a model under a template in one dialect.
pub(crate) enum Stream<'a> {
    Rotlang(eval::Layers<'a>),
    OrcaSlicer(orcaslicer::Layers<'a>),
}

fn to_c(finding: &dialect::Finding) -> RotlangFinding {
    let kind = match finding.code {
        dialect::HANGS => RotlangFindingKind::Hangs,
        dialect::UNDEFINED => RotlangFindingKind::Undefined,
        _ => RotlangFindingKind::Nan,
    };
    RotlangFinding {
        kind,
        first_layer: finding.first_layer,
        layers: finding.layers,
    }
}

impl<'a> Stream<'a> {
    pub(crate) fn open(
        data: &'a TemplateData,
        model: &'a Model,
        settings: Settings,
    ) -> Result<Stream<'a>, Failure> {
        match settings.dialect {
            RotlangDialect::Rotlang => {
                if let Some(at) = data.invalid_utf8 {
                    return Err(Failure::with(
                        RotlangStatus::InvalidUtf8,
                        format!(
                            "invalid byte at offset {at}; only the OrcaSlicer dialect reads such a template"
                        ),
                    ));
                }
                if data.parsed().parse.has_errors() {
                    return Err(RotlangStatus::TemplateHasErrors.into());
                }
                Ok(Stream::Rotlang(eval::layers(
                    &data.parsed().parse.template,
                    model,
                    settings.options,
                )))
            }
            // OrcaSlicer reads raw text, valid or not: parse errors do not matter.
            RotlangDialect::Orcaslicer => Ok(Stream::OrcaSlicer(orcaslicer::layers(
                &data.text,
                model,
                settings.options,
            ))),
        }
    }

    /// The index of the layer `next` yields.
    pub(crate) fn layer_position(&self) -> usize {
        match self {
            Stream::Rotlang(layers) => layers.position(),
            Stream::OrcaSlicer(layers) => layers.position(),
        }
    }

    /// The findings so far, in C form.
    pub(crate) fn findings(&self) -> Vec<RotlangFinding> {
        match self {
            Stream::Rotlang(_) => Vec::new(),
            Stream::OrcaSlicer(layers) => layers.findings().iter().map(to_c).collect(),
        }
    }

    /// Folds over every layer left and returns the result with the findings.
    #[inline]
    pub(crate) fn fold_to_top<B, F: FnMut(B, Layer) -> B>(
        self,
        init: B,
        f: F,
    ) -> (B, Vec<RotlangFinding>) {
        match self {
            // `fold`, not `next`: the rotlang stream keeps its state in registers across
            // layers that way (see `eval::Layers::fold`). It has no findings.
            Stream::Rotlang(layers) => (layers.fold(init, f), Vec::new()),
            Stream::OrcaSlicer(mut layers) => {
                let result = layers.fold_rest(init, f);
                let found = layers.findings().iter().map(to_c).collect();
                (result, found)
            }
        }
    }

    /// The fixed cycle of angles when the template is a plain list (see
    /// `eval::Layers::cycle`): layer `k` is entry `k mod n`, with no findings.
    pub(crate) fn plain_cycle(&self) -> Option<eval::Cycle> {
        match self {
            Stream::Rotlang(layers) => layers.plain_cycle(),
            Stream::OrcaSlicer(layers) => layers.plain_cycle(),
        }
    }

    /// Skips to layer `index` (at or after the current position).
    pub(crate) fn seek(&mut self, index: usize) {
        while self.layer_position() < index {
            if self.next().is_none() {
                break;
            }
        }
    }
}

impl Iterator for Stream<'_> {
    type Item = Layer;

    #[inline]
    fn next(&mut self) -> Option<Layer> {
        match self {
            Stream::Rotlang(layers) => layers.next(),
            Stream::OrcaSlicer(layers) => layers.next(),
        }
    }
}

/// The caller's findings output, checked (pointer, alignment, `items` for `capacity`
/// entries) before anything is evaluated, so that a bad one fails the call with nothing
/// written.
pub(crate) struct FindingsOut<'a> {
    out: &'a mut RotlangFindings,
    items: &'a mut [RotlangFinding],
}

/// Checks `out` (NULL: not wanted, `None`).
///
/// # Safety
/// `out` is NULL or points to a `RotlangFindings` whose `items` hold `capacity` entries.
pub(crate) unsafe fn findings_out<'a>(
    out: *mut RotlangFindings,
) -> Result<Option<FindingsOut<'a>>, Failure> {
    if out.is_null() {
        return Ok(None);
    }
    // SAFETY: the caller's contract.
    let out = unsafe { crate::util::out(out) }?;
    let items = match out.capacity {
        0 => &mut [][..],
        // SAFETY: the caller's contract on `items` and `capacity`.
        n => unsafe { crate::util::slice_mut(out.items, n, "findings.items") }?,
    };
    Ok(Some(FindingsOut { out, items }))
}

impl FindingsOut<'_> {
    /// Writes the count and as many findings as there is room for.
    pub(crate) fn write(self, findings: &[RotlangFinding]) {
        let n = findings.len().min(self.items.len());
        self.items[..n].copy_from_slice(&findings[..n]);
        self.out.count = findings.len();
    }
}

/// Writes `findings` into the caller's `RotlangFindings`, if given.
///
/// # Safety
/// `out` is NULL or points to a `RotlangFindings` whose `items` hold `capacity` entries.
pub(crate) unsafe fn report(
    out: *mut RotlangFindings,
    findings: &[RotlangFinding],
) -> Result<(), Failure> {
    // SAFETY: the caller's contract.
    if let Some(out) = unsafe { findings_out(out) }? {
        out.write(findings);
    }
    Ok(())
}
