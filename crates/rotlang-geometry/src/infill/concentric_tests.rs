//! The quicker concentric loops (`concentric.rs`, `loops::Eroder`) against the code they
//! replaced (`concentric_reference.rs`): the same polylines to the bit, on the comparison's
//! shapes and on random ones.

use geo::{Coord, LineString, MultiPolygon, Polygon};
use proptest::prelude::*;

use super::concentric::concentric;
use super::concentric_reference;
use crate::infill::loops::Eroder;
use crate::infill::{Region, shapes};
use crate::math;

const W: f64 = 0.4;

fn loops(
    shape: &MultiPolygon<f64>,
    density: f64,
    theta: f64,
) -> (Vec<Vec<Coord>>, Vec<Vec<Coord>>) {
    let region = Region::new(shape, W).expect("region");
    let (mut fast, mut slow) = (Vec::new(), Vec::new());
    concentric(&region, theta, W / density, &mut fast);
    concentric_reference::concentric(&region, theta, W / density, &mut slow);
    (fast, slow)
}

fn named_shapes() -> Vec<(&'static str, MultiPolygon<f64>)> {
    let mut named = vec![
        ("square", shapes::square(20.0)),
        ("circle", shapes::circle(10.0)),
    ];
    named.extend(crate::infill::tests::ring_shapes());
    named
}

/// Every shape of the Polyslice comparison (at its 10, 20 and 40% and its 45°) and a few
/// with more rings, at densities from 5 to 60% and three seam directions: the loops (and
/// the middle stretches, and the stretches given way) are exactly the former ones.
#[test]
fn concentric_gives_the_former_loops() {
    for (name, shape) in named_shapes() {
        for density in [0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6] {
            // 45°: the Polyslice comparison's direction (its quality numbers hold as they are).
            for theta in [0.0, 45f64.to_radians(), 2.0] {
                let (fast, slow) = loops(&shape, density, theta);
                assert!(!fast.is_empty(), "{name} at {density}: no loop");
                assert_eq!(fast, slow, "{name} at {density}, θ {theta}");
            }
        }
    }
}

/// One `Eroder` asked for many distances, in any order, gives each time the rings a fresh
/// erosion gives (its reused buffers carry nothing over).
#[test]
fn a_reused_eroder_gives_the_rings_of_a_fresh_one() {
    for (name, shape) in named_shapes() {
        let mut eroder = Eroder::new(&shape, 0.5);
        for d in [6.3, 0.2, 2.0, 12.0, 1.0, 5.2, 3.0, 9.0, 0.2, 4.0] {
            assert_eq!(
                eroder.rings(d),
                concentric_reference::eroded_rings(&shape, d, 0.5),
                "{name} by {d}"
            );
        }
    }
}

/// A ring of `n` points at the given radii (each between 0.3 and 1 of `size`) about the
/// origin: star-like, concave where the radii dip.
fn ring(radii: &[f64], size: f64, at: Coord) -> LineString<f64> {
    let n = radii.len();
    let mut pts: Vec<Coord> = radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            Coord {
                x: at.x + r * size * math::cos(a),
                y: at.y + r * size * math::sin(a),
            }
        })
        .collect();
    pts.push(pts[0]);
    LineString::new(pts)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Random star-like outlines and regular polygons (convex: their loops cross nothing
    /// until the hole's meet the outline's), some with a hole off the centre: the same
    /// loops as the former code.
    #[test]
    fn concentric_gives_the_former_loops_on_random_shapes(
        radii in prop::collection::vec(0.3f64..1.0, 3..24),
        regular in any::<bool>(),
        size in 4.0f64..25.0,
        hole in prop::option::of((0.05f64..0.25, -0.1f64..0.1, -0.1f64..0.1)),
        density in 0.05f64..0.6,
        theta in 0.0f64..6.3,
    ) {
        let holes = hole
            .map(|(r, x, y)| {
                let circle = (0..24).map(|_| 1.0).collect::<Vec<_>>();
                vec![ring(&circle, r * size, Coord { x: x * size, y: y * size })]
            })
            .unwrap_or_default();
        let radii = if regular { vec![1.0; radii.len()] } else { radii };
        let shape = MultiPolygon::new(vec![Polygon::new(
            ring(&radii, size, Coord { x: 0.0, y: 0.0 }),
            holes,
        )]);
        let (fast, slow) = loops(&shape, density, theta);
        prop_assert_eq!(fast, slow);
    }
}
