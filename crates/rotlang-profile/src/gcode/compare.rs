//! Comparing what a slicer printed with what a template says, layer by layer.

use super::measure::{Direction, difference};
use super::read::{Flavor, Layer};
use super::settings::Settings;
use crate::eval::{self, Dialect, Model, Options};

/// What each layer's sparse infill should run along, in the G-code's frame: degrees
/// counter-clockwise from +X, modulo 180.
#[derive(Clone, Debug, PartialEq)]
pub enum Expected {
    /// A template read in a dialect (rotlang's, or OrcaSlicer's own reading), plus a base
    /// direction added to every angle.
    Template {
        text: String,
        dialect: Dialect,
        base: f64,
        seed: u64,
    },
    /// Directions cycled layer by layer (a slicer's list of angles).
    Cycle(Vec<f64>),
    /// `start + increment × layer`.
    Ramp { start: f64, increment: f64 },
}

/// One layer of a comparison.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Row {
    pub index: usize,
    pub z: Option<f64>,
    pub height: Option<f64>,
    pub sparse: Option<Direction>,
    pub solid: Option<Direction>,
    /// The expected direction of the sparse infill, in [0, 180).
    pub expected: Option<f64>,
    /// measured − expected, in (−90, 90], for a layer with sparse infill.
    pub difference: Option<f64>,
    /// Whether |difference| ≤ the tolerance; `None` for a layer without sparse infill.
    pub matches: Option<bool>,
}

/// The rows, and how many sparse layers matched.
#[derive(Clone, Debug, Default)]
pub struct Comparison {
    pub rows: Vec<Row>,
    pub compared: usize,
    pub matched: usize,
    pub tolerance: f64,
}

/// The model the layers describe: their heights (from the comments, or the rise of Z),
/// the standard layer height and the shell counts (from the settings when given).
pub fn model(layers: &[Layer], settings: &Settings) -> Result<Model, String> {
    let mut heights = Vec::with_capacity(layers.len());
    let mut last = 0.0;
    for l in layers {
        // The rise of Z first: PrusaSlicer's `;HEIGHT:` is the height of what it extrudes,
        // which can differ from the layer's (0.4 on a 0.2 mm layer under a top shell).
        let h = match (l.z, l.height) {
            (Some(z), _) if z > last + 1e-9 => z - last,
            (_, Some(h)) if h > 0.0 => h,
            _ => settings.number("layer_height").unwrap_or(0.2),
        };
        if let Some(z) = l.z {
            last = z;
        }
        heights.push(h);
    }
    let standard = settings
        .number("layer_height")
        .or_else(|| heights.get(1).copied())
        .or_else(|| heights.first().copied())
        .unwrap_or(0.2);
    let count = |keys: &[&str], default: u32| {
        keys.iter()
            .find_map(|k| settings.number(k))
            .filter(|v| *v >= 0.0 && *v <= f64::from(u32::MAX))
            .map_or(default, |v| v as u32)
    };
    let bottom = count(
        &[
            "bottom_shell_layers",
            "bottom_solid_layers",
            "bottom_layers",
        ],
        3,
    );
    let top = count(&["top_shell_layers", "top_solid_layers", "top_layers"], 4);
    Model::from_heights(heights, standard)
        .map(|m| m.with_shells(bottom, top))
        .map_err(|e| format!("the file's layers make no model: {e}"))
}

/// The expectation the file's own settings give, a description of it, and notes.
pub fn expected_from_settings(
    flavor: Flavor,
    settings: &Settings,
) -> Option<(Expected, String, Vec<String>)> {
    let mut notes = Vec::new();
    match flavor {
        Flavor::OrcaSlicer | Flavor::BambuStudio => {
            let text = settings.get("sparse_infill_rotate_template").unwrap_or("");
            let direction = settings
                .number("sparse_infill_direction")
                .or_else(|| settings.number("infill_direction"))
                .unwrap_or(45.0);
            if text.is_empty() {
                notes.push(format!(
                    "no sparse_infill_rotate_template: the infill direction {direction}° on \
                     every layer (patterns that alternate by themselves differ)"
                ));
                return Some((
                    Expected::Cycle(vec![direction]),
                    format!("infill_direction = {direction}"),
                    notes,
                ));
            }
            let options = crate::dialect::orcaslicer::profile_options(
                text,
                Options {
                    base: direction,
                    seed: 0,
                },
            );
            Some((
                Expected::Template {
                    text: text.to_owned(),
                    dialect: Dialect::OrcaSlicer,
                    base: options.base,
                    seed: 0,
                },
                format!("sparse_infill_rotate_template = {text} (OrcaSlicer's reading)"),
                notes,
            ))
        }
        Flavor::PrusaSlicer | Flavor::SuperSlicer => {
            let angle = settings.number("fill_angle").unwrap_or(45.0);
            let pattern = settings.get("fill_pattern").unwrap_or("");
            if flavor == Flavor::SuperSlicer
                && let Some(list) = settings
                    .get("fill_angle_template")
                    .filter(|t| !t.is_empty())
            {
                let angles = numbers(list);
                if !angles.is_empty() {
                    return Some((
                        Expected::Cycle(angles),
                        format!("fill_angle_template = {list}"),
                        notes,
                    ));
                }
            }
            notes.push(
                "a project's per-range fill_angle (layer-range modifiers) is not written in \
                 the G-code: pass --template to compare with the template it came from"
                    .into(),
            );
            let increment = settings.number("fill_angle_increment").unwrap_or(0.0);
            if increment != 0.0 {
                return Some((
                    Expected::Ramp {
                        start: angle,
                        increment,
                    },
                    format!("fill_angle = {angle}, fill_angle_increment = {increment}"),
                    notes,
                ));
            }
            // PrusaSlicer's rectilinear-family patterns add 90° on every other layer;
            // `alignedrectilinear` does not (measured on PrusaSlicer 2.5).
            let cross = flavor == Flavor::SuperSlicer
                && settings.get("fill_angle_cross").is_some_and(|v| v == "0");
            if pattern == "alignedrectilinear" || cross {
                Some((
                    Expected::Cycle(vec![angle]),
                    format!("fill_angle = {angle}"),
                    notes,
                ))
            } else {
                notes.push(format!(
                    "fill_pattern = {pattern}: {} turns it 90° on every other layer",
                    flavor.name()
                ));
                Some((
                    Expected::Cycle(vec![angle, angle + 90.0]),
                    format!("fill_angle = {angle} ({pattern}, crossed)"),
                    notes,
                ))
            }
        }
        Flavor::Cura => {
            let list = settings.get("infill_angles").unwrap_or("[]");
            let mut angles = numbers(list);
            if angles.is_empty() {
                notes.push("infill_angles is empty: Cura's default for lines, [45, 135]".into());
                angles = vec![45.0, 135.0];
            }
            Some((
                Expected::Cycle(angles.iter().map(|c| cura_to_direction(*c)).collect()),
                format!("infill_angles = {list}"),
                notes,
            ))
        }
        Flavor::Unknown => None,
    }
}

/// Cura measures from +Y, clockwise (seen from above): Cura's `c` is our `90 − c`
/// (checked against CuraEngine 4.13's output, see tests/slicers.rs).
pub fn cura_to_direction(c: f64) -> f64 {
    (90.0 - c).rem_euclid(180.0)
}

/// The numbers of a list `[0, 90]`, `0,90` or `0;90`.
fn numbers(list: &str) -> Vec<f64> {
    list.split([',', ';', '[', ']', ' '])
        .filter(|p| !p.trim().is_empty())
        .filter_map(|p| p.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .collect()
}

/// Compares every layer with `expected` on `model` (whose layers are those of `layers`).
pub fn compare(
    layers: &[Layer],
    model: &Model,
    expected: &Expected,
    tolerance: f64,
) -> Result<Comparison, String> {
    let directions = expected_directions(expected, model)?;
    let mut out = Comparison {
        tolerance,
        ..Comparison::default()
    };
    for (l, want) in layers.iter().zip(directions) {
        let diff = l.sparse.map(|d| difference(d.direction, want));
        let matches = diff.map(|d| d.abs() <= tolerance);
        if let Some(m) = matches {
            out.compared += 1;
            out.matched += usize::from(m);
        }
        out.rows.push(Row {
            index: l.index,
            z: l.z,
            height: l.height,
            sparse: l.sparse,
            solid: l.solid,
            expected: Some(want),
            difference: diff,
            matches,
        });
    }
    Ok(out)
}

/// The expected direction of every layer of `model`, in [0, 180).
pub fn expected_directions(expected: &Expected, model: &Model) -> Result<Vec<f64>, String> {
    let wrap = |a: f64| a.rem_euclid(180.0);
    Ok(match expected {
        Expected::Cycle(list) if list.is_empty() => return Err("an empty list of angles".into()),
        Expected::Cycle(list) => (0..model.len())
            .map(|i| wrap(list[i % list.len()]))
            .collect(),
        Expected::Ramp { start, increment } => (0..model.len())
            .map(|i| wrap(start + increment * i as f64))
            .collect(),
        Expected::Template {
            text,
            dialect,
            base,
            seed,
        } => {
            let options = Options {
                base: *base,
                seed: *seed,
            };
            match dialect {
                Dialect::OrcaSlicer => crate::dialect::orcaslicer::layers(text, model, options)
                    .map(|l| wrap(l.angle))
                    .collect(),
                Dialect::Rotlang => {
                    let (parse, layers) =
                        eval::parse_layers(text, crate::Target::Sparse, model, options);
                    if parse.has_errors() {
                        let first = parse
                            .diagnostics
                            .iter()
                            .find(|d| d.is_error())
                            .map_or(String::new(), |d| format!(": {}", d.message));
                        return Err(format!("the template `{text}` has errors{first}"));
                    }
                    layers.map(|l| wrap(l.angle)).collect()
                }
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cura_angles_turn_into_directions() {
        assert_eq!(cura_to_direction(30.0), 60.0);
        assert_eq!(cura_to_direction(0.0), 90.0);
        assert_eq!(cura_to_direction(90.0), 0.0);
        assert_eq!(cura_to_direction(135.0), 135.0);
        assert_eq!(numbers("[0, 90]"), [0.0, 90.0]);
        assert_eq!(numbers("[ ]"), Vec::<f64>::new());
    }

    #[test]
    fn a_template_with_errors_is_an_error() {
        let model = Model::cube20();
        let e = expected_directions(
            &Expected::Template {
                text: "+30X".into(),
                dialect: Dialect::Rotlang,
                base: 0.0,
                seed: 0,
            },
            &model,
        );
        assert!(e.is_err());
        let ok = expected_directions(
            &Expected::Ramp {
                start: 170.0,
                increment: 20.0,
            },
            &model,
        )
        .expect("ramp");
        assert_eq!(&ok[..2], &[170.0, 10.0]);
    }
}
