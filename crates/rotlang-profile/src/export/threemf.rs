//! A PrusaSlicer 3MF project: one object (a mesh read from an STL file) whose layer-range
//! modifiers set `fill_angle` per height range, and the print settings of the export.
//!
//! PrusaSlicer keeps a project's print settings in `Metadata/Slic3r_PE.config` (`; key =
//! value` lines) and an object's layer ranges in
//! `Metadata/Prusa_Slicer_layer_config_ranges.xml` (objects numbered from 1, ranges in mm
//! above the object's bottom); both are read by its command line as by its window
//! (checked with PrusaSlicer 2.5, tests/slicers.rs).

use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::{Cursor, Write};

use super::Export;
use crate::number;

/// A triangle mesh: vertices and triangles (indices into them).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub vertices: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// The largest STL read (a few million triangles).
const MAX_TRIANGLES: usize = 5_000_000;

/// Reads an STL file, binary or ASCII. Shared vertices are merged.
pub fn read_stl(bytes: &[u8]) -> Result<Mesh, String> {
    let mut mesh = Mesh::default();
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut add = |mesh: &mut Mesh, v: [f32; 3]| -> Result<u32, String> {
        if v.iter().any(|c| !c.is_finite()) {
            return Err("a vertex is not a finite number".into());
        }
        let key = v.map(f32::to_bits);
        if let Some(&i) = index.get(&key) {
            return Ok(i);
        }
        let i = mesh.vertices.len() as u32;
        mesh.vertices.push(v);
        index.insert(key, i);
        Ok(i)
    };
    let binary_len = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize);
    if let Some(n) = binary_len.filter(|&n| 84 + n.saturating_mul(50) == bytes.len()) {
        if n > MAX_TRIANGLES {
            return Err(format!("{n} triangles: more than {MAX_TRIANGLES}"));
        }
        for t in 0..n {
            let at = 84 + t * 50 + 12;
            let mut tri = [0u32; 3];
            for (k, slot) in tri.iter_mut().enumerate() {
                let mut v = [0f32; 3];
                for (c, x) in v.iter_mut().enumerate() {
                    let o = at + k * 12 + c * 4;
                    *x = f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
                }
                *slot = add(&mut mesh, v)?;
            }
            mesh.triangles.push(tri);
        }
    } else {
        let text = std::str::from_utf8(bytes).map_err(|_| {
            "neither a binary STL (its size does not match its triangle count) nor ASCII"
                .to_string()
        })?;
        let mut corners = Vec::with_capacity(3);
        for (line_no, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            if words.next() != Some("vertex") {
                continue;
            }
            let mut v = [0f32; 3];
            for x in &mut v {
                *x = words
                    .next()
                    .and_then(|w| w.parse().ok())
                    .ok_or_else(|| format!("line {}: a vertex needs three numbers", line_no + 1))?;
            }
            corners.push(add(&mut mesh, v)?);
            if corners.len() == 3 {
                mesh.triangles.push([corners[0], corners[1], corners[2]]);
                corners.clear();
                if mesh.triangles.len() > MAX_TRIANGLES {
                    return Err(format!("more than {MAX_TRIANGLES} triangles"));
                }
            }
        }
    }
    if mesh.triangles.is_empty() {
        return Err("the STL has no triangles".into());
    }
    Ok(mesh)
}

/// The 3MF project's bytes: `mesh` as one object named `name`, with the export's settings
/// and layer ranges.
pub fn project(export: &Export, mesh: &Mesh, name: &str) -> Result<Vec<u8>, String> {
    let mut model = String::with_capacity(64 * mesh.triangles.len() + 1024);
    model.push_str(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" \
         xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" \
         xmlns:slic3rpe=\"http://schemas.slic3r.org/3mf/2017/06\">\n \
         <metadata name=\"slic3rpe:Version3mf\">1</metadata>\n <resources>\n  \
         <object id=\"1\" type=\"model\">\n   <mesh>\n    <vertices>\n",
    );
    for v in &mesh.vertices {
        let _ = writeln!(
            model,
            "     <vertex x=\"{}\" y=\"{}\" z=\"{}\"/>",
            v[0], v[1], v[2]
        );
    }
    model.push_str("    </vertices>\n    <triangles>\n");
    for t in &mesh.triangles {
        let _ = writeln!(
            model,
            "     <triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>",
            t[0], t[1], t[2]
        );
    }
    model.push_str(
        "    </triangles>\n   </mesh>\n  </object>\n </resources>\n <build>\n  \
         <item objectid=\"1\" printable=\"1\"/>\n </build>\n</model>\n",
    );

    let mut config = String::from("; generated by rotlang export --to prusaslicer\n");
    for (k, v) in &export.settings {
        let _ = writeln!(config, "; {k} = {v}");
    }

    let mut objects = String::from(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<config>\n <object id=\"1\" instances_count=\"1\">\n",
    );
    let _ = writeln!(
        objects,
        "  <metadata type=\"object\" key=\"name\" value=\"{}\"/>",
        escape(name)
    );
    let _ = writeln!(
        objects,
        "  <volume firstid=\"0\" lastid=\"{}\">\n   <metadata type=\"volume\" key=\"name\" value=\"{}\"/>\n  </volume>\n </object>\n</config>",
        mesh.triangles.len().saturating_sub(1),
        escape(name)
    );

    let mut ranges =
        String::from("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<objects>\n <object id=\"1\">\n");
    // PrusaSlicer 2.5 reads every range's `layer_height` when it plans the layers (it
    // crashes on a range without one): the export's layer height.
    let layer_height = export.setting("layer_height").unwrap_or("0.2");
    for r in &export.ranges {
        let _ = writeln!(
            ranges,
            "  <range min_z=\"{}\" max_z=\"{}\">\n   <option opt_key=\"extruder\">0</option>\n   <option opt_key=\"layer_height\">{}</option>\n   <option opt_key=\"fill_angle\">{}</option>\n  </range>",
            number::height(r.min_z).as_str(),
            number::height(r.max_z).as_str(),
            escape(layer_height),
            number::angle(r.fill_angle).as_str()
        );
    }
    ranges.push_str(" </object>\n</objects>\n");

    let content_types = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\n <Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\n <Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n</Types>\n";
    let rels = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n <Relationship Target=\"/3D/3dmodel.model\" Id=\"rel-1\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\n</Relationships>\n";

    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let files: [(&str, &str); 6] = [
        ("[Content_Types].xml", content_types),
        ("_rels/.rels", rels),
        ("3D/3dmodel.model", &model),
        ("Metadata/Slic3r_PE.config", &config),
        ("Metadata/Slic3r_PE_model.config", &objects),
        ("Metadata/Prusa_Slicer_layer_config_ranges.xml", &ranges),
    ];
    for (path, body) in files {
        zip.start_file(path, options)
            .and_then(|()| zip.write_all(body.as_bytes()).map_err(Into::into))
            .map_err(|e| format!("cannot write the 3MF: {e}"))?;
    }
    let cursor = zip
        .finish()
        .map_err(|e| format!("cannot write the 3MF: {e}"))?;
    Ok(cursor.into_inner())
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stl_binary_and_ascii_read_the_same_mesh() {
        let ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n";
        let a = read_stl(ascii.as_bytes()).expect("ascii");
        assert_eq!((a.vertices.len(), a.triangles.len()), (4, 2));
        let mut bin = vec![0u8; 80];
        bin.extend_from_slice(&2u32.to_le_bytes());
        for tri in [
            [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]],
            [[1., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
        ] {
            bin.extend_from_slice(&[0u8; 12]);
            for v in tri {
                for c in v {
                    bin.extend_from_slice(&c.to_le_bytes());
                }
            }
            bin.extend_from_slice(&[0u8; 2]);
        }
        assert_eq!(read_stl(&bin).expect("binary"), a);
        assert!(read_stl(b"solid nothing\nendsolid\n").is_err());
        assert!(read_stl(b"solid x\nvertex 1 2\n").is_err());
    }
}
