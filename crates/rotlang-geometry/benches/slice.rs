//! Slicing benchmarks (divan): `cargo bench --bench slice`.
//!
//! A 100,000-triangle torus (major radius 30 mm, minor 10 mm: 20 mm tall) cut into 500
//! layers (0.04 mm), sections only (`sections_500`) and sections filled with 20% lines
//! inside two walls under a turning template, top and bottom surfaces solid (`part_500`;
//! without them, `part_500_without_shells`), on one thread.
//! Target: seconds on 2 cores, and ≥ 10× Polyslice's slicing of the same mesh:
//! `polyslice/MESH.md` compares them (`examples/write_mesh.rs` writes this torus as STL;
//! `polyslice/compare-mesh.mjs` reads this bench's divan output).

use divan::{Bencher, black_box};
use rotlang::eval::Options;
use rotlang_geometry::infill::Settings;
use rotlang_geometry::mesh::{Mesh, shapes};
use rotlang_geometry::slice::{Part, PartOptions, Slicer, part::model_for};

fn main() {
    divan::main();
}

fn torus() -> Mesh {
    // 500 × 100 quads, two triangles each.
    shapes::torus(30.0, 10.0, 500, 100)
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn sections_500(bencher: Bencher) {
    let mesh = torus();
    assert_eq!(mesh.triangles.len(), 100_000);
    bencher.bench(|| {
        let mut slicer = Slicer::new(black_box(&mesh));
        (0..500)
            .map(|i| slicer.section(0.02 + 0.04 * i as f64).region.0.len())
            .sum::<usize>()
    });
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn part_500(bencher: Bencher) {
    part(bencher, true);
}

/// The same without top and bottom surfaces (no solid areas): what finding them costs.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn part_500_without_shells(bencher: Bencher) {
    part(bencher, false);
}

fn part(bencher: Bencher, shells: bool) {
    let mesh = torus();
    let template = rotlang::parse("0MB, +15, +30/5", rotlang::Target::Sparse).template;
    let model = model_for(&mesh, 0.04, None).expect("model");
    assert_eq!(model.len(), 500);
    bencher.bench(|| {
        Part::new(
            black_box(&mesh),
            &template,
            &model,
            Options::default(),
            Settings::default(),
            PartOptions {
                shells,
                ..PartOptions::default()
            },
        )
        .map(|l| l.map_or(0, |l| l.paths.polylines.len()))
        .sum::<usize>()
    });
}
