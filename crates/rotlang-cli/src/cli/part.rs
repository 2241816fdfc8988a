//! `rotlang preview --shape part.stl`: a real part, sliced, filled layer by layer.

use std::io::Write;

use super::UsageError;
use super::plot::emit;
use super::preview::{Format, PreviewArgs};
use super::stream::stream;
use crate::infill::preview::{self, Panel, PreviewOptions};
use crate::ir::Fill;
use crate::mesh::Mesh;
use crate::plot::{num, shorten};
use crate::slice::json::{self, About, Document};
use crate::slice::{Part, PartLayer, PartOptions};
use geo::Area;

mod args;
mod file;

pub use args::PartArgs;

/// The most bytes a mesh file may have (a 25-million-triangle binary STL).
const MAX_MESH_BYTES: u64 = 84 + 50 * crate::mesh::MAX_TRIANGLES as u64;

/// Whether `--shape` names a mesh file.
pub fn is_mesh(shape: &str) -> bool {
    let lower = shape.to_ascii_lowercase();
    lower.ends_with(".stl") || lower.ends_with(".obj") || lower.ends_with(".3mf")
}

/// The mesh of `name` (`object` of a 3MF), and whether the file is an OrcaSlicer project
/// (a 3MF with settings).
fn read_mesh(name: &str, object: Option<&str>) -> Result<(Mesh, bool), UsageError> {
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
    let project = name.to_ascii_lowercase().ends_with(".3mf") && file::is_project(&bytes);
    let mesh = if name.to_ascii_lowercase().ends_with(".3mf") {
        let objects = crate::mesh::read_3mf(&bytes).map_err(cannot)?;
        Mesh::pick(name, &objects, object).map_err(|e| UsageError(e.0))?
    } else {
        Mesh::read(name, &bytes).map_err(cannot)?
    };
    if mesh.triangles.is_empty() {
        return Err(UsageError(format!("{name} has no triangles")));
    }
    Ok((mesh, project))
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
    if args.profile.object.is_some()
        && args.profile.profile.is_none()
        && !shape.to_ascii_lowercase().ends_with(".3mf")
    {
        return Err(UsageError(format!(
            "--object picks an object of a 3MF, or of the --profile project; {shape} is neither"
        )));
    }
    let (mesh, project) = read_mesh(shape, args.profile.object.as_deref())?;
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let plan = match file::plan(args, shape, text.as_ref(), (hi[2] - lo[2], project), err)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    for note in &plan.notes {
        writeln!(err, "note: {note}")
            .map_err(|e| UsageError(format!("cannot write to stderr: {e}")))?;
    }
    let (input, parse, model, settings) = (&plan.input, &plan.parse, &plan.model, plan.settings);
    if !(0.01..=10.0).contains(&settings.nozzle) {
        return Err(UsageError(format!(
            "--nozzle must be between 0.01 and 10 mm, found {}",
            settings.nozzle
        )));
    }
    let range = args.range(model.len(), "part")?;
    let mut part = Part::new(
        &mesh,
        &parse.template,
        model,
        plan.options,
        settings,
        PartOptions {
            walls: plan.walls,
            shells: true,
        },
    );
    if let Some((_, solid)) = &plan.solid {
        part = part.with_solid_template(&solid.template, plan.solid_options);
    }
    // Every layer is filled for the summary; only the shown ones are kept (as JSON, by
    // the document the playground's part() builds too).
    let json = matches!(args.format, Format::Json);
    let mut doc = Document::new(About {
        solid_template: plan.solid.as_ref().map(|(i, _)| i.text.as_str()),
        speed: args.part.speed,
        travel_speed: args.part.travel_speed,
        ..About::new(&input.text, model, settings, plan.walls, plan.options.base)
    });
    let mut shown = Vec::new();
    // The layers of the 3D picture (every `step`-th): their sections and paths.
    let step = model.len().div_ceil(150).max(1);
    let mut stacked = Vec::new();
    let stack = args.part.three_d.is_some().then_some(step);
    if json {
        // A layer at a time (the same text as the whole document: `layers` is its first
        // key), so that every layer of a tall part can be listed in one layer's memory.
        stream(args.out.as_deref(), out, |w| {
            w.text("{\"layers\":[");
            each(part, &mut doc, &range, stack, &mut stacked, &mut |layer| {
                w.item(&json::layer(&layer));
                !w.closed()
            })?;
            // (No layer kept in it: a cheap copy.)
            let mut rest = doc.clone().finish();
            if let Some(map) = rest.as_object_mut() {
                map.remove("layers");
            }
            let rest = serde_json::to_string(&rest).unwrap_or_default();
            w.text("],");
            w.text(rest.strip_prefix('{').unwrap_or(&rest));
            w.text("\n");
            Ok(())
        })?;
    } else {
        each(part, &mut doc, &range, stack, &mut stacked, &mut |layer| {
            shown.push(layer);
            true
        })?;
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
    let summary = *doc.summary();
    // The picture (the JSON went out above, a layer at a time).
    if !json {
        {
            let labels: Vec<(String, String)> = shown
                .iter()
                .map(|l| {
                    let instruction = l
                        .layer
                        .instruction
                        .and_then(|s| input.text.get(s.range()))
                        .map_or_else(|| "(holds)".to_owned(), |t| shorten(t, 28));
                    let kind = kind(l);
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
            let walls: Vec<_> = shown.iter().map(PartLayer::wall_loops).collect();
            let panels: Vec<Panel<'_>> = shown
                .iter()
                .zip(&labels)
                .zip(&walls)
                .map(|((l, (title, subtitle)), walls)| Panel {
                    region: &l.section.region,
                    walls,
                    paths: &l.paths,
                    title: title.clone(),
                    subtitle: subtitle.clone(),
                })
                .collect();
            let options = PreviewOptions {
                columns: args.columns,
                ..PreviewOptions::default()
            };
            let text = preview::svg(&panels, settings.nozzle, &options);
            emit(&text, args.out.as_deref(), out)?;
        }
    }
    let _ = writeln!(
        err,
        "{}: {} layers, infill {} m extruded ({} m solid), {} m travel, {} at {} mm/s (travel {} mm/s){}",
        shape,
        summary.layers,
        num(summary.extrusion / 1000.0, 2),
        num(summary.solid_extrusion / 1000.0, 2),
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

/// The layers of the 3D picture: their height, section and paths.
type Stacked = Vec<(f64, geo::MultiPolygon<f64>, crate::infill::Toolpaths)>;

/// Fills every layer of `part`, counting each in `doc`'s summary, keeping every
/// `stack`-th for the 3D picture, and giving those in `range` to `shown` (which answers
/// whether to go on: not when nobody reads the answer any more).
fn each(
    part: Part<'_>,
    doc: &mut Document<'_>,
    range: &std::ops::Range<usize>,
    stack: Option<usize>,
    stacked: &mut Stacked,
    shown: &mut dyn FnMut(PartLayer) -> bool,
) -> Result<(), UsageError> {
    for layer in part {
        let layer = layer.map_err(|e| UsageError(e.to_string()))?;
        doc.add(&layer, false);
        if stack.is_some_and(|step| layer.layer.index % step == 0) {
            stacked.push((
                layer.section.z,
                layer.section.region.clone(),
                layer.paths.clone(),
            ));
        }
        if range.contains(&layer.layer.index) && !shown(layer) {
            break;
        }
    }
    Ok(())
}

/// The subtitle's fill: the sparse pattern and density, and the solid area's share.
fn kind(l: &PartLayer) -> String {
    let (sparse, solid) = (&l.sparse, &l.solid);
    if l.all_solid() {
        return if l.layer.fill == Fill::Sparse {
            format!(
                "shell ({} {}°)",
                solid.params.pattern,
                num(solid.params.angle, 2)
            )
        } else {
            format!("{} ({})", solid.fill.name(), solid.params.pattern)
        };
    }
    let text = format!(
        "{} {}%",
        sparse.params.pattern,
        num(sparse.params.density * 100.0, 1)
    );
    if solid.region.0.is_empty() {
        return text;
    }
    let share = solid.region.unsigned_area() / l.infill_area.unsigned_area().max(1e-12);
    format!(
        "{text} + solid {}% ({} {}°)",
        num(share * 100.0, 0),
        solid.params.pattern,
        num(solid.params.angle, 2)
    )
}

fn duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}h {:02}min", s / 3600, (s % 3600) / 60)
    } else {
        format!("{}min {:02}s", s / 60, s % 60)
    }
}
