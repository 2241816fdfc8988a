//! A real part in the playground (the `full` module): a mesh file (STL, OBJ or the objects
//! of a 3MF) read once and kept, then sliced and filled layer by layer under a template,
//! with the same answers as `rotlang preview --shape part.stl --format json` (same model,
//! walls, settings and JSON fields; `rotlang_geometry::slice::Part` does the work for both).

use rotlang::Target;
use rotlang_geometry::infill::{Pattern, Settings};
use rotlang_geometry::mesh::Mesh;
use rotlang_geometry::slice::json::{About, Document};
use rotlang_geometry::slice::{Part, PartOptions};

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

/// A mesh file's triangles: an STL or OBJ by [`Mesh::read`], a 3MF's objects merged as
/// `rotlang preview --shape project.3mf` merges them without `--object`.
pub fn read_mesh(name: &str, bytes: &[u8]) -> Result<(Mesh, Vec<String>), Failure> {
    let cannot = |e: rotlang_geometry::mesh::MeshError| {
        Failure::model(format!("cannot read a mesh from {name}: {e}"))
    };
    let (mesh, objects) = if name.to_ascii_lowercase().ends_with(".3mf") {
        let objects = rotlang_geometry::mesh::read_3mf(bytes).map_err(cannot)?;
        let mut merged = Mesh::default();
        let mut names = Vec::new();
        for (n, m) in objects {
            merged.append(&m);
            names.push(n);
        }
        (merged, names)
    } else {
        (Mesh::read(name, bytes).map_err(cannot)?, Vec::new())
    };
    if mesh.triangles.is_empty() {
        return Err(Failure::model(format!("{name} has no triangles")));
    }
    Ok((mesh, objects))
}

/// What the playground shows of a mesh just read.
pub fn mesh_json(mesh: &Mesh, objects: &[String]) -> Value {
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    obj!({
        "triangles": mesh.triangles.len(),
        "vertices": mesh.vertices.len(),
        "min": lo.to_vec(),
        "max": hi.to_vec(),
        "objects": objects.to_vec(),
    })
}

/// The part's layers (all, or `from`..`to`) under the template (and the solid template,
/// which turns the top and bottom surfaces): the document `rotlang preview --shape part.stl
/// --format json` prints, built by the same code (`rotlang_geometry::slice::json`).
pub fn part(
    mesh: &Mesh,
    text: &str,
    solid: Option<&str>,
    req: &Request,
    walls: f64,
) -> Result<Value, Failure> {
    let target = req.target()?;
    let options = req.eval_options()?;
    if !(walls.is_nan() || (walls.fract() == 0.0 && (0.0..=100.0).contains(&walls))) {
        return Err(Failure::options(format!(
            "`walls` must be a whole number from 0 to 100, found {walls}"
        )));
    }
    let walls = if walls.is_nan() { 2 } else { walls as u32 };
    // As tall as the mesh unless the request gives the model's layers or height (as the CLI).
    let (lo, hi) = mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let sized = req.number(slot::LAYERS).is_some() || req.number(slot::HEIGHT).is_some();
    let req_model = if sized {
        req.clone()
    } else {
        req.clone().with(slot::HEIGHT, (hi[2] - lo[2]).max(1e-3))
    };
    let model = req_model.model(None)?;
    if model.len() > MAX_LAYERS {
        return Err(Failure::limit(format!(
            "the part has {} layers; at most {MAX_LAYERS} are sliced here (a larger layer height, or the CLI)",
            model.len()
        )));
    }
    let pattern = match req.index(slot::PATTERN, Pattern::ALL.len() - 1)? {
        Some(i) => Pattern::ALL[i],
        None => Pattern::Lines,
    };
    let density = req.number(slot::DENSITY).unwrap_or(0.2);
    if !(density > 0.0 && density <= 1.0) {
        return Err(Failure::options(format!(
            "`density` must be above 0 and at most 1, found {density}"
        )));
    }
    let settings = Settings {
        pattern,
        density,
        ..Settings::default()
    };
    let (from, to) = req.range()?;
    let shown = from.unwrap_or(0)..to.unwrap_or(model.len()).min(model.len());
    let parse = crate::api::parse_clean(text, target)?;
    let solid_parse = solid
        .map(|s| {
            crate::api::parse_clean(s, Target::Solid).map_err(|mut f| {
                f.message = f.message.replacen("the template", "the solid template", 1);
                f
            })
        })
        .transpose()?;
    let mut layers = Part::new(
        mesh,
        &parse.template,
        &model,
        options,
        settings,
        PartOptions {
            walls,
            shells: true,
        },
    );
    if let Some(p) = &solid_parse {
        layers = layers.with_solid_template(&p.template, options);
    }
    let mut doc = Document::new(About {
        solid_template: solid,
        ..About::new(text, &model, settings, walls, options.base)
    });
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
        let (mesh, _) = read_mesh("cube.stl", &stl).unwrap();
        let answer = parsed(part(&mesh, "+45", None, &Request::default(), f64::NAN).unwrap());
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
        let answer = parsed(part(&mesh, "+45", Some("90"), &Request::default(), 2.0).unwrap());
        assert_eq!(answer["solid_template"], "90");
        assert_eq!(answer["layers"][0]["areas"][0]["angle"], 90.0);
        assert_eq!(answer["layers"][10]["areas"][0]["angle"], 45.0 * 11.0);
    }

    #[test]
    fn bad_meshes_walls_and_templates_are_refused_with_a_reason() {
        let e = read_mesh("x.stl", b"not a mesh").unwrap_err();
        assert_eq!(e.kind, "model");
        let e = read_mesh("x.3mf", b"PK not really").unwrap_err();
        assert!(e.message.contains("x.3mf"), "{}", e.message);
        let (mesh, _) =
            read_mesh("c.stl", &shapes::cuboid([1.0, 1.0, 1.0]).to_binary_stl()).unwrap();
        let e = part(&mesh, "0", None, &Request::default(), 2.5).unwrap_err();
        assert_eq!(e.kind, "options");
        let e = part(&mesh, "0", Some("+"), &Request::default(), 2.0).unwrap_err();
        assert_eq!(e.kind, "template");
        assert!(e.message.starts_with("the solid template"), "{}", e.message);
        let tall = Request::default()
            .with(slot::LAYER_HEIGHT, 0.01)
            .with(slot::HEIGHT, 500.0);
        assert_eq!(
            part(&mesh, "0", None, &tall, 2.0).unwrap_err().kind,
            "limit"
        );
    }
}
