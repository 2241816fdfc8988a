//! A part, layer by layer: the mesh's section at each layer's middle, less its walls,
//! filled as the template says; and what printing it costs (extrusion, travel, time).

use geo::MultiPolygon;

use super::{Section, Slicer};
use crate::eval::{self, Layer, Model};
use crate::infill::{self, Error, Params, Region, Settings, Toolpaths};
use crate::ir::{Fill, Template};
use crate::mesh::Mesh;

/// How the part is printed around its infill.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartOptions {
    /// Wall loops: the infill starts `walls × line width` inside the section.
    pub walls: u32,
    /// Fill the bottom and top shell layers (the model's counts) solid, as slicers do,
    /// whatever the template says for them (a solid sign of the template is kept).
    pub shells: bool,
}

impl Default for PartOptions {
    fn default() -> Self {
        PartOptions {
            walls: 2,
            shells: true,
        }
    }
}

/// One layer of the part.
#[derive(Clone, Debug, PartialEq)]
pub struct PartLayer {
    pub layer: Layer,
    /// The mesh's section at the layer's middle.
    pub section: Section,
    /// The section less its walls: what the infill fills.
    pub infill_area: MultiPolygon<f64>,
    pub params: Params,
    pub paths: Toolpaths,
}

/// The layers of `mesh` (its lowest point on the plate) under `template`, one at a time:
/// memory is one layer's section and paths. `model` gives the layer heights (see
/// [`model_for`]).
pub struct Part<'a> {
    slicer: Slicer<'a>,
    evaluator: eval::Evaluator<'a>,
    model: &'a Model,
    settings: Settings,
    options: PartOptions,
    bottom: f64,
    next: usize,
}

/// A uniform model as tall as the mesh.
pub fn model_for(
    mesh: &Mesh,
    layer_height: f64,
    first: Option<f64>,
) -> Result<Model, eval::ModelError> {
    let height = mesh.bounds().map_or(0.0, |(lo, hi)| hi[2] - lo[2]);
    Model::from_total_height(height, layer_height, first)
}

impl<'a> Part<'a> {
    pub fn new(
        mesh: &'a Mesh,
        template: &'a Template,
        model: &'a Model,
        eval_options: eval::Options,
        settings: Settings,
        options: PartOptions,
    ) -> Part<'a> {
        Part {
            slicer: Slicer::new(mesh),
            evaluator: eval::Evaluator::new(template, model, eval_options),
            model,
            settings,
            options,
            bottom: mesh.bounds().map_or(0.0, |(lo, _)| lo[2]),
            next: 0,
        }
    }

    /// The fill kind of a layer: the template's, or solid in the shells.
    fn fill_of(&self, layer: &Layer) -> Fill {
        let n = self.model.len();
        let shell = layer.index < self.model.bottom_shells() as usize
            || layer.index + (self.model.top_shells() as usize) >= n;
        if self.options.shells && shell && layer.fill == Fill::Sparse {
            Fill::Solid
        } else {
            layer.fill
        }
    }
}

impl Iterator for Part<'_> {
    type Item = Result<PartLayer, Error>;

    fn next(&mut self) -> Option<Self::Item> {
        let layer = self.evaluator.layer(self.next)?;
        self.next += 1;
        let section = self
            .slicer
            .section(self.bottom + (layer.bottom + layer.top) / 2.0);
        let w = self.settings.nozzle;
        let infill_area = infill::inset(&section.region, self.options.walls as f64 * w);
        let fill = self.fill_of(&layer);
        let params = self
            .settings
            .params(fill, layer.angle, (layer.bottom + layer.top) / 2.0);
        let paths = match Region::new(&infill_area, w).and_then(|r| r.fill(&params)) {
            Ok(p) => p,
            Err(e) => return Some(Err(e)),
        };
        Some(Ok(PartLayer {
            layer,
            section,
            infill_area,
            params,
            paths,
        }))
    }
}

/// What printing the infill of a part costs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Summary {
    pub layers: usize,
    /// Extruded infill (mm of line).
    pub extrusion: f64,
    /// Travel between infill paths (mm), routed inside each layer.
    pub travel: f64,
    /// Printing time (s) at `speed` mm/s and travel at `travel_speed` mm/s.
    pub time: f64,
    /// Layers with sections that could not be closed (holes in the mesh's surface).
    pub open_layers: usize,
    /// Gaps closed between chain ends.
    pub bridged: usize,
}

impl Summary {
    pub fn add(&mut self, layer: &PartLayer, speed: f64, travel_speed: f64) {
        self.layers += 1;
        self.extrusion += layer.paths.length;
        self.travel += layer.paths.travel;
        self.time += layer.paths.length / speed + layer.paths.travel / travel_speed;
        self.open_layers += usize::from(layer.section.open > 0);
        self.bridged += layer.section.bridged;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;
    use geo::Area;

    #[test]
    fn a_cube_is_filled_inside_its_walls_with_solid_shells() {
        let cube = shapes::cuboid([20.0, 20.0, 10.0]);
        let template = crate::parse("+45", crate::Target::Sparse).template;
        let model = model_for(&cube, 0.2, None).unwrap().with_shells(3, 4);
        assert_eq!(model.len(), 50);
        let part = Part::new(
            &cube,
            &template,
            &model,
            eval::Options::default(),
            Settings::default(),
            PartOptions::default(),
        );
        let mut summary = Summary::default();
        let layers: Vec<PartLayer> = part.map(|l| l.unwrap()).collect();
        assert_eq!(layers.len(), 50);
        for l in &layers {
            summary.add(l, 100.0, 200.0);
            // Two walls of 0.4 mm: a 18.4 mm square left for the infill.
            let a = l.infill_area.unsigned_area();
            assert!(
                (a - 18.4 * 18.4).abs() < 1e-6,
                "layer {}: {a}",
                l.layer.index
            );
            let solid = !(3..46).contains(&l.layer.index);
            assert_eq!(l.params.density == 1.0, solid, "layer {}", l.layer.index);
        }
        assert_eq!(summary.layers, 50);
        assert!(summary.extrusion > 0.0 && summary.time > summary.extrusion / 100.0);
    }
}
