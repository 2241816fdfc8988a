//! Hashes the toolpaths and travels of every pattern at several densities, angles and
//! on the comparison's shapes, bit for bit, to check that a speed change kept the paths:
//! `cargo run --release -p rotlang-geometry --example hash_fill` before and after. Now
//! `all 6a1eb91350c9c5b4` (since concentric's middle ring at half steps; before it
//! `030ae57d1e1477a3`).
use rotlang_geometry::infill::{self, Params, Pattern, shapes};
use std::hash::{DefaultHasher, Hash, Hasher};

fn main() {
    let shapes = [
        ("square20", shapes::square(20.0)),
        ("circle10", shapes::circle(10.0)),
        ("holed40", shapes::holed_square(40.0, 10.0)),
        ("star10", shapes::star(10.0, 4.5)),
        ("l20", shapes::l_shape(20.0)),
    ];
    let mut all = DefaultHasher::new();
    for (name, region) in &shapes {
        for pattern in Pattern::ALL {
            for density in [5.0, 10.0, 20.0, 40.0, 80.0] {
                for angle in [45.0, 30.0, 0.0] {
                    let params = Params::new(pattern, density / 100.0, 0.4)
                        .angle(angle)
                        .z(8.1);
                    let mut h = DefaultHasher::new();
                    match infill::fill(region, &params) {
                        Ok(t) => {
                            for set in [&t.polylines, &t.travels] {
                                set.len().hash(&mut h);
                                for l in set {
                                    l.0.len().hash(&mut h);
                                    for c in &l.0 {
                                        c.x.to_bits().hash(&mut h);
                                        c.y.to_bits().hash(&mut h);
                                    }
                                }
                            }
                            t.length.to_bits().hash(&mut h);
                            t.travel.to_bits().hash(&mut h);
                        }
                        Err(e) => e.to_string().hash(&mut h),
                    }
                    let v = h.finish();
                    v.hash(&mut all);
                    println!("{name} {pattern} {density} {angle} {v:016x}");
                }
            }
        }
    }
    println!("all {:016x}", all.finish());
}
