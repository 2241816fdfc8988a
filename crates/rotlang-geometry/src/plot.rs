//! The angle plot: a template's infill angle against height, as an SVG picture.
//!
//! Two panels share the height axis: above, the angle as evaluated (unwrapped, base
//! included) as a line; below, the direction of the infill lines (the angle modulo 180°)
//! as points, solid layers as orange squares. The layers each instruction governs are
//! shaded behind both panels (one colour per instruction) and labelled with its text
//! where there is room. No geometry library: it is written directly, and a pure function
//! of its inputs (the playground calls it in the browser).
//!
//! However many layers, the picture stays small: layers are gathered per pixel column
//! (first, lowest, highest and last angle; one point per pixel).
//!
//! ```
//! use rotlang::eval::{Model, Options};
//! let text = "+10L25%, -10l25%";
//! let template = rotlang::parse(text, rotlang::Target::Sparse).template;
//! let svg = rotlang_geometry::plot::svg(&template, &Model::cube20(), Options::default(), text, &Default::default());
//! assert!(svg.starts_with("<svg") && svg.contains("height (mm)"));
//! ```

use crate::math;
use std::fmt::Write;

use crate::eval::{self, Model};
use crate::ir::{Fill, Template};

/// The picture's size and title.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotOptions {
    /// Width and height in pixels.
    pub width: f64,
    pub height: f64,
    /// Shown above the chart; the template text when `None`.
    pub title: Option<String>,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            width: 960.0,
            height: 560.0,
            title: None,
        }
    }
}

/// A rectangle in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

/// Where things are drawn: the two panels and the scales of their axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// The angle panel (unwrapped angle against height).
    pub angles: Rect,
    /// The direction panel (angle mod 180 against height).
    pub directions: Rect,
    /// The height axis runs from 0 to this (mm): the model's top.
    pub z_max: f64,
    /// The angle axis range (degrees).
    pub angle_min: f64,
    pub angle_max: f64,
    /// The direction axis runs from this to 180° above it: 0 (directions in [0, 180)), or
    /// −90 (in [−90, 90)) when the directions cluster around 0°, where [0, 180) would split
    /// them between its two edges.
    pub direction_min: f64,
}

impl Layout {
    /// The x pixel of height `z` (mm).
    pub fn x(&self, z: f64) -> f64 {
        self.angles.x + z / self.z_max * self.angles.w
    }

    /// The y pixel of an unwrapped angle in the angle panel.
    pub fn y_angle(&self, angle: f64) -> f64 {
        let r = &self.angles;
        r.y + r.h - (angle - self.angle_min) / (self.angle_max - self.angle_min) * r.h
    }

    /// The y pixel of an angle's direction in the direction panel (any angle: it is
    /// wrapped into the panel's range, `direction_min` to 180° above it).
    pub fn y_direction(&self, angle: f64) -> f64 {
        let r = &self.directions;
        r.y + r.h - wrap180(angle - self.direction_min) / 180.0 * r.h
    }
}

const LEFT: f64 = 72.0;
const RIGHT: f64 = 24.0;
const TOP: f64 = 64.0;
const BOTTOM: f64 = 64.0;
const GAP: f64 = 34.0;

/// The colour of the angle line.
pub const LINE_COLOUR: &str = "#1f4e9c";
/// The colour of the direction points of sparse layers.
pub const POINT_COLOUR: &str = "#2a7f62";
/// The colour of solid layers' markers.
pub const SOLID_COLOUR: &str = "#e07000";
/// Rows of instruction labels, and the width of one character of them (11 px sans-serif,
/// generously: digits and signs are about 6.1 px).
const LABEL_ROWS: usize = 3;
const LABEL_CHAR: f64 = 6.8;

const SHADES: [&str; 6] = [
    "#e8eef9", "#fbeee0", "#e6f4ea", "#f6e6f2", "#fff8d6", "#e6f3f7",
];

/// What one pixel column of the chart holds.
#[derive(Clone, Debug)]
struct Column {
    first: f64,
    min: f64,
    max: f64,
    last: f64,
    /// The instruction governing the column's first layer (index in the template).
    instruction: Option<usize>,
    /// Direction pixel rows with a point: (row in [0, 180), row in [−90, 90), solid).
    points: Vec<(u16, u16, bool)>,
    solid: bool,
}

struct Data {
    columns: Vec<Option<Column>>,
    z_max: f64,
    angle_min: f64,
    angle_max: f64,
    layers: usize,
    /// Sparse-or-solid points near 0° (or 180°), and near 90°: which range to draw on.
    near_0: usize,
    near_90: usize,
}

fn frame(options: &PlotOptions) -> (Rect, Rect) {
    let w = (options.width - LEFT - RIGHT).max(100.0);
    let h = (options.height - TOP - BOTTOM - GAP).max(100.0);
    let angles = Rect {
        x: LEFT,
        y: TOP,
        w,
        h: (h * 0.58).round(),
    };
    let directions = Rect {
        x: LEFT,
        y: TOP + angles.h + GAP,
        w,
        h: h - angles.h,
    };
    (angles, directions)
}

fn gather(
    template: &Template,
    layers_of: impl Iterator<Item = eval::Layer>,
    model: &Model,
    plot: &PlotOptions,
) -> Data {
    let (angles, directions) = frame(plot);
    let n = angles.w.ceil() as usize;
    let z_max = model.object_height().max(1e-9);
    let mut columns: Vec<Option<Column>> = vec![None; n];
    let (mut angle_min, mut angle_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let index_of = |span: crate::Span| template.instructions.iter().position(|i| i.span == span);
    let mut layers = 0;
    let (mut near_0, mut near_90) = (0, 0);
    for layer in layers_of {
        layers += 1;
        let z = (layer.bottom + layer.top) / 2.0;
        let c = ((z / z_max * angles.w) as usize).min(n - 1);
        let a = layer.angle;
        angle_min = angle_min.min(a);
        angle_max = angle_max.max(a);
        let solid = layer.fill != Fill::Sparse;
        let direction = wrap180(a);
        let row_of = |from: f64| {
            ((1.0 - wrap180(a - from) / 180.0) * directions.h)
                .round()
                .clamp(0.0, u16::MAX as f64) as u16
        };
        let (row, centred_row) = (row_of(0.0), row_of(-90.0));
        if !(30.0..150.0).contains(&direction) {
            near_0 += 1;
        } else if (60.0..120.0).contains(&direction) {
            near_90 += 1;
        }
        let column = columns[c].get_or_insert_with(|| Column {
            first: a,
            min: a,
            max: a,
            last: a,
            instruction: layer.instruction.and_then(index_of),
            points: Vec::new(),
            solid: false,
        });
        column.min = column.min.min(a);
        column.max = column.max.max(a);
        column.last = a;
        column.solid |= solid;
        if !column.points.contains(&(row, centred_row, solid)) {
            column.points.push((row, centred_row, solid));
        }
    }
    if !angle_min.is_finite() {
        (angle_min, angle_max) = (0.0, 0.0);
    }
    Data {
        columns,
        z_max,
        angle_min,
        angle_max,
        layers,
        near_0,
        near_90,
    }
}

fn wrap180(angle: f64) -> f64 {
    let d = angle.rem_euclid(180.0);
    if d >= 180.0 { 0.0 } else { d + 0.0 }
}

/// The chart's layout for these inputs (what [`svg`] draws with): tests and tools use it
/// to find where a layer's angle is drawn.
pub fn layout(
    template: &Template,
    model: &Model,
    options: eval::Options,
    plot: &PlotOptions,
) -> Layout {
    let data = gather(
        template,
        eval::layers(template, model, options),
        model,
        plot,
    );
    layout_of(&data, plot)
}

fn layout_of(data: &Data, plot: &PlotOptions) -> Layout {
    let (angles, directions) = frame(plot);
    let (lo, hi, _) = nice_range(data.angle_min, data.angle_max);
    Layout {
        angles,
        directions,
        z_max: data.z_max,
        angle_min: lo,
        angle_max: hi,
        // Only for a clear cluster: directions turning evenly stay on [0, 180).
        direction_min: if data.near_0 > 2 * data.near_90 {
            -90.0
        } else {
            0.0
        },
    }
}

/// An axis range holding `[lo, hi]` with round ends, and its tick step.
fn nice_range(lo: f64, hi: f64) -> (f64, f64, f64) {
    let (lo, hi) = if hi - lo < 1e-9 {
        (lo - 45.0, hi + 45.0)
    } else {
        (lo, hi)
    };
    let step = nice_step((hi - lo) / 5.0);
    ((lo / step).floor() * step, (hi / step).ceil() * step, step)
}

fn nice_step(raw: f64) -> f64 {
    let raw = raw.max(1e-9);
    let p = math::powf(10.0, math::log10(raw).floor());
    let m = raw / p;
    p * if m <= 1.0 {
        1.0
    } else if m <= 2.0 {
        2.0
    } else if m <= 5.0 {
        5.0
    } else {
        10.0
    }
}

/// A number for a label: at most `decimals` decimals, no trailing zeros, no `-0`.
pub fn num(x: f64, decimals: usize) -> String {
    let s = format!("{:.*}", decimals, x);
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" { "0".into() } else { s }
}

/// Text safe inside SVG elements and attributes.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// At most `max` characters of `text`, with an ellipsis when cut.
pub fn shorten(text: &str, max: usize) -> String {
    let text = text.trim();
    if text.chars().count() <= max {
        text.to_owned()
    } else {
        let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
        s.push('…');
        s
    }
}

/// The SVG chart of `template`'s angles on `model`. `source` is the template's text
/// (instruction labels are cut out of it by their spans).
pub fn svg(
    template: &Template,
    model: &Model,
    options: eval::Options,
    source: &str,
    plot: &PlotOptions,
) -> String {
    let data = gather(
        template,
        eval::layers(template, model, options),
        model,
        plot,
    );
    draw(template, data, (model, options), source, plot)
}

/// The chart of OrcaSlicer's angles for `source` (`rotlang plot --dialect orcaslicer`):
/// its reading of any text, valid or not, with the finite angles the dialect gives where
/// OrcaSlicer hangs, crashes or computes NaN; `template` (rotlang's parse of the text, as
/// far as it goes) labels the instructions. The findings are returned with the picture.
pub fn svg_orcaslicer(
    template: &Template,
    model: &Model,
    options: eval::Options,
    source: &str,
    plot: &PlotOptions,
) -> (String, Vec<crate::dialect::Finding>) {
    let mut layers = crate::dialect::orcaslicer::layers(source, model, options);
    let data = gather(template, layers.by_ref(), model, plot);
    let findings = layers.findings().to_vec();
    (
        draw(template, data, (model, options), source, plot),
        findings,
    )
}

fn draw(
    template: &Template,
    data: Data,
    (model, options): (&Model, eval::Options),
    source: &str,
    plot: &PlotOptions,
) -> String {
    let layout = layout_of(&data, plot);
    let (a, d) = (layout.angles, layout.directions);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#,
        w = num(plot.width, 1),
        h = num(plot.height, 1)
    );
    let _ = write!(s, r##"<rect width="100%" height="100%" fill="#ffffff"/>"##);
    let title = plot
        .title
        .clone()
        .unwrap_or_else(|| format!("template: {}", shorten(source, 90)));
    let _ = write!(
        s,
        r#"<text x="{}" y="20" font-size="15" font-weight="bold">{}</text>"#,
        LEFT,
        escape(&title)
    );
    let _ = write!(
        s,
        r##"<text x="{}" y="38" fill="#555">{} layers, {} mm; base {}°, seed {}</text>"##,
        LEFT,
        data.layers,
        num(model.object_height(), 3),
        num(options.base, 4),
        options.seed
    );
    // Instruction ranges: runs of columns governed by the same instruction. Their labels
    // are whole, never cut to a letter: each goes in the first of three rows where it does
    // not run into the label before it, and is left out (the shading still shows its
    // range) when none has room.
    let mut run_start = 0;
    let mut row_ends = [f64::NEG_INFINITY; LABEL_ROWS];
    // Drawn after all the shading, which would otherwise cover a label running on.
    let mut labels = String::new();
    let n = data.columns.len();
    let governing = |c: usize| data.columns[c].as_ref().and_then(|col| col.instruction);
    for c in 1..=n {
        let same = c < n && (governing(c) == governing(run_start) || data.columns[c].is_none());
        if same {
            continue;
        }
        if let Some(index) = governing(run_start) {
            let x0 = a.x + run_start as f64;
            let width = (c - run_start) as f64;
            let shade = SHADES[index % SHADES.len()];
            for r in [a, d] {
                let _ = write!(
                    s,
                    r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{shade}"/>"#,
                    num(x0, 2),
                    num(r.y, 2),
                    num(width, 2),
                    num(r.h, 2)
                );
            }
            let text = template
                .instructions
                .get(index)
                .and_then(|i| source.get(i.span.range()))
                .unwrap_or("");
            let label = shorten(text, 40);
            let label_width = LABEL_CHAR * label.chars().count() as f64;
            // From the range's start, kept inside the panel.
            let x = (x0 + 2.0).min(a.x + a.w - label_width - 2.0).max(a.x + 2.0);
            let row = row_ends.iter().position(|&end| x >= end + 6.0);
            if let (Some(row), false) = (row, label.is_empty()) {
                row_ends[row] = x + label_width;
                let _ = write!(
                    labels,
                    r##"<text x="{}" y="{}" fill="#333" font-size="11">{}</text>"##,
                    num(x, 2),
                    num(a.y + 13.0 + 13.0 * row as f64, 2),
                    escape(&label)
                );
            }
        }
        run_start = c;
    }
    s.push_str(&labels);
    axes(&mut s, &layout, &data);
    // The unwrapped angle: a line through every column's first, lowest, highest and last.
    let mut path = String::new();
    for (c, col) in data.columns.iter().enumerate() {
        let Some(col) = col else { continue };
        let x = a.x + c as f64 + 0.5;
        let (lo, hi) = if col.first <= col.last {
            (col.min, col.max)
        } else {
            (col.max, col.min)
        };
        let mut values = vec![col.first, lo, hi, col.last];
        values.dedup();
        for v in values {
            let cmd = if path.is_empty() { 'M' } else { 'L' };
            let _ = write!(path, "{cmd}{} {}", num(x, 2), num(layout.y_angle(v), 2));
        }
    }
    let _ = write!(
        s,
        r#"<path d="{path}" fill="none" stroke="{LINE_COLOUR}" stroke-width="2" stroke-linejoin="round"/>"#
    );
    // The wrapped directions, one point per pixel; solid layers as squares.
    let mut dots = String::new();
    let mut squares = String::new();
    for (c, col) in data.columns.iter().enumerate() {
        let Some(col) = col else { continue };
        let x = a.x + c as f64 + 0.5;
        for &(row, centred_row, solid) in &col.points {
            let row = if layout.direction_min < 0.0 {
                centred_row
            } else {
                row
            };
            let y = d.y + row as f64;
            if solid {
                let _ = write!(squares, "M{} {}h5v5h-5z", num(x - 2.5, 2), num(y - 2.5, 2));
            } else {
                let _ = write!(dots, "M{} {}h0", num(x, 2), num(y, 2));
            }
        }
    }
    let _ = write!(
        s,
        r#"<path d="{dots}" stroke="{POINT_COLOUR}" stroke-width="4" stroke-linecap="round"/>"#
    );
    let _ = write!(s, r#"<path d="{squares}" fill="{SOLID_COLOUR}"/>"#);
    // Solid layers also get a band under the height axis, where they are easy to count.
    for (c, col) in data.columns.iter().enumerate() {
        if col.as_ref().is_some_and(|col| col.solid) {
            let _ = write!(
                s,
                r#"<rect x="{}" y="{}" width="1" height="5" fill="{SOLID_COLOUR}"/>"#,
                num(a.x + c as f64, 2),
                num(d.y + d.h + 2.0, 2)
            );
        }
    }
    legend(&mut s, plot);
    s.push_str("</svg>\n");
    s
}

fn axes(s: &mut String, layout: &Layout, data: &Data) {
    let (a, d) = (layout.angles, layout.directions);
    for r in [a, d] {
        let _ = write!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#444"/>"##,
            num(r.x, 2),
            num(r.y, 2),
            num(r.w, 2),
            num(r.h, 2)
        );
    }
    // Height ticks on both panels, labels under the lower one.
    let step = nice_step(data.z_max / 8.0);
    let mut k = 0.0;
    while k * step <= data.z_max + 1e-9 {
        let z = k * step;
        let x = layout.x(z);
        for r in [a, d] {
            let _ = write!(
                s,
                r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#bbb" stroke-dasharray="2 3"/>"##,
                num(r.y, 2),
                num(r.y + r.h, 2),
                x = num(x, 2)
            );
        }
        let _ = write!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            num(x, 2),
            num(d.y + d.h + 20.0, 2),
            num(z, 3)
        );
        k += 1.0;
    }
    let _ = write!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">height (mm)</text>"#,
        num(a.x + a.w / 2.0, 2),
        num(d.y + d.h + 40.0, 2)
    );
    // Angle ticks.
    let (_, _, astep) = nice_range(data.angle_min, data.angle_max);
    let mut v = layout.angle_min;
    while v <= layout.angle_max + 1e-9 {
        let y = layout.y_angle(v);
        tick(s, a, y, &format!("{}°", num(v, 3)));
        v += astep;
    }
    for k in 0..=4 {
        let v = layout.direction_min + 45.0 * k as f64;
        let y = d.y + d.h - 45.0 * k as f64 / 180.0 * d.h;
        tick(s, d, y, &format!("{}°", num(v, 0)));
    }
    // The direction axis says which range the angles were wrapped into, on a second line.
    let wrapped = if layout.direction_min < 0.0 {
        "mod 180, in [−90, 90)"
    } else {
        "mod 180, in [0, 180)"
    };
    for (r, label, x, size) in [
        (a, "angle (°)", 16.0, 12),
        (d, "direction (°)", 14.0, 12),
        (d, wrapped, 28.0, 10),
    ] {
        let y = r.y + r.h / 2.0;
        let _ = write!(
            s,
            r#"<text x="{x}" y="{y}" font-size="{size}" text-anchor="middle" transform="rotate(-90 {x} {y})">{label}</text>"#,
            x = num(x, 2),
            y = num(y, 2)
        );
    }
}

fn tick(s: &mut String, r: Rect, y: f64, label: &str) {
    let _ = write!(
        s,
        r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">{}</text>"##,
        num(r.x, 2),
        num(r.x + r.w, 2),
        num(r.x - 6.0, 2),
        num(y + 4.0, 2),
        escape(label),
        y = num(y, 2)
    );
}

fn legend(s: &mut String, plot: &PlotOptions) {
    let y = 54.0;
    let x = (plot.width - RIGHT - 430.0).max(LEFT);
    let _ = write!(
        s,
        r#"<line x1="{x0}" y1="{yl}" x2="{x1}" y2="{yl}" stroke="{LINE_COLOUR}" stroke-width="2"/><text x="{xt}" y="{y}">angle</text>"#,
        x0 = num(x, 2),
        x1 = num(x + 18.0, 2),
        xt = num(x + 22.0, 2),
        yl = num(y - 4.0, 2),
        y = num(y, 2)
    );
    let _ = write!(
        s,
        r#"<circle cx="{}" cy="{}" r="2" fill="{POINT_COLOUR}"/><text x="{}" y="{}">direction of the lines</text>"#,
        num(x + 80.0, 2),
        num(y - 4.0, 2),
        num(x + 88.0, 2),
        num(y, 2)
    );
    let _ = write!(
        s,
        r#"<rect x="{}" y="{}" width="5" height="5" fill="{SOLID_COLOUR}"/><text x="{}" y="{}">solid layer (D S O M R)</text>"#,
        num(x + 240.0, 2),
        num(y - 6.5, 2),
        num(x + 250.0, 2),
        num(y, 2)
    );
}
