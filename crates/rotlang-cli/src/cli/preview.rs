//! `rotlang preview`: the infill of some layers, drawn (SVG) or listed (JSON).

use std::io::Write;
use std::ops::Range;
use std::path::PathBuf;

use geo::{Coord, LineString, MultiPolygon, Polygon};

use super::plot::{emit, template};
use super::stream::{JsonOut, stream};
use super::{UsageError, read_file};
use crate::infill::preview::{self, PreviewOptions};
use crate::infill::{Centring, Settings, shapes};

mod args;
use args::MAX_PANELS;
pub use args::{CentringArg, Format, PatternArg, PreviewArgs};

impl PreviewArgs {
    /// The infill settings the options give.
    pub(super) fn settings(&self) -> Settings {
        Settings {
            pattern: self.pattern.unwrap_or_default().into(),
            density: self.density.unwrap_or(0.2),
            nozzle: self.nozzle.unwrap_or(0.4),
            centring: match self.centring {
                CentringArg::Object => Centring::Object,
                CentringArg::Global => Centring::Global,
            },
            solid_pattern: self.solid_pattern.unwrap_or_default().into(),
        }
    }

    /// The layers to draw (`--layers`, else the first eight) of `len`, which must start
    /// inside them, cut at the last; `what` names the model or part in the message. A
    /// picture shows at most [`MAX_PANELS`]; JSON lists any number.
    pub(super) fn range(&self, len: usize, what: &str) -> Result<Range<usize>, UsageError> {
        let range = self.layers.clone().unwrap_or(0..8);
        if range.start >= len {
            return Err(UsageError(format!(
                "--layers starts at layer {} but the {what} has {len} layers (0..{len})",
                range.start
            )));
        }
        let range = range.start..range.end.min(len);
        if self.format == Format::Svg && range.len() > MAX_PANELS {
            return Err(UsageError(format!(
                "--layers {}..{} is {} layers; a picture shows at most {MAX_PANELS} \
                 (--format json lists any number)",
                range.start,
                range.end,
                range.len()
            )));
        }
        Ok(range)
    }
}

/// The region `--shape` names.
pub fn shape(name: &str, size: Option<f64>) -> Result<MultiPolygon<f64>, UsageError> {
    if let Some(size) = size.filter(|s| !(s.is_finite() && *s > 0.0 && *s <= 10_000.0)) {
        return Err(UsageError(format!(
            "--size must be between 0 and 10000 mm, found {size}"
        )));
    }
    let given = size;
    let size = size.unwrap_or(20.0);
    let r = size / 2.0;
    Ok(match name.to_ascii_lowercase().as_str() {
        "square" => shapes::square(size),
        "circle" => shapes::circle(r),
        "ring" => shapes::ring_shape(r, r / 2.0),
        "star" => shapes::star(r, r * 0.45),
        "l" => shapes::l_shape(size),
        _ => {
            let path = PathBuf::from(name);
            if !path.exists() {
                return Err(UsageError(format!(
                    "--shape {name:?} is not square, circle, ring, star or l, nor a file"
                )));
            }
            let text = read_file(&path)?;
            let lower = name.to_ascii_lowercase();
            let region = if lower.ends_with(".json") || text.trim_start().starts_with(['[', '{']) {
                shapes::from_json(&text)
            } else {
                from_svg(&text)
            };
            let region =
                region.map_err(|e| UsageError(format!("cannot read a region from {name}: {e}")))?;
            match given {
                Some(size) => resized(region, size),
                None => region,
            }
        }
    })
}

/// The region scaled about its bounding box's centre so that its wider side is `size`.
fn resized(region: MultiPolygon<f64>, size: f64) -> MultiPolygon<f64> {
    use geo::{BoundingRect, MapCoords};
    let Some(rect) = region.bounding_rect() else {
        return region;
    };
    let wide = rect.width().max(rect.height());
    if wide.is_nan() || wide <= 0.0 {
        return region;
    }
    let (centre, k) = (rect.center(), size / wide);
    region.map_coords(|c| centre + (c - centre) * k)
}

/// The outlines of every `<path>` and `<polygon>` in an SVG document: curves flattened,
/// y flipped (SVG's y points down), rings nested in an odd number of others are holes.
pub fn from_svg(text: &str) -> Result<MultiPolygon<f64>, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("invalid SVG: {e}"))?;
    let mut rings: Vec<Vec<Coord>> = Vec::new();
    for node in doc.descendants().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "path" => {
                if let Some(d) = node.attribute("d") {
                    path_rings(d, &mut rings)?;
                }
            }
            "polygon" => {
                if let Some(points) = node.attribute("points") {
                    let ring: Vec<Coord> = svgtypes::PointsParser::from(points)
                        .map(|(x, y)| Coord { x, y: -y })
                        .collect();
                    rings.push(ring);
                }
            }
            _ => {}
        }
    }
    rings.retain(|r| r.len() >= 3);
    if rings.is_empty() {
        return Err("no <path> or <polygon> with an area".into());
    }
    Ok(nest(rings))
}

fn path_rings(d: &str, rings: &mut Vec<Vec<Coord>>) -> Result<(), String> {
    use svgtypes::SimplePathSegment as S;
    let mut ring: Vec<Coord> = Vec::new();
    let mut at = Coord::zero();
    for segment in svgtypes::SimplifyingPathParser::from(d) {
        let segment = segment.map_err(|e| format!("invalid path data: {e}"))?;
        let curve = |points: &dyn Fn(f64) -> Coord, ring: &mut Vec<Coord>| {
            for k in 1..=16 {
                ring.push(points(k as f64 / 16.0));
            }
        };
        match segment {
            S::MoveTo { x, y } => {
                if ring.len() >= 3 {
                    rings.push(std::mem::take(&mut ring));
                }
                ring.clear();
                at = Coord { x, y: -y };
                ring.push(at);
            }
            S::LineTo { x, y } => {
                at = Coord { x, y: -y };
                ring.push(at);
            }
            S::Quadratic { x1, y1, x, y } => {
                let (p0, p1, p2) = (at, Coord { x: x1, y: -y1 }, Coord { x, y: -y });
                curve(
                    &|t| p0 * ((1.0 - t) * (1.0 - t)) + p1 * (2.0 * t * (1.0 - t)) + p2 * (t * t),
                    &mut ring,
                );
                at = p2;
            }
            S::CurveTo {
                x1,
                y1,
                x2,
                y2,
                x,
                y,
            } => {
                let (p0, p1, p2, p3) = (
                    at,
                    Coord { x: x1, y: -y1 },
                    Coord { x: x2, y: -y2 },
                    Coord { x, y: -y },
                );
                curve(
                    &|t| {
                        let u = 1.0 - t;
                        p0 * (u * u * u)
                            + p1 * (3.0 * u * u * t)
                            + p2 * (3.0 * u * t * t)
                            + p3 * (t * t * t)
                    },
                    &mut ring,
                );
                at = p3;
            }
            S::ClosePath => {
                if let Some(&first) = ring.first() {
                    at = first;
                }
                if ring.len() >= 3 {
                    rings.push(std::mem::take(&mut ring));
                }
                ring.clear();
            }
        }
    }
    if ring.len() >= 3 {
        rings.push(ring);
    }
    Ok(())
}

/// Rings to polygons by nesting: a ring inside an even number of others is an outline,
/// inside an odd number a hole of the smallest outline around it.
fn nest(rings: Vec<Vec<Coord>>) -> MultiPolygon<f64> {
    let contains = |outer: &[Coord], p: Coord| {
        let mut inside = false;
        for i in 0..outer.len() {
            let (a, b) = (outer[i], outer[(i + 1) % outer.len()]);
            if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
                inside = !inside;
            }
        }
        inside
    };
    let area = |r: &[Coord]| {
        (0..r.len())
            .map(|i| {
                let (a, b) = (r[i], r[(i + 1) % r.len()]);
                a.x * b.y - a.y * b.x
            })
            .sum::<f64>()
            .abs()
            / 2.0
    };
    let parents: Vec<Vec<usize>> = rings
        .iter()
        .enumerate()
        .map(|(i, r)| {
            (0..rings.len())
                .filter(|&j| j != i && area(&rings[j]) > area(r) && contains(&rings[j], r[0]))
                .collect()
        })
        .collect();
    let close = |r: &Vec<Coord>| {
        let mut c = r.clone();
        c.push(r[0]);
        LineString::new(c)
    };
    let mut polygons: Vec<(usize, Polygon<f64>)> = Vec::new();
    for (i, r) in rings.iter().enumerate() {
        if parents[i].len().is_multiple_of(2) {
            polygons.push((i, Polygon::new(close(r), vec![])));
        }
    }
    for (i, r) in rings.iter().enumerate() {
        if parents[i].len() % 2 == 1 {
            // The smallest outline around it is its parent of the largest depth.
            if let Some(&parent) = parents[i].iter().max_by_key(|&&j| parents[j].len())
                && let Some((_, p)) = polygons.iter_mut().find(|(k, _)| *k == parent)
            {
                p.interiors_push(close(r));
            }
        }
    }
    MultiPolygon::new(polygons.into_iter().map(|(_, p)| p).collect())
}

/// Runs `rotlang preview`; returns the exit code.
pub fn run(
    args: &PreviewArgs,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<i32, UsageError> {
    if super::part::is_mesh(&args.shape) {
        return super::part::run(args, &args.shape, &args.template, out, err);
    }
    // `rotlang preview part.stl`: the mesh in the template's place, the template from
    // --file, or none (every layer at the base direction).
    if let Some(mesh) = args
        .template
        .as_ref()
        .filter(|t| super::part::is_mesh(t) && std::path::Path::new(t).is_file())
    {
        let template = if args.file.is_some() {
            None
        } else {
            Some(String::new())
        };
        return super::part::run(args, mesh, &template, out, err);
    }
    let region = shape(&args.shape, args.size)?;
    let nozzle = args.settings().nozzle;
    if !(0.01..=10.0).contains(&nozzle) {
        return Err(UsageError(format!(
            "--nozzle must be between 0.01 and 10 mm, found {nozzle}"
        )));
    }
    let drawn = match template(
        &args.template,
        &args.file,
        &args.profile,
        (args.target, crate::eval::Dialect::Rotlang),
        args.color,
        (&args.model, None),
        err,
    )? {
        Ok(t) => t,
        Err(code) => return Ok(code),
    };
    let (input, parse, model) = (drawn.input, drawn.parse, drawn.model);
    let settings = args.settings();
    let range = args.range(model.len(), "model")?;
    let options = drawn.options;
    let fail = |e: crate::infill::Error| UsageError(e.to_string());
    let text = match args.format {
        Format::Svg => {
            let preview = PreviewOptions {
                columns: args.columns,
                ..PreviewOptions::default()
            };
            preview::render(
                &parse.template,
                &model,
                options,
                &input.text,
                &region,
                &settings,
                range,
                &preview,
            )
            .map_err(fail)?
        }
        Format::Json => {
            let prepared = crate::infill::Region::new(&region, settings.nozzle).map_err(fail)?;
            stream(args.out.as_deref(), out, |w| {
                json(
                    &parse.template,
                    &model,
                    options,
                    &prepared,
                    &settings,
                    range,
                    w,
                )
            })?;
            return Ok(0);
        }
    };
    emit(&text, args.out.as_deref(), out)?;
    Ok(0)
}

/// `{"layers": [...]}`, a layer at a time (memory bounded by one layer's paths).
fn json(
    template: &crate::Template,
    model: &crate::eval::Model,
    options: crate::eval::Options,
    prepared: &crate::infill::Region,
    settings: &Settings,
    range: Range<usize>,
    w: &mut JsonOut<'_>,
) -> Result<(), UsageError> {
    let mut schedule =
        crate::infill::Schedule::new(template, model, options, *settings).with_shells(model);
    w.text("{\"layers\":[");
    for index in range.clone() {
        let fill = match schedule.layer(index, prepared) {
            Ok(Some(fill)) => fill,
            Ok(None) => break,
            Err(e) => return Err(UsageError(e.to_string())),
        };
        let l = &fill.layer;
        w.item(&serde_json::json!({
            "index": l.index,
            "bottom": l.bottom,
            "top": l.top,
            "angle": l.angle,
            "fill": l.fill.name(),
            "printed": fill.printed.name(),
            "instruction": l.instruction.map(|s| serde_json::json!({"start": s.start, "end": s.end})),
            "pattern": fill.params.pattern.name(),
            "density": fill.params.density,
            "length": fill.paths.length,
            "travel": fill.paths.travel,
            "polylines": fill.paths.polylines.iter().map(|p| p.0.iter().map(|c| [c.x, c.y]).collect::<Vec<_>>()).collect::<Vec<_>>(),
        }));
        if w.closed() {
            break;
        }
    }
    w.text("]}\n");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: PreviewArgs,
    }

    fn preview(argv: &[&str]) -> (Result<i32, String>, String, String) {
        let cli = Cli::try_parse_from(std::iter::once("preview").chain(argv.iter().copied()))
            .unwrap_or_else(|e| panic!("{argv:?}: {e}"));
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let code = run(&cli.args, &mut out, &mut err).map_err(|e| e.0);
        (
            code,
            String::from_utf8(out).unwrap(),
            String::from_utf8(err).unwrap(),
        )
    }

    #[test]
    fn json_lists_the_paths_of_each_layer() {
        let (code, out, _) = preview(&[
            "+45",
            "--pattern",
            "grid",
            "--layers",
            "2..=3",
            "--format",
            "json",
        ]);
        assert_eq!(code, Ok(0));
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let layers = v["layers"].as_array().unwrap();
        assert_eq!(layers.len(), 2);
        assert_eq!(
            (layers[0]["index"].clone(), layers[0]["angle"].clone()),
            (2.into(), 135.0.into())
        );
        // Layer 2 is the cube's last bottom shell, printed solid; layer 3 is sparse grid.
        assert_eq!(
            (&layers[0]["printed"], &layers[0]["pattern"]),
            (&"solid".into(), &"lines".into())
        );
        assert_eq!(layers[1]["pattern"], "grid");
        assert!(!layers[1]["polylines"].as_array().unwrap().is_empty());
    }

    #[test]
    fn svg_has_one_panel_per_layer() {
        let (code, out, _) = preview(&["0, 90", "--shape", "star", "--layers", "3"]);
        assert_eq!(code, Ok(0));
        assert!(
            out.starts_with("<svg") && out.contains("layer 3 · z 0.8 mm · 90°"),
            "{out}"
        );
    }

    #[test]
    fn shapes_from_files() {
        let dir = std::env::temp_dir().join(format!("rotlang-preview-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let svg = dir.join("part.svg");
        std::fs::write(
            &svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 H20 V20 H0 Z M5 5 V15 H15 V5 Z"/></svg>"#,
        )
        .unwrap();
        let region = shape(svg.to_str().unwrap(), None).unwrap();
        assert_eq!((region.0.len(), region.0[0].interiors().len()), (1, 1));
        let json = dir.join("part.json");
        std::fs::write(&json, "[[[0,0],[10,0],[10,10],[0,10]]]").unwrap();
        assert_eq!(shape(json.to_str().unwrap(), None).unwrap().0.len(), 1);
        std::fs::write(&json, "[1, 2]").unwrap();
        assert!(shape(json.to_str().unwrap(), None).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn usage_errors() {
        for argv in [
            &["0", "--shape", "/nonexistent.svg"][..],
            &["0", "--layers", "200..210"],
            &["0", "--nozzle", "0"],
            &["0", "--size=-1"],
        ] {
            assert!(preview(argv).0.is_err(), "{argv:?}");
        }
        for argv in [
            &["0", "--density", "0"][..],
            &["0", "--density", "150%"],
            &["0", "--layers", "5..2"],
        ] {
            assert!(
                Cli::try_parse_from(std::iter::once("preview").chain(argv.iter().copied()))
                    .is_err()
            );
        }
        assert_eq!(preview(&["+30X5"]).0, Ok(1));
    }
}
