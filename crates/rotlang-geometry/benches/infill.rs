//! Infill benchmarks (divan): `cargo bench --bench infill`.
//!
//! One layer of each pattern at 20% with a 0.4 mm nozzle on a 20 mm square, a 10 mm-radius
//! circle (64-gon), a 40 mm square with a 10 mm-radius hole, a star (radii 10 and 4.5)
//! and a 20 mm L (consts 0 to 4), inset included (`layer`)
//! and on a region inset once (`fill`); and whole objects: 100 layers of the holed square
//! under a rotating template. Target: 10× faster than Polyslice (JavaScript) per layer:
//! grid 0.029 ms and gyroid 0.48 ms on the square, 2.4–8 ms on shapes with a hole.

use divan::{Bencher, black_box};
use rotlang::eval::{Model, Options};
use rotlang_geometry::infill::{
    self, MultiPolygon, Params, Pattern, Region, Schedule, Settings, shapes,
};

fn main() {
    divan::main();
}

const PATTERNS: [Pattern; Pattern::ALL.len()] = Pattern::ALL;
const W: f64 = 0.4;

fn shape(name: &str) -> MultiPolygon<f64> {
    match name {
        "square20" => shapes::square(20.0),
        "circle10" => shapes::circle(10.0),
        "star10" => shapes::star(10.0, 4.5),
        "l20" => shapes::l_shape(20.0),
        _ => shapes::holed_square(40.0, 10.0),
    }
}

const SHAPES: [&str; 5] = ["square20", "circle10", "holed40", "star10", "l20"];

/// A whole layer: inset the region by half a nozzle, fill it, order the paths.
#[divan::bench(consts = [0, 1, 2, 3, 4], args = PATTERNS, max_time = 0.3)]
fn layer<const S: usize>(bencher: Bencher, pattern: Pattern) {
    let region = shape(SHAPES[S]);
    let params = Params::new(pattern, 0.2, W).angle(30.0).z(5.1);
    bencher.bench(|| infill::fill(black_box(&region), &params).map(|p| p.polylines.len()));
}

/// The pairs of `benches/polyslice/compare.mjs`: a whole layer of each of Polyslice's
/// patterns at 10, 20 and 40%, angle 45° (its grid's), at layer 40's height (z 8.1).
#[divan::bench(consts = [0, 1, 2, 3, 4], args = COMPARED, max_time = 0.2)]
fn compare<const S: usize>(bencher: Bencher, case: &str) {
    let (pattern, density) = case.split_once(' ').expect("pattern density");
    let pattern: Pattern = pattern.parse().expect("pattern");
    let density: f64 = density.parse::<f64>().expect("density") / 100.0;
    let region = shape(SHAPES[S]);
    let params = Params::new(pattern, density, W).angle(45.0).z(8.1);
    bencher.bench(|| infill::fill(black_box(&region), &params).map(|p| p.polylines.len()));
}

const COMPARED: [&str; 21] = [
    "grid 10",
    "grid 20",
    "grid 40",
    "triangles 10",
    "triangles 20",
    "triangles 40",
    "hexagons 10",
    "hexagons 20",
    "hexagons 40",
    "concentric 10",
    "concentric 20",
    "concentric 40",
    "gyroid 10",
    "gyroid 20",
    "gyroid 40",
    "spiral 10",
    "spiral 20",
    "spiral 40",
    "lightning 10",
    "lightning 20",
    "lightning 40",
];

/// Filling a region that was inset once (a slicer reusing a layer's region).
#[divan::bench(consts = [0, 1, 2, 3, 4], args = PATTERNS, max_time = 0.3)]
fn fill<const S: usize>(bencher: Bencher, pattern: Pattern) {
    let region = Region::new(&shape(SHAPES[S]), W).expect("region");
    let params = Params::new(pattern, 0.2, W).angle(30.0).z(5.1);
    bencher.bench(|| black_box(&region).fill(&params).map(|p| p.polylines.len()));
}

/// The template of `object_100_layers`: bottom shells monotonic, then turns (a test in
/// tests/pictures.rs parses every bench template: an error would make the bench measure
/// whatever instructions were left).
pub const OBJECT_TEMPLATE: &str = "0MB, +15, +30/5";

/// 100 layers of the holed square under a rotating template (bottom shells monotonic).
#[divan::bench(args = PATTERNS, max_time = 2)]
fn object_100_layers(bencher: Bencher, pattern: Pattern) {
    let template = rotlang::parse(OBJECT_TEMPLATE, rotlang::Target::Sparse).template;
    let model = Model::cube20();
    let region = shape("holed40");
    let settings = Settings {
        pattern,
        ..Settings::default()
    };
    bencher.bench(|| {
        let prepared = Region::new(&region, W).expect("region");
        let mut schedule = Schedule::new(&template, &model, Options::default(), settings);
        (0..100)
            .map(|i| {
                schedule
                    .layer(i, &prepared)
                    .map_or(0, |l| l.map_or(0, |l| l.paths.polylines.len()))
            })
            .sum::<usize>()
    });
}
