//! The meshes of a 3MF file (feature `3mf`): every `<object>` of the model files
//! (`3D/3dmodel.model` and, in OrcaSlicer and Bambu projects, `3D/Objects/*.model`), their
//! `<components>` resolved, and each build `<item>` placed by its transform.

use std::collections::HashMap;
use std::io::{Cursor, Read};

use super::{Builder, Mesh, MeshError};

/// An inflated model file may be this large (a 25-million-triangle mesh as XML is larger:
/// such a file is refused, not read into memory).
const MAX_ENTRY_BYTES: u64 = 1 << 30;

type Transform = [f64; 12];
const IDENTITY: Transform = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];

/// One object of a model file: its own triangles, and components (path, id, transform).
#[derive(Default)]
struct Object {
    name: Option<String>,
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
    components: Vec<(Option<String>, String, Transform)>,
}

/// The objects of a 3MF's build, each placed as the build says, with their names
/// (`name` of the object, or `object ID`).
pub fn read_3mf(bytes: &[u8]) -> Result<Vec<(String, Mesh)>, MeshError> {
    let err = |e: String| MeshError(e);
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| err(format!("not a 3MF (zip) file: {e}")))?;
    let names: Vec<String> = archive
        .file_names()
        .filter(|n| n.to_ascii_lowercase().ends_with(".model"))
        .map(str::to_owned)
        .collect();
    let mut objects: HashMap<(String, String), Object> = HashMap::new();
    let mut build: Vec<(String, Transform)> = Vec::new();
    let root = names
        .iter()
        .find(|n| n.eq_ignore_ascii_case("3D/3dmodel.model"))
        .cloned()
        .ok_or_else(|| err("the 3MF has no 3D/3dmodel.model".into()))?;
    for name in &names {
        let mut file = archive
            .by_name(name)
            .map_err(|e| err(format!("{name}: {e}")))?;
        let mut text = String::new();
        file.by_ref()
            .take(MAX_ENTRY_BYTES + 1)
            .read_to_string(&mut text)
            .map_err(|e| err(format!("{name}: {e}")))?;
        if text.len() as u64 > MAX_ENTRY_BYTES {
            return Err(err(format!("{name}: larger than 1 GiB once inflated")));
        }
        let key = format!("/{}", name.trim_start_matches('/'));
        let items =
            parse_model(&text, &key, &mut objects).map_err(|e| err(format!("{name}: {e}")))?;
        if *name == root {
            build = items;
        }
    }
    let root_key = format!("/{}", root.trim_start_matches('/'));
    let mut out = Vec::new();
    for (id, transform) in build {
        let mut builder = Builder::with_capacity(0);
        place(&objects, &root_key, &id, &transform, &mut builder, 0)?;
        let name = objects
            .get(&(root_key.clone(), id.clone()))
            .and_then(|o| o.name.clone())
            .unwrap_or_else(|| format!("object {id}"));
        out.push((name, builder.mesh));
    }
    Ok(out)
}

/// Adds object `id` of file `path`, transformed, with its components (at most 16 deep).
fn place(
    objects: &HashMap<(String, String), Object>,
    path: &str,
    id: &str,
    transform: &Transform,
    builder: &mut Builder,
    depth: usize,
) -> Result<(), MeshError> {
    if depth > 16 {
        return Err(MeshError(
            "components nest more than 16 deep (a cycle?)".into(),
        ));
    }
    let object = objects
        .get(&(path.to_owned(), id.to_owned()))
        .ok_or_else(|| MeshError(format!("{path}: no object with id {id}")))?;
    let at = |v: [f64; 3]| apply(transform, v);
    for t in &object.triangles {
        let corner = |i: usize| {
            object.vertices.get(i).copied().ok_or_else(|| {
                MeshError(format!(
                    "{path}: object {id}: a triangle names vertex {i}, which is not there"
                ))
            })
        };
        builder.triangle([at(corner(t[0])?), at(corner(t[1])?), at(corner(t[2])?)])?;
    }
    for (file, child, local) in &object.components {
        let file = file.clone().unwrap_or_else(|| path.to_owned());
        place(
            objects,
            &file,
            child,
            &compose(transform, local),
            builder,
            depth + 1,
        )?;
    }
    Ok(())
}

/// `transform` as 3MF writes it: `m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32`, row
/// vectors: p' = p·M + t.
fn apply(m: &Transform, v: [f64; 3]) -> [f64; 3] {
    [
        v[0] * m[0] + v[1] * m[3] + v[2] * m[6] + m[9],
        v[0] * m[1] + v[1] * m[4] + v[2] * m[7] + m[10],
        v[0] * m[2] + v[1] * m[5] + v[2] * m[8] + m[11],
    ]
}

/// `inner` then `outer`.
fn compose(outer: &Transform, inner: &Transform) -> Transform {
    let mut m = [0.0; 12];
    for r in 0..4 {
        let row = [inner[3 * r], inner[3 * r + 1], inner[3 * r + 2]];
        let v = if r < 3 {
            // A direction: no translation.
            let p = apply(outer, row);
            [p[0] - outer[9], p[1] - outer[10], p[2] - outer[11]]
        } else {
            apply(outer, row)
        };
        m[3 * r..3 * r + 3].copy_from_slice(&v);
    }
    m
}

fn parse_transform(text: Option<&str>) -> Result<Transform, String> {
    let Some(text) = text else {
        return Ok(IDENTITY);
    };
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|w| {
            w.parse::<f64>()
                .map_err(|_| format!("a transform has {w:?}"))
        })
        .collect::<Result<_, _>>()?;
    if v.len() != 12 || v.iter().any(|x| !x.is_finite()) {
        return Err(format!("a transform needs 12 finite numbers: {text:?}"));
    }
    Ok(v.try_into().unwrap_or(IDENTITY))
}

/// Reads the objects of one model file into `objects`; returns its build items.
fn parse_model(
    text: &str,
    path: &str,
    objects: &mut HashMap<(String, String), Object>,
) -> Result<Vec<(String, Transform)>, String> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(text);
    let mut current: Option<(String, Object)> = None;
    let mut items = Vec::new();
    loop {
        let event = reader
            .read_event()
            .map_err(|e| format!("invalid XML at byte {}: {e}", reader.error_position()))?;
        match event {
            Event::Eof => break,
            Event::Start(e) | Event::Empty(e) => {
                let mut attrs: HashMap<String, String> = HashMap::new();
                for a in e.attributes().flatten() {
                    let key = a.key.local_name().as_ref().to_owned();
                    // Numbers, ids, names: entities are rare; an unreadable one is kept raw.
                    let raw = a.value.to_string();
                    let value = quick_xml::escape::unescape(&raw)
                        .map(|v| v.into_owned())
                        .unwrap_or(raw);
                    attrs.insert(key, value);
                }
                let number = |k: &str| -> Result<f64, String> {
                    attrs
                        .get(k)
                        .and_then(|v| v.trim().parse::<f64>().ok())
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| {
                            format!(
                                "a <{}> without a finite `{k}`",
                                e.local_name().as_ref().to_owned()
                            )
                        })
                };
                let index = |k: &str| -> Result<usize, String> {
                    attrs
                        .get(k)
                        .and_then(|v| v.trim().parse::<usize>().ok())
                        .ok_or_else(|| format!("a <triangle> without a vertex index `{k}`"))
                };
                match e.local_name().as_ref() {
                    "object" => {
                        let id = attrs.get("id").cloned().unwrap_or_default();
                        let object = Object {
                            name: attrs.get("name").cloned(),
                            ..Object::default()
                        };
                        current = Some((id, object));
                    }
                    "vertex" => {
                        if let Some((_, o)) = current.as_mut() {
                            o.vertices.push([number("x")?, number("y")?, number("z")?]);
                        }
                    }
                    "triangle" => {
                        if let Some((_, o)) = current.as_mut() {
                            o.triangles.push([index("v1")?, index("v2")?, index("v3")?]);
                            if o.triangles.len() > super::MAX_TRIANGLES {
                                return Err("more than the triangles a mesh may have".into());
                            }
                        }
                    }
                    "component" => {
                        if let Some((_, o)) = current.as_mut() {
                            let id = attrs.get("objectid").cloned().unwrap_or_default();
                            let file = attrs.get("path").cloned();
                            o.components.push((
                                file,
                                id,
                                parse_transform(attrs.get("transform").map(String::as_str))?,
                            ));
                        }
                    }
                    "item" => {
                        let id = attrs.get("objectid").cloned().unwrap_or_default();
                        items.push((
                            id,
                            parse_transform(attrs.get("transform").map(String::as_str))?,
                        ));
                    }
                    _ => {}
                }
            }
            Event::End(e) if e.local_name().as_ref() == "object" => {
                if let Some((id, o)) = current.take() {
                    objects.insert((path.to_owned(), id), o);
                }
            }
            _ => {}
        }
    }
    Ok(items)
}
