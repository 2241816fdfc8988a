//! The template drives the infill: evaluate once, fill any layer.

use super::{Centring, Error, Order, Params, Pattern, Region, Toolpaths};
use crate::eval::{self, Evaluator, Layer, Model};
use crate::ir::{Fill, Template};

/// The profile's infill settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The sparse infill pattern.
    pub pattern: Pattern,
    /// The sparse infill density, in (0, 1].
    pub density: f64,
    pub nozzle: f64,
    pub centring: Centring,
    /// The pattern of `S` layers (the profile's solid infill pattern).
    pub solid_pattern: Pattern,
}

impl Default for Settings {
    /// Lines at 20% with a 0.4 mm nozzle, object-centred; solid layers of lines.
    fn default() -> Self {
        Settings {
            pattern: Pattern::Lines,
            density: 0.2,
            nozzle: 0.4,
            centring: Centring::Object,
            solid_pattern: Pattern::Lines,
        }
    }
}

impl Settings {
    /// What a layer of fill kind `fill` at `angle` and height `z` is filled with:
    /// sparse layers with the pattern at its density; the solid signs at 100%: `D` the
    /// sparse pattern, `S` the solid pattern, `O` concentric, `M` lines printed
    /// monotonically, `R` lines.
    pub fn params(&self, fill: Fill, angle: f64, z: f64) -> Params {
        let (pattern, density, order) = match fill {
            Fill::Sparse => (self.pattern, self.density, Order::Nearest),
            Fill::Dense => (self.pattern, 1.0, Order::Nearest),
            Fill::Solid => (self.solid_pattern, 1.0, Order::Nearest),
            Fill::Concentric => (Pattern::Concentric, 1.0, Order::Nearest),
            Fill::Monotonic => (Pattern::Lines, 1.0, Order::Monotonic),
            Fill::Rectilinear => (Pattern::Lines, 1.0, Order::Nearest),
        };
        Params {
            pattern,
            density,
            nozzle: self.nozzle,
            angle,
            z,
            centring: self.centring,
            order,
        }
    }
}

/// One filled layer: what the template said and what was printed.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerFill {
    pub layer: Layer,
    /// What is printed: the template's fill, or solid in a shell layer
    /// ([`Schedule::with_shells`]).
    pub printed: Fill,
    pub params: Params,
    pub paths: Toolpaths,
}

/// A template evaluated on a model, filling layers on demand. Asking for layers bottom
/// to top costs O(1) evaluation per layer (see [`Evaluator`]).
///
/// ```
/// use rotlang_geometry::infill::{self, Pattern, Region, Schedule, Settings};
/// use rotlang::eval::{Model, Options};
///
/// let template = rotlang::parse("+45", rotlang::Target::Sparse).template;
/// let model = Model::cube20();
/// let settings = Settings { pattern: Pattern::Grid, ..Settings::default() };
/// let mut schedule = Schedule::new(&template, &model, Options::default(), settings);
/// let region = Region::new(&infill::shapes::square(20.0), settings.nozzle)?;
/// let layer = schedule.layer(3, &region)?.expect("the cube has 100 layers");
/// assert_eq!(layer.params.angle, 180.0);
/// assert!(!layer.paths.polylines.is_empty());
/// # Ok::<(), rotlang_geometry::infill::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Schedule<'a> {
    evaluator: Evaluator<'a>,
    settings: Settings,
    /// The model's bottom and top shell counts and its layer count, when shell layers
    /// are printed solid.
    shells: Option<(usize, usize, usize)>,
}

impl<'a> Schedule<'a> {
    pub fn new(
        template: &'a Template,
        model: &'a Model,
        options: eval::Options,
        settings: Settings,
    ) -> Self {
        Schedule {
            evaluator: Evaluator::new(template, model, options),
            settings,
            shells: None,
        }
    }

    /// Prints the model's bottom and top shell layers solid where the template says
    /// sparse, as a slicer does (the template still turns them): what `rotlang preview`
    /// and the playground draw.
    pub fn with_shells(mut self, model: &Model) -> Self {
        self.shells = Some((
            model.bottom_shells() as usize,
            model.top_shells() as usize,
            model.len(),
        ));
        self
    }

    /// What `layer` is printed as: its fill, or solid in a shell.
    pub fn printed(&self, layer: &Layer) -> Fill {
        match self.shells {
            Some((bottom, top, n))
                if layer.fill == Fill::Sparse
                    && (layer.index < bottom || layer.index + top >= n) =>
            {
                Fill::Solid
            }
            _ => layer.fill,
        }
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The evaluated layer `index` (angle, fill, heights), or `None` past the top.
    pub fn evaluate(&mut self, index: usize) -> Option<Layer> {
        self.evaluator.layer(index)
    }

    /// Fills `region` as layer `index`; `None` past the top of the model.
    pub fn layer(&mut self, index: usize, region: &Region) -> Result<Option<LayerFill>, Error> {
        let Some(layer) = self.evaluator.layer(index) else {
            return Ok(None);
        };
        let printed = self.printed(&layer);
        let params = self
            .settings
            .params(printed, layer.angle, (layer.bottom + layer.top) / 2.0);
        let paths = region.fill(&params)?;
        Ok(Some(LayerFill {
            layer,
            printed,
            params,
            paths,
        }))
    }
}
