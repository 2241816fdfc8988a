//! Batch evaluation into the caller's arrays.

use crate::handle::RotlangTemplate;
use crate::model::{RotlangFill, RotlangModel, RotlangOptions, Settings};
use crate::status::{Failure, RotlangStatus, guard};
use crate::stream::{FindingsOut, RotlangFindings, Stream, findings_out};
use crate::util::{input, out, slice_mut};
use rotlang::eval::Layer;

/// `count` value of `rotlang_expand`: every layer from `first` to the top (`SIZE_MAX`).
pub const ROTLANG_TO_TOP: usize = usize::MAX;

/// The number of layers of a model, after checking it (`INVALID_MODEL` with the reason
/// in `rotlang_last_error` when it is unusable). Use it to size the output arrays.
///
/// # Safety
/// `model` points to a `RotlangModel` (whose `heights` holds `heights_len` doubles);
/// `out` to one writable `size_t`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_model_layer_count(
    model: *const RotlangModel,
    out: *mut usize,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract.
        let out = unsafe { crate::util::out(out) }?;
        // SAFETY: the caller's contract.
        let model = unsafe { input(model, "the model") }?;
        // SAFETY: the caller's contract on `heights`.
        *out = unsafe { model.checked_model() }?.len();
        Ok(())
    })
}

/// Evaluates layers `first .. first + count` of `model` (`count` = `ROTLANG_TO_TOP`: up
/// to the top) and writes their angles (degrees, base included, not wrapped, always
/// finite) to `angles[0..]` and, when `fills` is not NULL, their fills (`RotlangFill`
/// values) to `fills[0..]`. Both arrays hold `capacity` entries. `options` may be NULL
/// (defaults); `findings` may be NULL (not wanted): it gets the OrcaSlicer dialect's
/// findings on the layers up to the end of the range.
///
/// Thread-safe: any number of threads may expand one template at once.
/// The cost is that of evaluating layers `0 .. first + count` (the evaluator streams
/// from the bottom); for layer-by-layer access use a `RotlangEvaluator`.
///
/// Errors: `NULL_POINTER`, `INVALID_HANDLE`, `INVALID_MODEL`, `INVALID_ARGUMENT` (unknown
/// dialect, base not finite), `TEMPLATE_HAS_ERRORS` (rotlang dialect), `OUT_OF_RANGE`
/// (`first` at or past the top, or the range past it), `BUFFER_TOO_SMALL` (`capacity`
/// below the range's length). Every argument is checked before anything is evaluated:
/// on error nothing is written (not the angles, the fills or the findings).
///
/// # Safety
/// `model` points to a valid `RotlangModel`; `options` is NULL or valid; `angles` (and
/// `fills` unless NULL) hold `capacity` writable entries; `findings` is NULL or valid.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)] // a C signature: the buffers and their length
pub unsafe extern "C" fn rotlang_expand(
    template: *const RotlangTemplate,
    model: *const RotlangModel,
    options: *const RotlangOptions,
    first: usize,
    count: usize,
    angles: *mut f64,
    fills: *mut u8,
    capacity: usize,
    findings: *mut RotlangFindings,
) -> RotlangStatus {
    guard(|| {
        // SAFETY: the caller's contract on `findings`.
        let findings = unsafe { findings_out(findings) }?;
        // SAFETY: the caller's contract.
        unsafe {
            expand_into(
                template, model, options, first, count, angles, fills, capacity, findings,
            )
        }
    })
}

/// The body of `rotlang_expand`, with the findings output already checked. Every check
/// comes before the first write.
///
/// # Safety
/// As `rotlang_expand`.
#[allow(clippy::too_many_arguments)]
unsafe fn expand_into(
    template: *const RotlangTemplate,
    model: *const RotlangModel,
    options: *const RotlangOptions,
    first: usize,
    count: usize,
    angles: *mut f64,
    fills: *mut u8,
    capacity: usize,
    findings: Option<FindingsOut<'_>>,
) -> Result<(), Failure> {
    let data = crate::template::data(template)?;
    // SAFETY: the caller's contract on each pointer.
    let model = unsafe { input(model, "the model")?.checked_model() }?;
    let options = (!options.is_null())
        // SAFETY: the caller's contract.
        .then(|| unsafe { input(options, "the options") })
        .transpose()?;
    let settings = Settings::from_c(options)?;
    if angles.is_null() {
        return Err(Failure::with(RotlangStatus::NullPointer, "angles"));
    }
    let len = model.len();
    if first >= len {
        return Err(Failure::with(
            RotlangStatus::OutOfRange,
            format!("first layer {first} of a model with {len} layers"),
        ));
    }
    let count = if count == ROTLANG_TO_TOP {
        len - first
    } else {
        count
    };
    if count > len - first {
        return Err(Failure::with(
            RotlangStatus::OutOfRange,
            format!("layers {first} + {count} of a model with {len} layers"),
        ));
    }
    if capacity < count {
        return Err(Failure::with(
            RotlangStatus::BufferTooSmall,
            format!("capacity {capacity} for {count} layers"),
        ));
    }
    // SAFETY: the caller's contract: `capacity >= count` entries.
    let angles = unsafe { slice_mut(angles, count, "angles") }?;
    let mut fills = match fills.is_null() {
        true => None,
        // SAFETY: as for `angles`.
        false => Some(unsafe { slice_mut(fills, count, "fills") }?),
    };
    let mut stream = Stream::open(&data, &model, settings)?;
    if let Some(cycle) = stream.plain_cycle() {
        // A plain list (`0, 90`): copies of its cycle, about a nanosecond a layer.
        cycle.write(first, angles, None);
        if let Some(fills) = fills {
            for (i, slot) in fills.iter_mut().enumerate() {
                *slot = RotlangFill::from(cycle.at(first + i).1) as u8;
            }
        }
        if let Some(out) = findings {
            out.write(&[]);
        }
        return Ok(());
    }
    stream.seek(first);
    let mut store = |i: usize, layer: Layer| {
        // `i < count` always (the range is inside the model); the check keeps the
        // writes in bounds without a panic path.
        if let Some(slot) = angles.get_mut(i) {
            *slot = layer.angle;
        }
        if let Some(slot) = fills.as_deref_mut().and_then(|f| f.get_mut(i)) {
            *slot = RotlangFill::from(layer.fill) as u8;
        }
        i + 1
    };
    let found = if first + count == len {
        stream.fold_to_top(0, &mut store).1
    } else {
        let mut i = 0;
        for layer in stream.by_ref().take(count) {
            i = store(i, layer);
        }
        stream.findings()
    };
    if let Some(out) = findings {
        out.write(&found);
    }
    Ok(())
}

/// Evaluates layer `index` alone into `*angle` (and `*fill` unless NULL): a convenience
/// for one-off questions. It streams from the bottom, so it costs O(index); for many
/// layers use `rotlang_expand` or an evaluator.
///
/// # Safety
/// As `rotlang_expand`; `angle` points to one writable double, `fill` is NULL or to one
/// writable byte.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotlang_angle_at(
    template: *const RotlangTemplate,
    model: *const RotlangModel,
    options: *const RotlangOptions,
    index: usize,
    angle: *mut f64,
    fill: *mut u8,
) -> RotlangStatus {
    guard(|| {
        // Both outputs are checked before either is written.
        // SAFETY: the caller's contract.
        let angle = unsafe { out(angle) }?;
        let fill = match fill.is_null() {
            true => None,
            // SAFETY: the caller's contract.
            false => Some(unsafe { out(fill) }?),
        };
        let (mut a, mut f) = (0.0, 0u8);
        // SAFETY: the caller's contract; the outputs are locals.
        unsafe { expand_into(template, model, options, index, 1, &mut a, &mut f, 1, None) }?;
        *angle = a;
        if let Some(fill) = fill {
            *fill = f;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::RotlangDialect;
    use crate::template::{rotlang_parse, rotlang_template_free};

    /// A plain list is copied from its cycle (issue 19): a range that starts inside the
    /// cycle gives each layer its entry's angle and fill, in both dialects.
    #[test]
    fn plain_list_ranges_match_the_stream() {
        let model = crate::model::rotlang_model_uniform(50, 0.2, 0.0);
        for plain in ["0, 90D, 45", "0, 90, 45"] {
            for dialect in [RotlangDialect::Rotlang, RotlangDialect::Orcaslicer] {
                let options = RotlangOptions {
                    base: 10.0,
                    seed: 0,
                    dialect: dialect as u32,
                };
                let mut t = std::ptr::null_mut();
                let (mut angles, mut fills) = ([0.0; 7], [9u8; 7]);
                // SAFETY: valid text, out-pointers and 7-entry buffers.
                let status = unsafe {
                    assert_eq!(
                        rotlang_parse(plain.as_ptr().cast(), plain.len(), 0, &mut t),
                        RotlangStatus::Ok
                    );
                    let status = rotlang_expand(
                        t,
                        &model,
                        &options,
                        4,
                        7,
                        angles.as_mut_ptr(),
                        fills.as_mut_ptr(),
                        7,
                        std::ptr::null_mut(),
                    );
                    rotlang_template_free(t);
                    status
                };
                assert_eq!(status, RotlangStatus::Ok);
                // Layers 4..11 take entries 1, 2, 0, 1, 2, 0, 1.
                assert_eq!(
                    angles,
                    [100.0, 55.0, 10.0, 100.0, 55.0, 10.0, 100.0],
                    "{plain}"
                );
                // `90D` is a dense layer in rotlang; OrcaSlicer reads it as `90`.
                let dense = u8::from(dialect == RotlangDialect::Rotlang && plain.contains('D'));
                assert_eq!(fills, [dense, 0, 0, dense, 0, 0, dense], "{plain}");
            }
        }
    }
}
