//! The options object that every call takes (JSON from the JS wrapper): target, dialect,
//! model, base, seed and a layer range.

use rotlang::Target;
use rotlang::eval::{Model, Options};
use serde::Deserialize;

use crate::Failure;

#[derive(Deserialize, Default)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct Request {
    #[serde(default)]
    pub target: Option<String>,
    #[serde(default)]
    pub dialect: Option<String>,
    #[serde(default)]
    pub model: Option<ModelSpec>,
    #[serde(default)]
    pub base: Option<f64>,
    #[serde(default)]
    pub seed: Option<u64>,
    /// First layer to return (expand).
    #[serde(default)]
    pub from: Option<usize>,
    /// One past the last layer to return (expand).
    #[serde(default)]
    pub to: Option<usize>,
    /// Extra parameters of a call (plot and preview sizes, the preview's layer…).
    #[serde(default, flatten)]
    pub extra: serde_json::Map<String, serde_json::Value>,
}

/// A model as the JS API takes it. The heights of a list model arrive as a separate
/// `Float64Array` buffer, not in the JSON.
#[derive(Deserialize, Default)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct ModelSpec {
    pub layers: Option<f64>,
    pub height: Option<f64>,
    pub layer_height: Option<f64>,
    pub first_layer_height: Option<f64>,
    pub bottom_shells: Option<f64>,
    pub top_shells: Option<f64>,
}

impl Request {
    pub fn parse(json: &str) -> Result<Request, Failure> {
        if json.trim().is_empty() {
            return Ok(Request::default());
        }
        serde_json::from_str(json).map_err(|e| Failure::options(format!("bad options: {e}")))
    }

    pub fn target(&self) -> Result<Target, Failure> {
        match self.target.as_deref() {
            None | Some("sparse") => Ok(Target::Sparse),
            Some("solid") => Ok(Target::Solid),
            Some(other) => Err(Failure::options(format!(
                "unknown target `{other}`: use \"sparse\" or \"solid\""
            ))),
        }
    }

    pub fn eval_options(&self) -> Result<Options, Failure> {
        let base = self.base.unwrap_or(0.0);
        if !base.is_finite() {
            return Err(Failure::options("the base angle must be a finite number"));
        }
        Ok(Options {
            base,
            seed: self.seed.unwrap_or(0),
        })
    }

    /// The model: list heights when given, else the uniform model described, else the
    /// documentation's 20 mm cube.
    pub fn model(&self, heights: Option<Vec<f64>>) -> Result<Model, Failure> {
        let spec = self.model.as_ref();
        let get = |f: fn(&ModelSpec) -> Option<f64>| spec.and_then(f);
        let layer_height = get(|m| m.layer_height);
        let model = if let Some(heights) = heights {
            let h = layer_height.or(heights.first().copied()).unwrap_or(0.2);
            Model::from_heights(heights, h)
        } else if let Some(n) = get(|m| m.layers) {
            let n = count(n, "layers")?;
            Model::uniform(
                n,
                layer_height.unwrap_or(0.2),
                get(|m| m.first_layer_height),
            )
        } else if let Some(height) = get(|m| m.height) {
            Model::from_total_height(
                height,
                layer_height.unwrap_or(0.2),
                get(|m| m.first_layer_height),
            )
        } else if spec.is_some()
            && (layer_height.is_some() || get(|m| m.first_layer_height).is_some())
        {
            return Err(Failure::model(
                "the model needs `layers`, `height` or a list of layer heights",
            ));
        } else {
            Ok(Model::cube20())
        };
        let mut model = model.map_err(|e| Failure::model(e.to_string()))?;
        let bottom = get(|m| m.bottom_shells);
        let top = get(|m| m.top_shells);
        if bottom.is_some() || top.is_some() {
            let b = match bottom {
                Some(b) => shells(b, "bottomShells")?,
                None => model.bottom_shells(),
            };
            let t = match top {
                Some(t) => shells(t, "topShells")?,
                None => model.top_shells(),
            };
            model = model.with_shells(b, t);
        }
        Ok(model)
    }
}

/// A whole, non-negative count from a JSON number.
fn count(v: f64, what: &str) -> Result<usize, Failure> {
    if !(v.is_finite() && v >= 0.0 && v.fract() == 0.0) {
        return Err(Failure::model(format!(
            "`{what}` must be a whole number of layers, not {v}"
        )));
    }
    if v > rotlang::eval::MAX_LAYERS as f64 {
        return Err(Failure::model(format!(
            "the model would have {v} layers; at most {} are supported",
            rotlang::eval::MAX_LAYERS
        )));
    }
    Ok(v as usize)
}

fn shells(v: f64, what: &str) -> Result<u32, Failure> {
    if !(v.is_finite() && v >= 0.0 && v.fract() == 0.0 && v <= u32::MAX as f64) {
        return Err(Failure::model(format!(
            "`{what}` must be a whole number of layers, not {v}"
        )));
    }
    Ok(v as u32)
}
