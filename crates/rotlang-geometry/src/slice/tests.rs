use super::*;
use crate::mesh::shapes;
use geo::Area;
use std::f64::consts::PI;

fn area_of(s: &Section) -> f64 {
    s.region.unsigned_area()
}

#[test]
fn a_cube_gives_its_square_on_every_layer() {
    let cube = shapes::cuboid([20.0, 10.0, 20.0]);
    let mut slicer = Slicer::new(&cube);
    for i in 0..100 {
        let s = slicer.section(0.1 + 0.2 * i as f64);
        assert_eq!(s.region.0.len(), 1, "layer {i}");
        assert!(
            (area_of(&s) - 200.0).abs() < 1e-9,
            "layer {i}: {}",
            area_of(&s)
        );
        assert_eq!((s.open, s.bridged), (0, 0));
    }
    // Above and below: nothing.
    assert!(slicer.section(20.5).region.0.is_empty());
}

#[test]
fn a_tube_has_its_hole_and_a_torus_its_rings() {
    let tube = shapes::tube(10.0, 5.0, 20.0, 96);
    let s = Slicer::new(&tube).section(7.3);
    assert_eq!(s.region.0.len(), 1);
    assert_eq!(s.region.0[0].interiors().len(), 1);
    let ring = PI * (100.0 - 25.0);
    assert!((area_of(&s) / ring - 1.0).abs() < 0.01, "{}", area_of(&s));
    // A torus (major 10, minor 3) cut through its middle: one ring with a hole; near
    // its top, a thinner ring.
    let torus = shapes::torus(10.0, 3.0, 96, 48);
    let mut slicer = Slicer::new(&torus);
    let middle = slicer.section(3.0 + 1e-3);
    assert_eq!(middle.region.0.len(), 1);
    assert_eq!(middle.region.0[0].interiors().len(), 1);
    let expected = PI * (13.0f64.powi(2) - 7.0f64.powi(2));
    assert!(
        (area_of(&middle) / expected - 1.0).abs() < 0.02,
        "{}",
        area_of(&middle)
    );
    let high = slicer.section(5.5);
    assert!(area_of(&high) < 0.7 * area_of(&middle));
}

#[test]
fn an_overhang_widens_the_section_above_it() {
    let t = shapes::overhang(10.0, 30.0, 10.0, 4.0);
    let mut slicer = Slicer::new(&t);
    let (low, high) = (slicer.section(5.1), slicer.section(12.1));
    assert!((area_of(&low) - 100.0).abs() < 1e-6);
    assert!((area_of(&high) - 300.0).abs() < 1e-6);
}

#[test]
fn a_hole_in_the_surface_is_reported_tiny_gaps_are_closed() {
    // A cube without one of its side triangles: the sections across it are open.
    let mut cube = shapes::cuboid([10.0, 10.0, 10.0]);
    cube.triangles.remove(6);
    let s = Slicer::new(&cube).section(5.1);
    assert!(s.open >= 1 || s.bridged >= 1, "{s:?}");
    // Every side triangle present, but one side's vertices moved by 0.01 mm (an exporter's
    // rounding): its edges are no longer shared, the gaps are bridged.
    let mut cube = shapes::cuboid([10.0, 10.0, 10.0]);
    let moved = cube.vertices.len() as u32;
    cube.vertices.push([10.0, 0.0, -0.0]);
    cube.vertices.push([10.0, 10.0, 0.01]);
    cube.vertices.push([10.0, 0.01, 10.0]);
    cube.triangles[6] = [moved, moved + 1, 6];
    cube.triangles[7] = [moved, 6, moved + 2];
    let s = Slicer::new(&cube).section(5.1);
    assert_eq!((s.open, s.region.0.len()), (0, 1), "{s:?}");
    assert!(s.bridged >= 1);
    assert!((area_of(&s) - 100.0).abs() < 0.5);
}

#[test]
fn heights_may_go_down_again() {
    let cube = shapes::cuboid([10.0, 10.0, 10.0]);
    let mut slicer = Slicer::new(&cube);
    let a = slicer.section(8.0);
    let b = slicer.section(2.0);
    assert_eq!(area_of(&a), area_of(&b));
}

/// A vase built by `shapes::vase` (a lathe profile: foot, belly, waist, flared lip,
/// hollow above a 3 mm floor): discs below the floor, rings above, every section closed,
/// the ring's area what the profile says.
#[test]
fn a_vase_gives_discs_then_rings() {
    let vase = shapes::vase(128);
    let mut slicer = Slicer::new(&vase);
    for i in 0..400 {
        let z = 0.1 + 0.2 * i as f64;
        let s = slicer.section(z);
        assert_eq!((s.open, s.bridged), (0, 0), "z {z}");
        assert_eq!(s.region.0.len(), 1, "z {z}");
        let holes = s.region.0[0].interiors().len();
        assert_eq!(holes, usize::from(z > 3.0), "z {z}");
    }
    // The belly (z 27) is wider than the waist (z 65); the plane crosses each quad's two
    // triangles, and the vertex between them (on the quad's diagonal, in line) is dropped.
    let (belly, waist) = (slicer.section(27.1), slicer.section(65.1));
    assert!(area_of(&belly) > 1.5 * area_of(&waist));
    assert_eq!(belly.region.0[0].exterior().0.len(), 129);
}

/// A fine cylinder (25,000 sides, r = 40): every vertex is within a micrometre of the line
/// through its neighbours, yet dropped vertices must stay within the tolerance of the edge
/// that replaces them, so the section stays on the circle (dropping them one by one
/// against a growing chord once gave a 33-gon up to 0.19 mm inside it).
#[test]
fn a_fine_circle_keeps_its_shape_within_the_tolerance() {
    let (r, n) = (40.0, 25_000);
    let cylinder = shapes::tube(r, 0.0, 2.0, n);
    let s = Slicer::new(&cylinder).section(1.0);
    assert_eq!(s.region.0.len(), 1);
    let ring = &s.region.0[0].exterior().0;
    let sag = r * (1.0 - (PI / n as f64).cos());
    let mut worst: f64 = 0.0;
    for w in ring.windows(2) {
        for k in 0..=16 {
            let t = k as f64 / 16.0;
            let p = w[0] + (w[1] - w[0]) * t;
            worst = worst.max((p.x.hypot(p.y) - r).abs());
        }
    }
    assert!(
        worst <= TOLERANCE + sag + 1e-9,
        "{} points, up to {worst} mm off the circle",
        ring.len()
    );
    // Still far fewer points than the mesh has sides.
    assert!(ring.len() < n / 10, "{}", ring.len());
}
