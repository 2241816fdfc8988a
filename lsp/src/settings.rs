//! Client settings: the model that previews are computed for.
//!
//! Accepted from `initializationOptions` and `workspace/didChangeConfiguration`, either as
//! `{"rotlang": {...}}` or as the inner object itself. Keys: `layers`, `layerHeight`,
//! `firstLayerHeight`, `bottomShellLayers`, `topShellLayers`, and `maxDocumentBytes` (the
//! largest document checked). A value that is missing or unusable keeps its previous
//! value, so one typo does not throw away the rest.

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
    /// The largest document (bytes) the server parses; `maxDocumentBytes` raises it up to
    /// the largest message the server reads.
    pub max_document_bytes: usize,
}

impl Default for ModelSettings {
    fn default() -> Self {
        ModelSettings {
            layers: 100,
            layer_height: 0.2,
            first_layer_height: None,
            bottom_shell_layers: 3,
            top_shell_layers: 4,
            max_document_bytes: DEFAULT_MAX_DOCUMENT_BYTES,
        }
    }
}

impl ModelSettings {
    /// These settings updated from a settings object; returns the keys that were rejected.
    pub fn update(&mut self, settings: &Value) -> Vec<String> {
        let inner = settings.get("rotlang").unwrap_or(settings);
        let Some(obj) = inner.as_object() else {
            return Vec::new();
        };
        let mut rejected = Vec::new();
        for (key, value) in obj {
            let ok = match key.as_str() {
                "layers" => set(&mut self.layers, whole(value, 1, MAX_LAYERS as u64)),
                "layerHeight" => set(&mut self.layer_height, height(value)),
                "firstLayerHeight" => {
                    if value.is_null() {
                        self.first_layer_height = None;
                        true
                    } else {
                        set(&mut self.first_layer_height, height(value).map(Some))
                    }
                }
                "bottomShellLayers" => set(
                    &mut self.bottom_shell_layers,
                    whole(value, 0, MAX_SHELLS.into()).map(|n| n as u32),
                ),
                "topShellLayers" => set(
                    &mut self.top_shell_layers,
                    whole(value, 0, MAX_SHELLS.into()).map(|n| n as u32),
                ),
                "maxDocumentBytes" => set(
                    &mut self.max_document_bytes,
                    whole(value, 1024, crate::transport::MAX_MESSAGE as u64),
                ),
                _ => true, // unknown keys belong to other tools or future versions
            };
            if !ok {
                rejected.push(key.clone());
            }
        }
        rejected
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
            crate::preview::fmt_num(self.layer_height)
        );
        if let Some(first) = self.first_layer_height
            && first != self.layer_height
        {
            s.push_str(&format!(
                ", first layer {} mm",
                crate::preview::fmt_num(first)
            ));
        }
        s.push_str(&format!(
            " ({} mm tall)",
            crate::preview::fmt_num(self.height())
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
    fn accepts_wrapped_and_bare_settings() {
        let mut m = ModelSettings::default();
        assert!(
            m.update(&json!({"rotlang": {"layers": 10, "layerHeight": 0.3}}))
                .is_empty()
        );
        assert_eq!((m.layers, m.layer_height), (10, 0.3));
        let rejected = m.update(&json!({"layers": 0, "bottomShellLayers": 3.0, "x": 1}));
        assert_eq!(rejected, vec!["layers".to_string()]);
        assert_eq!((m.layers, m.bottom_shell_layers), (10, 3));
        assert!(!m.update(&json!({"layerHeight": -1})).is_empty());
        assert!(!m.update(&json!({"layerHeight": 0.0005})).is_empty());
        assert_eq!(m.layer_height, 0.3);
        assert!(m.update(&json!(null)).is_empty());
    }
}
