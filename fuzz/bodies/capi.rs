//! Fuzz target `capi`: the C ABI with arbitrary bytes, as a C caller could pass them.
//! Bytes 0..8 choose the target, dialect, model (uniform, or heights read from the input as
//! raw doubles: NaN, negative, zero, huge), the layer range and the buffer size; the rest
//! is the template, not necessarily UTF-8, read by `rotlang_parse` or (byte 0's high bit)
//! `rotlang_parse_bytes`, which keeps invalid bytes for the OrcaSlicer dialect. Every call must return a status (never
//! `INTERNAL`, which is a caught panic), successful angles must be finite, the evaluator
//! must agree with the batch, and a second free must be refused.

use rotlang_capi::*;

const MAX_LAYERS: usize = 600;

pub fn run(data: &[u8]) {
    let (head, rest) = data.split_at(data.len().min(8));
    let mut h = [0u8; 8];
    h[..head.len()].copy_from_slice(head);

    let mut template = std::ptr::null_mut();
    let bytes = h[0] & 0x80 != 0;
    let parse = if bytes {
        rotlang_parse_bytes
    } else {
        rotlang_parse
    };
    // SAFETY: `rest` is readable for its length; `template` is writable.
    let status = unsafe {
        parse(
            rest.as_ptr().cast(),
            rest.len(),
            u32::from(h[0] % 3),
            &mut template,
        )
    };
    let utf8 = std::str::from_utf8(rest).is_ok();
    match status {
        RotlangStatus::Ok => assert!((utf8 || bytes) && h[0] % 3 < 2 && !template.is_null()),
        RotlangStatus::InvalidUtf8 => assert!(!utf8 && !bytes && template.is_null()),
        RotlangStatus::InvalidArgument => assert!(h[0] % 3 == 2 && template.is_null()),
        other => panic!("rotlang_parse: {other:?}"),
    }
    if template.is_null() {
        return;
    }
    diagnostics(template);

    // The model: uniform from the header, or heights taken from the input bytes.
    let heights: Vec<f64> = rest
        .chunks_exact(8)
        .take(usize::from(h[1] % 64))
        .map(|c| f64::from_ne_bytes(c.try_into().expect("8 bytes")))
        .collect();
    let model = if h[1] & 0x80 == 0 {
        let layers = usize::from(h[2]) * 2 + usize::from(h[1] % 4) * 100;
        let first = [0.0, 0.3, -1.0, f64::NAN][usize::from(h[3] % 4)];
        rotlang_model_uniform(layers.min(MAX_LAYERS), 0.2, first)
    } else {
        rotlang_model_heights(heights.as_ptr(), heights.len(), 0.2)
    };
    let options = RotlangOptions {
        base: f64::from(h[4]) - 128.0,
        seed: u64::from(h[4]),
        dialect: u32::from(h[3] >> 6),
    };

    let mut layers = 0usize;
    // SAFETY: `model` points into `heights`, alive here; `layers` is writable.
    let counted = unsafe { rotlang_model_layer_count(&model, &mut layers) };
    assert!(
        matches!(counted, RotlangStatus::Ok | RotlangStatus::InvalidModel),
        "{counted:?}"
    );

    let first = usize::from(h[5]) % (layers + 2);
    let count = if h[6] == 0xFF {
        ROTLANG_TO_TOP
    } else {
        usize::from(h[6])
    };
    let capacity = usize::from(h[7]).max(1) * 4;
    let mut angles = vec![f64::NAN; capacity];
    let mut fills = vec![0xEEu8; capacity];
    let mut items = [RotlangFinding {
        kind: RotlangFindingKind::Nan,
        first_layer: 0,
        layers: 0,
    }; 4];
    let mut findings = RotlangFindings {
        items: items.as_mut_ptr(),
        capacity: items.len(),
        count: 0,
    };
    // SAFETY: every buffer holds `capacity` entries; the rest are valid structs.
    let status = unsafe {
        rotlang_expand(
            template,
            &model,
            &options,
            first,
            count,
            angles.as_mut_ptr(),
            fills.as_mut_ptr(),
            capacity,
            &mut findings,
        )
    };
    let has_errors = {
        let mut e = 0;
        // SAFETY: `e` is writable.
        assert_eq!(
            unsafe { rotlang_template_has_errors(template, &mut e) },
            RotlangStatus::Ok
        );
        e == 1
    };
    match status {
        RotlangStatus::Ok => {
            let n = if count == ROTLANG_TO_TOP {
                layers - first
            } else {
                count
            };
            assert!(n <= capacity && first + n <= layers);
            for i in 0..n {
                assert!(angles[i].is_finite(), "layer {}: {}", first + i, angles[i]);
                assert!(fills[i] <= RotlangFill::Rectilinear as u8);
            }
            evaluator_agrees(template, &model, &options, first, &angles[..n]);
        }
        RotlangStatus::InvalidModel => assert_eq!(counted, RotlangStatus::InvalidModel),
        RotlangStatus::InvalidArgument => assert!(options.dialect > 1),
        RotlangStatus::TemplateHasErrors => assert!(has_errors && options.dialect == 0),
        // Kept bytes that are not UTF-8 read only in the OrcaSlicer dialect.
        RotlangStatus::InvalidUtf8 => assert!(bytes && !utf8 && options.dialect == 0),
        RotlangStatus::OutOfRange | RotlangStatus::BufferTooSmall => {}
        other => panic!("rotlang_expand: {other:?}"),
    }

    assert_eq!(rotlang_template_free(template), RotlangStatus::Ok);
    assert_eq!(
        rotlang_template_free(template),
        RotlangStatus::InvalidHandle
    );
}

fn diagnostics(template: *mut RotlangTemplate) {
    let mut n = 0;
    // SAFETY: `n` is writable.
    assert_eq!(
        unsafe { rotlang_template_diagnostic_count(template, &mut n) },
        RotlangStatus::Ok
    );
    for i in 0..=n {
        let mut d = std::mem::MaybeUninit::<RotlangDiagnostic>::uninit();
        // SAFETY: `d` is writable.
        let status = unsafe { rotlang_template_diagnostic(template, i, d.as_mut_ptr()) };
        if i == n {
            assert_eq!(status, RotlangStatus::OutOfRange);
        } else {
            assert_eq!(status, RotlangStatus::Ok);
            // SAFETY: written by the library on success.
            let d = unsafe { d.assume_init() };
            assert!(d.start <= d.end && !d.code.is_null() && !d.message.is_null());
        }
    }
}

fn evaluator_agrees(
    template: *mut RotlangTemplate,
    model: &RotlangModel,
    options: &RotlangOptions,
    first: usize,
    angles: &[f64],
) {
    let mut evaluator = std::ptr::null_mut();
    // SAFETY: valid pointers; the model's heights outlive the call.
    let status = unsafe { rotlang_evaluator_new(template, model, options, &mut evaluator) };
    assert_eq!(status, RotlangStatus::Ok);
    // Backwards, so that the evaluator has to go back.
    for (i, want) in angles.iter().enumerate().rev() {
        let mut layer = std::mem::MaybeUninit::<RotlangLayer>::uninit();
        // SAFETY: `layer` is writable.
        let status = unsafe { rotlang_evaluator_layer(evaluator, first + i, layer.as_mut_ptr()) };
        assert_eq!(status, RotlangStatus::Ok);
        // SAFETY: written on success.
        let layer = unsafe { layer.assume_init() };
        assert_eq!(layer.angle.to_bits(), want.to_bits(), "layer {}", first + i);
    }
    assert_eq!(rotlang_evaluator_free(evaluator), RotlangStatus::Ok);
    assert_eq!(
        rotlang_evaluator_free(evaluator),
        RotlangStatus::InvalidHandle
    );
}
