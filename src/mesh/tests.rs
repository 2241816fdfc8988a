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
