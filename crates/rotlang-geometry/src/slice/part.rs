//! A part, layer by layer: the mesh's section at each layer's middle, less its walls,
//! filled as the template says; and what printing it costs (extrusion, travel, time).
//!
//! Top and bottom shells are areas, not whole layers, as slicers make them: the part of a
//! layer not covered by every one of the `T` layers above it is a top surface (or under
//! one), the part not covered by every one of the `B` layers below it a bottom surface;
//! both are filled solid, turned by the solid template (or, without one, by the sparse
//! template's angle), and the rest is sparse, turned by the sparse template. A cube's
//! first `B` and last `T` layers are solid throughout; the top of a step is solid on its
//! last `T` layers while the tower above it stays sparse. A solid sign of the template
//! (`D S O M R`) still makes its whole layer solid. Memory: the sections of a window of
//! `B + T + 1` layers.

use crate::math;
use std::collections::VecDeque;

use geo::{Area, BooleanOps, Coord, LineString, MultiPolygon, Polygon};

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
    /// Fill the top and bottom surfaces solid, `T` and `B` layers deep (the model's shell
    /// counts), as slicers do, wherever they are in the part; the rest is sparse.
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

/// One area of a layer and its infill.
#[derive(Clone, Debug, PartialEq)]
pub struct FilledArea {
    /// What it is printed as: `Sparse`, `Solid` (a top or bottom surface), or the
    /// template's solid sign on a layer it makes solid.
    pub fill: Fill,
    /// The area (part of the layer's infill area); empty when the layer has none of it.
    pub region: MultiPolygon<f64>,
    pub params: Params,
    pub paths: Toolpaths,
}

/// One layer of the part.
#[derive(Clone, Debug, PartialEq)]
pub struct PartLayer {
    /// The sparse template's layer: its angle turns the sparse area.
    pub layer: Layer,
    /// The angle the solid area is turned by: the solid template's at this layer, or the
    /// sparse template's without one (and on a layer a solid sign makes solid).
    pub solid_angle: f64,
    /// The mesh's section at the layer's middle.
    pub section: Section,
    /// The section less its walls: what the infill fills.
    pub infill_area: MultiPolygon<f64>,
    /// How many wall loops go round the infill area (see [`PartLayer::wall_loops`]).
    pub walls: u32,
    /// The sparse part of the infill area.
    pub sparse: FilledArea,
    /// The solid part: top and bottom surfaces, or the whole area on a solid layer.
    pub solid: FilledArea,
    /// Every path of the layer: the sparse area's, then the solid area's (lengths and
    /// travel summed, with the move between them).
    pub paths: Toolpaths,
}

impl PartLayer {
    /// The parameters that describe the layer as one: the sparse area's when it has any,
    /// else the solid area's.
    pub fn params(&self) -> &Params {
        if self.sparse.region.0.is_empty() && !self.solid.region.0.is_empty() {
            &self.solid.params
        } else {
            &self.sparse.params
        }
    }

    /// The wall loops, outermost first: the middle line of each wall, the section moved in
    /// by `(k + ½)` line widths for the `k`-th loop, each ring closed. Computed when asked
    /// (a preview draws a few layers; a summary needs none), from the same section and
    /// line width the infill area was inset from, so the infill starts where the last
    /// loop's line ends. A loop too narrow for the section is absent, as in a slicer.
    pub fn wall_loops(&self) -> Vec<LineString<f64>> {
        let w = self.sparse.params.nozzle;
        (0..self.walls)
            .flat_map(|k| {
                let inset = infill::inset(&self.section.region, (k as f64 + 0.5) * w);
                inset
                    .0
                    .into_iter()
                    .flat_map(|p| {
                        let (exterior, interiors) = p.into_inner();
                        std::iter::once(exterior).chain(interiors)
                    })
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    /// Whether the layer is solid throughout (no sparse area, some solid one).
    pub fn all_solid(&self) -> bool {
        self.sparse.region.0.is_empty() && !self.solid.region.0.is_empty()
    }
}

/// The layers of `mesh` (its lowest point on the plate) under `template`, one at a time:
/// memory is the sections of `B + T + 1` layers and one layer's paths. `model` gives the
/// layer heights and shell counts (see [`model_for`]).
pub struct Part<'a> {
    slicer: Slicer<'a>,
    evaluator: eval::Evaluator<'a>,
    /// The solid template's evaluator, when one turns the solid areas.
    solid: Option<eval::Evaluator<'a>>,
    model: &'a Model,
    settings: Settings,
    options: PartOptions,
    bottom: f64,
    next: usize,
    /// The sections of the layers around `next`, by index, lowest first.
    window: VecDeque<(usize, Section)>,
    /// The next layer to cut.
    cut: usize,
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
            solid: None,
            model,
            settings,
            options,
            bottom: mesh.bounds().map_or(0.0, |(lo, _)| lo[2]),
            next: 0,
            window: VecDeque::new(),
            cut: 0,
        }
    }

    /// Turns the solid areas by `template` (a `solid_infill_rotate_template`) instead of
    /// the sparse template's angle.
    pub fn with_solid_template(mut self, template: &'a Template, options: eval::Options) -> Self {
        self.solid = Some(eval::Evaluator::new(template, self.model, options));
        self
    }

    /// The shell depths in use: (bottom, top).
    fn shells(&self) -> (usize, usize) {
        if self.options.shells {
            (
                self.model.bottom_shells() as usize,
                self.model.top_shells() as usize,
            )
        } else {
            (0, 0)
        }
    }

    /// Cuts the layers up to `last` (those the model has), and forgets those below
    /// `first`.
    fn slide(&mut self, first: usize, last: usize) {
        while self.cut <= last {
            let Some((lo, hi)) = self.model.layer_bounds(self.cut) else {
                break;
            };
            let section = self.slicer.section(self.bottom + (lo + hi) / 2.0);
            self.window.push_back((self.cut, section));
            self.cut += 1;
        }
        while self.window.front().is_some_and(|(i, _)| *i < first) {
            self.window.pop_front();
        }
    }

    fn section_of(&self, index: usize) -> Option<&Section> {
        let first = self.window.front()?.0;
        self.window
            .get(index.checked_sub(first)?)
            .map(|(_, s)| s)
            .filter(|s| !s.region.0.is_empty())
    }

    /// The part of `area` (layer `i`'s infill area) covered by each of the `bottom`
    /// layers below and the `top` layers above: what is not a top or bottom surface.
    fn covered(&self, i: usize, area: &MultiPolygon<f64>) -> MultiPolygon<f64> {
        let (bottom, top) = self.shells();
        let empty = MultiPolygon::new(vec![]);
        if i < bottom || i + top >= self.model.len() {
            return empty;
        }
        let mut covered = area.clone();
        for j in (i - bottom..i).rev().chain(i + 1..=i + top) {
            let Some(s) = self.section_of(j) else {
                return empty;
            };
            covered = covered.intersection(&s.region);
            if covered.0.is_empty() {
                break;
            }
        }
        covered
    }
}

/// The solid part of `area` given the part `covered` by the layers around it: what is not
/// covered, less the slivers narrower than half a line (`w`), which a wall's slope leaves
/// between two boolean results and which no solid line could fill; then the sparse rest.
fn split(
    area: &MultiPolygon<f64>,
    covered: MultiPolygon<f64>,
    w: f64,
) -> (MultiPolygon<f64>, MultiPolygon<f64>) {
    if covered.0.is_empty() {
        return (area.clone(), MultiPolygon::new(vec![]));
    }
    let solid: Vec<Polygon<f64>> = area
        .difference(&covered)
        .0
        .into_iter()
        .filter(|p| 2.0 * p.unsigned_area() >= 0.5 * w * perimeter(p))
        .collect();
    if solid.is_empty() {
        return (MultiPolygon::new(vec![]), area.clone());
    }
    let solid = MultiPolygon::new(solid);
    let sparse = area.difference(&solid);
    (solid, sparse)
}

fn perimeter(p: &Polygon<f64>) -> f64 {
    std::iter::once(p.exterior())
        .chain(p.interiors())
        .map(|r| ring_length(&r.0))
        .sum()
}

fn ring_length(points: &[Coord]) -> f64 {
    points
        .windows(2)
        .map(|w| math::hypot((w[1] - w[0]).x, (w[1] - w[0]).y))
        .sum()
}

/// The rings of `region` (open: no repeated closing point), outlines first, for routing.
fn rings(region: &MultiPolygon<f64>) -> Vec<Vec<Coord>> {
    let open = |r: &LineString<f64>| {
        let mut c = r.0.clone();
        if c.len() > 1 && c.first() == c.last() {
            c.pop();
        }
        c
    };
    let mut out: Vec<Vec<Coord>> = region.0.iter().map(|p| open(p.exterior())).collect();
    out.extend(region.0.iter().flat_map(|p| p.interiors().iter().map(open)));
    out
}

/// The paths of both areas as one layer's: the sparse ones, then the solid ones, with
/// the move between them routed inside `area`.
fn joined(area: &MultiPolygon<f64>, sparse: &Toolpaths, solid: &Toolpaths) -> Toolpaths {
    let mut all = sparse.clone();
    all.polylines.extend(solid.polylines.iter().cloned());
    all.length += solid.length;
    let end = sparse.polylines.last().and_then(|p| p.0.last().copied());
    let start = solid.polylines.first().and_then(|p| p.0.first().copied());
    if let (Some(p), Some(q)) = (end, start) {
        let rings = rings(area);
        let router = crate::infill::travel::Router::new(&rings);
        let route = router.route(p, q);
        all.travel += ring_length(&route);
        all.travels.push(LineString::new(route));
    }
    all.travel += solid.travel;
    all.travels.extend(solid.travels.iter().cloned());
    all
}

impl Iterator for Part<'_> {
    type Item = Result<PartLayer, Error>;

    fn next(&mut self) -> Option<Self::Item> {
        let layer = self.evaluator.layer(self.next)?;
        let i = self.next;
        self.next += 1;
        let solid_layer = self.solid.as_mut().and_then(|e| e.layer(i));
        let (bottom, top) = self.shells();
        self.slide(i.saturating_sub(bottom), i + top);
        let section = match self.window.iter().find(|(j, _)| *j == i) {
            Some((_, s)) => s.clone(),
            None => Section {
                z: self.bottom + (layer.bottom + layer.top) / 2.0,
                region: MultiPolygon::new(vec![]),
                open: 0,
                bridged: 0,
            },
        };
        let w = self.settings.nozzle;
        let infill_area = infill::inset(&section.region, self.options.walls as f64 * w);
        let z = (layer.bottom + layer.top) / 2.0;
        let (solid_fill, solid_angle, solid_area, sparse_area) = if layer.fill != Fill::Sparse {
            // A solid sign: the whole layer, turned by the sparse template.
            (
                layer.fill,
                layer.angle,
                infill_area.clone(),
                MultiPolygon::new(vec![]),
            )
        } else {
            let covered = self.covered(i, &infill_area);
            let (solid, sparse) = split(&infill_area, covered, w);
            let angle = solid_layer.as_ref().map_or(layer.angle, |l| l.angle);
            (Fill::Solid, angle, solid, sparse)
        };
        let fill = |region: MultiPolygon<f64>, params: Params| {
            let paths = if region.0.is_empty() {
                Toolpaths::default()
            } else {
                Region::new(&region, w).and_then(|r| r.fill(&params))?
            };
            Ok::<_, Error>((region, params, paths))
        };
        let sparse = match fill(
            sparse_area,
            self.settings.params(Fill::Sparse, layer.angle, z),
        ) {
            Ok((region, params, paths)) => FilledArea {
                fill: Fill::Sparse,
                region,
                params,
                paths,
            },
            Err(e) => return Some(Err(e)),
        };
        let solid = match fill(solid_area, self.settings.params(solid_fill, solid_angle, z)) {
            Ok((region, params, paths)) => FilledArea {
                fill: solid_fill,
                region,
                params,
                paths,
            },
            Err(e) => return Some(Err(e)),
        };
        let paths = joined(&infill_area, &sparse.paths, &solid.paths);
        Some(Ok(PartLayer {
            layer,
            solid_angle,
            section,
            infill_area,
            walls: self.options.walls,
            sparse,
            solid,
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
    /// Of `extrusion`, the solid areas' (top and bottom surfaces, solid layers).
    pub solid_extrusion: f64,
}

impl Summary {
    pub fn add(&mut self, layer: &PartLayer, speed: f64, travel_speed: f64) {
        self.layers += 1;
        self.extrusion += layer.paths.length;
        self.travel += layer.paths.travel;
        self.time += layer.paths.length / speed + layer.paths.travel / travel_speed;
        self.open_layers += usize::from(layer.section.open > 0);
        self.bridged += layer.section.bridged;
        self.solid_extrusion += layer.solid.paths.length;
    }
}

#[cfg(test)]
mod tests;
