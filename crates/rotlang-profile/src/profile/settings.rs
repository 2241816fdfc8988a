//! A profile's own model: the settings a template depends on, and OrcaSlicer's defaults
//! where a key is missing (with a note saying so).

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::eval::{Model, Options};
use crate::{Span, Target};

/// The keys that make the model and base: `layer_height` (`h`, and the height of every
/// layer above the first), `initial_layer_print_height`, `bottom_shell_layers` (`B`),
/// `top_shell_layers` (`T`), and the infill direction (the angle of an empty template):
/// `sparse_infill_direction` (or the older `infill_direction`) for sparse templates,
/// `solid_infill_direction` for solid ones.
pub const MODEL_KEYS: [&str; 7] = [
    "layer_height",
    "initial_layer_print_height",
    "bottom_shell_layers",
    "top_shell_layers",
    "sparse_infill_direction",
    "infill_direction",
    "solid_infill_direction",
];

/// The keys a part is filled with (`rotlang preview project.3mf`), read beside
/// [`MODEL_KEYS`] (a project's and each object's): the sparse infill's density and
/// pattern, the solid infill's pattern, the wall loops, the line widths and the nozzle.
pub const INFILL_KEYS: [&str; 7] = [
    "sparse_infill_density",
    "sparse_infill_pattern",
    "internal_solid_infill_pattern",
    "wall_loops",
    "line_width",
    "sparse_infill_line_width",
    "nozzle_diameter",
];

/// Whether a key's value is kept in [`Settings`]: a model key, an infill key, `inherits`.
pub(crate) fn is_setting(key: &str) -> bool {
    MODEL_KEYS.contains(&key) || INFILL_KEYS.contains(&key) || key == "inherits"
}

/// A profile says nothing about the object: the documentation's 20 mm cube.
pub const DEFAULT_OBJECT_HEIGHT: f64 = 20.0;

/// OrcaSlicer's defaults for the model keys.
const DEFAULT_LAYER_HEIGHT: f64 = 0.2;
const DEFAULT_FIRST_LAYER: f64 = 0.2;
const DEFAULT_BOTTOM: u32 = 3;
const DEFAULT_TOP: u32 = 4;
const DEFAULT_DIRECTION: f64 = 45.0;

/// One setting as written, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    /// The value as text (`"0.2"` and `0.2` both give `0.2`).
    pub value: String,
    /// Index into the profile's sources, and the value's span there.
    pub source: usize,
    pub span: Span,
    /// The parent preset it was inherited from, if not the file itself.
    pub inherited_from: Option<PathBuf>,
}

/// The model and infill keys (and `inherits`) of a profile or of one 3mf object.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    pub values: BTreeMap<String, Setting>,
}

/// The model a profile gives its templates, its infill direction, and notes on every
/// default used.
///
/// One reading of a profile, the slicer's: the direction (`sparse_infill_direction`, the
/// older `infill_direction`, or `solid_infill_direction`) is the angle of an **empty**
/// template only; any other template's angles are the template's alone. Both readings,
/// rotlang's and OrcaSlicer's, take their options from [`ProfileModel::options`], so a
/// profile gives the same angles in every tool and the two readings never part on the
/// direction.
#[derive(Clone, Debug)]
pub struct ProfileModel {
    pub model: Model,
    /// The infill direction for the target, and the key it comes from.
    pub direction: Direction,
    /// Notes on the model's defaults (layer heights, shells). The direction's own note is
    /// in [`Direction::note`]: it matters only for an empty template
    /// ([`ProfileModel::notes_for`]).
    pub notes: Vec<String>,
}

/// A profile's infill direction for one target.
#[derive(Clone, Debug, PartialEq)]
pub struct Direction {
    /// In degrees: the profile's value, or OrcaSlicer's default 45°.
    pub degrees: f64,
    /// The key as the file (or a preset it inherits, or its 3mf object) spells it:
    /// `sparse_infill_direction`, `infill_direction` or `solid_infill_direction`; `None`
    /// when no usable value is set and OrcaSlicer's default is used.
    pub key: Option<String>,
    /// Why the default is used (not set, not a number), if it is.
    pub note: Option<String>,
}

impl ProfileModel {
    /// The options of `text`, a template of this profile, in either reading: the direction
    /// is the base of an empty template, and of no other
    /// ([`crate::dialect::orcaslicer::profile_options`]).
    pub fn options(&self, text: &str) -> Options {
        crate::dialect::orcaslicer::profile_options(
            text,
            Options {
                base: self.direction.degrees,
                seed: 0,
            },
        )
    }

    /// The notes that bear on `text`: the model's, and the direction's only for an empty
    /// template (the only one it turns).
    pub fn notes_for(&self, text: &str) -> Vec<String> {
        let mut notes = self.notes.clone();
        if text.is_empty()
            && let Some(n) = &self.direction.note
        {
            notes.push(n.clone());
        }
        notes
    }

    /// The OrcaSlicer compat lint of `text` on this model, with the options of
    /// [`ProfileModel::options`] in both readings
    /// ([`crate::dialect::compat::compat`]).
    pub fn compat(&self, text: &str, target: Target) -> Vec<crate::Diagnostic> {
        crate::dialect::compat::compat(text, target, &self.model, self.options(text))
    }
}

impl Settings {
    pub(crate) fn set(&mut self, key: &str, value: String, source: usize, span: Span) {
        self.values.entry(key.to_owned()).or_insert(Setting {
            value,
            source,
            span,
            inherited_from: None,
        });
    }

    /// Adds the keys of `other` that are not set here.
    pub(crate) fn merge_missing(&mut self, other: Settings) {
        for (k, v) in other.values {
            self.values.entry(k).or_insert(v);
        }
    }

    /// The `inherits` value, if any.
    pub fn inherits(&self) -> Option<&str> {
        self.values
            .get("inherits")
            .map(|s| s.value.as_str())
            .filter(|s| !s.is_empty())
    }

    /// The model for a template of `target` on an object `height` mm tall (the profile
    /// does not know the object: [`DEFAULT_OBJECT_HEIGHT`] unless told): `own` (a 3mf
    /// object's settings) first, then these, then OrcaSlicer's defaults, each default or
    /// unusable value noted. The direction is the target's ([`ProfileModel::options`]
    /// decides where it applies).
    pub fn model(&self, own: Option<&Settings>, target: Target, height: f64) -> ProfileModel {
        let mut notes = Vec::new();
        let lookup = |key: &str| own.and_then(|o| o.values.get(key)).or(self.values.get(key));
        let missing = |key: &str, default: String, notes: &mut Vec<String>| {
            let why = match self.inherits() {
                Some(parent) => format!(
                    "not set here, and the parent preset `{parent}` (inherits) was not found beside it"
                ),
                None => "not set".to_owned(),
            };
            notes.push(format!(
                "`{key}` {why}: OrcaSlicer's default {default} is used"
            ));
        };
        let number = |keys: &[&str], default: f64, unit: &str, notes: &mut Vec<String>| {
            for key in keys {
                if let Some(s) = lookup(key) {
                    match parse_number(&s.value) {
                        Some(v) => return v,
                        None => {
                            notes.push(format!(
                                "`{key}` = `{}` is not a number: OrcaSlicer's default {default}{unit} is used",
                                s.value
                            ));
                            return default;
                        }
                    }
                }
            }
            missing(keys[0], format!("{default}{unit}"), notes);
            default
        };
        let h = number(&["layer_height"], DEFAULT_LAYER_HEIGHT, " mm", &mut notes);
        let first = number(
            &["initial_layer_print_height"],
            DEFAULT_FIRST_LAYER,
            " mm",
            &mut notes,
        );
        let bottom = number(
            &["bottom_shell_layers"],
            f64::from(DEFAULT_BOTTOM),
            "",
            &mut notes,
        );
        let top = number(
            &["top_shell_layers"],
            f64::from(DEFAULT_TOP),
            "",
            &mut notes,
        );
        let direction = direction(
            match target {
                Target::Sparse => &["sparse_infill_direction", "infill_direction"],
                Target::Solid => &["solid_infill_direction"],
            },
            &lookup,
            &missing,
        );
        let count = |v: f64, default: u32, key: &str, notes: &mut Vec<String>| {
            if (0.0..=1e6).contains(&v) && v.fract() == 0.0 {
                v as u32
            } else {
                notes.push(format!(
                    "`{key}` = {v} is not a layer count: OrcaSlicer's default {default} is used"
                ));
                default
            }
        };
        let (bottom, top) = (
            count(bottom, DEFAULT_BOTTOM, "bottom_shell_layers", &mut notes),
            count(top, DEFAULT_TOP, "top_shell_layers", &mut notes),
        );
        let model = match Model::from_total_height(height, h, Some(first)) {
            Ok(m) => m,
            Err(e) => {
                notes.push(format!(
                    "the profile's layer heights make no model ({e}): the 20 mm cube of 0.2 mm layers is used"
                ));
                Model::cube20()
            }
        };
        ProfileModel {
            model: model.with_shells(bottom, top),
            direction,
            notes,
        }
    }
}

/// The direction of the first of `keys` set (as the file spells it), or OrcaSlicer's
/// default with a note saying why.
fn direction<'a>(
    keys: &[&str],
    lookup: &dyn Fn(&str) -> Option<&'a Setting>,
    missing: &dyn Fn(&str, String, &mut Vec<String>),
) -> Direction {
    let default = |note: String| Direction {
        degrees: DEFAULT_DIRECTION,
        key: None,
        note: Some(note),
    };
    let Some((key, s)) = keys.iter().find_map(|k| lookup(k).map(|s| (*k, s))) else {
        let mut notes = Vec::new();
        missing(keys[0], format!("{DEFAULT_DIRECTION}°"), &mut notes);
        return default(notes.remove(0));
    };
    match parse_number(&s.value) {
        Some(v) if v.abs() <= 1e6 => Direction {
            degrees: v,
            key: Some(key.to_owned()),
            note: None,
        },
        Some(v) => default(format!(
            "`{key}` = {v} is not a usable direction: OrcaSlicer's default {DEFAULT_DIRECTION}° is used"
        )),
        None => default(format!(
            "`{key}` = `{}` is not a number: OrcaSlicer's default {DEFAULT_DIRECTION}° is used",
            s.value
        )),
    }
}

/// `0.2`, `"0.2"`, ` 0.2 `, `15%` is not a height: only plain decimal numbers.
fn parse_number(text: &str) -> Option<f64> {
    let t = text.trim();
    let v: f64 = t.parse().ok()?;
    v.is_finite().then_some(v)
}
