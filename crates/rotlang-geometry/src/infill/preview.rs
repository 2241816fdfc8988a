//! The preview picture: one panel per layer, the region and its infill as printed.
//!
//! Lines are drawn at the nozzle's width, coloured by the order they are printed (blue
//! first, through green and yellow, to red last); travel moves are thin dashed grey lines;
//! the region's outline and holes are drawn in dark grey over a light fill. Each panel is
//! labelled with the layer, its height, its angle and fill, and the instruction that
//! governs it. A pure function of its inputs (the playground calls it in the browser).

use crate::math;
use std::fmt::Write;
use std::ops::Range;

use geo::{Coord, LineString, MultiPolygon};

use super::{Error, Region, Schedule, Settings, Toolpaths};
use crate::eval::{self, Model};
use crate::ir::{Fill, Template};
use crate::plot::{escape, num, shorten};

/// The size and layout of the panels.
#[derive(Clone, Debug, PartialEq)]
pub struct PreviewOptions {
    /// The side of a panel's drawing area, in pixels.
    pub panel: f64,
    /// Panels per row.
    pub columns: usize,
    /// Draw the travel moves between paths.
    pub travel: bool,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        PreviewOptions {
            panel: 280.0,
            columns: 4,
            travel: true,
        }
    }
}

/// One panel: a region, its toolpaths and two lines of labels.
#[derive(Clone, Debug)]
pub struct Panel<'a> {
    pub region: &'a MultiPolygon<f64>,
    /// Wall loops to draw round the infill (a part's layer; none for a bare region),
    /// closed rings at the line width, in grey.
    pub walls: &'a [LineString<f64>],
    pub paths: &'a Toolpaths,
    pub title: String,
    pub subtitle: String,
}

/// The wall loops' grey: apart from the print order's hues and the travel's dashes.
const WALL: &str = "#b8b8b8";

/// The height of a panel's label area above its drawing (pixels).
pub const LABEL_HEIGHT: f64 = 40.0;
const MARGIN: f64 = 12.0;
const GAP: f64 = 16.0;
/// The strip under the panels that says what the colours and dashes mean.
const LEGEND_HEIGHT: f64 = 22.0;

/// The mapping from region coordinates (mm, y up) to the pixels of panel number `index`
/// (y down): `(scale, offset)` with `pixel = (x·scale + offset.x, −y·scale + offset.y)`.
pub fn transform(
    region: &MultiPolygon<f64>,
    index: usize,
    options: &PreviewOptions,
) -> (f64, Coord) {
    let (min, max) = bounds(region);
    let size = max - min;
    let inner = options.panel - 2.0 * MARGIN;
    let scale = inner / size.x.max(size.y).max(1e-9);
    let columns = options.columns.max(1);
    let (col, row) = ((index % columns) as f64, (index / columns) as f64);
    let left = GAP + col * (options.panel + GAP);
    let top = GAP + row * (options.panel + LABEL_HEIGHT + GAP) + LABEL_HEIGHT;
    // Centred in the panel.
    let cx = left + options.panel / 2.0 - (min.x + size.x / 2.0) * scale;
    let cy = top + options.panel / 2.0 + (min.y + size.y / 2.0) * scale;
    (scale, Coord { x: cx, y: cy })
}

fn bounds(region: &MultiPolygon<f64>) -> (Coord, Coord) {
    let mut min = Coord {
        x: f64::INFINITY,
        y: f64::INFINITY,
    };
    let mut max = Coord {
        x: f64::NEG_INFINITY,
        y: f64::NEG_INFINITY,
    };
    for p in &region.0 {
        for c in p.exterior().coords() {
            min = Coord {
                x: min.x.min(c.x),
                y: min.y.min(c.y),
            };
            max = Coord {
                x: max.x.max(c.x),
                y: max.y.max(c.y),
            };
        }
    }
    if min.x.is_finite() {
        (min, max)
    } else {
        (Coord::zero(), Coord { x: 1.0, y: 1.0 })
    }
}

/// Appends the SVG path data of a polyline through `points` (`M x y L x y …`), each
/// coordinate printed with `digits` decimals at most.
fn path_data(out: &mut String, points: impl Iterator<Item = (f64, f64)>, digits: usize) {
    for (k, (x, y)) in points.enumerate() {
        let _ = write!(
            out,
            "{}{} {}",
            if k == 0 { 'M' } else { 'L' },
            num(x, digits),
            num(y, digits)
        );
    }
}

/// The colour of the `i`-th of `n` paths: a hue from blue (first) to red (last).
pub fn colour(i: usize, n: usize) -> String {
    let t = if n <= 1 {
        0.0
    } else {
        i as f64 / (n - 1) as f64
    };
    format!("hsl({:.0},85%,42%)", 240.0 * (1.0 - t))
}

/// The picture of `panels`, `options.columns` to a row.
pub fn svg(panels: &[Panel<'_>], nozzle: f64, options: &PreviewOptions) -> String {
    let columns = options.columns.max(1);
    let rows = panels.len().div_ceil(columns).max(1);
    let walled = panels.iter().any(|p| !p.walls.is_empty());
    let width = GAP + columns.min(panels.len().max(1)) as f64 * (options.panel + GAP);
    // The legend's last entry (the walls', at 410–480 px) stays inside the picture.
    let width = if walled {
        width.max(GAP + 480.0)
    } else {
        width
    };
    let height = GAP + rows as f64 * (options.panel + LABEL_HEIGHT + GAP) + LEGEND_HEIGHT;
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#,
        w = num(width, 1),
        h = num(height, 1)
    );
    s.push_str(r##"<rect width="100%" height="100%" fill="#ffffff"/>"##);
    for (index, panel) in panels.iter().enumerate() {
        let (scale, offset) = transform(panel.region, index, options);
        let px = |c: Coord| (c.x * scale + offset.x, -c.y * scale + offset.y);
        let columns = options.columns.max(1);
        let left = GAP + (index % columns) as f64 * (options.panel + GAP);
        let top = GAP + (index / columns) as f64 * (options.panel + LABEL_HEIGHT + GAP);
        let _ = write!(
            s,
            r##"<text x="{}" y="{}" font-weight="bold">{}</text><text x="{}" y="{}" fill="#444">{}</text>"##,
            num(left, 2),
            num(top + 14.0, 2),
            escape(&panel.title),
            num(left, 2),
            num(top + 30.0, 2),
            escape(&panel.subtitle)
        );
        // The region: light fill, holes cut out (even-odd), outline on top.
        let mut outline = String::new();
        for p in &panel.region.0 {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                path_data(&mut outline, ring.0.iter().map(|&c| px(c)), 2);
                outline.push('Z');
            }
        }
        let _ = write!(
            s,
            r##"<path d="{outline}" fill="#eeeeee" fill-rule="evenodd" stroke="none"/>"##
        );
        let n = panel.paths.polylines.len();
        let stroke = (nozzle * scale).max(1.0);
        if !panel.walls.is_empty() {
            let mut walls = String::new();
            for ring in panel.walls {
                path_data(&mut walls, ring.0.iter().map(|&c| px(c)), 2);
            }
            let _ = write!(
                s,
                r##"<path class="walls" d="{walls}" fill="none" stroke="{WALL}" stroke-width="{}" stroke-linejoin="round"/>"##,
                num(stroke, 2)
            );
        }
        if options.travel {
            let mut travel = String::new();
            for route in &panel.paths.travels {
                path_data(&mut travel, route.0.iter().map(|&c| px(c)), 2);
            }
            let _ = write!(
                s,
                r##"<path d="{travel}" fill="none" stroke="#9a9a9a" stroke-width="0.6" stroke-dasharray="2 2"/>"##
            );
        }
        for (i, line) in panel.paths.polylines.iter().enumerate() {
            let mut d = String::new();
            path_data(&mut d, line.0.iter().map(|&c| px(c)), 2);
            let _ = write!(
                s,
                r#"<path d="{d}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"/>"#,
                colour(i, n),
                num(stroke, 2)
            );
        }
        let _ = write!(
            s,
            r##"<path d="{outline}" fill="none" stroke="#222222" stroke-width="1.2"/>"##
        );
    }
    // The legend: print order as a blue-to-red bar, and the travel's dashes when drawn.
    let y = height - LEGEND_HEIGHT - GAP / 2.0 + 6.0;
    s.push_str(r#"<defs><linearGradient id="print-order">"#);
    for k in 0..=4 {
        let _ = write!(
            s,
            r#"<stop offset="{}" stop-color="{}"/>"#,
            num(k as f64 / 4.0, 2),
            colour(k, 5)
        );
    }
    s.push_str("</linearGradient></defs>");
    let _ = write!(
        s,
        r##"<rect x="{x}" y="{y}" width="60" height="8" fill="url(#print-order)"/><text x="{tx}" y="{ty}" fill="#444">print order: first (blue) to last (red)</text>"##,
        x = num(GAP, 2),
        y = num(y, 2),
        tx = num(GAP + 68.0, 2),
        ty = num(y + 8.0, 2)
    );
    if walled {
        let _ = write!(
            s,
            r##"<path d="M{x1} {ym}L{x2} {ym}" fill="none" stroke="{WALL}" stroke-width="4"/><text x="{tx}" y="{ty}" fill="#444">walls</text>"##,
            x1 = num(GAP + 410.0, 2),
            x2 = num(GAP + 440.0, 2),
            ym = num(y + 4.0, 2),
            tx = num(GAP + 446.0, 2),
            ty = num(y + 8.0, 2)
        );
    }
    if options.travel {
        let _ = write!(
            s,
            r##"<path d="M{x1} {ym}L{x2} {ym}" fill="none" stroke="#9a9a9a" stroke-width="0.6" stroke-dasharray="2 2"/><text x="{tx}" y="{ty}" fill="#444">travel</text>"##,
            x1 = num(GAP + 320.0, 2),
            x2 = num(GAP + 350.0, 2),
            ym = num(y + 4.0, 2),
            tx = num(GAP + 356.0, 2),
            ty = num(y + 8.0, 2)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// The filled layers `layers` of `model` under `template` (text `source`), as given to
/// [`svg`]: every layer's panel is labelled with its index, height, angle, fill and
/// instruction.
pub fn layers(
    template: &Template,
    model: &Model,
    options: eval::Options,
    source: &str,
    region: &MultiPolygon<f64>,
    settings: &Settings,
    layers: Range<usize>,
) -> Result<Vec<(Toolpaths, String, String)>, Error> {
    // The sparse density is checked whatever the layers drawn: a shell layer, printed
    // solid, would not look at it.
    if !(settings.density > 0.0 && settings.density <= 1.0) {
        return Err(Error::Density(settings.density));
    }
    let prepared = Region::new(region, settings.nozzle)?;
    let mut schedule = Schedule::new(template, model, options, *settings).with_shells(model);
    let mut out = Vec::new();
    for index in layers {
        let Some(fill) = schedule.layer(index, &prepared)? else {
            break;
        };
        let l = &fill.layer;
        let instruction = l
            .instruction
            .and_then(|s| source.get(s.range()))
            .map_or_else(|| "(holds)".to_owned(), |t| shorten(t, 28));
        let kind = match (l.fill, fill.printed) {
            (Fill::Sparse, Fill::Sparse) => format!(
                "{} {}%",
                fill.params.pattern,
                num(fill.params.density * 100.0, 1)
            ),
            // A shell layer: the template says sparse, the slicer prints it solid.
            (Fill::Sparse, _) => format!("shell, solid ({})", fill.params.pattern),
            (solid, _) => format!("{} ({})", solid.name(), fill.params.pattern),
        };
        let title = format!(
            "layer {} · z {} mm · {}°",
            l.index,
            num(l.top, 3),
            num(l.angle, 2)
        );
        let subtitle = format!("{instruction} · {kind}");
        out.push((fill.paths, title, subtitle));
    }
    Ok(out)
}

/// [`layers`] drawn by [`svg`]: the whole preview in one call.
#[allow(clippy::too_many_arguments)]
pub fn render(
    template: &Template,
    model: &Model,
    options: eval::Options,
    source: &str,
    region: &MultiPolygon<f64>,
    settings: &Settings,
    range: Range<usize>,
    preview: &PreviewOptions,
) -> Result<String, Error> {
    let filled = layers(template, model, options, source, region, settings, range)?;
    let panels: Vec<Panel<'_>> = filled
        .iter()
        .map(|(paths, title, subtitle)| Panel {
            region,
            walls: &[],
            paths,
            title: title.clone(),
            subtitle: subtitle.clone(),
        })
        .collect();
    Ok(svg(&panels, settings.nozzle, preview))
}

/// One layer of a 3D picture: its height, section and toolpaths.
#[derive(Clone, Copy, Debug)]
pub struct Slab<'a> {
    pub z: f64,
    pub region: &'a MultiPolygon<f64>,
    pub paths: &'a Toolpaths,
}

/// The layers stacked in an isometric view (x to the lower right, y to the lower left, z
/// up), drawn bottom to top: each section's outline in grey (not filled, so that the
/// infill of every layer shows through), its infill coloured by height (blue at the
/// bottom to red at the top).
pub fn isometric(slabs: &[Slab<'_>], width: f64) -> String {
    let (s, c) = math::sin_cos(30f64.to_radians());
    let project = |p: Coord, z: f64| Coord {
        x: (p.x - p.y) * c,
        y: -(p.x + p.y) * s - z,
    };
    // Bounds of every projected vertex.
    let mut min = Coord {
        x: f64::INFINITY,
        y: f64::INFINITY,
    };
    let mut max = Coord {
        x: f64::NEG_INFINITY,
        y: f64::NEG_INFINITY,
    };
    for slab in slabs {
        for p in &slab.region.0 {
            for q in p.exterior().coords() {
                let v = project(*q, slab.z);
                min = Coord {
                    x: min.x.min(v.x),
                    y: min.y.min(v.y),
                };
                max = Coord {
                    x: max.x.max(v.x),
                    y: max.y.max(v.y),
                };
            }
        }
    }
    if !min.x.is_finite() {
        min = Coord::zero();
        max = Coord { x: 1.0, y: 1.0 };
    }
    let margin = 16.0;
    let scale = (width - 2.0 * margin) / (max.x - min.x).max(1e-9);
    let height = (max.y - min.y) * scale + 2.0 * margin;
    let px = |p: Coord, z: f64| {
        let v = project(p, z);
        (
            (v.x - min.x) * scale + margin,
            (v.y - min.y) * scale + margin,
        )
    };
    let (z0, z1) = slabs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), l| {
            (a.min(l.z), b.max(l.z))
        });
    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}"><rect width="100%" height="100%" fill="white"/>"#,
        num(width, 0),
        num(height, 0),
        num(width, 0),
        num(height, 0)
    );
    for slab in slabs {
        let mut outline = String::new();
        for p in &slab.region.0 {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                path_data(&mut outline, ring.coords().map(|q| px(*q, slab.z)), 1);
            }
        }
        let t = if z1 > z0 {
            (slab.z - z0) / (z1 - z0)
        } else {
            0.0
        };
        let mut lines = String::new();
        for line in &slab.paths.polylines {
            path_data(&mut lines, line.0.iter().map(|q| px(*q, slab.z)), 1);
        }
        let _ = write!(
            out,
            r##"<g data-z="{}"><path d="{outline}" fill="none" stroke="#999" stroke-width="0.4"/><path d="{lines}" fill="none" stroke="hsl({:.0},80%,45%)" stroke-width="0.8"/></g>"##,
            num(slab.z, 3),
            240.0 * (1.0 - t)
        );
    }
    out.push_str("</svg>\n");
    out
}
