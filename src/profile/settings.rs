//! A profile's own model: the settings a template depends on, and OrcaSlicer's defaults
//! where a key is missing (with a note saying so).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::eval::{Model, Options};
use crate::{Span, Target};

/// The keys that make the model and base: `layer_height` (`h`, and the height of every
/// layer above the first), `initial_layer_print_height`, `bottom_shell_layers` (`B`),
/// `top_shell_layers` (`T`), and the base direction: `sparse_infill_direction` (or the
/// older `infill_direction`) for sparse templates, `solid_infill_direction` for solid ones.
pub const MODEL_KEYS: [&str; 7] = [
    "layer_height",
    "initial_layer_print_height",
    "bottom_shell_layers",
    "top_shell_layers",
    "sparse_infill_direction",
    "infill_direction",
    "solid_infill_direction",
];

/// A profile says nothing about the object: the documentation's 20 mm cube.
pub const DEFAULT_OBJECT_HEIGHT: f64 = 20.0;

/// OrcaSlicer's defaults for the model keys.
const DEFAULT_LAYER_HEIGHT: f64 = 0.2;
const DEFAULT_FIRST_LAYER: f64 = 0.2;
const DEFAULT_BOTTOM: u32 = 3;
const DEFAULT_TOP: u32 = 4;
const DEFAULT_DIRECTION: f64 = 45.0;

/// How deep `inherits` chains are followed (OrcaSlicer's own are 2–4 deep).
const MAX_INHERITS: usize = 16;

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

/// The model keys (and `inherits`) of a profile or of one 3mf object.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    pub values: BTreeMap<String, Setting>,
}

/// The model and options a profile gives its templates, and notes on every default used.
#[derive(Clone, Debug)]
pub struct ProfileModel {
    pub model: Model,
    pub options: Options,
    pub notes: Vec<String>,
    /// Whether the direction in `options.base` is the profile's own (set in it, an object
    /// of it, or a preset it inherits), not OrcaSlicer's default.
    pub direction_set: bool,
}

impl ProfileModel {
    /// The OrcaSlicer compat lint of `text` on this model and base
    /// ([`crate::dialect::compat::compat`]). `orcaslicer::direction-ignored` only where the
    /// profile sets the direction itself: a default it never chose is nothing to act on,
    /// and the angles are compared without it all the same.
    pub fn compat(&self, text: &str, target: Target) -> Vec<crate::Diagnostic> {
        let mut found = crate::dialect::compat::compat(text, target, &self.model, self.options);
        if !self.direction_set {
            found.retain(|d| d.code != crate::dialect::compat::DIRECTION_IGNORED);
        }
        found
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
    /// unusable value noted. The base is the infill direction for the target.
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
        let direction_keys: &[&str] = match target {
            Target::Sparse => &["sparse_infill_direction", "infill_direction"],
            Target::Solid => &["solid_infill_direction"],
        };
        let direction_set = direction_keys
            .iter()
            .find_map(|k| lookup(k))
            .is_some_and(|s| parse_number(&s.value).is_some());
        let base = match target {
            Target::Sparse => number(
                &["sparse_infill_direction", "infill_direction"],
                DEFAULT_DIRECTION,
                "°",
                &mut notes,
            ),
            Target::Solid => number(
                &["solid_infill_direction"],
                DEFAULT_DIRECTION,
                "°",
                &mut notes,
            ),
        };
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
        let base = if base.is_finite() && base.abs() <= 1e6 {
            base
        } else {
            notes.push(format!(
                "the infill direction {base} is not usable: 0° is used"
            ));
            0.0
        };
        ProfileModel {
            model: model.with_shells(bottom, top),
            options: Options { base, seed: 0 },
            notes,
            direction_set,
        }
    }
}

/// `0.2`, `"0.2"`, ` 0.2 `, `15%` is not a height: only plain decimal numbers.
fn parse_number(text: &str) -> Option<f64> {
    let t = text.trim();
    let v: f64 = t.parse().ok()?;
    v.is_finite().then_some(v)
}

/// Fills the keys `settings` lacks from its parent presets: `<inherits>.json` in the
/// folder of `path` (OrcaSlicer's own preset folders are laid out so), then its parent.
pub(crate) fn resolve_inherits(settings: &mut Settings, path: &Path) {
    let Some(dir) = path.parent() else { return };
    let mut seen = vec![path.to_owned()];
    let mut parent = settings.inherits().map(str::to_owned);
    while let Some(name) = parent.take() {
        if seen.len() > MAX_INHERITS || name.contains(['/', '\\']) {
            break;
        }
        let file = dir.join(format!("{name}.json"));
        if seen.contains(&file) || !file.is_file() {
            break;
        }
        seen.push(file.clone());
        let Ok(profile) = super::read_bounded(&file).and_then(|b| super::parse(&file, &b)) else {
            break;
        };
        parent = profile.settings.inherits().map(str::to_owned);
        for (key, mut setting) in profile.settings.values {
            if key == "inherits" {
                continue;
            }
            setting.inherited_from = Some(file.clone());
            settings.values.entry(key).or_insert(setting);
        }
    }
    // Resolved: the note about a missing parent no longer applies.
    if seen.len() > 1 {
        settings.values.remove("inherits");
    }
}
