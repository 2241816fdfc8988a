//! The model options shared by `expand` and `explain`, and model files.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{UsageError, args, read_file};
use crate::eval::{self, Model};

/// OrcaSlicer's default shell counts, what a model file may leave out.
const DEFAULT_BOTTOM: u32 = 3;
const DEFAULT_TOP: u32 = 4;

#[derive(clap::Args, Debug, Clone, Default)]
pub struct ModelArgs {
    /// A uniform model of N layers (see --layer-height, --first-layer-height).
    /// Without --layers, --height or --model: the documentation's 20 mm cube.
    #[arg(long, help_heading = "Model", value_name = "N", value_parser = args::layers, allow_negative_numbers = true,
          conflicts_with_all = ["height", "model"])]
    pub layers: Option<usize>,
    /// A uniform model tall enough for an object of MM millimetres, e.g. --height 42.
    #[arg(long, help_heading = "Model", value_name = "MM", value_parser = args::millimetres, allow_negative_numbers = true,
          conflicts_with = "model")]
    pub height: Option<f64>,
    /// The standard layer height h in mm, with --layers or --height [default: 0.2].
    /// `#` lengths count it, and counts reaching past the top extend by it.
    #[arg(long, help_heading = "Model", value_name = "MM", value_parser = args::millimetres, allow_negative_numbers = true,
          conflicts_with = "model")]
    pub layer_height: Option<f64>,
    /// The first layer's height in mm, with --layers or --height [default: the layer height].
    #[arg(long, help_heading = "Model", value_name = "MM", value_parser = args::millimetres, allow_negative_numbers = true,
          conflicts_with = "model")]
    pub first_layer_height: Option<f64>,
    /// A model from a JSON file: {"layer_heights": [...], "layer_height": H,
    /// "bottom_shell_layers": B, "top_shell_layers": T} (shell counts optional: 3 and 4).
    /// For a file holding named models (like the conformance models.json), FILE:NAME.
    #[arg(long, help_heading = "Model", value_name = "FILE[:NAME]")]
    pub model: Option<String>,
    /// The bottom shell layer count, what `B` counts [default: 3, or the --model file's].
    #[arg(long, help_heading = "Model", value_name = "N", value_parser = args::shells, allow_negative_numbers = true)]
    pub bottom_shell_layers: Option<u32>,
    /// The top shell layer count, what `T` counts [default: 4, or the --model file's].
    #[arg(long, help_heading = "Model", value_name = "N", value_parser = args::shells, allow_negative_numbers = true)]
    pub top_shell_layers: Option<u32>,
}

/// A model and a few words on where it came from (echoed in JSON output).
pub struct Resolved {
    pub model: Model,
    /// `cube20`, `uniform`, or the file (and name) it was read from.
    pub source: String,
}

impl ModelArgs {
    /// The model the options describe (a usage error, with the reason, on any problem).
    pub fn resolve(&self) -> Result<Resolved, UsageError> {
        let h = self.layer_height.unwrap_or(0.2);
        let h0 = self.first_layer_height;
        let invalid = |e: eval::ModelError| UsageError(format!("invalid model: {e}"));
        let (model, source) = match (&self.model, self.layers, self.height) {
            (Some(spec), _, _) => {
                let (model, source) = model_file(spec)?;
                (model, source)
            }
            (None, Some(layers), _) => (
                Model::uniform(layers, h, h0).map_err(invalid)?,
                "uniform".to_owned(),
            ),
            (None, None, Some(height)) => (
                Model::from_total_height(height, h, h0).map_err(invalid)?,
                "uniform".to_owned(),
            ),
            (None, None, None) if self.layer_height.is_some() || h0.is_some() => {
                return Err(UsageError(
                    "--layer-height and --first-layer-height need --layers N or --height MM \
                     (without them the model is the 20 mm cube)"
                        .into(),
                ));
            }
            (None, None, None) => (Model::cube20(), "cube20".to_owned()),
        };
        let (bottom, top) = (
            self.bottom_shell_layers.unwrap_or(model.bottom_shells()),
            self.top_shell_layers.unwrap_or(model.top_shells()),
        );
        Ok(Resolved {
            model: model.with_shells(bottom, top),
            source,
        })
    }
}

/// `FILE` or `FILE:NAME`. A path that exists as written wins, so a path with a `:` in it
/// still works.
fn split_spec(spec: &str) -> (PathBuf, Option<&str>) {
    if Path::new(spec).exists() {
        return (PathBuf::from(spec), None);
    }
    match spec.rsplit_once(':') {
        Some((file, name)) if !file.is_empty() && !name.contains(['/', '\\']) => {
            (PathBuf::from(file), Some(name))
        }
        _ => (PathBuf::from(spec), None),
    }
}

/// Reads a model file: one model object, or an object of named models (with NAME).
fn model_file(spec: &str) -> Result<(Model, String), UsageError> {
    let (path, name) = split_spec(spec);
    let shown = path.display().to_string();
    let text = read_file(&path)?;
    let value: Value = serde_json::from_str(&text).map_err(|e| {
        UsageError(format!(
            "invalid model file {shown}: not JSON ({e})\n  {}",
            EXPECTED
        ))
    })?;
    let Value::Object(map) = &value else {
        return Err(UsageError(format!(
            "invalid model file {shown}: expected one JSON object\n  {EXPECTED}"
        )));
    };
    let single = map.contains_key("layer_heights");
    let (object, source) = match (name, single) {
        (None, true) => (&value, shown.clone()),
        (Some(name), true) => {
            return Err(UsageError(format!(
                "{shown} holds one model, not a map of named models: drop `:{name}`"
            )));
        }
        (name, false) => {
            let names: Vec<&str> = map.keys().map(String::as_str).collect();
            let list = if names.len() > 12 {
                format!("{}, …", names[..12].join(", "))
            } else {
                names.join(", ")
            };
            let Some(name) = name else {
                return Err(UsageError(format!(
                    "{shown} has no \"layer_heights\": if it holds named models ({list}), \
                     choose one with --model {shown}:NAME"
                )));
            };
            let object = map.get(name).ok_or_else(|| {
                UsageError(format!(
                    "{shown} has no model named `{name}`; it has: {list}"
                ))
            })?;
            (object, format!("{shown}:{name}"))
        }
    };
    let model =
        model_object(object).map_err(|e| UsageError(format!("invalid model {source}: {e}")))?;
    Ok((model, source))
}

const EXPECTED: &str = "expected an object like {\"layer_heights\": [0.3, 0.2, 0.2], \
\"layer_height\": 0.2, \"bottom_shell_layers\": 3, \"top_shell_layers\": 4} \
(shell counts optional), or an object of such objects by name";

/// One model object. Every error names its field.
fn model_object(value: &Value) -> Result<Model, String> {
    let Value::Object(map) = value else {
        return Err(format!("expected an object\n  {EXPECTED}"));
    };
    for key in map.keys() {
        if !matches!(
            key.as_str(),
            "layer_heights"
                | "layer_height"
                | "bottom_shell_layers"
                | "top_shell_layers"
                | "description"
        ) {
            return Err(format!(
                "unknown field `{key}`; the fields are layer_heights, layer_height, \
                 bottom_shell_layers, top_shell_layers and description"
            ));
        }
    }
    let heights = match map.get("layer_heights") {
        Some(Value::Array(items)) => items
            .iter()
            .enumerate()
            .map(|(i, v)| {
                v.as_f64()
                    .ok_or_else(|| format!("`layer_heights[{i}]` must be a number, not {v}"))
            })
            .collect::<Result<Vec<f64>, String>>()?,
        Some(other) => {
            return Err(format!(
                "`layer_heights` must be a list of numbers (mm), not {}",
                short(other)
            ));
        }
        None => return Err("missing field `layer_heights` (a list of numbers, mm)".into()),
    };
    let h = match map.get("layer_height") {
        Some(v) => v
            .as_f64()
            .ok_or_else(|| format!("`layer_height` must be a number (mm), not {}", short(v)))?,
        None => return Err("missing field `layer_height` (the standard layer height, mm)".into()),
    };
    let shells = |field: &str, default: u32| -> Result<u32, String> {
        match map.get(field) {
            None | Some(Value::Null) => Ok(default),
            Some(v) => v
                .as_u64()
                .and_then(|n| u32::try_from(n).ok())
                .ok_or_else(|| {
                    format!(
                        "`{field}` must be a whole number from 0 to {}, not {}",
                        u32::MAX,
                        short(v)
                    )
                }),
        }
    };
    let bottom = shells("bottom_shell_layers", DEFAULT_BOTTOM)?;
    let top = shells("top_shell_layers", DEFAULT_TOP)?;
    let model = Model::from_heights(heights, h).map_err(|e| match e {
        eval::ModelError::LayerHeight { index, .. } => {
            format!("`layer_heights[{index}]`: {e}")
        }
        eval::ModelError::StandardLayerHeight(_) => format!("`layer_height`: {e}"),
        eval::ModelError::NoLayers => format!("`layer_heights`: {e}"),
        other => other.to_string(),
    })?;
    Ok(model.with_shells(bottom, top))
}

/// A JSON value for an error message, cut short.
fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}
