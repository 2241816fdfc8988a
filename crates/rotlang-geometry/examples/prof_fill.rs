//! One layer filled `n` times, for profiling by instruction counts (the build machine is
//! shared: wall time is noisy): `CARGO_PROFILE_RELEASE_DEBUG=true cargo build --release -p
//! rotlang-geometry --example prof_fill`, then `valgrind --tool=callgrind
//! target/release/examples/prof_fill star10 grid 10 1000` (÷ 1000: per layer). Shapes:
//! star10, l20, square20, circle10, else the holed square; the pattern's name; the density in percent.
use rotlang_geometry::infill::{self, Params, Pattern, shapes};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let region = match a[1].as_str() {
        "star10" => shapes::star(10.0, 4.5),
        "l20" => shapes::l_shape(20.0),
        "square20" => shapes::square(20.0),
        "circle10" => shapes::circle(10.0),
        _ => shapes::holed_square(40.0, 10.0),
    };
    let pattern: Pattern = a[2].parse().unwrap();
    let density: f64 = a[3].parse::<f64>().unwrap() / 100.0;
    let n: usize = a[4].parse().unwrap();
    let params = Params::new(pattern, density, 0.4).angle(45.0).z(8.1);
    let mut t = 0;
    for _ in 0..n {
        t += infill::fill(std::hint::black_box(&region), &params)
            .map(|p| p.polylines.len())
            .unwrap_or(0);
    }
    println!("{t}");
}
