//! A profile file as every binding shows it: its templates (each with the base direction
//! the tools add to it), the model its settings describe, the profile's direction and the
//! notes, read by `rotlang_profile::profile` (with [`crate::profile::ProfileModel`] for the
//! model and the direction) for a binding to turn into its own objects.

use std::path::Path;

use crate::Target;
use crate::eval::Model;
use crate::profile::{self, DEFAULT_OBJECT_HEIGHT};
use rotlang::api::{ApiError, ErrorKind};

/// One template of the file.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileTemplate {
    /// The key (`sparse_infill_rotate_template`); `None` for a `.rot` file.
    pub key: Option<String>,
    /// For a per-object override of a `.3mf` project: the object it applies to.
    pub object: Option<String>,
    /// The setting it is the template of.
    pub target: Target,
    /// The template, unescaped.
    pub text: String,
    /// What every tool adds to this template's angles: the profile's direction only
    /// where the template is empty, as OrcaSlicer reads a profile.
    pub base: f64,
}

/// A note on the file: an error fails it, the rest is information.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProfileNote {
    /// One line of English.
    pub message: String,
    /// Whether it fails the file.
    pub error: bool,
}

/// What a binding shows of a profile file.
#[derive(Clone, Debug)]
pub struct ProfileSummary {
    /// `json`, `ini`, `3mf` or `template` (a `.rot` file); `None` when the kind was not recognised.
    pub kind: Option<&'static str>,
    /// The templates, in the file's order.
    pub templates: Vec<ProfileTemplate>,
    /// The model of the file's settings for its first template's target (an object
    /// [`DEFAULT_OBJECT_HEIGHT`] mm tall).
    pub model: Model,
    /// The model's first layer (mm), rounded as heights are printed.
    pub first_layer_height: Option<f64>,
    /// The profile's infill direction (degrees).
    pub base: f64,
    /// The file's notes, then the model's (as information).
    pub notes: Vec<ProfileNote>,
    /// Whether a note is an error.
    pub has_errors: bool,
}

/// The file `name` (its extension picks the kind: `.json`/`.jsonc` presets, `.ini`
/// exports, `.rot` templates, `.3mf` projects where built in) holding `bytes`. A file
/// that cannot be read at all is an [`ErrorKind::Profile`] error.
pub fn profile(name: &str, bytes: &[u8]) -> Result<ProfileSummary, ApiError> {
    let p = profile::parse(Path::new(name), bytes).map_err(|e| ApiError {
        kind: ErrorKind::Profile,
        message: e.message,
    })?;
    let target = p.templates.first().map_or(Target::Sparse, |t| t.target);
    let pm = p.model(target, None, DEFAULT_OBJECT_HEIGHT);
    let templates = p
        .templates
        .iter()
        .map(|t| ProfileTemplate {
            key: t.key.clone(),
            object: t.object.clone(),
            target: t.target,
            text: t.text.clone(),
            base: p
                .model(t.target, t.object.as_deref(), DEFAULT_OBJECT_HEIGHT)
                .options(&t.text)
                .base,
        })
        .collect();
    let notes = p
        .notes
        .iter()
        .map(|n| ProfileNote {
            message: n.message.clone(),
            error: n.error,
        })
        .chain(pm.notes.iter().map(|n| ProfileNote {
            message: n.clone(),
            error: false,
        }))
        .collect();
    let first_layer_height = pm
        .model
        .layer_bounds(0)
        .map(|(bottom, top)| crate::number::round_height(top - bottom));
    Ok(ProfileSummary {
        kind: p.kind.map(|k| k.name()),
        templates,
        first_layer_height,
        base: pm.direction.degrees,
        has_errors: p.has_errors(),
        notes,
        model: pm.model,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_preset_gives_its_templates_model_and_direction() {
        let text = r#"{"sparse_infill_rotate_template": "0, 90", "solid_infill_rotate_template": "",
            "layer_height": "0.25", "initial_layer_print_height": "0.3", "infill_direction": "30",
            "bottom_shell_layers": "2"}"#;
        let p = profile("pla.json", text.as_bytes()).unwrap();
        assert_eq!(p.kind, Some("json"));
        assert_eq!(p.model.layer_height(), 0.25);
        assert_eq!(p.first_layer_height, Some(0.3));
        assert_eq!(p.model.bottom_shells(), 2);
        assert_eq!(p.base, 30.0);
        let sparse = &p.templates[0];
        assert_eq!((sparse.text.as_str(), sparse.base), ("0, 90", 0.0));
        assert!(!p.has_errors, "{:?}", p.notes);
    }

    #[test]
    fn an_unreadable_file_is_a_profile_error() {
        let e = profile("x.json", &[0x7b, 0xff, 0xfe]).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Profile);
        assert!(e.message.contains("UTF-8"), "{e}");
        let broken = profile("x.json", b"this is not JSON {").unwrap();
        assert!(broken.has_errors && broken.notes.iter().any(|n| n.error));
    }
}
