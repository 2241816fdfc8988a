use super::*;

#[test]
fn binary_and_ascii_stl_read_the_same_mesh_with_shared_vertices() {
    let cube = shapes::cuboid([10.0, 20.0, 5.0]);
    let binary = Mesh::from_stl(&cube.to_binary_stl()).unwrap();
    assert_eq!((binary.vertices.len(), binary.triangles.len()), (8, 12));
    let mut ascii = String::from("solid cube\n");
    for t in &cube.triangles {
        ascii.push_str(" facet normal 0 0 0\n  outer loop\n");
        for &i in t {
            let v = cube.vertices[i as usize];
            ascii.push_str(&format!("   vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        ascii.push_str("  endloop\n endfacet\n");
    }
    ascii.push_str("endsolid cube\n");
    let read = Mesh::from_stl(ascii.as_bytes()).unwrap();
    assert_eq!(read, binary);
    assert_eq!(read.bounds(), Some(([0.0, 0.0, 0.0], [10.0, 20.0, 5.0])));
}

#[test]
fn obj_faces_are_fanned_and_negative_indices_count_back() {
    let text = "# a square pyramid\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 2 2 3\n\
                f 1/1 4/4 3/3 2/2\nf 1 2 5\nf 2 3 5\nf -2 -3 -1\nf 4 1 5\n";
    let m = Mesh::read("pyramid.obj", text.as_bytes()).unwrap();
    assert_eq!((m.vertices.len(), m.triangles.len()), (5, 6));
}

#[test]
fn bad_files_are_errors_with_a_position() {
    for (name, bytes, says) in [
        ("a.stl", &b"\xff\xfe not a mesh"[..], "not an STL"),
        ("a.stl", b"solid x\nvertex 1 2\n", "line 2"),
        ("a.stl", b"hello", "no `solid`"),
        ("a.obj", b"v 0 0 0\nf 1 2 3\n", "line 2"),
        ("a.obj", b"v 0 0 nan\n", "not finite"),
    ] {
        let e = Mesh::read(name, bytes).unwrap_err();
        assert!(e.0.contains(says), "{name}: {e}");
    }
    // A binary STL whose count says more than it holds is read as text, and refused.
    let mut lying = vec![0u8; 84];
    lying[80] = 200;
    assert!(Mesh::from_stl(&lying).is_err());
}

/// A 3MF as OrcaSlicer writes one: the build item points at an object whose component
/// lives in 3D/Objects/object_1.model; the item's transform moves it.
#[cfg(feature = "3mf")]
#[test]
fn a_3mf_project_gives_its_placed_objects() {
    use std::io::Write;
    let cube = shapes::cuboid([10.0, 10.0, 10.0]);
    let mut mesh = String::from(
        r#"<?xml version="1.0"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" type="model"><mesh><vertices>"#,
    );
    for v in &cube.vertices {
        mesh.push_str(&format!(
            r#"<vertex x="{}" y="{}" z="{}"/>"#,
            v[0], v[1], v[2]
        ));
    }
    mesh.push_str("</vertices><triangles>");
    for t in &cube.triangles {
        mesh.push_str(&format!(
            r#"<triangle v1="{}" v2="{}" v3="{}"/>"#,
            t[0], t[1], t[2]
        ));
    }
    mesh.push_str("</triangles></mesh></object></resources></model>");
    let root = r#"<?xml version="1.0"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06"><resources><object id="2" name="Cube" type="model"><components><component p:path="/3D/Objects/object_1.model" objectid="1" transform="1 0 0 0 1 0 0 0 1 0 0 0"/></components></object></resources><build><item objectid="2" transform="1 0 0 0 1 0 0 0 1 100 50 0"/></build></model>"#;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default();
    zip.start_file("3D/3dmodel.model", options).unwrap();
    zip.write_all(root.as_bytes()).unwrap();
    zip.start_file("3D/Objects/object_1.model", options)
        .unwrap();
    zip.write_all(mesh.as_bytes()).unwrap();
    let bytes = zip.finish().unwrap().into_inner();
    let objects = read_3mf(&bytes).unwrap();
    assert_eq!(objects.len(), 1);
    let (name, m) = &objects[0];
    assert_eq!(name, "Cube");
    assert_eq!(m.triangles.len(), 12);
    assert_eq!(m.bounds(), Some(([100.0, 50.0, 0.0], [110.0, 60.0, 10.0])));
    assert!(read_3mf(b"not a zip").is_err());
}
