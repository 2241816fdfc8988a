//! A real part in the playground (the `full` module): a mesh file (STL, OBJ or the objects
//! of a 3MF) read once and kept, then sliced and filled layer by layer under a template,
//! with the same answers as `rotlang preview --shape part.stl --format json` (same model,
//! walls, settings and JSON fields; `rotlang_geometry::slice::Part` does the work for both).

use std::path::Path;

use rotlang::Target;
use rotlang::eval::{Model, Options};
use rotlang_geometry::infill::{Pattern, Settings};
use rotlang_geometry::mesh::Mesh;
use rotlang_geometry::slice::json::{About, Document};
use rotlang_geometry::slice::{Part, PartOptions};
use rotlang_profile::profile::{self, Profile};

use crate::Failure;
use crate::json::Value;
use crate::obj;
use crate::options::{Request, slot};

/// Most layers one part call slices (a 300 mm part at 0.015 mm): a taller one is refused
/// with a limit failure rather than left to run for minutes.
pub const MAX_LAYERS: usize = 20_000;
/// Most points (section and infill) one answer holds, about 60 MB of JSON: a part beyond
/// it is read in ranges (`from`/`to`).
pub const MAX_POINTS: usize = 3_000_000;

/// A mesh file read and kept for [`part`]: its objects (a 3MF's, by name; an STL's or
/// OBJ's one, unnamed) and, for an OrcaSlicer project, its settings.
#[derive(Debug)]
pub struct Kept {
    name: String,
    objects: Vec<(String, Mesh)>,
    is_3mf: bool,
    project: Option<Profile>,
}

/// A mesh file: an STL or OBJ by [`Mesh::read`], a 3MF's objects (kept apart: [`part`]
/// merges them, or picks one, as `rotlang preview --shape project.3mf [--object NAME]`)
/// and an OrcaSlicer project's settings (read by `rotlang_profile::profile`, as the CLI
/// reads them; a project whose settings have errors is refused, as the CLI refuses it).
pub fn read_mesh(name: &str, bytes: &[u8]) -> Result<Kept, Failure> {
    let cannot = |e: rotlang_geometry::mesh::MeshError| {
        Failure::model(format!("cannot read a mesh from {name}: {e}"))
    };
    let is_3mf = name.to_ascii_lowercase().ends_with(".3mf");
    let objects = if is_3mf {
        rotlang_geometry::mesh::read_3mf(bytes).map_err(cannot)?
    } else {
        vec![(String::new(), Mesh::read(name, bytes).map_err(cannot)?)]
    };
    if objects.iter().all(|(_, m)| m.triangles.is_empty()) {
        return Err(Failure::model(format!("{name} has no triangles")));
    }
    let project = if is_3mf && profile::is_project(bytes) {
        let p =
            profile::parse(Path::new(name), bytes).map_err(|e| Failure::model(e.to_string()))?;
        if let Some(n) = p.notes.iter().find(|n| n.error) {
            return Err(Failure::model(format!("{name}: {}", n.message)));
        }
        Some(p)
    } else {
        None
    };
    Ok(Kept {
        name: name.to_owned(),
        objects,
        is_3mf,
        project,
    })
}

/// What the playground shows of a mesh just read: the size and bounds of all its objects,
/// their names (a 3MF's) and whether it is an OrcaSlicer project (whose settings `part`
/// applies where the options do not say).
pub fn mesh_json(kept: &Kept) -> Value {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let (mut triangles, mut vertices) = (0, 0);
    for (_, m) in &kept.objects {
        triangles += m.triangles.len();
        vertices += m.vertices.len();
        if let Some((l, h)) = m.bounds() {
            for k in 0..3 {
                lo[k] = lo[k].min(l[k]);
                hi[k] = hi[k].max(h[k]);
            }
        }
    }
    let names: Vec<String> = if kept.is_3mf {
        kept.objects.iter().map(|(n, _)| n.clone()).collect()
    } else {
        Vec::new()
    };
    obj!({
        "triangles": triangles,
        "vertices": vertices,
        "min": lo.to_vec(),
        "max": hi.to_vec(),
        "objects": names,
        "project": kept.project.is_some(),
    })
}

/// Which solid template turns a part's solid areas (its top and bottom surfaces).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid<'a> {
    /// An OrcaSlicer project's own (the object's first), else none.
    FromFile,
    /// This one, over a project's (`solidTemplate`, the CLI's `--solid-template`).
    Given(&'a str),
    /// None, even where a project sets one: the solid areas turn with the template
    /// (`noSolidTemplate`, the CLI's `--no-solid-template`).
    Off,
}

/// What a part is filled with: the request's values, else (for an OrcaSlicer project) the
/// file's, an object's overrides first, else the defaults; as `rotlang preview` plans it
/// (`crates/rotlang-cli/src/cli/part/file.rs`), from the same readers
/// (`Profile::part_template`, `Profile::part_infill`, `Profile::model`).
struct Plan<'a> {
    mesh: std::borrow::Cow<'a, Mesh>,
    text: &'a str,
    solid: Option<&'a str>,
    model: Model,
    options: Options,
    solid_options: Options,
    settings: Settings,
    walls: u32,
}

fn plan<'a>(
    kept: &'a Kept,
    text: &'a str,
    solid: Solid<'a>,
    req: &Request,
    walls: f64,
    object: Option<&str>,
) -> Result<Plan<'a>, Failure> {
    let target = req.target()?;
    let mut options = req.eval_options()?;
    if !(walls.is_nan() || (walls.fract() == 0.0 && (0.0..=100.0).contains(&walls))) {
        return Err(Failure::options(format!(
            "`walls` must be a whole number from 0 to 100, found {walls}"
        )));
    }
    let mesh = match (kept.is_3mf, object) {
        (true, _) => std::borrow::Cow::Owned(
            Mesh::pick(&kept.name, &kept.objects, object).map_err(|e| Failure::options(e.0))?,
        ),
        (false, None) => std::borrow::Cow::Borrowed(&kept.objects[0].1),
        (false, Some(_)) => {
            return Err(Failure::options(format!(
                "`object` picks an object of a 3MF; {} is not one",
                kept.name
            )));
        }
    };
    if mesh.triangles.is_empty() {
        return Err(Failure::model(format!("{} has no triangles", kept.name)));
    }
    let file = kept.project.as_ref();
    // An empty template is the file's (the object's own first), as the CLI reads
    // `rotlang preview '' --shape project.3mf`.
    let text = match file {
        Some(f) if text.is_empty() => f
            .part_template(target, object)
            .map_or("", |t| t.text.as_str()),
        _ => text,
    };
    let solid = match solid {
        Solid::Given(s) => Some(s),
        Solid::FromFile => file
            .and_then(|f| f.part_template(Target::Solid, object))
            .map(|t| t.text.as_str()),
        Solid::Off => None,
    };
    // As tall as the mesh unless the request gives the model's layers or height (as the
    // CLI); the file's layer heights and shells where the request gives none.
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let height = hi[2] - lo[2];
    let sized = req.number(slot::LAYERS).is_some() || req.number(slot::HEIGHT).is_some();
    let mut req_model = req.clone();
    if !sized {
        req_model = req_model.with(slot::HEIGHT, height.max(1e-3));
        if let Some(f) = file {
            let pm = f.model(target, object, height);
            let first = pm.model.layer_bounds(0).map(|(_, t)| t);
            for (slot, value) in [
                (slot::LAYER_HEIGHT, Some(pm.model.layer_height())),
                (slot::FIRST_LAYER_HEIGHT, first),
                (
                    slot::BOTTOM_SHELLS,
                    Some(f64::from(pm.model.bottom_shells())),
                ),
                (slot::TOP_SHELLS, Some(f64::from(pm.model.top_shells()))),
            ] {
                if let (None, Some(v)) = (req.number(slot), value) {
                    req_model = req_model.with(slot, v);
                }
            }
        }
    }
    let model = req_model.model(None)?;
    if model.len() > MAX_LAYERS {
        return Err(Failure::limit(format!(
            "the part has {} layers; at most {MAX_LAYERS} are sliced here (a larger layer height, or the CLI)",
            model.len()
        )));
    }
    // A profile's direction turns an empty template only; a base given replaces it.
    let base_for = |text: &str, t: Target, options: Options| match file {
        Some(f) if options.base == 0.0 => Options {
            base: f.model(t, object, height).options(text).base,
            ..options
        },
        _ => options,
    };
    let solid_options = solid.map_or_else(
        || base_for(text, target, options),
        |s| base_for(s, Target::Solid, options),
    );
    options = base_for(text, target, options);
    let from = file.map(|f| f.part_infill(object)).unwrap_or_default();
    let pattern = match req.index(slot::PATTERN, Pattern::ALL.len() - 1)? {
        Some(i) => Pattern::ALL[i],
        None => from
            .pattern
            .and_then(|p| p.parse().ok())
            .unwrap_or(Pattern::Lines),
    };
    let density = req.number(slot::DENSITY).or(from.density).unwrap_or(0.2);
    if !(density > 0.0 && density <= 1.0) {
        return Err(Failure::options(format!(
            "`density` must be above 0 and at most 1, found {density}"
        )));
    }
    let defaults = Settings::default();
    let settings = Settings {
        pattern,
        density,
        solid_pattern: from
            .solid_pattern
            .and_then(|p| p.parse().ok())
            .unwrap_or(defaults.solid_pattern),
        nozzle: from.line_width.unwrap_or(defaults.nozzle),
        ..defaults
    };
    let walls = if walls.is_nan() {
        from.walls.unwrap_or(2)
    } else {
        walls as u32
    };
    Ok(Plan {
        mesh,
        text,
        solid,
        model,
        options,
        solid_options,
        settings,
        walls,
    })
}

/// The part's layers (all, or `from`..`to`) of the kept mesh (all its objects, or
/// `object`'s) under the template (and the solid template, which turns the top and bottom
/// surfaces): the document `rotlang preview --shape part.stl --format json` prints, built
/// by the same code (`rotlang_geometry::slice::json`). With `settings_only`, the document
/// without slicing: what the part would be filled with (its template, solid template,
/// settings, and `first_layer_height`), for the playground to show.
pub fn part(
    kept: &Kept,
    text: &str,
    solid: Solid,
    req: &Request,
    (walls, object, settings_only): (f64, Option<&str>, bool),
) -> Result<Value, Failure> {
    let target = req.target()?;
    let plan = plan(kept, text, solid, req, walls, object)?;
    let model = &plan.model;
    let (from, to) = req.range()?;
    let shown = from.unwrap_or(0)..to.unwrap_or(model.len()).min(model.len());
    let mut doc = Document::new(About {
        solid_template: plan.solid,
        ..About::new(
            plan.text,
            model,
            plan.settings,
            plan.walls,
            plan.options.base,
        )
    });
    // What the part is filled with, even where a template has errors (the page shows
    // them in its editor).
    if settings_only {
        let mut json = doc.finish();
        json["first_layer_height"] = model.layer_bounds(0).map(|(_, t)| t).into();
        json["solid_base"] = plan.solid_options.base.into();
        return Ok(Value::Raw(json.to_string()));
    }
    let parse = crate::api::parse_clean(plan.text, target)?;
    let solid_parse = plan
        .solid
        .map(|s| {
            crate::api::parse_clean(s, Target::Solid).map_err(|mut f| {
                f.message = f.message.replacen("the template", "the solid template", 1);
                f
            })
        })
        .transpose()?;
    let mut layers = Part::new(
        &plan.mesh,
        &parse.template,
        model,
        plan.options,
        plan.settings,
        PartOptions {
            walls: plan.walls,
            shells: true,
        },
    );
    if let Some(p) = &solid_parse {
        layers = layers.with_solid_template(&p.template, plan.solid_options);
    }
    for layer in layers {
        let l = layer.map_err(|e| Failure::options(e.to_string()))?;
        doc.add(&l, shown.contains(&l.layer.index));
        if doc.points() > MAX_POINTS {
            return Err(Failure::limit(format!(
                "the part's layers hold more than {MAX_POINTS} points; ask for fewer layers (`from`/`to`)"
            )));
        }
    }
    Ok(Value::Raw(doc.finish().to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotlang_geometry::mesh::shapes;

    fn parsed(v: Value) -> serde_json::Value {
        let mut text = String::new();
        v.write(&mut text);
        serde_json::from_str(&text).unwrap()
    }

    #[test]
    fn a_cube_is_sliced_at_its_height_into_square_sections() {
        let stl = shapes::cuboid([20.0, 20.0, 10.0]).to_binary_stl();
        let mesh = read_mesh("cube.stl", &stl).unwrap();
        let answer = parsed(
            part(
                &mesh,
                "+45",
                Solid::FromFile,
                &Request::default(),
                (f64::NAN, None, false),
            )
            .unwrap(),
        );
        let layers = answer["layers"].as_array().unwrap();
        assert_eq!(layers.len(), 50);
        // One polygon, no hole: a closed square of five points.
        let rings = layers[10]["section"][0].as_array().unwrap();
        assert_eq!(rings.len(), 1);
        assert_eq!(rings[0].as_array().unwrap().len(), 5);
        // The first and last layers are solid, turned by the solid template when given.
        assert_eq!(layers[0]["printed"], "solid");
        assert_eq!(layers[49]["printed"], "solid");
        assert_eq!(layers[10]["printed"], "sparse");
        assert_eq!(answer["solid_template"], serde_json::Value::Null);
        let answer = parsed(
            part(
                &mesh,
                "+45",
                Solid::Given("90"),
                &Request::default(),
                (2.0, None, false),
            )
            .unwrap(),
        );
        assert_eq!(answer["solid_template"], "90");
        assert_eq!(answer["layers"][0]["areas"][0]["angle"], 90.0);
        assert_eq!(answer["layers"][10]["areas"][0]["angle"], 45.0 * 11.0);
    }

    #[test]
    fn bad_meshes_walls_and_templates_are_refused_with_a_reason() {
        let e = read_mesh("x.stl", b"not a mesh").unwrap_err();
        assert_eq!(e.kind, "model");
        // An object of an STL: there is none to pick.
        let e = part(
            &read_mesh("c.stl", &shapes::cuboid([1.0, 1.0, 1.0]).to_binary_stl()).unwrap(),
            "0",
            Solid::FromFile,
            &Request::default(),
            (2.0, Some("a"), false),
        )
        .unwrap_err();
        assert!(e.message.contains("not one"), "{}", e.message);
        let e = read_mesh("x.3mf", b"PK not really").unwrap_err();
        assert!(e.message.contains("x.3mf"), "{}", e.message);
        let mesh = read_mesh("c.stl", &shapes::cuboid([1.0, 1.0, 1.0]).to_binary_stl()).unwrap();
        let e = part(
            &mesh,
            "0",
            Solid::FromFile,
            &Request::default(),
            (2.5, None, false),
        )
        .unwrap_err();
        assert_eq!(e.kind, "options");
        let e = part(
            &mesh,
            "0",
            Solid::Given("+"),
            &Request::default(),
            (2.0, None, false),
        )
        .unwrap_err();
        assert_eq!(e.kind, "template");
        assert!(e.message.starts_with("the solid template"), "{}", e.message);
        let tall = Request::default()
            .with(slot::LAYER_HEIGHT, 0.01)
            .with(slot::HEIGHT, 500.0);
        assert_eq!(
            part(&mesh, "0", Solid::FromFile, &tall, (2.0, None, false))
                .unwrap_err()
                .kind,
            "limit"
        );
    }
}
