//! A part's JSON: what `rotlang preview --shape part.stl --format json` prints and what the
//! playground's `part()` answers, built here once so that the two cannot differ.
//!
//! ```
//! use rotlang_geometry::mesh::shapes;
//! use rotlang_geometry::slice::json::{About, Document};
//! use rotlang_geometry::slice::{Part, PartOptions};
//!
//! let cube = shapes::cuboid([10.0, 10.0, 2.0]);
//! let model = rotlang::eval::Model::from_total_height(2.0, 0.2, None).unwrap();
//! let template = rotlang::parse("+45", rotlang::Target::Sparse).template;
//! let settings = rotlang_geometry::infill::Settings::default();
//! let options = rotlang::eval::Options::default();
//! let mut doc = Document::new(About::new("+45", &model, settings, 2, options.base));
//! for layer in Part::new(&cube, &template, &model, options, settings, PartOptions::default()) {
//!     let layer = layer.unwrap();
//!     let shown = layer.layer.index < 3;
//!     doc.add(&layer, shown);
//! }
//! let json = doc.finish();
//! assert_eq!(json["summary"]["layers"], 10);
//! assert_eq!(json["layers"].as_array().unwrap().len(), 3);
//! assert_eq!(json["layers"][0]["printed"], "solid");
//! ```

use geo::{Area, LineString, MultiPolygon};
use serde_json::{Value, json};

use super::{FilledArea, PartLayer, Summary};
use crate::eval::Model;
use crate::infill::{Settings, Toolpaths};
use crate::ir::Fill;

/// The CLI's default speeds (`--speed`, `--travel-speed`), for the summary's time.
pub const SPEED: f64 = 100.0;
pub const TRAVEL_SPEED: f64 = 200.0;

/// What the part was filled with: the JSON's `template`, `solid_template` and `settings`,
/// and the speeds its summary's time is counted at.
#[derive(Clone, Copy, Debug)]
pub struct About<'a> {
    pub template: &'a str,
    /// The solid template's text, when one turns the solid areas.
    pub solid_template: Option<&'a str>,
    pub model: &'a Model,
    pub settings: Settings,
    pub walls: u32,
    /// The base direction the templates are evaluated with.
    pub base: f64,
    /// Infill and travel speeds (mm/s).
    pub speed: f64,
    pub travel_speed: f64,
}

impl<'a> About<'a> {
    /// No solid template, the default speeds.
    pub fn new(
        template: &'a str,
        model: &'a Model,
        settings: Settings,
        walls: u32,
        base: f64,
    ) -> About<'a> {
        About {
            template,
            solid_template: None,
            model,
            settings,
            walls,
            base,
            speed: SPEED,
            travel_speed: TRAVEL_SPEED,
        }
    }
}

/// The part's JSON, built a layer at a time: every layer counts in the summary, the shown
/// ones are kept.
#[derive(Clone, Debug)]
pub struct Document<'a> {
    about: About<'a>,
    summary: Summary,
    layers: Vec<Value>,
    points: usize,
}

impl<'a> Document<'a> {
    pub fn new(about: About<'a>) -> Document<'a> {
        Document {
            about,
            summary: Summary::default(),
            layers: Vec::new(),
            points: 0,
        }
    }

    /// Counts `l` in the summary and, when `shown`, keeps its JSON.
    pub fn add(&mut self, l: &PartLayer, shown: bool) {
        self.summary
            .add(l, self.about.speed, self.about.travel_speed);
        if shown {
            let walls = l.wall_loops();
            self.points += points(l) + walls.iter().map(|r| r.0.len()).sum::<usize>();
            self.layers.push(layer_with(l, &walls));
        }
    }

    /// The summary so far (every layer added).
    pub fn summary(&self) -> &Summary {
        &self.summary
    }

    /// The points (sections, areas and paths) of the layers kept so far: what bounds the
    /// answer's size.
    pub fn points(&self) -> usize {
        self.points
    }

    /// The whole JSON: `template`, `solid_template`, `settings`, `summary`, `layers`.
    pub fn finish(self) -> Value {
        let (a, s, m) = (&self.about, &self.summary, self.about.model);
        json!({
            "template": a.template,
            "solid_template": a.solid_template,
            "settings": {
                "pattern": a.settings.pattern.name(),
                "density": a.settings.density,
                "solid_pattern": a.settings.solid_pattern.name(),
                "line_width": a.settings.nozzle,
                "walls": a.walls,
                "layer_height": m.layer_height(),
                "layers": m.len(),
                "bottom_shell_layers": m.bottom_shells(),
                "top_shell_layers": m.top_shells(),
                "base": a.base,
            },
            "summary": {
                "layers": s.layers,
                "extrusion_mm": s.extrusion,
                "travel_mm": s.travel,
                "time_s": s.time,
                "speed": a.speed,
                "travel_speed": a.travel_speed,
                "open_layers": s.open_layers,
                "bridged": s.bridged,
                "solid_extrusion_mm": s.solid_extrusion,
            },
            "layers": self.layers,
        })
    }
}

/// One layer's JSON (an element of the document's `layers`).
pub fn layer(l: &PartLayer) -> Value {
    layer_with(l, &l.wall_loops())
}

/// One layer's JSON with its wall loops (`walls`: closed rings, outermost first).
fn layer_with(l: &PartLayer, walls: &[LineString<f64>]) -> Value {
    // The areas that are not empty: the sparse one, then the solid one.
    let areas: Vec<Value> = [&l.sparse, &l.solid]
        .into_iter()
        .filter(|a| !a.region.0.is_empty())
        .map(area)
        .collect();
    json!({
        "index": l.layer.index,
        "bottom": l.layer.bottom,
        "top": l.layer.top,
        "z": l.section.z,
        "angle": l.layer.angle,
        "solid_angle": l.solid_angle,
        "fill": l.layer.fill.name(),
        "printed": printed(l),
        "pattern": l.params().pattern.name(),
        "density": l.params().density,
        "length": l.paths.length,
        "travel": l.paths.travel,
        "open": l.section.open,
        "bridged": l.section.bridged,
        "section": rings(&l.section.region),
        "walls": walls
            .iter()
            .map(|r| r.0.iter().map(|c| [c.x, c.y]).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "areas": areas,
        "polylines": polylines(&l.paths),
    })
}

/// What a layer prints: `sparse`, a solid fill throughout (`solid` for top and bottom
/// surfaces, or the template's solid sign), or `sparse+solid`.
pub fn printed(l: &PartLayer) -> &'static str {
    match (l.sparse.region.0.is_empty(), l.solid.region.0.is_empty()) {
        (false, false) => "sparse+solid",
        (true, false) => l.solid.fill.name(),
        _ => "sparse",
    }
}

fn area(a: &FilledArea) -> Value {
    json!({
        "fill": a.fill.name(),
        "solid": a.fill != Fill::Sparse,
        "angle": a.params.angle,
        "pattern": a.params.pattern.name(),
        "density": a.params.density,
        "area_mm2": a.region.unsigned_area(),
        "region": rings(&a.region),
        "length": a.paths.length,
        "travel": a.paths.travel,
        "polylines": polylines(&a.paths),
    })
}

fn points(l: &PartLayer) -> usize {
    let region = |r: &MultiPolygon<f64>| -> usize {
        r.0.iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
            .map(|r| r.0.len())
            .sum()
    };
    let paths = |p: &Toolpaths| -> usize { p.polylines.iter().map(|p| p.0.len()).sum() };
    region(&l.section.region)
        + paths(&l.paths)
        + [&l.sparse, &l.solid]
            .iter()
            .map(|a| region(&a.region) + paths(&a.paths))
            .sum::<usize>()
}

fn polylines(paths: &Toolpaths) -> Vec<Vec<[f64; 2]>> {
    paths
        .polylines
        .iter()
        .map(|p| p.0.iter().map(|c| [c.x, c.y]).collect())
        .collect()
}

/// A region's polygons, each its outline then its holes, as `[x, y]` lists.
fn rings(region: &MultiPolygon<f64>) -> Vec<Vec<Vec<[f64; 2]>>> {
    region
        .0
        .iter()
        .map(|p| {
            std::iter::once(p.exterior())
                .chain(p.interiors())
                .map(|r| r.0.iter().map(|c| [c.x, c.y]).collect())
                .collect()
        })
        .collect()
}
