//! The settings a slicer writes into its G-code: `; key = value` comments (OrcaSlicer,
//! Bambu Studio, PrusaSlicer and SuperSlicer, at the end of the file) and Cura's
//! `;SETTING_3` lines (its profile, serialised as JSON of INI text). Only the keys that
//! bear on infill direction and layers are kept.

use std::collections::BTreeMap;

/// The keys kept. Everything else is skipped, so memory does not grow with the file.
const KEYS: &[&str] = &[
    "sparse_infill_rotate_template",
    "solid_infill_rotate_template",
    "sparse_infill_direction",
    "infill_direction",
    "solid_infill_direction",
    "sparse_infill_pattern",
    "layer_height",
    "initial_layer_print_height",
    "first_layer_height",
    "bottom_shell_layers",
    "top_shell_layers",
    "bottom_solid_layers",
    "top_solid_layers",
    "fill_angle",
    "fill_angle_increment",
    "fill_angle_template",
    "fill_angle_cross",
    "fill_pattern",
    "infill_angles",
    "skin_angles",
    "infill_pattern",
    "top_bottom_pattern",
    "bottom_layers",
    "top_layers",
    "layer_height_0",
    "infill_sparse_thickness",
];

/// The largest settings text of Cura kept (its whole profile is a few tens of KB).
const MAX_CURA: usize = 4 << 20;

/// Settings read from a G-code file.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    values: BTreeMap<&'static str, String>,
    cura: Vec<u8>,
}

impl Settings {
    /// The value of `key`, as written (trimmed).
    pub fn get(&self, key: &str) -> Option<&str> {
        self.values.get(key).map(String::as_str)
    }

    /// A number, or `None` when absent or unreadable (`45%` reads 45).
    pub fn number(&self, key: &str) -> Option<f64> {
        let v = self.get(key)?.trim().trim_end_matches('%');
        v.parse::<f64>().ok().filter(|v| v.is_finite())
    }

    /// Every kept setting, by key.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, &str)> {
        self.values.iter().map(|(k, v)| (*k, v.as_str()))
    }

    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// `key = value` (the comment's text after `; `).
    pub(crate) fn comment(&mut self, text: &[u8]) {
        let Some(eq) = text.iter().position(|&c| c == b'=') else {
            return;
        };
        let key = String::from_utf8_lossy(&text[..eq]);
        let key = key.trim();
        if let Some(k) = KEYS.iter().find(|k| **k == key) {
            let value = String::from_utf8_lossy(&text[eq + 1..]).trim().to_owned();
            self.values.insert(k, value);
        }
    }

    pub(crate) fn cura_chunk(&mut self, chunk: &[u8]) {
        if self.cura.len() + chunk.len() <= MAX_CURA {
            self.cura.extend_from_slice(chunk);
        }
    }

    /// Reads Cura's collected `;SETTING_3` text: a JSON object whose strings are INI
    /// profiles (global first, then extruders, which override it).
    pub(crate) fn finish(&mut self) {
        if self.cura.is_empty() {
            return;
        }
        let cura = std::mem::take(&mut self.cura);
        // Cura escapes the JSON once more for a comment (a backslash doubled, newlines as
        // `\n`): undone first; JSON that is not escaped is read as it is.
        let value = serde_json::from_slice::<serde_json::Value>(&unescape(&cura))
            .or_else(|_| serde_json::from_slice::<serde_json::Value>(&cura));
        let Ok(value) = value else {
            return;
        };
        let mut texts = Vec::new();
        collect_strings(&value, &mut texts);
        for text in texts {
            let mut in_values = false;
            for line in text.lines() {
                let line = line.trim();
                if line.starts_with('[') {
                    in_values = line == "[values]";
                } else if in_values {
                    self.comment(line.as_bytes());
                }
            }
        }
    }
}

/// Undoes Cura's escaping of its settings for G-code comments.
fn unescape(b: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1)) {
            (b'\\', Some(b'\\')) => {
                out.push(b'\\');
                i += 2;
            }
            (b'\\', Some(b'n')) => {
                out.push(b'\n');
                i += 2;
            }
            (b'\\', Some(b'r')) => {
                out.push(b'\r');
                i += 2;
            }
            (c, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    out
}

fn collect_strings<'a>(v: &'a serde_json::Value, out: &mut Vec<&'a str>) {
    match v {
        serde_json::Value::String(s) => out.push(s),
        serde_json::Value::Array(items) => items.iter().for_each(|i| collect_strings(i, out)),
        serde_json::Value::Object(map) => {
            // Global before extruders: extruder stacks override the global one.
            if let Some(g) = map.get("global_quality") {
                collect_strings(g, out);
            }
            for (k, v) in map {
                if k != "global_quality" {
                    collect_strings(v, out);
                }
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cura_settings_are_read_from_their_json() {
        let mut s = Settings::default();
        let text = r#"{"global_quality": "[general]\nversion = 4\n[values]\nlayer_height = 0.2\n", "extruder_quality": ["[general]\n[values]\ninfill_angles = [0, 90]\ninfill_pattern = lines\n"]}"#;
        let (a, b) = text.split_at(30);
        s.cura_chunk(a.as_bytes());
        s.cura_chunk(b.as_bytes());
        s.finish();
        assert_eq!(s.get("infill_angles"), Some("[0, 90]"));
        assert_eq!(s.number("layer_height"), Some(0.2));
    }

    #[test]
    fn cura_settings_as_cura_writes_them() {
        // What Cura 4's G-code writer puts after `;SETTING_3 `: JSON, escaped once more.
        let mut s = Settings::default();
        let line = r#"{"global_quality": "[general]\\nversion = 4\\n[values]\\nlayer_height = 0.15\\n", "extruder_quality": ["[general]\\n[values]\\ninfill_angles = [30,120]\\n"]}"#;
        for chunk in line.as_bytes().chunks(80) {
            s.cura_chunk(chunk);
        }
        s.finish();
        assert_eq!(s.get("infill_angles"), Some("[30,120]"));
        assert_eq!(s.number("layer_height"), Some(0.15));
    }

    #[test]
    fn only_known_keys_are_kept() {
        let mut s = Settings::default();
        s.comment(b"fill_angle = 30");
        s.comment(b"wipe_tower_x = 170");
        s.comment(b"no equals sign");
        assert_eq!(s.number("fill_angle"), Some(30.0));
        assert_eq!(s.iter().count(), 1);
    }
}
