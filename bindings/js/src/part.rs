//! A real part in the playground (the `full` module): a mesh file (STL, OBJ or the objects
//! of a 3MF) read once and kept, then sliced and filled layer by layer under a template,
//! with the same answers as `rotlang preview --shape part.stl --format json` (same model,
//! walls, settings and JSON fields; `rotlang_geometry::slice::Part` does the work for both).

use rotlang_geometry::infill::{Pattern, Settings};
use rotlang_geometry::mesh::Mesh;
use rotlang_geometry::slice::{Part, PartOptions, Summary};

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
/// The CLI's default speeds (`--speed`, `--travel-speed`), for the summary's time.
const SPEED: f64 = 100.0;
const TRAVEL_SPEED: f64 = 200.0;

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
            let base = merged.vertices.len() as u32;
            merged.vertices.extend(&m.vertices);
            merged
                .triangles
                .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
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

/// The part's layers (all, or `from`..`to`) under the template: each layer's section and
/// infill paths, and the summary over every layer, as the CLI's JSON has them.
pub fn part(mesh: &Mesh, text: &str, req: &Request, walls: f64) -> Result<Value, Failure> {
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
    let layers = Part::new(
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
    let mut summary = Summary::default();
    let mut out = Vec::new();
    let mut points = 0usize;
    for layer in layers {
        let l = layer.map_err(|e| Failure::options(e.to_string()))?;
        summary.add(&l, SPEED, TRAVEL_SPEED);
        if !shown.contains(&l.layer.index) {
            continue;
        }
        let section = rings(&l.section.region, &mut points);
        let polylines: Vec<Value> = l
            .paths
            .polylines
            .iter()
            .map(|p| {
                points += p.0.len();
                p.0.iter()
                    .map(|c| Value::Array(vec![Value::Num(c.x), Value::Num(c.y)]))
                    .collect()
            })
            .collect();
        if points > MAX_POINTS {
            return Err(Failure::limit(format!(
                "the part's layers hold more than {MAX_POINTS} points; ask for fewer layers (`from`/`to`)"
            )));
        }
        out.push(obj!({
            "index": l.layer.index,
            "bottom": l.layer.bottom,
            "top": l.layer.top,
            "z": l.section.z,
            "angle": l.layer.angle,
            "fill": l.layer.fill.name(),
            "pattern": l.params().pattern.name(),
            "density": l.params().density,
            "length": l.paths.length,
            "travel": l.paths.travel,
            "open": l.section.open,
            "bridged": l.section.bridged,
            "section": section,
            "polylines": Value::Array(polylines),
        }));
    }
    Ok(obj!({
        "template": text,
        "summary": obj!({
            "layers": summary.layers,
            "extrusion_mm": summary.extrusion,
            "travel_mm": summary.travel,
            "time_s": summary.time,
            "speed": SPEED,
            "travel_speed": TRAVEL_SPEED,
            "open_layers": summary.open_layers,
            "bridged": summary.bridged,
            "walls": walls,
        }),
        "layers": Value::Array(out),
    }))
}

/// A section's polygons, each its outline then its holes, as `[x, y]` lists.
fn rings(region: &rotlang_geometry::infill::MultiPolygon<f64>, points: &mut usize) -> Value {
    region
        .0
        .iter()
        .map(|p| {
            std::iter::once(p.exterior())
                .chain(p.interiors())
                .map(|r| {
                    *points += r.0.len();
                    r.0.iter()
                        .map(|c| Value::Array(vec![Value::Num(c.x), Value::Num(c.y)]))
                        .collect()
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotlang_geometry::mesh::shapes;

    fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
        match v {
            Value::Object(f) => &f.iter().find(|(k, _)| *k == key).expect(key).1,
            _ => panic!("not an object"),
        }
    }

    #[test]
    fn a_cube_is_sliced_at_its_height_into_square_sections() {
        let stl = shapes::cuboid([20.0, 20.0, 10.0]).to_binary_stl();
        let (mesh, _) = read_mesh("cube.stl", &stl).unwrap();
        let answer = part(&mesh, "+45", &Request::default(), f64::NAN).unwrap();
        let Value::Array(layers) = field(&answer, "layers") else {
            panic!()
        };
        assert_eq!(layers.len(), 50);
        let Value::Array(section) = field(&layers[10], "section") else {
            panic!()
        };
        // One polygon, no hole: a closed square of five points.
        let Value::Array(rings) = &section[0] else {
            panic!()
        };
        assert_eq!(rings.len(), 1);
        assert!(matches!(&rings[0], Value::Array(r) if r.len() == 5));
    }

    #[test]
    fn bad_meshes_and_walls_are_refused_with_a_reason() {
        let e = read_mesh("x.stl", b"not a mesh").unwrap_err();
        assert_eq!(e.kind, "model");
        let e = read_mesh("x.3mf", b"PK not really").unwrap_err();
        assert!(e.message.contains("x.3mf"), "{}", e.message);
        let (mesh, _) =
            read_mesh("c.stl", &shapes::cuboid([1.0, 1.0, 1.0]).to_binary_stl()).unwrap();
        let e = part(&mesh, "0", &Request::default(), 2.5).unwrap_err();
        assert_eq!(e.kind, "options");
        let tall = Request::default()
            .with(slot::LAYER_HEIGHT, 0.01)
            .with(slot::HEIGHT, 500.0);
        assert_eq!(part(&mesh, "0", &tall, 2.0).unwrap_err().kind, "limit");
    }
}
