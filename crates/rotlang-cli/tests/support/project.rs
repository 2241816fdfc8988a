//! An OrcaSlicer-like 3MF project built by the tests: objects (meshes placed by a build
//! translation), `Metadata/project_settings.config` (JSON) and
//! `Metadata/model_settings.config` (each object's name and overrides).

use std::io::Write;

use rotlang_geometry::mesh::Mesh;

/// One object: its name, mesh, where the build puts it (x, y), and its overrides.
pub struct Object<'a> {
    pub name: &'a str,
    pub mesh: &'a Mesh,
    pub at: [f64; 2],
    pub overrides: &'a [(&'a str, &'a str)],
}

/// The project's bytes. `settings` is the JSON of `project_settings.config`.
pub fn project(objects: &[Object<'_>], settings: &str) -> Vec<u8> {
    let mut resources = String::new();
    let mut build = String::new();
    let mut config = String::from(r#"<?xml version="1.0" encoding="UTF-8"?><config>"#);
    for (i, o) in objects.iter().enumerate() {
        let id = i + 1;
        resources.push_str(&format!(
            r#"<object id="{id}" name="{}" type="model"><mesh><vertices>"#,
            o.name
        ));
        for v in &o.mesh.vertices {
            resources.push_str(&format!(
                r#"<vertex x="{}" y="{}" z="{}"/>"#,
                v[0], v[1], v[2]
            ));
        }
        resources.push_str("</vertices><triangles>");
        for t in &o.mesh.triangles {
            resources.push_str(&format!(
                r#"<triangle v1="{}" v2="{}" v3="{}"/>"#,
                t[0], t[1], t[2]
            ));
        }
        resources.push_str("</triangles></mesh></object>");
        build.push_str(&format!(
            r#"<item objectid="{id}" transform="1 0 0 0 1 0 0 0 1 {} {} 0"/>"#,
            o.at[0], o.at[1]
        ));
        config.push_str(&format!(
            r#"<object id="{id}"><metadata key="name" value="{}"/>"#,
            o.name
        ));
        for (k, v) in o.overrides {
            config.push_str(&format!(r#"<metadata key="{k}" value="{v}"/>"#));
        }
        config.push_str("</object>");
    }
    config.push_str("</config>");
    let model = format!(
        r#"<?xml version="1.0"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>{resources}</resources><build>{build}</build></model>"#
    );
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, text) in [
        ("3D/3dmodel.model", model.as_str()),
        ("Metadata/project_settings.config", settings),
        ("Metadata/model_settings.config", config.as_str()),
    ] {
        zip.start_file(name, zip::write::SimpleFileOptions::default())
            .unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap().into_inner()
}
