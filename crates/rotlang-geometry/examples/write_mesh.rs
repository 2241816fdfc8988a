//! Writes one of the benchmark meshes as binary STL, so that other programs (Polyslice, in
//! `benches/polyslice/compare-mesh.mjs`) slice exactly the mesh that `benches/slice.rs` does.
//!
//! ```sh
//! cargo run --release -p rotlang-geometry --example write_mesh -- torus out/torus.stl
//! cargo run --release -p rotlang-geometry --example write_mesh -- vase out/vase.stl
//! ```
//!
//! `torus`: `shapes::torus(30, 10, 500, 100)`, 100,000 triangles, 20 mm tall (the mesh of
//! `benches/slice.rs`); `vase`: `shapes::vase(384)`, a lathe part (foot, belly, waist, flared
//! lip, 80 mm tall, hollow above a 3 mm floor).

use rotlang_geometry::mesh::{Mesh, shapes};
use std::process::ExitCode;

fn mesh(name: &str) -> Option<Mesh> {
    match name {
        "torus" => Some(shapes::torus(30.0, 10.0, 500, 100)),
        "vase" => Some(shapes::vase(384)),
        _ => None,
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [name, path] = args.as_slice() else {
        eprintln!("usage: write_mesh torus|vase FILE.stl");
        return ExitCode::from(2);
    };
    let Some(mesh) = mesh(name) else {
        eprintln!("write_mesh: no mesh named `{name}` (torus, vase)");
        return ExitCode::from(2);
    };
    if let Err(e) = std::fs::write(path, mesh.to_binary_stl()) {
        eprintln!("write_mesh: cannot write {path}: {e}");
        return ExitCode::FAILURE;
    }
    eprintln!("{name}: {} triangles -> {path}", mesh.triangles.len());
    ExitCode::SUCCESS
}
