//! The export to each slicer, from the layers of the template on a model.

use super::{Export, ExportError, Note, Slicer};
use crate::eval::{self, Model, Options};
use crate::gcode::difference;
use crate::ir::Fill;
use crate::number;

/// Two directions closer than this are the same (they come from the same arithmetic).
const SAME: f64 = 1e-9;
/// The longest period looked for (a longer one is exported layer by layer).
const MAX_PERIOD: usize = 4096;

/// PrusaSlicer: the layers from `min_z` to `max_z` (mm above the object's bottom) have
/// `fill_angle` (degrees, in [0, 180)).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Range {
    pub min_z: f64,
    pub max_z: f64,
    pub fill_angle: f64,
    /// The model's layers `first..=last` the range covers.
    pub first: usize,
    pub last: usize,
}

/// The layers of the template: direction in [0, 180) and fill.
struct Layers {
    directions: Vec<f64>,
    angles: Vec<f64>,
    fills: Vec<Fill>,
}

fn evaluate(
    text: &str,
    target: crate::Target,
    model: &Model,
    options: Options,
) -> Result<Layers, ExportError> {
    let (parse, layers) = eval::parse_layers(text, target, model, options);
    if parse.has_errors() {
        return Err(ExportError::Template(Box::new(parse)));
    }
    let mut out = Layers {
        directions: Vec::with_capacity(model.len()),
        angles: Vec::with_capacity(model.len()),
        fills: Vec::with_capacity(model.len()),
    };
    for l in layers {
        out.directions.push(wrap180(l.angle));
        out.angles.push(l.angle);
        out.fills.push(l.fill);
    }
    Ok(out)
}

fn wrap180(a: f64) -> f64 {
    let w = number::round_angle(a).rem_euclid(180.0);
    if w >= 180.0 - SAME { 0.0 } else { w }
}

fn same(a: f64, b: f64) -> bool {
    difference(a, b).abs() < SAME
}

/// The smallest period `p` (at most half the layers) with `d[i] = d[i − p]` everywhere.
fn period(d: &[f64]) -> Option<usize> {
    let limit = (d.len() / 2).min(MAX_PERIOD);
    (1..=limit).find(|&p| (p..d.len()).all(|i| same(d[i], d[i - p])))
}

/// `d[i] = d[0] + k·i` (mod 180) for every layer: the turn `k`.
fn ramp(d: &[f64], angles: &[f64]) -> Option<f64> {
    if d.len() < 2 {
        return Some(0.0);
    }
    // The turn as the template makes it (unwrapped), so `+30` is 30, not −150.
    let k = number::round_angle(angles[1] - angles[0]);
    (0..d.len())
        .all(|i| same(d[i], d[0] + k * i as f64))
        .then_some(k)
}

fn text(a: f64) -> String {
    number::angle(a).as_str().to_owned()
}

/// Runs of solid layers: "layers 0–2 (monotonic)".
fn solid_note(fills: &[Fill], slicer: &str) -> Option<Note> {
    let mut runs = Vec::new();
    let mut i = 0;
    while i < fills.len() {
        if fills[i] == Fill::Sparse {
            i += 1;
            continue;
        }
        let start = i;
        while i < fills.len() && fills[i] == fills[start] {
            i += 1;
        }
        runs.push(format!("{}–{} ({})", start, i - 1, fills[start].name()));
    }
    if runs.is_empty() {
        return None;
    }
    let shown = if runs.len() > 6 {
        format!("{}, … ({} runs)", runs[..6].join(", "), runs.len())
    } else {
        runs.join(", ")
    };
    Some(Note {
        code: "slicer::solid-layers",
        message: format!(
            "the template makes layers {shown} solid: {slicer} cannot make chosen layers solid \
             from an angle setting, so they are exported as sparse layers with their angle"
        ),
    })
}

/// Exports the template `text` (rotlang's reading) on `model` to `slicer`.
pub fn export(
    text: &str,
    slicer: Slicer,
    model: &Model,
    options: Options,
) -> Result<Export, ExportError> {
    let layers = evaluate(text, crate::Target::Sparse, model, options)?;
    let mut out = Export {
        slicer,
        settings: Vec::new(),
        ranges: Vec::new(),
        notes: Vec::new(),
        max_error: 0.0,
        layers: model.len(),
    };
    match slicer {
        Slicer::Cura => cura(&layers, model, &mut out),
        Slicer::SuperSlicer => superslicer(&layers, model, &mut out),
        Slicer::PrusaSlicer => prusaslicer(&layers, model, &mut out),
        Slicer::OrcaSlicer => orcaslicer(text, &layers, model, options, &mut out)?,
    }
    Ok(out)
}

fn shells(out: &mut Export, model: &Model, bottom: &str, top: &str) {
    out.settings
        .push((bottom.into(), model.bottom_shells().to_string()));
    out.settings
        .push((top.into(), model.top_shells().to_string()));
}

fn per_layer_note(out: &mut Export, count: usize) {
    out.notes.push(Note {
        code: "slicer::per-layer-list",
        message: format!(
            "the template does not repeat within the model: the list has one angle per layer \
             ({count}); it fits this model only (other heights need another export)"
        ),
    });
}

/// Cura's list of the directions `d` (its period, or every layer): the text and the
/// largest rounding.
fn cura_list(d: &[f64], out: &mut Export) -> (String, f64) {
    let list: &[f64] = match period(d) {
        Some(p) => &d[..p],
        None => {
            per_layer_note(out, d.len());
            d
        }
    };
    let mut max_error: f64 = 0.0;
    let cura: Vec<String> = list
        .iter()
        .map(|&dir| {
            let exact = (90.0 - dir).rem_euclid(180.0);
            let rounded = exact.round().rem_euclid(180.0);
            max_error = max_error.max(difference(exact, rounded).abs());
            format!("{}", rounded as i64)
        })
        .collect();
    (format!("[{}]", cura.join(",")), max_error)
}

fn cura(layers: &Layers, model: &Model, out: &mut Export) {
    let (list, max_error) = cura_list(&layers.directions, out);
    out.settings.push(("infill_angles".into(), list));
    // Cura combines sparse layers when the infill layer thickness is above the layer
    // height; the list is cycled per infill layer, so they must be one.
    out.settings.push((
        "infill_sparse_thickness".into(),
        number::height(model.layer_height()).as_str().to_owned(),
    ));
    shells(out, model, "bottom_layers", "top_layers");
    out.max_error = number::round_angle(max_error);
    if max_error > SAME {
        out.notes.push(Note {
            code: "slicer::rounded",
            message: format!(
                "Cura keeps whole degrees: the angles are rounded, by up to {}°",
                text(out.max_error)
            ),
        });
    }
    out.notes.push(Note {
        code: "slicer::axis",
        message: "Cura measures from the Y axis, clockwise: rotlang's 0° (along X) is Cura's 90°; \
                  set infill_pattern to lines or zigzag (grid and others add directions of \
                  their own); solid layers keep Cura's skin_angles unless --solid gives a \
                  template for them"
            .into(),
    });
    if let Some(n) = solid_note(&layers.fills, "Cura") {
        out.notes.push(n);
    }
}

/// Adds the setting of the solid infill's directions (a `solid_infill_rotate_template`,
/// read as a solid template) to `out`: Cura's `skin_angles`, OrcaSlicer's
/// `solid_infill_rotate_template`. SuperSlicer and PrusaSlicer turn solid infill with
/// the sparse infill's angle: an error.
pub fn export_solid(
    out: &mut Export,
    text: &str,
    model: &Model,
    options: Options,
) -> Result<(), ExportError> {
    let layers = evaluate(text, crate::Target::Solid, model, options)?;
    match out.slicer {
        Slicer::Cura => {
            let (list, max_error) = cura_list(&layers.directions, out);
            out.settings.push(("skin_angles".into(), list));
            if max_error > SAME {
                out.max_error = out.max_error.max(number::round_angle(max_error));
                out.notes.push(Note {
                    code: "slicer::rounded",
                    message: format!(
                        "Cura keeps whole degrees: the skin angles are rounded, by up to {}°",
                        text_of(number::round_angle(max_error))
                    ),
                });
            }
            Ok(())
        }
        Slicer::OrcaSlicer => {
            let mut solid = Export {
                settings: Vec::new(),
                notes: Vec::new(),
                ..out.clone()
            };
            orcaslicer_key(
                text,
                &layers,
                model,
                options,
                &mut solid,
                "solid_infill_rotate_template",
                crate::Target::Solid,
            )?;
            out.settings.extend(
                solid
                    .settings
                    .into_iter()
                    .filter(|(k, _)| k == "solid_infill_rotate_template"),
            );
            out.notes.extend(solid.notes);
            Ok(())
        }
        Slicer::SuperSlicer | Slicer::PrusaSlicer => Err(ExportError::Inexpressible {
            code: "slicer::inexpressible",
            message: format!(
                "{} turns solid infill with the sparse infill's angle: it has no setting for \
                 a solid template",
                out.slicer.name()
            ),
        }),
    }
}

fn text_of(a: f64) -> String {
    text(a)
}

fn superslicer(layers: &Layers, model: &Model, out: &mut Export) {
    let d = &layers.directions;
    if let Some(k) = ramp(d, &layers.angles) {
        out.settings.push(("fill_angle".into(), text(d[0])));
        out.settings.push(("fill_angle_increment".into(), text(k)));
        out.settings
            .push(("fill_angle_template".into(), String::new()));
    } else {
        let list: &[f64] = match period(d) {
            Some(p) => &d[..p],
            None => {
                per_layer_note(out, d.len());
                d
            }
        };
        out.settings.push(("fill_angle".into(), text(d[0])));
        out.settings
            .push(("fill_angle_increment".into(), "0".into()));
        let list: Vec<String> = list.iter().map(|&a| text(a)).collect();
        out.settings
            .push(("fill_angle_template".into(), list.join(",")));
    }
    // SuperSlicer adds 90° on every other layer unless told not to.
    out.settings.push(("fill_angle_cross".into(), "0".into()));
    shells(out, model, "bottom_solid_layers", "top_solid_layers");
    if let Some(n) = solid_note(&layers.fills, "SuperSlicer") {
        out.notes.push(n);
    }
}

fn prusaslicer(layers: &Layers, model: &Model, out: &mut Export) {
    let d = &layers.directions;
    // PrusaSlicer finds the shells of each region apart: a range boundary among the shell
    // layers thins the shells (measured: per-layer ranges for `0, 90` left 1 bottom and 1
    // top solid layer of 2). The bottom and top shell layers are one range each; their
    // solid infill is not what the template turns.
    let n = d.len();
    let bottom = (model.bottom_shells() as usize).min(n);
    let top = (model.top_shells() as usize).min(n - bottom);
    let group = |i: usize| -> (u8, usize) {
        if i < bottom {
            (0, 0)
        } else if i >= n - top {
            (2, 0)
        } else {
            (1, i)
        }
    };
    let mut i = 0;
    while i < d.len() {
        let start = i;
        while i < d.len()
            && match (group(start), group(i)) {
                ((1, _), (1, _)) => same(d[i], d[start]),
                (a, b) => a == b,
            }
        {
            i += 1;
        }
        let (min_z, _) = model.layer_bounds(start).unwrap_or((0.0, 0.0));
        let (_, max_z) = model.layer_bounds(i - 1).unwrap_or((0.0, 0.0));
        out.ranges.push(Range {
            min_z: number::round_height(min_z),
            max_z: number::round_height(max_z),
            fill_angle: d[start],
            first: start,
            last: i - 1,
        });
    }
    out.settings
        .push(("fill_angle".into(), text(d.first().copied().unwrap_or(0.0))));
    // `rectilinear` (and `line`) turn 90° more on every other layer in PrusaSlicer 2.5;
    // `alignedrectilinear` draws the same lines without it (measured, tests/slicers.rs).
    out.settings
        .push(("fill_pattern".into(), "alignedrectilinear".into()));
    out.settings.push((
        "layer_height".into(),
        number::height(model.layer_height()).as_str().to_owned(),
    ));
    let first = model
        .layer_bounds(0)
        .map_or(model.layer_height(), |(b, t)| t - b);
    out.settings.push((
        "first_layer_height".into(),
        number::height(first).as_str().to_owned(),
    ));
    shells(out, model, "bottom_solid_layers", "top_solid_layers");
    if out.ranges.len() > 1 {
        out.notes.push(Note {
            code: "slicer::layer-ranges",
            message: format!(
                "PrusaSlicer has one fill_angle per height range: {} ranges, written as the \
                 layer-range modifiers of a 3MF project (--out FILE.3mf --mesh PART.stl); \
                 its layers must be the model's (layer heights above)",
                out.ranges.len()
            ),
        });
    }
    if let Some(n) = solid_note(&layers.fills, "PrusaSlicer") {
        out.notes.push(n);
    }
}

fn orcaslicer(
    text_in: &str,
    layers: &Layers,
    model: &Model,
    options: Options,
    out: &mut Export,
) -> Result<(), ExportError> {
    orcaslicer_key(
        text_in,
        layers,
        model,
        options,
        out,
        "sparse_infill_rotate_template",
        crate::Target::Sparse,
    )
}

fn orcaslicer_key(
    text_in: &str,
    layers: &Layers,
    model: &Model,
    options: Options,
    out: &mut Export,
    key: &str,
    target: crate::Target,
) -> Result<(), ExportError> {
    if let Some(n) = solid_note(&layers.fills, "OrcaSlicer") {
        return Err(ExportError::Inexpressible {
            code: "slicer::inexpressible",
            message: format!(
                "no OrcaSlicer template expresses solid signs (`D S O M R`): {}",
                n.message
                    .split(": ")
                    .next()
                    .unwrap_or("the template has solid layers")
            ),
        });
    }
    // OrcaSlicer's reading must give rotlang's angle on every layer (modulo 360: the
    // direction of the infill, and of anything that turns with it).
    let reads_the_same = |candidate: &str| {
        let ours = crate::dialect::orcaslicer::layers(
            candidate,
            model,
            Options {
                base: 0.0,
                ..options
            },
        );
        let mut theirs = ours.map(|l| l.angle);
        layers.angles.iter().all(|&a| {
            theirs.next().is_some_and(|b| {
                ((a - b).rem_euclid(360.0) < SAME) || ((b - a).rem_euclid(360.0) < SAME)
            })
        })
    };
    let mut candidates: Vec<(String, &'static str)> = Vec::new();
    if options.base == 0.0 {
        candidates.push((text_in.trim().to_owned(), "the template itself"));
        let fixed = crate::fix::apply_all_with(text_in, target, |t| {
            crate::dialect::compat(t, target, model, options)
        });
        if !fixed.parse.has_errors() {
            candidates.push((fixed.text, "the template with the compat fixes"));
        }
    }
    let list = |angles: &[f64]| -> String {
        angles
            .iter()
            .map(|&a| text(number::round_angle(a).rem_euclid(360.0)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let full: Vec<f64> = layers.angles.iter().map(|a| a.rem_euclid(360.0)).collect();
    if let Some(p) = period(&full) {
        candidates.push((list(&full[..p]), "a plain list of the template's period"));
    }
    candidates.push((list(&full), "a plain list of every layer"));
    for (candidate, what) in candidates {
        if reads_the_same(&candidate) {
            out.settings.push((key.into(), candidate.clone()));
            shells(out, model, "bottom_shell_layers", "top_shell_layers");
            if candidate != text_in.trim() {
                let per_layer = what.ends_with("every layer");
                out.notes.push(Note {
                    code: if per_layer {
                        "slicer::per-layer-list"
                    } else {
                        "slicer::rewritten"
                    },
                    message: format!(
                        "OrcaSlicer reads the template differently: exported as {what}, which it \
                         reads as rotlang does{}",
                        if per_layer {
                            " (for this model only)"
                        } else {
                            ""
                        }
                    ),
                });
            }
            return Ok(());
        }
    }
    Err(ExportError::Inexpressible {
        code: "slicer::inexpressible",
        message: "no OrcaSlicer template gives these angles (OrcaSlicer's reading of every \
                  candidate differs)"
            .into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Model {
        Model::cube20()
    }

    #[test]
    fn cura_gets_the_period_with_the_axis_turned() {
        let e = export("0, 90", Slicer::Cura, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("infill_angles"), Some("[90,0]"));
        assert_eq!(e.max_error, 0.0);
        let e = export("0, 15, 30", Slicer::Cura, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("infill_angles"), Some("[90,75,60]"));
        // `+10L25%, -10l25%` repeats every half of the height (50 layers); `+30/50%` never.
        let e = export(
            "+10L25%, -10l25%",
            Slicer::Cura,
            &cube(),
            Options::default(),
        )
        .expect("export");
        assert_eq!(
            e.setting("infill_angles").map(|l| l.split(',').count()),
            Some(50)
        );
        let e = export("+30/50%", Slicer::Cura, &cube(), Options::default()).expect("export");
        let list = e.setting("infill_angles").expect("list");
        assert_eq!(list.split(',').count(), 100);
        assert!(e.max_error > 0.0 && e.max_error <= 0.5, "{}", e.max_error);
        assert!(e.notes.iter().any(|n| n.code == "slicer::rounded"));
        assert!(e.notes.iter().any(|n| n.code == "slicer::per-layer-list"));
    }

    #[test]
    fn superslicer_takes_the_shortest_form() {
        let e = export("+30", Slicer::SuperSlicer, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("fill_angle_increment"), Some("30"));
        assert_eq!(e.setting("fill_angle_template"), Some(""));
        // `0, 90` is a turn of 90° a layer: shorter than a list.
        let e = export("0, 90", Slicer::SuperSlicer, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("fill_angle_increment"), Some("90"));
        let e = export(
            "0, 15, 30",
            Slicer::SuperSlicer,
            &cube(),
            Options::default(),
        )
        .expect("export");
        assert_eq!(e.setting("fill_angle_template"), Some("0,15,30"));
        let e = export("45", Slicer::SuperSlicer, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("fill_angle"), Some("45"));
        assert_eq!(e.setting("fill_angle_increment"), Some("0"));
    }

    #[test]
    fn prusaslicer_ranges_follow_runs_of_one_direction() {
        let e = export("+45#3", Slicer::PrusaSlicer, &cube(), Options::default()).expect("export");
        let r = &e.ranges;
        assert!(r.len() > 10, "{r:?}");
        // The 3 bottom and 4 top shell layers are one range each.
        assert_eq!((r[0].first, r[0].last, r[0].min_z), (0, 2, 0.0));
        assert_eq!(r.last().map(|r| (r.first, r.min_z)), Some((96, 19.2)));
        assert_eq!(r.last().map(|r| (r.last, r.max_z)), Some((99, 20.0)));
        for w in r.windows(2) {
            assert_eq!(w[0].max_z, w[1].min_z);
            assert!(!same(w[0].fill_angle, w[1].fill_angle));
        }
    }

    #[test]
    fn orcaslicer_gets_a_template_it_reads_the_same() {
        let e = export("0, 90", Slicer::OrcaSlicer, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("sparse_infill_rotate_template"), Some("0, 90"));
        // `0 90` is `0` for OrcaSlicer: the compat fix writes the comma.
        let e = export("0 90", Slicer::OrcaSlicer, &cube(), Options::default()).expect("export");
        assert_eq!(e.setting("sparse_infill_rotate_template"), Some("0, 90"));
        assert!(e.notes.iter().any(|n| n.code == "slicer::rewritten"));
        let err = export(
            "+30M3, +30",
            Slicer::OrcaSlicer,
            &cube(),
            Options::default(),
        )
        .expect_err("solid signs");
        assert!(err.to_string().contains("solid"), "{err}");
    }
}
