//! One reading of a template: the model and the options (the base) its angles are computed
//! on. Hover, inlay hints, symbols and the compat diagnostics of a template all take it from
//! here, so they never disagree on a layer.
//!
//! In a profile (JSON, `.ini`) the reading is the library's: the profile's own layer
//! heights, shells and infill direction (`rotlang_profile::profile::ProfileModel`), with the base
//! the library decides (OrcaSlicer's rule: the direction turns an empty template only). In a
//! `.rot` file it is the model of the client's settings, with no base.

use rotlang::eval::{Model, Options};
use rotlang_profile::profile::ProfileModel;

#[derive(Clone, Debug)]
pub struct Reading {
    pub model: Model,
    pub options: Options,
    /// The model in words, for hovers and tooltips.
    pub describe: String,
}

impl Reading {
    /// The reading of `text`, a template of a profile whose model the library gave: the one
    /// place the server takes a profile's base from.
    pub fn of_profile(profile: &ProfileModel, text: &str) -> Reading {
        // The library's options for this template: its base is the profile's direction only
        // where OrcaSlicer uses it (an empty template). When the library's `ProfileModel`
        // gives `options(text)` itself, this line becomes that call.
        let options = profile.options(text);
        Reading {
            describe: format!(
                "{}, from this profile (the object's height is not in a profile: {} mm assumed)",
                rotlang::explain::model(&profile.model),
                rotlang::explain::num(rotlang_profile::profile::DEFAULT_OBJECT_HEIGHT)
            ),
            model: profile.model.clone(),
            options,
        }
    }

    /// The number of layers of the model.
    pub fn layers(&self) -> usize {
        self.model.len()
    }
}
