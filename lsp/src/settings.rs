//! Client settings: the model that previews are computed for.
//!
//! Accepted from `initializationOptions`, `workspace/didChangeConfiguration` and
//! `workspace/configuration`, either as `{"rotlang": {...}}` or as the inner object
//! itself. Keys: `layers`, `layerHeight`, `firstLayerHeight`, `bottomShellLayers`,
//! `topShellLayers`, and `maxDocumentBytes` (the largest document checked). Each source sends the whole section, so a key it leaves out is back
//! at its default (removing a setting restores the default); an unusable value keeps its
//! previous value, so one typo does not throw away the rest, and is reported.

use serde_json::Value;

/// More layers than any printer makes; previews cost time per layer, so they stop here
/// (well below the evaluator's own limit).
pub const MAX_LAYERS: usize = 1_000_000;
const MAX_SHELLS: u32 = 10_000;
/// Documents larger than this are not checked (one diagnostic says so): templates are a
/// line of text, and a pasted log file must not cost the editor hundreds of megabytes.
pub const DEFAULT_MAX_DOCUMENT_BYTES: usize = 4 << 20;
use rotlang::eval::{MAX_LAYER_HEIGHT as MAX_HEIGHT, MIN_LAYER_HEIGHT as MIN_HEIGHT};

/// The model previews are evaluated on. The default is the documentation's 20 mm cube as
/// the library defines it (`Model::cube20`): 100 layers of 0.2 mm, 3 bottom and 4 top
/// shell layers (OrcaSlicer's defaults, what `B` and `T` count).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelSettings {
    pub layers: usize,
    pub layer_height: f64,
    pub first_layer_height: Option<f64>,
    pub bottom_shell_layers: u32,
    pub top_shell_layers: u32,
    /// `compat`: the OrcaSlicer compat lint (`rotlang::dialect::compat`) in diagnostics.
    pub compat: Compat,
    /// The largest document (bytes) the server parses; `maxDocumentBytes` raises it up to
    /// the largest message the server reads.
    pub max_document_bytes: usize,
}

/// When to add the OrcaSlicer compat findings to a document's diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Compat {
    /// `"auto"` (the default): for JSON and `.ini` profiles, which are OrcaSlicer's files.
    #[default]
    Auto,
    /// `"orcaslicer"` or `true`: for every document, `.rot` files included.
    On,
    /// `"off"` or `false`.
    Off,
}

impl Compat {
    /// Whether OrcaSlicer's reading matters for a document of `kind`: the compat findings
    /// are published, and formatting keeps what OrcaSlicer reads.
    pub fn applies_to(self, kind: crate::document::Kind) -> bool {
        match self {
            Compat::Off => false,
            Compat::On => true,
            Compat::Auto => kind != crate::document::Kind::Rot,
        }
    }

    fn from_value(value: &Value) -> Option<Compat> {
        match value {
            Value::Bool(true) => Some(Compat::On),
            Value::Bool(false) => Some(Compat::Off),
            Value::Null => Some(Compat::Auto),
            Value::String(s) => match s.to_ascii_lowercase().as_str() {
                "auto" => Some(Compat::Auto),
                "orcaslicer" | "on" => Some(Compat::On),
                "off" | "none" => Some(Compat::Off),
                _ => None,
            },
            _ => None,
        }
    }
}

impl Default for ModelSettings {
    fn default() -> Self {
        ModelSettings {
            layers: 100,
            layer_height: 0.2,
            first_layer_height: None,
            bottom_shell_layers: 3,
            top_shell_layers: 4,
            compat: Compat::Auto,
            max_document_bytes: DEFAULT_MAX_DOCUMENT_BYTES,
        }
    }
}

impl ModelSettings {
    /// The `rotlang` section of a settings object: `{"rotlang": {...}}`, or the inner
    /// object itself when it has one of our keys. `None` when the object says nothing
    /// about rotlang (a client pushing another tool's settings, or `null`).
    pub fn section(settings: &Value) -> Option<&Value> {
        match settings.get("rotlang") {
            Some(inner) => Some(inner),
            None => settings
                .as_object()
                .filter(|o| KEYS.iter().any(|k| o.contains_key(*k)))
                .map(|_| settings),
        }
    }

    /// These settings replaced by a whole `rotlang` section: keys left out go back to
    /// their defaults, invalid values keep the previous ones. Returns one line per
    /// problem (`layers = 0: …`), empty when everything was accepted.
    pub fn replace(&mut self, section: &Value) -> Vec<String> {
        if section.is_null() {
            *self = ModelSettings::default();
            return Vec::new();
        }
        let Some(obj) = section.as_object() else {
            return vec![format!(
                "rotlang = {section}: an object of settings expected"
            )];
        };
        let previous = *self;
        *self = ModelSettings::default();
        let mut rejected = Vec::new();
        for (key, value) in obj {
            let ok = match key.as_str() {
                "layers" => set(&mut self.layers, whole(value, 1, MAX_LAYERS as u64)),
                "layerHeight" => set(&mut self.layer_height, height(value)),
                "firstLayerHeight" => {
                    value.is_null() || set(&mut self.first_layer_height, height(value).map(Some))
                }
                "bottomShellLayers" => set(
                    &mut self.bottom_shell_layers,
                    whole(value, 0, MAX_SHELLS.into()).map(|n| n as u32),
                ),
                "topShellLayers" => set(
                    &mut self.top_shell_layers,
                    whole(value, 0, MAX_SHELLS.into()).map(|n| n as u32),
                ),
                "compat" => set(&mut self.compat, Compat::from_value(value)),
                "maxDocumentBytes" => set(
                    &mut self.max_document_bytes,
                    whole(value, 1024, crate::transport::MAX_MESSAGE as u64),
                ),
                // The VS Code extension's own settings (`rotlang.server.path`,
                // `rotlang.trace.server`) arrive in the same section.
                "server" | "trace" => continue,
                _ => {
                    rejected.push(format!(
                        "{}: not a rotlang setting (known: {})",
                        short(key),
                        KEYS.join(", ")
                    ));
                    continue;
                }
            };
            if !ok {
                self.keep(key, &previous);
                rejected.push(format!(
                    "{key} = {}: {}",
                    short(&value.to_string()),
                    expected(key)
                ));
            }
        }
        rejected
    }

    /// Put back the previous value of one key (after an invalid new one).
    fn keep(&mut self, key: &str, previous: &ModelSettings) {
        match key {
            "layers" => self.layers = previous.layers,
            "layerHeight" => self.layer_height = previous.layer_height,
            "firstLayerHeight" => self.first_layer_height = previous.first_layer_height,
            "bottomShellLayers" => self.bottom_shell_layers = previous.bottom_shell_layers,
            "topShellLayers" => self.top_shell_layers = previous.top_shell_layers,
            "compat" => self.compat = previous.compat,
            "maxDocumentBytes" => self.max_document_bytes = previous.max_document_bytes,
            _ => {}
        }
    }

    /// The object height in millimetres.
    pub fn height(&self) -> f64 {
        let first = self.first_layer_height.unwrap_or(self.layer_height);
        first + self.layer_height * (self.layers.saturating_sub(1)) as f64
    }

    /// "100 layers × 0.2 mm (20 mm)", with the first layer and shells when set.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{} layers × {} mm",
            self.layers,
            rotlang::explain::num(self.layer_height)
        );
        if let Some(first) = self.first_layer_height
            && first != self.layer_height
        {
            s.push_str(&format!(
                ", first layer {} mm",
                rotlang::explain::num(first)
            ));
        }
        s.push_str(&format!(
            " ({} mm tall)",
            rotlang::explain::num(self.height())
        ));
        if self.bottom_shell_layers > 0 || self.top_shell_layers > 0 {
            s.push_str(&format!(
                ", shells B = {}, T = {}",
                self.bottom_shell_layers, self.top_shell_layers
            ));
        }
        s
    }
}

/// The settings keys, as clients write them.
pub const KEYS: [&str; 7] = [
    "layers",
    "layerHeight",
    "firstLayerHeight",
    "bottomShellLayers",
    "topShellLayers",
    "compat",
    "maxDocumentBytes",
];

/// A value or key as quoted in a warning: a pasted megabyte must not become the message.
fn short(text: &str) -> String {
    const MAX: usize = 40;
    match text.char_indices().nth(MAX) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

/// What a key accepts, for the warning about an invalid value.
fn expected(key: &str) -> String {
    match key {
        "layers" => {
            format!("a whole number from 1 to {MAX_LAYERS} expected; kept the previous value")
        }
        "maxDocumentBytes" => format!(
            "a whole number of bytes from 1024 to {} expected; kept the previous value",
            crate::transport::MAX_MESSAGE
        ),
        "bottomShellLayers" | "topShellLayers" => {
            format!("a whole number from 0 to {MAX_SHELLS} expected; kept the previous value")
        }
        "compat" => {
            "\"auto\" (JSON and .ini profiles), \"orcaslicer\" (every document) or \"off\" expected; kept the previous value".to_owned()
        }
        "firstLayerHeight" => format!(
            "a height in mm from {MIN_HEIGHT} to {MAX_HEIGHT}, or null, expected; kept the previous value"
        ),
        _ => format!(
            "a height in mm from {MIN_HEIGHT} to {MAX_HEIGHT} expected; kept the previous value"
        ),
    }
}

fn set<T>(slot: &mut T, value: Option<T>) -> bool {
    match value {
        Some(v) => {
            *slot = v;
            true
        }
        None => false,
    }
}

/// A whole number in `[min, max]`; accepts `3` and `3.0` (some clients send floats).
fn whole(value: &Value, min: u64, max: u64) -> Option<usize> {
    let n = value.as_u64().or_else(|| {
        value
            .as_f64()
            .filter(|f| f.fract() == 0.0 && *f >= 0.0)
            .map(|f| f as u64)
    })?;
    (min..=max).contains(&n).then_some(n as usize)
}

/// A layer height in millimetres, within the evaluator's limits (0.001 – 1000 mm).
fn height(value: &Value) -> Option<f64> {
    value
        .as_f64()
        .filter(|h| h.is_finite() && (MIN_HEIGHT..=MAX_HEIGHT).contains(h))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_section_replaces_the_settings() {
        let mut m = ModelSettings::default();
        let wrapped = json!({"rotlang": {"layers": 10, "layerHeight": 0.3}});
        assert!(
            m.replace(ModelSettings::section(&wrapped).unwrap())
                .is_empty()
        );
        assert_eq!((m.layers, m.layer_height), (10, 0.3));
        // Bare; an invalid value keeps the previous one; a key left out is the default.
        let bare = json!({"layers": 0, "bottomShellLayers": 5.0, "x": 1});
        let rejected = m.replace(ModelSettings::section(&bare).unwrap());
        assert_eq!(rejected.len(), 2, "{rejected:?}");
        assert!(
            rejected[0].starts_with("layers = 0: a whole number from 1"),
            "{rejected:?}"
        );
        assert!(
            rejected[1].starts_with("x: not a rotlang setting"),
            "{rejected:?}"
        );
        assert_eq!((m.layers, m.bottom_shell_layers), (10, 5));
        assert_eq!(m.layer_height, 0.2, "left out: back to the default");
        assert!(!m.replace(&json!({"layerHeight": -1})).is_empty());
        assert!(!m.replace(&json!({"layerHeight": 0.0005})).is_empty());
        assert!(!m.replace(&json!("big")).is_empty());
        let huge = "x".repeat(100_000);
        let rejected = m.replace(&json!({ "layers": huge.clone(), huge.clone(): 1 }));
        assert!(rejected.iter().all(|r| r.len() < 200), "{rejected:?}");
        // Nothing about rotlang: no section.
        assert!(ModelSettings::section(&json!(null)).is_none());
        assert!(ModelSettings::section(&json!({"python": {}})).is_none());
        assert!(m.replace(&json!(null)).is_empty());
        assert_eq!(m, ModelSettings::default());
    }
}
