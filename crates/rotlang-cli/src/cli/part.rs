//! `rotlang preview --shape part.stl`: a real part, sliced, filled layer by layer.

use std::io::Write;

use super::UsageError;
use super::plot::{emit, template};
use super::preview::{Format, PreviewArgs};
use crate::infill::preview::{self, Panel, PreviewOptions};
use crate::ir::Fill;
use crate::mesh::Mesh;
use crate::plot::{num, shorten};
use crate::slice::{Part, PartOptions, Summary};

/// The most bytes a mesh file may have (a 25-million-triangle binary STL).
const MAX_MESH_BYTES: u64 = 84 + 50 * crate::mesh::MAX_TRIANGLES as u64;

#[derive(clap::Args, Debug, Clone)]
pub struct PartArgs {
    /// For a mesh: wall loops around the infill (each a nozzle wide).
    #[arg(long, value_name = "N", default_value_t = 2, help_heading = "Part (a mesh as --shape)",
          value_parser = clap::value_parser!(u32).range(0..=100))]
    pub walls: u32,
    /// For a mesh: the infill print speed in mm/s, for the summary's time.
    #[arg(
        long,
        value_name = "MM/S",
        default_value_t = 100.0,
        help_heading = "Part (a mesh as --shape)"
    )]
    pub speed: f64,
    /// For a mesh: the travel speed in mm/s, for the summary's time.
    #[arg(
        long,
        value_name = "MM/S",
        default_value_t = 200.0,
        help_heading = "Part (a mesh as --shape)"
    )]
    pub travel_speed: f64,
    /// For a mesh: also draw the part's layers stacked in 3D (isometric) to FILE: an
    /// .svg, or an .html page holding it. At most 150 layers are drawn, evenly spread.
    #[arg(
        long = "3d",
        value_name = "FILE",
        help_heading = "Part (a mesh as --shape)"
    )]
    pub three_d: Option<std::path::PathBuf>,
}

/// Whether `--shape` names a mesh file.
pub fn is_mesh(shape: &str) -> bool {
    let lower = shape.to_ascii_lowercase();
    lower.ends_with(".stl") || lower.ends_with(".obj") || lower.ends_with(".3mf")
}

fn read_mesh(name: &str, object: Option<&str>) -> Result<Mesh, UsageError> {
    use std::io::Read;
    let file =
        std::fs::File::open(name).map_err(|e| UsageError(format!("cannot read {name}: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_MESH_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| UsageError(format!("cannot read {name}: {e}")))?;
    if bytes.len() as u64 > MAX_MESH_BYTES {
        return Err(UsageError(format!(
            "{name} is larger than {MAX_MESH_BYTES} bytes"
        )));
    }
    let cannot =
        |e: crate::mesh::MeshError| UsageError(format!("cannot read a mesh from {name}: {e}"));
    let mesh = if name.to_ascii_lowercase().ends_with(".3mf") {
        let objects = crate::mesh::read_3mf(&bytes).map_err(cannot)?;
        let mut merged = Mesh::default();
        let mut found = false;
        for (n, m) in &objects {
            if object.is_none_or(|o| o == n) {
                found = true;
                let base = merged.vertices.len() as u32;
                merged.vertices.extend(&m.vertices);
                merged
                    .triangles
                    .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
            }
        }
        if !found {
            let names: Vec<&str> = objects.iter().map(|(n, _)| n.as_str()).collect();
            return Err(UsageError(format!(
                "{name} has no object {:?}; its objects: {}",
                object.unwrap_or_default(),
                names.join(", ")
            )));
        }
        merged
    } else {
        Mesh::read(name, &bytes).map_err(cannot)?
    };
    if mesh.triangles.is_empty() {
        return Err(UsageError(format!("{name} has no triangles")));
    }
    Ok(mesh)
}

/// Previews the mesh `shape` under the template `text` (or `--file`).
pub fn run(
    args: &PreviewArgs,
    shape: &str,
    text: &Option<String>,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<i32, UsageError> {
    for (name, v) in [
        ("--speed", args.part.speed),
        ("--travel-speed", args.part.travel_speed),
    ] {
        if !(v.is_finite() && v > 0.0 && v <= 10_000.0) {
            return Err(UsageError(format!(
                "{name} must be above 0 and at most 10000 mm/s, found {v}"
            )));
        }
    }
    if !(0.01..=10.0).contains(&args.nozzle) {
        return Err(UsageError(format!(
            "--nozzle must be between 0.01 and 10 mm, found {}",
            args.nozzle
        )));
    }
    let mesh = read_mesh(shape, args.profile.object.as_deref())?;
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let m = &args.model;
    let model = if m.height.is_none() && m.model.is_none() {
        // As tall as the mesh.
        let model = crate::eval::Model::from_total_height(
            (hi[2] - lo[2]).max(1e-3),
            m.layer_height.unwrap_or(0.2),
            m.first_layer_height,
        )
        .map_err(|e| UsageError(format!("invalid model: {e}")))?;
        let (bottom, top) = (
            m.bottom_shell_layers.unwrap_or(model.bottom_shells()),
            m.top_shell_layers.unwrap_or(model.top_shells()),
        );
        model.with_shells(bottom, top)
    } else {
        m.build(None)?
    };
    let drawn = match template(
        text,
        &args.file,
        // `--object` picks the mesh's object; it names a project's overrides only with
        // --profile.
        &super::paths::ProfileArgs {
            profile: args.profile.profile.clone(),
            object: args
                .profile
                .profile
                .as_ref()
                .and(args.profile.object.clone()),
        },
        (args.target, crate::eval::Dialect::Rotlang),
        args.color,
        (&args.model, None),
        err,
    )? {
        Ok(t) => t,
        Err(code) => return Ok(code),
    };
    let (input, parse) = (drawn.input, drawn.parse);
    let settings = args.settings();
    let range = args.range(model.len(), "part")?;
    let part = Part::new(
        &mesh,
        &parse.template,
        &model,
        args.model.options(),
        settings,
        PartOptions {
            walls: args.part.walls,
            shells: true,
        },
    );
    // Every layer is filled for the summary; only the shown ones are kept.
    let mut summary = Summary::default();
    let mut shown = Vec::new();
    // The layers of the 3D picture (every `step`-th): their sections and paths.
    let step = model.len().div_ceil(150).max(1);
    let mut stacked = Vec::new();
    for layer in part {
        let layer = layer.map_err(|e| UsageError(e.to_string()))?;
        summary.add(&layer, args.part.speed, args.part.travel_speed);
        if args.part.three_d.is_some() && layer.layer.index % step == 0 {
            stacked.push((
                layer.section.z,
                layer.section.region.clone(),
                layer.paths.clone(),
            ));
        }
        if range.contains(&layer.layer.index) {
            shown.push(layer);
        }
    }
    if let Some(path) = &args.part.three_d {
        let slabs: Vec<preview::Slab<'_>> = stacked
            .iter()
            .map(|(z, region, paths)| preview::Slab {
                z: *z,
                region,
                paths,
            })
            .collect();
        let svg = preview::isometric(&slabs, 900.0);
        let html = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"));
        let text = if html {
            format!(
                "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>{}</title></head>\n<body style=\"margin:0\">\n{svg}</body></html>\n",
                crate::plot::escape(shape)
            )
        } else {
            svg
        };
        std::fs::write(path, text)
            .map_err(|e| UsageError(format!("cannot write {}: {e}", path.display())))?;
    }
    let text = match args.format {
        Format::Svg => {
            let labels: Vec<(String, String)> = shown
                .iter()
                .map(|l| {
                    let instruction = l
                        .layer
                        .instruction
                        .and_then(|s| input.text.get(s.range()))
                        .map_or_else(|| "(holds)".to_owned(), |t| shorten(t, 28));
                    let kind = match l.params.density {
                        d if d < 1.0 => {
                            format!("{} {}%", l.params.pattern, num(d * 100.0, 1))
                        }
                        _ if l.layer.fill == Fill::Sparse => {
                            format!("shell ({})", l.params.pattern)
                        }
                        _ => format!("{} ({})", l.layer.fill.name(), l.params.pattern),
                    };
                    (
                        format!(
                            "layer {} · z {} mm · {}°",
                            l.layer.index,
                            num(l.layer.top, 3),
                            num(l.layer.angle, 2)
                        ),
                        format!("{instruction} · {kind}"),
                    )
                })
                .collect();
            let panels: Vec<Panel<'_>> = shown
                .iter()
                .zip(&labels)
                .map(|(l, (title, subtitle))| Panel {
                    region: &l.section.region,
                    paths: &l.paths,
                    title: title.clone(),
                    subtitle: subtitle.clone(),
                })
                .collect();
            let options = PreviewOptions {
                columns: args.columns,
                ..PreviewOptions::default()
            };
            preview::svg(&panels, settings.nozzle, &options)
        }
        Format::Json => {
            let layers: Vec<serde_json::Value> = shown
                .iter()
                .map(|l| {
                    serde_json::json!({
                        "index": l.layer.index,
                        "bottom": l.layer.bottom,
                        "top": l.layer.top,
                        "z": l.section.z,
                        "angle": l.layer.angle,
                        "fill": l.layer.fill.name(),
                        "pattern": l.params.pattern.name(),
                        "density": l.params.density,
                        "length": l.paths.length,
                        "travel": l.paths.travel,
                        "open": l.section.open,
                        "bridged": l.section.bridged,
                        "section": rings(&l.section.region),
                        "polylines": l.paths.polylines.iter().map(|p| p.0.iter().map(|c| [c.x, c.y]).collect::<Vec<_>>()).collect::<Vec<_>>(),
                    })
                })
                .collect();
            let mut text = serde_json::to_string(&serde_json::json!({
                "template": input.text,
                "summary": summary_json(&summary, args),
                "layers": layers,
            }))
            .unwrap_or_default();
            text.push('\n');
            text
        }
    };
    emit(&text, args.out.as_deref(), out)?;
    let _ = writeln!(
        err,
        "{}: {} layers, infill {} m extruded, {} m travel, {} at {} mm/s (travel {} mm/s){}",
        shape,
        summary.layers,
        num(summary.extrusion / 1000.0, 2),
        num(summary.travel / 1000.0, 2),
        duration(summary.time),
        num(args.part.speed, 1),
        num(args.part.travel_speed, 1),
        if summary.open_layers > 0 {
            format!(
                "; {} layers have sections that could not be closed (holes in the mesh)",
                summary.open_layers
            )
        } else {
            String::new()
        }
    );
    Ok(0)
}

fn summary_json(s: &Summary, args: &PreviewArgs) -> serde_json::Value {
    serde_json::json!({
        "layers": s.layers,
        "extrusion_mm": s.extrusion,
        "travel_mm": s.travel,
        "time_s": s.time,
        "speed": args.part.speed,
        "travel_speed": args.part.travel_speed,
        "open_layers": s.open_layers,
        "bridged": s.bridged,
        "walls": args.part.walls,
    })
}

fn rings(region: &geo::MultiPolygon<f64>) -> Vec<Vec<Vec<[f64; 2]>>> {
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

fn duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}h {:02}min", s / 3600, (s % 3600) / 60)
    } else {
        format!("{}min {:02}s", s / 60, s % 60)
    }
}
