//! Geometric properties of every pattern on a square, a circle, an L, a star and a square
//! with a round hole; the schedule's fill kinds; random regions (proptest).

use super::*;
use crate::eval::{Model, Options};
use crate::ir::Fill;
use crate::math;
use geo::Coord;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

const W: f64 = 0.4;

/// The test shapes at unit scale (about 20 mm across).
fn shapes() -> Vec<(&'static str, MultiPolygon<f64>)> {
    vec![
        ("square", shapes::square(20.0)),
        ("circle", shapes::circle(10.0)),
        ("L", shapes::l_shape(20.0)),
        ("star", shapes::star(10.0, 4.5)),
        ("holed square", shapes::holed_square(20.0, 5.0)),
    ]
}

fn scaled(region: &MultiPolygon<f64>, k: f64) -> MultiPolygon<f64> {
    use geo::MapCoords;
    region.map_coords(|c| c * k)
}

/// The width of one repeat of the pattern (mm).
fn cell(pattern: Pattern, rho: f64) -> f64 {
    match pattern {
        Pattern::Lines | Pattern::Concentric | Pattern::Spiral => W / rho,
        Pattern::Grid => 2.0 * W / rho,
        Pattern::Triangles => 3.0 * W / rho,
        Pattern::Hexagons => 2.0 * W / rho,
        Pattern::Gyroid => TAU * W * GYROID_LAMBDA / rho,
        Pattern::Lightning => 5.0 * W / rho,
        Pattern::Cubic => 3.0 * W / rho,
    }
}

fn rings_of(region: &MultiPolygon<f64>) -> Vec<Vec<Coord>> {
    region
        .0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|r| r.0.clone())
        .collect()
}

fn inside(rings: &[Vec<Coord>], p: Coord) -> bool {
    let mut inside = false;
    for r in rings {
        for w in r.windows(2) {
            let (a, b) = (w[0], w[1]);
            if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
                inside = !inside;
            }
        }
    }
    inside
}

fn distance_to_boundary(rings: &[Vec<Coord>], p: Coord) -> f64 {
    let mut best = f64::INFINITY;
    for r in rings {
        for w in r.windows(2) {
            let (a, b) = (w[0], w[1]);
            let ab = b - a;
            let t = (((p - a).x * ab.x + (p - a).y * ab.y) / (ab.x * ab.x + ab.y * ab.y))
                .clamp(0.0, 1.0);
            let q = a + ab * t;
            best = best.min(math::hypot((p - q).x, (p - q).y));
        }
    }
    best
}

/// Every vertex and points along every segment lie inside the region, outside its holes,
/// at least 0.35 nozzle from its boundary (the inset is half a nozzle; dropping vertices
/// closer than a tenth of a nozzle and the arcs of the offset take a little of it).
fn assert_inside(name: &str, region: &MultiPolygon<f64>, paths: &Toolpaths, w: f64) {
    let rings = rings_of(region);
    for line in &paths.polylines {
        for seg in line.0.windows(2) {
            for k in 0..=2 {
                let p = seg[0] + (seg[1] - seg[0]) * (k as f64 / 2.0);
                assert!(inside(&rings, p), "{name}: {p:?} is outside the region");
                let d = distance_to_boundary(&rings, p);
                assert!(d >= 0.35 * w, "{name}: {p:?} is {d} mm from the boundary");
            }
        }
    }
}

fn assert_segments(name: &str, paths: &Toolpaths, w: f64) {
    for line in &paths.polylines {
        assert!(line.0.len() >= 2, "{name}: a path of one point");
        for seg in line.0.windows(2) {
            let len = math::hypot((seg[1] - seg[0]).x, (seg[1] - seg[0]).y);
            assert!(len >= w / 10.0 - 1e-9, "{name}: a segment of {len} mm");
            assert!(seg[0].x.is_finite() && seg[0].y.is_finite());
        }
    }
}

fn density(region: &Region, paths: &Toolpaths) -> f64 {
    paths.length * W / region.area()
}

#[test]
fn gyroid_lambda_is_the_mean_wall_length() {
    // The wall length per unit area of the unit gyroid's section, averaged over z.
    let lambda = |z: f64| {
        let (mut sz, mut cz) = math::sin_cos(z);
        if sz.abs() > cz.abs() {
            std::mem::swap(&mut sz, &mut cz);
        }
        let n = 720;
        let mut length = 0.0;
        for branch in [1.0, -1.0] {
            let y = |x: f64| {
                let (a, b, c) = (math::sin(x), cz, sz * math::cos(x));
                math::atan2(b, a) + branch * math::acos((-c / math::hypot(a, b)).clamp(-1.0, 1.0))
            };
            for i in 0..n {
                let (x0, x1) = (TAU * i as f64 / n as f64, TAU * (i + 1) as f64 / n as f64);
                let dy = (y(x1) - y(x0) + PI).rem_euclid(TAU) - PI;
                length += math::hypot(x1 - x0, dy);
            }
        }
        length / (TAU * TAU)
    };
    let m = 200;
    let mean = (0..m)
        .map(|k| lambda((k as f64 + 0.5) * PI / 2.0 / m as f64))
        .sum::<f64>()
        / m as f64;
    assert!((mean - GYROID_LAMBDA).abs() < 1e-4, "{mean}");
}

#[test]
fn every_pattern_stays_inside_every_shape() {
    for (name, region) in shapes() {
        for pattern in Pattern::ALL {
            for &rho in &[0.05, 0.3, 1.0] {
                for &angle in &[0.0, 17.0, 233.0] {
                    let prepared = Region::new(&region, W).unwrap();
                    let params = Params::new(pattern, rho, W).angle(angle).z(1.3);
                    let paths = prepared.fill(&params).unwrap();
                    let label = format!("{pattern} on {name} at {rho} and {angle}°");
                    assert!(!paths.polylines.is_empty(), "{label}: nothing");
                    assert_inside(&label, &region, &paths, W);
                    assert_segments(&label, &paths, W);
                    assert_eq!(
                        prepared.fill(&params).unwrap(),
                        paths,
                        "{label}: not deterministic"
                    );
                }
            }
        }
    }
}

/// The density is within 10% of the one asked, from 5% to 80%, on regions at least a
/// dozen pattern repeats across (a shape only one or two lines wide gets one line more or
/// less depending on where the lines fall: that is placement, not the formula). The
/// shapes are scaled up for sparse patterns accordingly.
///
/// Each shape is scaled to span at least 12 repeats of the pattern (`cell`) across its
/// narrowest part: the rule the module documentation states (with fewer, a line more or
/// less across the region is a large share of it: at 4 repeats densities are up to a
/// quarter off). Exceptions: a gyroid
/// layer varies with its height like the surface's section (asserted: each layer within
/// −15%/+30%, the mean over a period of heights within 10%).
#[test]
fn density_is_what_was_asked() {
    let mut failures = Vec::new();
    let mut check = |ok: bool, what: String| {
        if !ok {
            failures.push(what);
        }
    };
    for (name, region) in shapes() {
        for pattern in Pattern::ALL {
            for &rho in &[0.05, 0.1, 0.2, 0.4, 0.8] {
                // A dozen repeats across the narrowest part (the L's arms are half its size).
                let narrow = if name == "L" { 0.5 } else { 1.0 };
                let k = (12.0 * cell(pattern, rho) / 20.0 / narrow).max(1.0);
                let region = scaled(&region, k);
                let prepared = Region::new(&region, W).unwrap();
                let label = format!("{pattern} on {name} ×{k:.1} at {rho}");
                match pattern {
                    Pattern::Lightning => {
                        // The branches are spaced again after a first tree so that the
                        // density printed is the one asked (it was 0.57–0.69 of it on
                        // compact shapes, about all of it on the star).
                        for angle in [0.0, 30.0, 71.0] {
                            let params = Params::new(pattern, rho, W).angle(angle);
                            let d = density(&prepared, &prepared.fill(&params).unwrap());
                            check(
                                (d / rho - 1.0).abs() < 0.1,
                                format!("{label} at {angle}°: {d}"),
                            );
                        }
                    }
                    Pattern::Gyroid => {
                        // Every layer of a whole period of heights (a quarter period
                        // once hid a wrong section on a quarter of all layers).
                        let period = TAU * W * GYROID_LAMBDA / rho;
                        let n = 24;
                        let mut sum = 0.0;
                        for i in 0..n {
                            let z = period * (i as f64 + 0.5) / n as f64;
                            let params = Params::new(pattern, rho, W).z(z).angle(30.0);
                            let d = density(&prepared, &prepared.fill(&params).unwrap());
                            check(
                                d > 0.85 * rho && d < 1.3 * rho,
                                format!("{label} at z {z}: {d}"),
                            );
                            sum += d;
                        }
                        let mean = sum / n as f64;
                        check(
                            (mean / rho - 1.0).abs() < 0.1,
                            format!("{label}: mean {mean}"),
                        );
                    }
                    _ => {
                        // Cubic moves with z: every layer of a whole period (its lines
                        // repeat every spacing·√2 of height); the others do not.
                        let heights: Vec<f64> = if pattern == Pattern::Cubic {
                            let period = 3.0 * W / rho * std::f64::consts::SQRT_2;
                            (0..8).map(|i| period * (i as f64 + 0.5) / 8.0).collect()
                        } else {
                            vec![0.0]
                        };
                        for (angle, z) in [0.0, 30.0, 71.0]
                            .into_iter()
                            .flat_map(|a| heights.iter().map(move |&z| (a, z)))
                        {
                            let params = Params::new(pattern, rho, W).angle(angle).z(z);
                            let d = density(&prepared, &prepared.fill(&params).unwrap());
                            check(
                                (d / rho - 1.0).abs() < 0.1,
                                format!("{label} at {angle}° z {z}: {d}"),
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The angle of a segment's direction, in [0, 180).
fn direction(a: Coord, b: Coord) -> f64 {
    math::atan2(b.y - a.y, b.x - a.x)
        .to_degrees()
        .rem_euclid(180.0)
}

fn same_direction(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(180.0);
    d.min(180.0 - d) < 1e-6
}

#[test]
fn straight_patterns_run_along_the_scheduled_angle() {
    let template = crate::parse("+37", crate::Target::Sparse).template;
    let model = Model::cube20();
    let region = Region::new(&shapes::star(10.0, 4.5), W).unwrap();
    for (pattern, offsets) in [
        (Pattern::Lines, &[0.0][..]),
        (Pattern::Grid, &[0.0, 90.0]),
        (Pattern::Triangles, &[0.0, 60.0, 120.0]),
        (Pattern::Cubic, &[0.0, 60.0, 120.0]),
    ] {
        let settings = Settings {
            pattern,
            ..Settings::default()
        };
        let mut schedule =
            Schedule::new(&template, &model, Options { base: 5.0, seed: 0 }, settings);
        for index in [0, 1, 7, 50] {
            let fill = schedule.layer(index, &region).unwrap().unwrap();
            let theta = 5.0 + 37.0 * (index + 1) as f64;
            assert_eq!(fill.params.angle, theta);
            let mut seen = vec![false; offsets.len()];
            for line in &fill.paths.polylines {
                let d = direction(line.0[0], line.0[1]);
                let family = offsets.iter().position(|o| same_direction(d, theta + o));
                let family = family.unwrap_or_else(|| {
                    panic!("{pattern} layer {index}: a line at {d}°, θ = {theta}")
                });
                seen[family] = true;
            }
            assert!(
                seen.iter().all(|&s| s),
                "{pattern} layer {index}: families {seen:?}"
            );
        }
    }
}

#[test]
fn every_pattern_turns_with_the_angle() {
    let region = Region::new(&shapes::l_shape(20.0), W).unwrap();
    for pattern in Pattern::ALL {
        let a = region
            .fill(&Params::new(pattern, 0.2, W).angle(10.0))
            .unwrap();
        let b = region
            .fill(&Params::new(pattern, 0.2, W).angle(70.0))
            .unwrap();
        assert_ne!(a.polylines, b.polylines, "{pattern} ignores the angle");
    }
    // Concentric: each loop starts at its farthest point in direction θ.
    let square = Region::new(&shapes::square(20.0), W).unwrap();
    let loops = square
        .fill(&Params::new(Pattern::Concentric, 0.2, W).angle(45.0))
        .unwrap();
    for l in &loops.polylines {
        let start = l.0[0];
        assert!(
            start.x > 0.0 && start.y > 0.0 && (start.x - start.y).abs() < 1e-9,
            "{start:?}"
        );
        assert_eq!(l.0.first(), l.0.last(), "loops are closed");
    }
    // Spiral: it starts in direction θ from the centre.
    let spiral = square
        .fill(&Params::new(Pattern::Spiral, 0.2, W).angle(120.0))
        .unwrap();
    // The end nearest the centre is the centre itself; the vertex after it shows the way.
    let (line, at_start) = spiral
        .polylines
        .iter()
        .flat_map(|l| [(l, true), (l, false)])
        .min_by(|(a, sa), (b, sb)| {
            let end = |l: &LineString<f64>, s: bool| if s { l.0[0] } else { l.0[l.0.len() - 1] };
            let (p, q) = (end(a, *sa), end(b, *sb));
            math::hypot(p.x, p.y).total_cmp(&math::hypot(q.x, q.y))
        })
        .unwrap();
    let next = if at_start {
        line.0[1]
    } else {
        line.0[line.0.len() - 2]
    };
    let angle = math::atan2(next.y, next.x).to_degrees();
    assert!(
        (angle - 120.0).abs() < 25.0,
        "the spiral starts at {angle}°"
    );
}

#[test]
fn hexagons_give_the_density_asked_not_two_thirds() {
    // The seed's side of 3w/(√3ρ) would give 2/3 of it.
    let region = Region::new(&shapes::square(60.0), W).unwrap();
    let d = density(
        &region,
        &region
            .fill(&Params::new(Pattern::Hexagons, 0.2, W))
            .unwrap(),
    );
    assert!((d - 0.2).abs() < 0.01, "{d}");
}

#[test]
fn holes_are_excluded_exactly_even_when_concave() {
    // A square with a star-shaped hole: no line may cross the hole's notches, which a
    // bounding-box test would fill.
    let star = shapes::star(8.0, 3.0);
    let mut hole = star.0[0].exterior().clone();
    hole.0.reverse();
    let region = MultiPolygon::new(vec![Polygon::new(
        shapes::square(30.0).0[0].exterior().clone(),
        vec![hole],
    )]);
    let prepared = Region::new(&region, W).unwrap();
    for pattern in Pattern::ALL {
        let paths = prepared
            .fill(&Params::new(pattern, 0.3, W).angle(12.0))
            .unwrap();
        assert_inside(&format!("{pattern} around a star hole"), &region, &paths, W);
        assert!(!paths.polylines.is_empty());
    }
}

#[test]
fn centring_object_or_global() {
    let near = shapes::square(20.0);
    let moved = scaled(&near, 1.0);
    use geo::Translate;
    let moved = moved.translate(3.0, 1.0);
    let fill = |region: &MultiPolygon<f64>, centring| {
        Region::new(region, W)
            .unwrap()
            .fill(&Params::new(Pattern::Lines, 0.2, W).centring(centring))
            .unwrap()
    };
    // Object: the pattern moves with the object.
    let (a, b) = (
        fill(&near, Centring::Object),
        fill(&moved, Centring::Object),
    );
    let shifted: Vec<f64> = a.polylines.iter().map(|l| l.0[0].y + 1.0).collect();
    let mut bys: Vec<f64> = b.polylines.iter().map(|l| l.0[0].y).collect();
    let mut shifted_sorted = shifted.clone();
    shifted_sorted.sort_by(f64::total_cmp);
    bys.sort_by(f64::total_cmp);
    for (x, y) in shifted_sorted.iter().zip(&bys) {
        assert!((x - y).abs() < 1e-9);
    }
    // Global: lines at multiples of the spacing from the origin, wherever the object is.
    let g = fill(&moved, Centring::Global);
    for l in &g.polylines {
        let k = l.0[0].y / 2.0;
        assert!((k - k.round()).abs() < 1e-9, "{}", l.0[0].y);
    }
}

#[test]
fn travel_is_reported_and_short() {
    let region = Region::new(&shapes::holed_square(40.0, 10.0), W).unwrap();
    for pattern in Pattern::ALL {
        let paths = region
            .fill(&Params::new(pattern, 0.2, W).angle(20.0))
            .unwrap();
        let travel: f64 = paths
            .polylines
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0].0[w[0].0.len() - 1], w[1].0[0]);
                math::hypot((b - a).x, (b - a).y)
            })
            .sum();
        // Routed around the hole where a straight move would cross it: never shorter.
        assert!(paths.travel >= travel - 1e-6, "{pattern}");
        let length: f64 = paths
            .polylines
            .iter()
            .flat_map(|l| {
                l.0.windows(2)
                    .map(|s| math::hypot((s[1] - s[0]).x, (s[1] - s[0]).y))
            })
            .sum();
        assert!((length - paths.length).abs() < 1e-6, "{pattern}");
    }
    // Lines on a square go back and forth: about 2 mm of travel between lines 2 mm apart.
    let square = Region::new(&shapes::square(40.0), W).unwrap();
    let lines = square.fill(&Params::new(Pattern::Lines, 0.2, W)).unwrap();
    assert!(
        lines.travel < 2.5 * lines.polylines.len() as f64,
        "{}",
        lines.travel
    );
}

/// The fast inset of convex outlines with convex holes (no geo buffer) covers the same
/// area as geo's buffer, whether the grown holes stay apart, meet each other, or meet the
/// outline (then the boolean difference); a non-convex ring is left to the buffer.
#[test]
fn convex_inset_matches_the_general_buffer() {
    use geo::{Area, Buffer};
    let two_holes = MultiPolygon::new(vec![Polygon::new(
        shapes::square(40.0).0[0].exterior().clone(),
        vec![
            shapes::circle(5.0).0[0]
                .exterior()
                .clone()
                .map_coords_shift(-8.0),
            shapes::circle(5.0).0[0]
                .exterior()
                .clone()
                .map_coords_shift(8.0),
        ],
    )]);
    let cases = [
        ("square", shapes::square(20.0)),
        ("circle", shapes::circle(10.0)),
        ("holed", shapes::holed_square(40.0, 10.0)),
        ("two holes", two_holes),
        ("islands", {
            let mut m = shapes::square(10.0);
            m.0.extend(shapes::circle(3.0).0.into_iter().map(|p| {
                use geo::Translate;
                p.translate(20.0, 0.0)
            }));
            m
        }),
    ];
    for (name, region) in &cases {
        for d in [0.2, 1.0, 2.9, 3.5, 6.0, 9.0] {
            let fast = region::convex_inset(region, d, 0.05).expect("all rings convex");
            let slow = region.buffer(-d);
            let (a, b) = (fast.unsigned_area(), slow.unsigned_area());
            assert!(
                (a - b).abs() <= 0.005 * b.max(1.0),
                "{name} inset by {d}: {a} here, {b} by geo's buffer"
            );
        }
    }
    assert!(region::convex_inset(&shapes::star(10.0, 4.5), 0.2, 0.2).is_none());
    assert!(region::convex_inset(&shapes::l_shape(20.0), 0.2, 0.2).is_none());
}

trait Shift {
    fn map_coords_shift(self, dx: f64) -> Self;
}

impl Shift for LineString<f64> {
    fn map_coords_shift(self, dx: f64) -> Self {
        use geo::MapCoords;
        self.map_coords(|c| Coord {
            x: c.x + dx,
            y: c.y,
        })
    }
}

/// Two lines are ordered too: the second is reversed so that it starts where the first
/// ended (an early return for `n <= 2` left them both left to right, 19.7 mm of travel).
#[test]
fn two_paths_are_ordered_with_reversal() {
    let rect = MultiPolygon::new(vec![Polygon::new(
        LineString::from(vec![
            (0.0, 0.0),
            (20.0, 0.0),
            (20.0, 5.0),
            (0.0, 5.0),
            (0.0, 0.0),
        ]),
        vec![],
    )]);
    let paths = super::fill(
        &rect,
        &Params::new(Pattern::Lines, 0.2, W).centring(Centring::Global),
    )
    .unwrap();
    assert_eq!(paths.polylines.len(), 2);
    let (a, b) = (&paths.polylines[0].0, &paths.polylines[1].0);
    assert!(
        (a[0].x < a[a.len() - 1].x) != (b[0].x < b[b.len() - 1].x),
        "both lines run the same way: {a:?} {b:?}"
    );
    assert!(paths.travel < 2.5, "travel {}", paths.travel);
}

#[test]
fn solid_signs_use_their_fill_kind() {
    let settings = Settings {
        pattern: Pattern::Gyroid,
        density: 0.15,
        solid_pattern: Pattern::Grid,
        ..Settings::default()
    };
    for (fill, pattern, density, order) in [
        (Fill::Sparse, Pattern::Gyroid, 0.15, Order::Nearest),
        (Fill::Dense, Pattern::Gyroid, 1.0, Order::Nearest),
        (Fill::Solid, Pattern::Grid, 1.0, Order::Nearest),
        (Fill::Concentric, Pattern::Concentric, 1.0, Order::Nearest),
        (Fill::Monotonic, Pattern::Lines, 1.0, Order::Monotonic),
        (Fill::Rectilinear, Pattern::Lines, 1.0, Order::Nearest),
    ] {
        let p = settings.params(fill, 30.0, 1.0);
        assert_eq!(
            (p.pattern, p.density, p.order),
            (pattern, density, order),
            "{fill:?}"
        );
    }
    // Through a template: `M` layers are monotonic lines, all the same way, in order.
    let template = crate::parse("30M, 60", crate::Target::Sparse).template;
    let model = Model::cube20();
    let mut schedule = Schedule::new(&template, &model, Options::default(), settings);
    let region = Region::new(&shapes::circle(10.0), W).unwrap();
    let m = schedule.layer(0, &region).unwrap().unwrap();
    assert_eq!(m.layer.fill, Fill::Monotonic);
    let frame = clip::Frame::new(region.centre(), 30f64.to_radians());
    let mut last_y = f64::NEG_INFINITY;
    for l in &m.paths.polylines {
        let (a, b) = (frame.to_local(l.0[0]), frame.to_local(l.0[1]));
        assert!(b.x > a.x && a.y >= last_y - 1e-9);
        last_y = a.y;
    }
    let d = density(&region, &m.paths);
    assert!((d - 1.0).abs() < 0.1, "{d}");
    let sparse = schedule.layer(1, &region).unwrap().unwrap();
    assert_eq!(
        (sparse.params.pattern, sparse.params.angle),
        (Pattern::Gyroid, 60.0)
    );
    assert!(schedule.layer(100, &region).unwrap().is_none());
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let square = shapes::square(20.0);
    for params in [
        Params::new(Pattern::Grid, 0.0, W),
        Params::new(Pattern::Grid, 1.5, W),
        Params::new(Pattern::Grid, f64::NAN, W),
        Params::new(Pattern::Grid, 0.2, W).angle(f64::INFINITY),
        Params::new(Pattern::Grid, 0.2, W).z(f64::NAN),
    ] {
        assert!(fill(&square, &params).is_err(), "{params:?}");
    }
    assert!(matches!(Region::new(&square, 0.0), Err(Error::Nozzle(_))));
    assert!(matches!(
        Region::new(&scaled(&square, 1e6), W),
        Err(Error::Coordinate(_))
    ));
    let nan = scaled(&square, f64::NAN);
    assert!(Region::new(&nan, W).is_err());
    // A kilometre square at 100% with a 0.01 mm nozzle: refused, not attempted.
    let huge = scaled(&square, 5e4);
    assert!(matches!(
        fill(&huge, &Params::new(Pattern::Gyroid, 1.0, 0.01)),
        Err(Error::TooLarge { .. })
    ));
    // Degenerate regions fill with nothing.
    let sliver = shapes::square(0.3);
    assert_eq!(
        fill(&sliver, &Params::new(Pattern::Grid, 0.2, W)).unwrap(),
        Toolpaths::default()
    );
    assert_eq!(
        fill(
            &MultiPolygon::new(vec![]),
            &Params::new(Pattern::Grid, 0.2, W)
        )
        .unwrap(),
        Toolpaths::default()
    );
    assert!(shapes::from_json("[[[0,0],[1,0]]]").is_err());
    assert!(shapes::from_json("{\"type\": \"Point\"}").is_err());
    let region = shapes::from_json(
        r#"{"type": "Polygon", "coordinates": [[[0,0],[10,0],[10,10],[0,10],[0,0]]]}"#,
    )
    .unwrap();
    assert_eq!(region.0.len(), 1);
}

/// A star-shaped polygon around the origin: convex when every radius is equal, concave
/// otherwise.
fn polygon(radii: &[f64], turn: f64) -> MultiPolygon<f64> {
    let n = radii.len();
    let ring: Vec<Coord> = radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = TAU * i as f64 / n as f64 + turn;
            Coord {
                x: r * math::cos(a),
                y: r * math::sin(a),
            }
        })
        .chain(std::iter::once(Coord {
            x: radii[0] * math::cos(turn),
            y: radii[0] * math::sin(turn),
        }))
        .collect();
    MultiPolygon::new(vec![Polygon::new(LineString::new(ring), vec![])])
}

fn pattern_strategy() -> impl Strategy<Value = Pattern> {
    (0..Pattern::ALL.len()).prop_map(|i| Pattern::ALL[i])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn random_regions_and_angles(
        radii in prop::collection::vec(2.0f64..15.0, 3..14),
        convex in any::<bool>(),
        turn in 0.0f64..TAU,
        pattern in pattern_strategy(),
        rho in 0.05f64..1.0,
        angle in -720.0f64..720.0,
        z in 0.0f64..50.0,
        global in any::<bool>(),
    ) {
        let radii: Vec<f64> = if convex { vec![radii[0]; radii.len()] } else { radii };
        let region = polygon(&radii, turn);
        let centring = if global { Centring::Global } else { Centring::Object };
        let params = Params::new(pattern, rho, W).angle(angle).z(z).centring(centring);
        let paths = fill(&region, &params).unwrap();
        let label = format!("{pattern} on {radii:?}");
        assert_inside(&label, &region, &paths, W);
        assert_segments(&label, &paths, W);
        prop_assert!(paths.travel.is_finite() && paths.length.is_finite());
    }
}

/// A radial polygon's ring (as `polygon` makes), moved to `centre`, clockwise if `hole`.
pub(super) fn radial_ring(radii: &[f64], turn: f64, centre: Coord, hole: bool) -> LineString<f64> {
    let mut ring = polygon(radii, turn).0.remove(0).into_inner().0;
    for c in &mut ring.0 {
        *c = *c + centre;
    }
    if hole {
        ring.0.reverse();
    }
    ring
}

/// Where the travel proptests' moves start and end in a region's rings: on an edge, at a
/// vertex, or anywhere in the rings' box.
pub(super) struct MoveEnds {
    pub(super) vertices: Vec<Coord>,
    pub(super) edges: Vec<(Coord, Coord)>,
    lo: Coord,
    hi: Coord,
}

impl MoveEnds {
    pub(super) fn new(rings: &[Vec<Coord>]) -> MoveEnds {
        let vertices: Vec<Coord> = rings.iter().flatten().copied().collect();
        let edges = rings
            .iter()
            .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
            .collect();
        let (lo, hi) = travel::bounds(&vertices);
        MoveEnds {
            vertices,
            edges,
            lo,
            hi,
        }
    }

    /// Kind 0: a point `t` along edge `i` (mod their number); 1: vertex `i`; else the
    /// point of the box at `t` across and `i / 1000` up.
    pub(super) fn point(&self, (i, t): (usize, f64), kind: u8) -> Coord {
        match kind {
            0 => {
                let (a, b) = self.edges[i % self.edges.len()];
                a + (b - a) * t
            }
            1 => self.vertices[i % self.vertices.len()],
            _ => Coord {
                x: self.lo.x + (self.hi.x - self.lo.x) * t,
                y: self.lo.y + (self.hi.y - self.lo.y) * (i as f64 / 1000.0),
            },
        }
    }
}

/// A radial outline of `outer` radii with a radial hole of each of `holes`' radii, the
/// holes' centres `spread` mm out, a third of a turn apart (the proptests' holed regions).
pub(super) fn holed_radial(
    outer: &[f64],
    holes: &[Vec<f64>],
    turn: f64,
    spread: f64,
) -> MultiPolygon<f64> {
    let interiors = holes
        .iter()
        .enumerate()
        .map(|(i, radii)| {
            let a = turn + TAU * i as f64 / 3.0;
            let centre = Coord {
                x: spread * math::cos(a),
                y: spread * math::sin(a),
            };
            radial_ring(radii, turn, centre, true)
        })
        .collect();
    MultiPolygon::new(vec![Polygon::new(
        radial_ring(outer, turn, Coord::zero(), false),
        interiors,
    )])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Regions with holes (concave ones too) and several islands, each island possibly
    /// holed: every path inside its island and outside every hole, no short segment.
    /// The outline's vertices are at least 8 mm out with six or more of them, so it holds
    /// the disc of 6.9 mm in which the holes (within 1.5 mm of points 3.5 mm out) lie apart;
    /// islands are 14 mm apart and at most 6 mm in radius, their holes within 0.9 mm of
    /// their centres (inside their 1.7 mm inner disc).
    #[test]
    fn random_regions_with_holes_and_islands(
        outer in prop::collection::vec(8.0f64..15.0, 6..14),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..8), 0..4),
        islands in prop::collection::vec(
            (prop::collection::vec(2.0f64..6.0, 6..12), any::<bool>()), 2..4),
        hole_radii in prop::collection::vec(0.3f64..0.9, 3..7),
        turn in 0.0f64..TAU,
        pattern in pattern_strategy(),
        rho in 0.05f64..1.0,
        angle in -720.0f64..720.0,
        z in 0.0f64..50.0,
        global in any::<bool>(),
    ) {
        let centring = if global { Centring::Global } else { Centring::Object };
        let params = Params::new(pattern, rho, W).angle(angle).z(z).centring(centring);
        // One outline with up to three holes.
        let holed = holed_radial(&outer, &holes, turn, 3.5);
        // Several islands, some holed.
        let archipelago = MultiPolygon::new(
            islands
                .iter()
                .enumerate()
                .map(|(i, (radii, holed))| {
                    let centre = Coord { x: 14.0 * i as f64, y: 3.0 * i as f64 };
                    let holes = if *holed {
                        vec![radial_ring(&hole_radii, -turn, centre, true)]
                    } else {
                        vec![]
                    };
                    Polygon::new(radial_ring(radii, turn, centre, false), holes)
                })
                .collect(),
        );
        for (name, region) in [("holed", &holed), ("islands", &archipelago)] {
            let paths = fill(region, &params).unwrap();
            let label = format!("{pattern} at {rho} on {name} {region:?}");
            assert_inside(&label, region, &paths, W);
            assert_segments(&label, &paths, W);
            prop_assert!(paths.travel.is_finite() && paths.length.is_finite());
            // Each island gets some infill when it is wide enough for a line.
            if name == "islands" && rho >= 0.2 && pattern != Pattern::Lightning {
                for polygon in &region.0 {
                    let rings = rings_of(&MultiPolygon::new(vec![polygon.clone()]));
                    let on = paths
                        .polylines
                        .iter()
                        .flat_map(|l| l.0.iter())
                        .any(|&p| inside(&rings, p));
                    prop_assert!(on, "{label}: an island without infill");
                }
            }
        }
    }
}

/// Cubic: the section of cubes standing on a corner. Its three families (θ, θ+120°,
/// θ+240°) move `z/√2` along their normals per mm of height, so that the family along θ
/// at height z is the one at height 0 moved by z/√2; at z = 0 they meet in points, as
/// triangles do.
#[test]
fn cubic_families_shift_with_height() {
    let region = Region::new(&shapes::square(40.0), W).unwrap();
    let rho = 0.2;
    let spacing = 3.0 * W / rho;
    for z in [0.0, 0.3, 1.0, 2.5, 7.0] {
        let paths = region
            .fill(&Params::new(Pattern::Cubic, rho, W).angle(0.0).z(z))
            .unwrap();
        // The horizontal family: y ≡ z/√2 (mod spacing); the centre is the origin.
        let mut horizontal = 0;
        for line in &paths.polylines {
            let (a, b) = (line.0[0], line.0[1]);
            if same_direction(direction(a, b), 0.0) {
                horizontal += 1;
                let phase = (a.y - z / std::f64::consts::SQRT_2).rem_euclid(spacing);
                assert!(
                    phase < 1e-6 || spacing - phase < 1e-6,
                    "z {z}: a line at y {}",
                    a.y
                );
            }
        }
        assert!(horizontal >= 5, "z {z}: {horizontal} horizontal lines");
        let d = paths.length * W / region.area();
        assert!((d / rho - 1.0).abs() < 0.1, "z {z}: density {d}");
    }
    // Different heights give different layers; a whole period (spacing·√2) the same one.
    let at = |z: f64| {
        region
            .fill(&Params::new(Pattern::Cubic, rho, W).angle(20.0).z(z))
            .unwrap()
    };
    assert_ne!(at(0.0).polylines, at(1.0).polylines);
    let (a, b) = (at(1.0), at(1.0 + spacing * std::f64::consts::SQRT_2));
    assert!((a.length - b.length).abs() < 1e-6 * a.length);
}

/// The gyroid surface is unchanged by a shift of half a period along x, y and z at once,
/// so a layer half a period higher is the same section, shifted: the same density and
/// about as many paths. Before the phase was made continuous, the layers where
/// `sin z < 0` and `|sin z| > |cos z|` (a quarter of all) were drawn as crossing lines
/// and arcs: three times the paths and 2.3–2.5 times the density.
#[test]
fn gyroid_layers_half_a_period_apart_are_alike() {
    let rho = 0.2;
    let region = Region::new(&shapes::square(40.0), W).unwrap();
    let period = TAU * W * GYROID_LAMBDA / rho;
    for i in 0..32 {
        let z = period / 2.0 * (i as f64 + 0.5) / 32.0;
        let fill = |z: f64| {
            region
                .fill(&Params::new(Pattern::Gyroid, rho, W).z(z).angle(45.0))
                .unwrap()
        };
        let (a, b) = (fill(z), fill(z + period / 2.0));
        let (da, db) = (density(&region, &a), density(&region, &b));
        assert!((da / db - 1.0).abs() < 0.05, "z {z}: {da} against {db}");
        let (na, nb) = (a.polylines.len() as f64, b.polylines.len() as f64);
        assert!(
            (na / nb - 1.0).abs() < 0.35,
            "z {z}: {na} paths against {nb}"
        );
    }
}

/// The raw offset of concave regions (an L, a star, a star with a hole, an L with two
/// holes, islands) covers the same area as geo's buffer wherever it answers, and it
/// answers at a half-nozzle inset of each (the inset once dominated a concave layer's
/// time: 15.7 µs of the star's 17.5 with lines). Where the offset pinches or an edge
/// vanishes, it declines.
#[test]
fn raw_inset_matches_the_general_buffer() {
    use geo::{Area, Buffer, Translate};
    let star_with_hole = MultiPolygon::new(vec![Polygon::new(
        shapes::star(10.0, 4.5).0[0].exterior().clone(),
        vec![shapes::circle(1.5).0[0].exterior().clone()],
    )]);
    let l_with_holes = MultiPolygon::new(vec![Polygon::new(
        shapes::l_shape(20.0).0[0].exterior().clone(),
        vec![
            shapes::circle(2.0).0[0]
                .exterior()
                .clone()
                .map_coords_shift(-5.0),
            shapes::star(2.0, 1.0).0[0]
                .exterior()
                .clone()
                .translate(5.0, -5.0),
        ],
    )]);
    let mut islands = shapes::star(10.0, 4.5);
    islands
        .0
        .extend(shapes::l_shape(10.0).translate(30.0, 0.0).0);
    let cases = [
        ("L", shapes::l_shape(20.0)),
        ("star", shapes::star(10.0, 4.5)),
        ("star with a hole", star_with_hole),
        ("L with holes", l_with_holes),
        ("islands", islands),
    ];
    for (name, region) in &cases {
        assert!(
            offset::raw_inset(region, W / 2.0, 0.2).is_some(),
            "{name}: no raw inset at half a nozzle"
        );
        for d in [0.2, 1.0, 2.0, 3.0, 4.0, 6.0] {
            let slow = region.buffer(-d);
            if let Some(fast) = offset::raw_inset(region, d, 0.05) {
                let (a, b) = (fast.unsigned_area(), slow.unsigned_area());
                assert!(
                    (a - b).abs() <= 0.005 * b.max(1.0),
                    "{name} inset by {d}: {a} here, {b} by geo's buffer"
                );
            }
        }
    }
    // The L's arms pinch off its corner square well before 6 mm; a star's tips vanish.
    assert!(offset::raw_inset(&shapes::star(10.0, 4.5), 4.0, 0.2).is_none());
}

/// Concentric loops where parts pinch off (the star's tips, the L's arms) or a grown hole
/// meets the outline: the raw offset cut at its crossings bounds the same area as geo's
/// buffer, with the same length of boundary, and declines none of these (before, each
/// such loop went through the buffer or the boolean difference, 10–40 µs a loop).
#[test]
fn eroded_rings_match_the_general_buffer() {
    use geo::algorithm::buffer::{BufferStyle, LineJoin};
    use geo::{Area, Buffer};
    let cases = shapes::ring_shapes();
    let length = |rings: &[Vec<Coord>]| -> f64 {
        rings
            .iter()
            .flat_map(|r| r.windows(2))
            .map(|w| math::hypot((w[1] - w[0]).x, (w[1] - w[0]).y))
            .sum()
    };
    for (name, region) in &cases {
        for d in [0.2, 1.0, 2.0, 3.0, 4.0, 5.2, 5.7, 6.3, 7.5, 9.0, 10.3, 12.0] {
            let rings = loops::eroded_rings(region, d, 0.05)
                .unwrap_or_else(|| panic!("{name} by {d}: declined"));
            let slow =
                region.buffer_with_style(BufferStyle::new(-d).line_join(LineJoin::Round(0.05)));
            // Outlines counter-clockwise, holes clockwise: the signed areas add up.
            let area: f64 = rings
                .iter()
                .map(|r| {
                    assert_eq!(r.first(), r.last(), "{name} by {d}: a ring not closed");
                    r.windows(2)
                        .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
                        .sum::<f64>()
                        / 2.0
                })
                .sum();
            let b = slow.unsigned_area();
            let slow_rings: Vec<Vec<Coord>> = slow
                .0
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .map(|r| r.0.clone())
                .collect();
            let (l, m) = (length(&rings), length(&slow_rings));
            assert!(
                (area - b).abs() <= 0.002 * b + 0.002 * m,
                "{name} by {d}: {area} here, {b} by geo's buffer"
            );
            assert!(
                (l - m).abs() <= 0.002 * m + 0.01,
                "{name} by {d}: boundary {l} here, {m} by geo's buffer"
            );
        }
    }
}

/// Travel stays inside the region: a move that would cross a hole (or leave a concave
/// outline) goes around it, and the travel reported is the length of the moves as routed.
/// Straight moves once crossed the holed square's hole on most layers.
#[test]
fn travel_goes_around_holes() {
    let two_holes = MultiPolygon::new(vec![Polygon::new(
        shapes::square(40.0).0[0].exterior().clone(),
        vec![
            shapes::circle(5.0).0[0]
                .exterior()
                .clone()
                .map_coords_shift(-9.0),
            shapes::star(6.0, 3.0).0[0]
                .exterior()
                .clone()
                .map_coords_shift(9.0),
        ],
    )]);
    let cases = [
        ("holed square", shapes::holed_square(40.0, 10.0)),
        ("two holes", two_holes),
        ("star", shapes::star(10.0, 4.5)),
        ("L", shapes::l_shape(20.0)),
    ];
    for (name, region) in &cases {
        let rings = rings_of(region);
        let prepared = Region::new(region, W).unwrap();
        for pattern in Pattern::ALL {
            for angle in [0.0, 35.0, 90.0] {
                let paths = prepared
                    .fill(&Params::new(pattern, 0.15, W).angle(angle).z(0.7))
                    .unwrap();
                let label = format!("{pattern} on {name} at {angle}°");
                assert_eq!(
                    paths.travels.len(),
                    paths.polylines.len().saturating_sub(1),
                    "{label}"
                );
                let mut total = 0.0;
                for (k, route) in paths.travels.iter().enumerate() {
                    assert_eq!(route.0.first(), paths.polylines[k].0.last(), "{label}");
                    assert_eq!(route.0.last(), paths.polylines[k + 1].0.first(), "{label}");
                    for seg in route.0.windows(2) {
                        total += math::hypot((seg[1] - seg[0]).x, (seg[1] - seg[0]).y);
                        for i in 1..8 {
                            let p = seg[0] + (seg[1] - seg[0]) * (i as f64 / 8.0);
                            assert!(
                                inside(&rings, p) || distance_to_boundary(&rings, p) < 0.05,
                                "{label}: travel {k} passes {p:?}, outside the region: {:?}",
                                route.0
                            );
                        }
                    }
                }
                assert!((total - paths.travel).abs() < 1e-6, "{label}");
            }
        }
    }
}

/// The largest gap concentric loops leave: the most any point of the inset area is from
/// every path, sampled every 0.1 mm.
fn largest_gap(region: &Region, paths: &Toolpaths) -> f64 {
    let rings = rings_of(region.inset());
    let segments: Vec<(Coord, Coord)> = paths
        .polylines
        .iter()
        .flat_map(|l| l.0.windows(2).map(|w| (w[0], w[1])).collect::<Vec<_>>())
        .collect();
    let (lo, hi) = (
        region.centre() - Coord { x: 12.0, y: 12.0 },
        region.centre() + Coord { x: 12.0, y: 12.0 },
    );
    let mut worst: f64 = 0.0;
    let mut y = lo.y;
    while y < hi.y {
        let mut x = lo.x;
        while x < hi.x {
            let p = Coord { x, y };
            if inside(&rings, p) {
                let d = segments
                    .iter()
                    .map(|&(a, b)| {
                        let e = b - a;
                        let t = (((p - a).x * e.x + (p - a).y * e.y)
                            / (e.x * e.x + e.y * e.y).max(1e-18))
                        .clamp(0.0, 1.0);
                        let q = a + e * t;
                        math::hypot((p - q).x, (p - q).y)
                    })
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(d);
            }
            x += 0.1;
        }
        y += 0.1;
    }
    worst
}

/// Concentric loops leave no band wider than about a spacing: where part of the region
/// ends between two loops (the L's arms at 20%: loops 1 and 3 mm in from each side of a
/// 9.6 mm arm), the middle gets pieces of a loop in between. Without them the arms kept a
/// 3.6 mm empty band (a point 1.8 mm from every line; Polyslice 1.2).
#[test]
fn concentric_leaves_no_wide_band() {
    for (name, shape) in [
        ("L", shapes::l_shape(20.0)),
        ("square", shapes::square(19.0)),
    ] {
        let region = Region::new(&shape, W).unwrap();
        let paths = region
            .fill(&Params::new(Pattern::Concentric, 0.2, W))
            .unwrap();
        let gap = largest_gap(&region, &paths);
        assert!(gap < 1.5, "{name}: a point {gap} mm from every line");
    }
}

/// Where the paths cross the vertical line at `x` between `y0` and `y1`: (y, path index),
/// sorted by y.
fn crossings_at(paths: &Toolpaths, x: f64, y0: f64, y1: f64) -> Vec<(f64, usize)> {
    let mut out = Vec::new();
    for (k, line) in paths.polylines.iter().enumerate() {
        for w in line.0.windows(2) {
            let (a, b) = (w[0], w[1]);
            if (a.x <= x) != (b.x <= x) {
                let y = a.y + (x - a.x) * (b.y - a.y) / (b.x - a.x);
                if (y0..=y1).contains(&y) {
                    out.push((y, k));
                }
            }
        }
    }
    out.sort_by(|p, q| p.0.total_cmp(&q.0));
    out
}

/// Where the outline's loops meet the hole's, a band narrower than a spacing is left
/// between the last loop of each: both were printed side by side, 0.6 mm apart at 40%
/// (s = 1 mm) between the 40 mm square and its 10 mm hole (and pieces of a middle loop
/// half a spacing from both, where their offsets met): +5% density there. Now the hole's
/// loop gives way where it comes within three quarters of a spacing of the outline's, and
/// no middle piece goes where two loops close in from both sides. Checked across the
/// band, from the hole to the square's side: no two paths closer than 0.7 spacing.
#[test]
fn concentric_loops_of_an_outline_and_a_hole_do_not_double() {
    let region = Region::new(&shapes::holed_square(40.0, 10.0), W).unwrap();
    for rho in [0.1, 0.2, 0.4] {
        let paths = region
            .fill(&Params::new(Pattern::Concentric, rho, W))
            .unwrap();
        let s = W / rho;
        for x in [0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0] {
            let hits = crossings_at(&paths, x, -20.0, -(10.2f64 * 10.2 - x * x).sqrt());
            for w in hits.windows(2) {
                let gap = w[1].0 - w[0].0;
                assert!(
                    w[0].1 == w[1].1 || gap > 0.7 * s,
                    "{rho}: paths {} and {} {gap} mm apart at x = {x}, y = {} (spacing {s})",
                    w[0].1,
                    w[1].1,
                    w[0].0
                );
            }
        }
        let density = paths.length * W / region.area();
        eprintln!("{rho}: density {density}");
        assert!(
            (density / rho - 1.0).abs() < 0.1,
            "{rho}: density {density}"
        );
        let gap = largest_gap(&region, &paths);
        assert!(gap < 2.0 * s, "{rho}: a point {gap} mm from every line");
    }
}

/// The old scan of `straight::families`: every line against the edge index.
fn families_by_scan(
    region: &Region,
    centre: Coord,
    theta: f64,
    offsets: &[f64],
    spacing: f64,
    shift: f64,
) -> Vec<Vec<Coord>> {
    let mut out = Vec::new();
    let mut intervals = Vec::new();
    for &offset in offsets {
        let frame = clip::Frame::new(centre, theta + offset.to_radians());
        let edges = clip::Edges::new(region.rings(), &frame);
        let shift = shift.rem_euclid(spacing);
        let first = ((edges.min.y - shift) / spacing).ceil() as i64;
        let last = ((edges.max.y - shift) / spacing).floor() as i64;
        for k in first..=last {
            let y = k as f64 * spacing + shift;
            edges.scan(y, &mut intervals);
            for &(x0, x1) in &intervals {
                out.push(vec![
                    frame.to_world(Coord { x: x0, y }),
                    frame.to_world(Coord { x: x1, y }),
                ]);
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The families found edge by edge are the scan's, point for point, on concave
    /// regions with holes, lines through vertices included (spacing a divisor of a
    /// vertex's height when `snap`).
    #[test]
    fn families_edge_by_edge_are_the_scan(
        outer in prop::collection::vec(4.0f64..15.0, 3..24),
        hole in prop::collection::vec(0.5f64..1.5, 3..8),
        holed in any::<bool>(),
        turn in 0.0f64..TAU,
        theta in -7.0f64..7.0,
        spacing in 0.3f64..12.0,
        shift in -5.0f64..5.0,
        families in 1usize..4,
        snap in any::<bool>(),
    ) {
        let holes = if holed {
            vec![radial_ring(&hole, -turn, Coord { x: 0.5, y: -0.25 }, true)]
        } else {
            vec![]
        };
        let shape = MultiPolygon::new(vec![Polygon::new(
            radial_ring(&outer, turn, Coord::zero(), false),
            holes,
        )]);
        let region = Region::new(&shape, W).unwrap();
        let (theta, spacing) = if snap { (0.0, 0.5) } else { (theta, spacing) };
        let offsets = &[0.0, 60.0, 120.0][..families];
        let centre = region.centre();
        let mut fast = Vec::new();
        straight::families(&region, centre, theta, offsets, spacing, shift, &mut fast);
        let slow = families_by_scan(&region, centre, theta, offsets, spacing, shift);
        prop_assert_eq!(fast, slow);
    }
}

/// On an axis-aligned square with lines through its corners and along its edges, both
/// give the same lines (the half-open rule counts a vertex on a line once).
#[test]
fn families_through_vertices_are_the_scan() {
    for shape in [
        shapes::square(20.0),
        shapes::l_shape(20.0),
        shapes::holed_square(40.0, 10.0),
    ] {
        let region = Region::new(&shape, W).unwrap();
        for (theta, spacing, shift) in [(0.0, 9.8, 0.0), (0.0, 0.2, 0.0), (FRAC_PI_2, 4.9, 0.1)] {
            let mut fast = Vec::new();
            let centre = Coord::zero();
            straight::families(
                &region,
                centre,
                theta,
                &[0.0, 90.0],
                spacing,
                shift,
                &mut fast,
            );
            let slow = families_by_scan(&region, centre, theta, &[0.0, 90.0], spacing, shift);
            assert!(!fast.is_empty());
            assert_eq!(fast, slow);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A region found clean is what cleaning it returns (so `infill::fill` may read it
    /// in place), and one with a repeated point is not; `infill::fill` (which keeps the
    /// outline only for concentric) fills the layer `Region::new` fills, every pattern.
    #[test]
    fn region_read_in_place_is_the_cleaned_copy(
        radii in prop::collection::vec(4.0f64..12.0, 3..30),
        hole in prop::collection::vec(0.5f64..1.5, 3..12),
        turn in 0.0f64..TAU,
        repeat in prop::option::of(0usize..30),
        pattern in 0usize..Pattern::ALL.len(),
    ) {
        let mut outline = radial_ring(&radii, turn, Coord::zero(), false);
        if let Some(i) = repeat {
            let i = i % (outline.0.len() - 1);
            outline.0.insert(i, outline.0[i]);
        }
        let region = MultiPolygon::new(vec![Polygon::new(
            outline,
            vec![radial_ring(&hole, turn, Coord::zero(), true)],
        )]);
        let clean = region::is_clean(&region);
        prop_assert_eq!(clean, repeat.is_none());
        if clean {
            prop_assert_eq!(&region::clean(&region), &region);
        }
        let params = Params::new(Pattern::ALL[pattern], 0.2, W).angle(turn.to_degrees());
        prop_assert_eq!(
            fill(&region, &params),
            Region::new(&region, W).unwrap().fill(&params)
        );
    }

    /// Moves along an edge (between two points of one edge of an L, a holed square or a
    /// star, straight ones parallel to it exactly), from an edge to any vertex, level and
    /// upright ones (parallel to edges, some leaving the region), and of no length: the shortcuts (a move on an edge it runs along, one heading into the region
    /// from a crossing) route them as the even-odd test of each stretch's middle does.
    #[test]
    fn moves_along_edges_are_the_general_routes(
        shape in 0usize..3,
        moves in prop::collection::vec((0usize..1000, 0.0f64..1.0, 0.0f64..1.0, 0usize..1000), 1..24),
    ) {
        let shape = match shape {
            0 => shapes::l_shape(20.0),
            1 => shapes::holed_square(40.0, 10.0),
            _ => shapes::star(10.0, 4.5),
        };
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let (edges, vertices) = (&ends.edges, &ends.vertices);
        let fast = travel::Router::new(rings);
        let general = travel::Router::new(rings).general();
        for (i, s, t, j) in moves {
            let (a, b) = edges[i % edges.len()];
            let (p, q) = (a + (b - a) * s, a + (b - a) * t);
            let v = vertices[j % vertices.len()];
            // Across and along: level and upright moves from p to v's height or x
            // (parallel to the L's and the square's edges, some over the L's notch or
            // the hole).
            let level = Coord { x: v.x, y: p.y };
            let upright = Coord { x: p.x, y: v.y };
            for (from, to) in [(p, q), (p, v), (v, p), (p, p), (a, b), (p, level), (p, upright)] {
                prop_assert_eq!(fast.route(from, to), general.route(from, to));
            }
        }
    }

    /// A move between two points of one edge (random fractions of it, on random radial
    /// regions with holes: not exactly parallel to it, by rounding) keeps that edge as
    /// one it may run along, so that the even-odd test of its middle is not needed; and
    /// it routes as the general router does, as do moves from there to any vertex.
    #[test]
    fn moves_nearly_along_an_edge_keep_it(
        outer in prop::collection::vec(4.0f64..12.0, 3..24),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..10), 0..3),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec((0usize..1000, 0.0f64..1.0, 0.0f64..1.0, 0usize..1000), 1..24),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.5);
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        let rings = region.rings();
        let edges: Vec<(usize, usize)> = rings
            .iter()
            .enumerate()
            .flat_map(|(r, ring)| (0..ring.len()).map(move |i| (r, i)))
            .collect();
        prop_assume!(!edges.is_empty());
        let vertices: Vec<Coord> = rings.iter().flatten().copied().collect();
        let fast = travel::Router::new(rings);
        let general = travel::Router::new(rings).general();
        for (e, s, t, j) in moves {
            let (r, i) = edges[e % edges.len()];
            let ring = &rings[r];
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let (p, q) = (a + (b - a) * s, a + (b - a) * t);
            if (q - p).x.abs() + (q - p).y.abs() > 1e-9 * (b - a).x.abs().max((b - a).y.abs()) {
                let kept = fast.crossings_of_move(p, q).iter().any(|&(t, ring, edge, _, near)| {
                    f64::from_bits(t).is_nan() && ring == r && edge == i && near
                });
                prop_assert!(kept, "the move from {:?} to {:?} along edge {} of ring {}", p, q, i, r);
            }
            let v = vertices[j % vertices.len()];
            for (from, to) in [(p, q), (q, p), (p, v), (v, q)] {
                prop_assert_eq!(fast.route(from, to), general.route(from, to));
            }
        }
    }

    /// The inset's crossing sweep (edges sorted by their left ends, each tested against
    /// those that start before it ends and overlap it in y) finds a crossing exactly when
    /// testing every pair of non-neighbouring edges does: star-like rings, some crossing
    /// themselves or each other once shifted, small (sorted by insertion) and large.
    #[test]
    fn crossing_sweep_is_every_pair(
        rings in prop::collection::vec(
            (prop::collection::vec(1.0f64..12.0, 3..40), -8.0f64..8.0, any::<bool>()), 1..4),
        turn in 0.0f64..TAU,
    ) {
        let rings: Vec<Vec<Coord>> = rings
            .iter()
            .map(|(radii, dx, scramble)| {
                let mut ring = radial_ring(radii, turn, Coord { x: *dx, y: 0.0 }, false).0;
                ring.pop();
                if *scramble {
                    // Every other vertex swapped with its neighbour: edges that cross.
                    for pair in ring.chunks_exact_mut(2).step_by(2) {
                        pair.swap(0, 1);
                    }
                }
                ring
            })
            .collect();
        let mut every_pair = false;
        for (r, ring) in rings.iter().enumerate() {
            for i in 0..ring.len() {
                for (s, other) in rings.iter().enumerate().skip(r) {
                    let from = if s == r { i + 1 } else { 0 };
                    for j in from..other.len() {
                        let n = ring.len();
                        if s == r && ((i + 1) % n == j || (j + 1) % n == i) {
                            continue;
                        }
                        let (a, b) = (ring[i], ring[(i + 1) % n]);
                        let (c, d) = (other[j], other[(j + 1) % other.len()]);
                        // Each edge's ends ordered as the sweep orders them.
                        let order = |p: Coord, q: Coord| {
                            if (p.x, p.y) <= (q.x, q.y) { (p, q) } else { (q, p) }
                        };
                        let ((a, b), (c, d)) = (order(a, b), order(c, d));
                        every_pair |= offset::segments_meet(a, b, c, d);
                    }
                }
            }
        }
        prop_assert_eq!(offset::crossings(&rings), every_pair);
    }

    /// The ring offset checks each edge's direction as its end vertex is moved (no list
    /// of where each vertex's points are): the same answer, the same points, as listing
    /// them and checking every edge after, on star-like rings moved far enough that
    /// edges turn around (outlines and holes, any arc step).
    #[test]
    fn edges_checked_as_moved_are_the_listed_check(
        radii in prop::collection::vec(1.0f64..12.0, 3..40),
        turn in 0.0f64..TAU,
        d in 0.05f64..5.0,
        arc in 0.1f64..0.8,
        hole in any::<bool>(),
    ) {
        let ring = radial_ring(&radii, turn, Coord::zero(), hole);
        let exterior = !hole;
        prop_assert_eq!(
            offset::offset_ring(&ring.0, d, arc, exterior),
            offset::offset_ring_listed(&ring.0, d, arc, exterior)
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Travel routed with each ring's edges in chunks (skipped by their boxes) is the
    /// route of every edge tested, point for point: between points on the rings (line
    /// ends), at vertices, and anywhere in the region's box.
    #[test]
    fn chunked_routes_are_the_plain_routes(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3), 1..24),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let point = |at, kind| ends.point(at, kind);
        let chunked = travel::Router::new(rings);
        let plain = travel::Router::with_chunk(rings, usize::MAX).general();
        let general = travel::Router::new(rings).general();
        for (a, b, kind) in moves {
            let (p, q) = (point(a, kind), point(b, kind));
            prop_assert_eq!(chunked.route(p, q), plain.route(p, q));
            // A move from the middle of an edge (a line's end) to any point: the
            // shortcut for a move heading into the region is the even-odd test's answer.
            let from_edge = point(a, 0);
            prop_assert_eq!(chunked.route(from_edge, q), general.route(from_edge, q));
            prop_assert_eq!(chunked.route(q, from_edge), general.route(q, from_edge));
        }
    }

    /// The line families found by scanning every line across the rings (a small region
    /// at a low density) are, to the bit, those found edge by edge from each edge's
    /// candidate lines: on holed regions, at any angle, spacing and shift, for one, two
    /// and three families.
    #[test]
    fn lines_scanned_are_the_lines_found_edge_by_edge(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        theta in 0.0f64..TAU,
        spacing in prop_oneof![0.3f64..20.0, Just(1.0), Just(0.5)],
        shift in prop_oneof![Just(0.0f64), -5.0f64..5.0],
        families in 0usize..3,
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let offsets = [&[0.0][..], &[0.0, 90.0], &[0.0, 60.0, 120.0]][families];
        let centre = region.centre();
        let (mut scanned, mut by_edge) = (Vec::new(), Vec::new());
        straight::families_by(&region, centre, theta, offsets, spacing, shift, true, &mut scanned);
        straight::families_by(&region, centre, theta, offsets, spacing, shift, false, &mut by_edge);
        let bits = |v: &[Vec<Coord>]| {
            v.iter()
                .map(|l| l.iter().map(|c| (c.x.to_bits(), c.y.to_bits())).collect::<Vec<_>>())
                .collect::<Vec<_>>()
        };
        prop_assert_eq!(bits(&scanned), bits(&by_edge));
    }

    /// The router's even-odd test reading only the chunks that may cross the ray (for
    /// the parity) or lie within a nanometre (for the edges' distance) is the test of
    /// both on every edge of a chunk that is either: at line ends on edges, at vertices,
    /// at points a nanometre or two off an edge, and anywhere in the box.
    #[test]
    fn inside_by_the_chunks_that_matter_is_inside_edge_by_edge(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        points in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), 0u8..3, -2e-6f64..2e-6, -2e-6f64..2e-6), 1..24),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        for chunk in [4, 8, usize::MAX] {
            let router = travel::Router::with_chunk(rings, chunk);
            for &(at, kind, dx, dy) in &points {
                let p = ends.point(at, kind);
                for p in [p, p + Coord { x: dx, y: dy }] {
                    prop_assert_eq!(router.inside(p), router.inside_each_edge(p), "{:?}", p);
                }
            }
        }
    }

    /// Moves routed passing the edges whose ends are both clearly on one side of the
    /// move's line are the moves routed testing every edge, and find the same crossings
    /// (the edges they pass could only have been kept as edges the move runs along):
    /// between line ends, vertices and points of the box, on holed star-like regions.
    #[test]
    fn edges_passed_by_their_sides_are_not_crossed(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3, 0u8..3), 1..24),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let sided = travel::Router::new(rings);
        let every = travel::Router::new(rings).every_edge();
        let crossed = |router: &travel::Router, p, q| {
            router
                .crossings_of_move(p, q)
                .into_iter()
                .filter(|c| !f64::from_bits(c.0).is_nan())
                .collect::<Vec<_>>()
        };
        for (a, b, ka, kb) in moves {
            let (p, q) = (ends.point(a, ka), ends.point(b, kb));
            for (from, to) in [(p, q), (q, p), (p, p)] {
                prop_assert_eq!(crossed(&sided, from, to), crossed(&every, from, to));
                prop_assert_eq!(sided.route(from, to), every.route(from, to));
            }
        }
    }

    /// A point `near_an_edge` finds clear of every edge answers for every point within
    /// `CLEAR / 2` of it: none of them is on an edge (`on_an_edge`). Points on edges, at
    /// vertices and in the box, moved by up to a little more than a nanometre (across
    /// the band `CLEAR` adds), then by up to `CLEAR / 2`.
    #[test]
    fn a_point_clear_of_the_edges_answers_for_its_neighbours(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        points in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), 0u8..3, -1.2e-6f64..1.2e-6, -1.2e-6f64..1.2e-6,
             -0.5f64..0.5, -0.5f64..0.5), 1..48),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let router = travel::Router::new(rings);
        let clear = travel::Router::CLEAR;
        for (at, kind, dx, dy, ex, ey) in points {
            let p = ends.point(at, kind) + Coord { x: dx, y: dy };
            let (near, on) = router.near_and_on_an_edge(p);
            prop_assert!(near || !on, "{:?} on an edge, not near one", p);
            if !near {
                let m = p + Coord { x: ex * clear, y: ey * clear };
                prop_assert!(!router.near_and_on_an_edge(m).1, "{:?} near {:?}", m, p);
            }
        }
    }

    /// A walked move whose middle is clearly off every edge answers for its stretch's
    /// middle nearby without a second search: the routes are those testing every
    /// stretch's middle, between line ends, vertices and points of the box (and points
    /// a nanometre or so off them), on holed star-like regions.
    #[test]
    fn a_middle_clear_of_the_edges_answers_for_its_stretch(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3, 0u8..3,
             -2e-6f64..2e-6), 1..24),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let reusing = travel::Router::new(rings);
        let every = travel::Router::new(rings).testing_every_middle();
        for (a, b, ka, kb, off) in moves {
            let (p, q) = (ends.point(a, ka), ends.point(b, kb));
            let shifted = q + Coord { x: off, y: -off };
            for (from, to) in [(p, q), (q, p), (p, shifted), (shifted, p)] {
                prop_assert_eq!(reusing.route(from, to), every.route(from, to));
            }
        }
    }

    /// Nearest-first ordering of a few paths (the plain scan) takes, from the last end,
    /// the nearest end of a path not yet taken, ties to the lowest index as generated
    /// and then to its first end, reversing the path entered at its last: ends on a
    /// small grid (many ties) and anywhere, up to the scan's 64 paths and past them (the
    /// grid search, the same rule).
    #[test]
    fn nearest_first_takes_the_nearest_end_ties_to_the_first(
        paths in prop::collection::vec(
            prop::collection::vec(
                prop_oneof![
                    (-3i32..3, -3i32..3).prop_map(|(x, y)| Coord { x: x as f64, y: y as f64 }),
                    (-5.0f64..5.0, -5.0f64..5.0).prop_map(|(x, y)| Coord { x, y }),
                ],
                2..4,
            ),
            1..70,
        ),
    ) {
        let mut left: Vec<(usize, Vec<Coord>)> = paths.iter().cloned().enumerate().skip(1).collect();
        let mut wanted = vec![paths[0].clone()];
        let mut at = *paths[0].last().unwrap();
        while !left.is_empty() {
            let mut best = (f64::INFINITY, 0, false);
            for (k, (_, p)) in left.iter().enumerate() {
                for (reversed, q) in [(false, p[0]), (true, *p.last().unwrap())] {
                    let d = (q - at).x * (q - at).x + (q - at).y * (q - at).y;
                    if d < best.0 {
                        best = (d, k, reversed);
                    }
                }
            }
            let (_, k, reversed) = best;
            let (_, mut p) = left.remove(k);
            if reversed {
                p.reverse();
            }
            at = *p.last().unwrap();
            wanted.push(p);
        }
        prop_assert_eq!(order::nearest(paths), wanted);
    }

    /// The edge index's even-odd test (the edges of the point's strip only) is the ray's
    /// parity over every edge: at vertices, on edges, at strip bounds and anywhere in the
    /// box, in a turned frame, on holed star-like regions.
    #[test]
    fn strips_hold_every_edge_the_ray_may_cross(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        theta in 0.0f64..TAU,
        points in prop::collection::vec(((0usize..1000, 0.0f64..1.0), 0u8..3), 1..32),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let frame = clip::Frame::new(region.centre(), theta);
        let edges = clip::Edges::new(region.rings(), &frame);
        let local: Vec<Vec<Coord>> = region
            .rings()
            .iter()
            .map(|r| r.iter().map(|&p| frame.to_local(p)).collect())
            .collect();
        let ends = MoveEnds::new(&local);
        let segments: Vec<(Coord, Coord)> = edges.segments().collect();
        for (at, kind) in points {
            let p = ends.point(at, kind);
            let parity = segments.iter().filter(|&&(a, b)| clip::ray_crosses(a, b, p)).count() % 2 == 1;
            prop_assert_eq!(edges.contains(p), parity, "{:?}", p);
        }
    }

    /// The router's cumulative lengths (each vertex and the next, then the closing edge)
    /// are, to the bit, the sums edge by edge round each ring, on every ring of a holed
    /// region.
    #[test]
    fn cumulative_lengths_are_the_sums_edge_by_edge(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let rings = region.rings();
        let router = travel::Router::new(rings);
        for (r, ring) in rings.iter().enumerate() {
            let n = ring.len();
            let mut s = 0.0;
            let mut wanted = vec![0.0f64];
            for i in 0..n {
                let e = ring[(i + 1) % n] - ring[i];
                s += (e.x * e.x + e.y * e.y).sqrt();
                wanted.push(s);
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(&router.cumulative_lengths(r)), bits(&wanted));
        }
    }
}

/// `Edges::clip` with every edge tested against every segment (no grid), for reference.
fn clip_plain(edges: &clip::Edges, pts: &[Coord]) -> Vec<Vec<Coord>> {
    let all: Vec<(Coord, Coord)> = edges.segments().collect();
    let mut cuts = vec![0.0];
    for (k, w) in pts.windows(2).enumerate() {
        let (p, q) = (w[0], w[1]);
        let d1 = q - p;
        let first = cuts.len();
        for &(a, b) in &all {
            let d2 = b - a;
            let den = d1.x * d2.y - d1.y * d2.x;
            if den == 0.0 {
                continue;
            }
            let ap = a - p;
            let t = (ap.x * d2.y - ap.y * d2.x) / den;
            let u = (ap.x * d1.y - ap.y * d1.x) / den;
            if (0.0..1.0).contains(&t) && (0.0..1.0).contains(&u) {
                cuts.push(k as f64 + t);
            }
        }
        cuts[first..].sort_unstable_by(f64::total_cmp);
    }
    cuts.push((pts.len() - 1) as f64);
    let at = |g: f64| {
        let k = (g.floor() as usize).min(pts.len() - 2);
        pts[k] + (pts[k + 1] - pts[k]) * (g - k as f64)
    };
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (g0, g1) = (w[0], w[1]);
        if g1 <= g0 || !edges.contains(at((g0 + g1) / 2.0)) {
            continue;
        }
        let mut piece = vec![at(g0)];
        let (first, last) = (g0.floor() as usize + 1, g1.ceil() as usize);
        piece.extend(pts[first.min(last)..last].iter().copied());
        piece.push(at(g1));
        out.push(piece);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Clipping through the edge grid (each segment visiting only the cells it passes
    /// row by row) cuts where every edge tested would, point for point: long diagonal
    /// segments and polylines across concave regions with holes.
    #[test]
    fn clip_through_the_grid_is_the_plain_clip(
        outer in prop::collection::vec(4.0f64..15.0, 6..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        lines in prop::collection::vec(
            prop::collection::vec((-16.0f64..16.0, -16.0f64..16.0), 2..6), 1..12),
    ) {
        let shape = holed_radial(&outer, &holes, turn, 2.2);
        let region = Region::new(&shape, W).unwrap();
        let mut edges = clip::Edges::new(region.rings(), &clip::Frame::new(Coord::zero(), turn));
        for line in lines {
            let pts: Vec<Coord> = line.into_iter().map(|(x, y)| Coord { x, y }).collect();
            let mut fast = Vec::new();
            edges.clip(&pts, &mut fast);
            prop_assert_eq!(fast, clip_plain(&edges, &pts));
        }
    }

    /// A small region's clip (its edges by their boxes' least x, a segment's scan
    /// stopped at the first wholly to its right) cuts where every edge tested in the
    /// region's order would: star-like outlines of a few points (at most 32 edges once
    /// inset), segments from short to across the region, polylines of several.
    #[test]
    fn clip_of_a_few_edges_by_their_least_x_is_the_plain_clip(
        outer in prop::collection::vec(2.0f64..15.0, 3..9),
        turn in 0.0f64..TAU,
        lines in prop::collection::vec(
            prop::collection::vec((-16.0f64..16.0, -16.0f64..16.0), 2..6), 1..12),
    ) {
        let shape = polygon(&outer, turn);
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        let mut edges = clip::Edges::new(region.rings(), &clip::Frame::new(Coord::zero(), turn));
        prop_assume!(edges.segments().count() <= 32);
        for line in lines {
            let pts: Vec<Coord> = line.into_iter().map(|(x, y)| Coord { x, y }).collect();
            let mut fast = Vec::new();
            edges.clip(&pts, &mut fast);
            prop_assert_eq!(fast, clip_plain(&edges, &pts));
        }
    }
}

/// Lightning as it was filled before the first tree was only measured: two trees built
/// whole, the first's paths measured, the last one printed (then simplified and ordered
/// as `Region::fill` does).
fn lightning_by_two_trees(region: &Region, params: &Params) -> Toolpaths {
    let (w, rho) = (params.nozzle, params.density);
    let centre = region.centre();
    let theta = params.angle.rem_euclid(360.0).to_radians();
    let mut edges = clip::Edges::new(region.rings(), &lightning::frame(centre));
    let mut paths = Vec::new();
    let mut spacing = 2.0 * w / rho;
    for _ in 0..2 {
        paths.clear();
        lightning::lightning(region, centre, theta, spacing, &mut edges, &mut paths);
        let length: f64 = paths.iter().map(|p| travel::length(p)).sum();
        let printed = length * w / region.area();
        if printed.is_nan() || printed <= 0.0 || (printed / rho - 1.0).abs() < 0.03 {
            break;
        }
        spacing *= (printed / rho).clamp(0.25, 4.0);
    }
    paths.retain_mut(|p| order::simplify(p, w / 10.0));
    let rings: &[Vec<Coord>] = if region.is_convex() {
        &[]
    } else {
        region.rings()
    };
    order::order(paths, Vec::new(), None, rings, false)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Measuring the first tree without making its paths, and not rebuilding a tree whose
    /// branch counts did not change, prints what building both trees printed.
    #[test]
    fn lightning_measured_once_is_lightning_built_twice(
        radii in prop::collection::vec(2.0f64..15.0, 3..14),
        hole in prop::collection::vec(0.5f64..1.5, 3..8),
        holed in any::<bool>(),
        turn in 0.0f64..TAU,
        rho in 0.05f64..1.0,
        angle in -360.0f64..360.0,
    ) {
        let holes = if holed {
            vec![radial_ring(&hole, -turn, Coord { x: 0.3, y: 0.2 }, true)]
        } else {
            vec![]
        };
        let shape = MultiPolygon::new(vec![Polygon::new(
            radial_ring(&radii, turn, Coord::zero(), false),
            holes,
        )]);
        let region = Region::new(&shape, W).unwrap();
        let params = Params::new(Pattern::Lightning, rho, W).angle(angle);
        prop_assert_eq!(region.fill(&params).unwrap(), lightning_by_two_trees(&region, &params));
    }
}

/// The five compared shapes at 10, 20 and 40%: the same paths as two whole trees.
#[test]
fn lightning_on_the_compared_shapes_is_unchanged() {
    for (_, shape) in shapes() {
        let region = Region::new(&shape, W).unwrap();
        for rho in [0.1, 0.2, 0.4] {
            let params = Params::new(Pattern::Lightning, rho, W).angle(45.0);
            assert_eq!(
                region.fill(&params).unwrap(),
                lightning_by_two_trees(&region, &params)
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The ray test that skips the division for edges wholly left or right of the point
    /// answers as the division does, edges near and through the point included.
    #[test]
    fn ray_crossing_without_division_is_the_division(
        a in (-50.0f64..50.0, -50.0f64..50.0),
        b in (-50.0f64..50.0, -50.0f64..50.0),
        t in 0.0f64..1.0,
        dx in prop::sample::select(vec![0.0, 1e-13, -1e-13, 1e-9, -1e-9, 0.3, -0.3, 7.0]),
    ) {
        let (a, b) = (Coord { x: a.0, y: a.1 }, Coord { x: b.0, y: b.1 });
        // A point at height t along the edge, moved by dx from it.
        let on = a + (b - a) * t;
        let p = Coord { x: on.x + dx, y: on.y };
        let plain = (a.y <= p.y) != (b.y <= p.y)
            && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x;
        prop_assert_eq!(clip::ray_crosses(a, b, p), plain);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Turning down a ring at its first reflex corner before copying it gives what the
    /// copy, deduplicated and oriented, gives: rings of either orientation, convex or
    /// not, with repeated points and a closing point or none.
    #[test]
    fn reflex_corners_found_before_copying(
        radii in prop::collection::vec(2.0f64..15.0, 3..16),
        convex in any::<bool>(),
        clockwise in any::<bool>(),
        closed in any::<bool>(),
        repeat in prop::collection::vec(0usize..16, 0..3),
    ) {
        let radii: Vec<f64> = if convex { vec![radii[0]; radii.len()] } else { radii };
        let mut ring = polygon(&radii, 0.3).0.remove(0).into_inner().0 .0;
        if !closed {
            ring.pop();
        }
        for &i in &repeat {
            let i = i % ring.len();
            ring.insert(i, ring[i]);
        }
        if clockwise {
            ring.reverse();
        }
        prop_assert_eq!(region::convex_ring(&ring), region::convex_ring_copied(&ring));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// Simplifying with the last kept vertex carried (nothing written before the first
    /// vertex dropped, a line decided at once) is simplifying vertex by vertex: paths of
    /// 0 to 40 vertices, steps from nothing to past the limit (some exactly at it), repeated
    /// points, a NaN.
    #[test]
    fn simplify_carried_is_simplify_each(
        steps in prop::collection::vec(
            (
                prop::sample::select(vec![0.0, 0.01, 0.125, 0.25, 0.26, 0.5, 3.0]),
                prop_oneof![
                    prop::sample::select(vec![(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]),
                    (0.0f64..TAU).prop_map(|a| (a.cos(), a.sin())),
                ],
            ),
            0..40,
        ),
        nan_at in prop::option::of(0usize..40),
        min in prop::sample::select(vec![0.0, 0.25, 0.5]),
    ) {
        // Axis steps of a dyadic length from the origin land exactly `min` away at times.
        let mut at = Coord { x: 0.0, y: 0.0 };
        let mut path: Vec<Coord> = steps
            .iter()
            .map(|&(r, (c, s))| {
                at = at + Coord { x: r * c, y: r * s };
                at
            })
            .collect();
        if let Some(i) = nan_at.filter(|&i| i < path.len()) {
            path[i].x = f64::NAN;
        }
        let (mut carried, mut each) = (path.clone(), path);
        let kept = order::simplify(&mut carried, min);
        prop_assert_eq!(kept, order::simplify_each(&mut each, min));
        // By bits: NaN coordinates compare unequal.
        let bits = |p: &[Coord]| p.iter().map(|c| (c.x.to_bits(), c.y.to_bits())).collect::<Vec<_>>();
        prop_assert_eq!(bits(&carried), bits(&each));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A walk whose way round is taken from the arc of fewer edges (where that is
    /// certain) goes the way the ring's cumulative lengths give: moves between line ends
    /// on edges, vertices and points of the box, each on a fresh router (the first walk
    /// of a layer is the one measured by its arc), on holed star-like regions and on
    /// the star, the L (a notch's short arc edges) and a long thin L (arcs near half its
    /// perimeter).
    #[test]
    fn ways_round_by_the_arc_are_the_measured_ways(
        outer in prop::collection::vec(4.0f64..15.0, 3..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        named in 0usize..5,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3, 0u8..3), 1..24),
    ) {
        use geo::MapCoords;
        let shape = match named {
            0 => shapes::star(10.0, 4.5),
            1 => shapes::l_shape(20.0),
            // A long thin L: arcs near half its perimeter, about its longer side.
            2 => shapes::l_shape(20.0).map_coords(|c| Coord { x: 3.0 * c.x, y: 0.25 * c.y }),
            _ => holed_radial(&outer, &holes, turn, 2.2),
        };
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        for (a, b, ka, kb) in moves {
            let (p, q) = (ends.point(a, ka), ends.point(b, kb));
            for (from, to) in [(p, q), (q, p)] {
                let bounded = travel::Router::new(rings).route(from, to);
                let measured = travel::Router::new(rings).measuring_ways().route(from, to);
                prop_assert_eq!(bounded, measured);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Moves each starting where the last ended (closed loops' travel), routed by a
    /// router that knows the last end found inside and on no edge, so that a move from
    /// there touching no edge is inside without the even-odd test, are the routes of a
    /// router testing every middle: chains through points of the box (most inside, some
    /// in holes or outside), line ends on edges, vertices and points a tenth of a
    /// nanometre off an edge, on holed star-like regions and on the holed square, square
    /// loops' corners on its diagonals included.
    #[test]
    fn moves_from_a_known_inside_end_are_the_tested_routes(
        outer in prop::collection::vec(4.0f64..15.0, 3..40),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 0..3),
        turn in 0.0f64..TAU,
        named in 0usize..3,
        points in prop::collection::vec(((0usize..1000, 0.0f64..1.0), 0u8..6), 2..32),
    ) {
        let shape = match named {
            0 => shapes::holed_square(40.0, 10.0),
            _ => holed_radial(&outer, &holes, turn, 2.2),
        };
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        let rings = region.rings();
        let ends = MoveEnds::new(rings);
        let point = |(at, kind): ((usize, f64), u8)| match kind {
            // A point of the box's diagonal (where a square's loops turn).
            3 => {
                let (lo, hi) = (ends.point((0, 0.0), 2), ends.point((1000, 1.0), 2));
                lo + (hi - lo) * at.1
            }
            // A point of one of two edges moved 0.8 nm off it, either
            // side: moves along an edge just inside or outside, their middles on it.
            4 | 5 => {
                let (a, b) = ends.edges[at.0 % 2];
                let e = b - a;
                let normal = Coord { x: -e.y, y: e.x } / (e.x * e.x + e.y * e.y).sqrt();
                let off = if kind == 4 { 8e-7 } else { -8e-7 };
                a + e * at.1 + normal * off
            }
            _ => ends.point(at, kind),
        };
        let chained = travel::Router::new(rings);
        let tested = travel::Router::new(rings).unchained();
        for pair in points.windows(2) {
            let (p, q) = (point(pair[0]), point(pair[1]));
            prop_assert_eq!(chained.route_on(p, q, true), tested.route(p, q));
        }
    }
}

/// A move along the holed square's hole 0.8 nm inside the hole (its middle on the
/// edge, within a nanometre: inside, for the even-odd test) does not make its end a
/// point known inside: the move from there across the hole (touching no edge) is walked
/// round it, as the even-odd test of its middle finds it outside the region.
#[test]
fn a_middle_on_an_edge_does_not_make_its_end_inside() {
    let region = Region::new(&shapes::holed_square(40.0, 10.0), W).unwrap();
    let rings = region.rings();
    let hole = &rings[1];
    let (a, b) = (hole[0], hole[1]);
    let e = b - a;
    let along = e / (e.x * e.x + e.y * e.y).sqrt();
    // Into the hole: towards its centre, the origin.
    let mut into = Coord {
        x: -along.y,
        y: along.x,
    };
    if into.x * (a + b).x + into.y * (a + b).y > 0.0 {
        into = -into;
    }
    let (p1, p2) = (a + e * 0.2 + into * 8e-7, a + e * 0.5 + into * 8e-7);
    // 2 mm on, a little into the hole: past the next edges, clear of them all.
    let p3 = p2 + (along + into * 0.3) * 2.0;
    let chained = travel::Router::new(rings);
    let tested = travel::Router::new(rings).unchained();
    assert_eq!(chained.route_on(p1, p2, true), vec![p1, p2]);
    let walked = tested.route(p2, p3);
    assert!(walked.len() > 2, "{walked:?}");
    assert_eq!(chained.route_on(p2, p3, true), walked);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The router made for a single ring of at most 32 edges (`Router::small`: one pass
    /// for its chunks' boxes and its orientation) has the boxes, scale and side of the
    /// general one in chunks of 4 (`with_chunk`), and routes every move as it does:
    /// random radial rings of 3 to 32 vertices, either way round, between points on
    /// edges, vertices and points of the box.
    #[test]
    fn a_small_rings_router_is_the_chunked_router(
        radii in prop::collection::vec(1.0f64..10.0, 3..=32),
        turn in 0.0f64..TAU,
        centre in (-50.0f64..50.0, -50.0f64..50.0),
        clockwise in any::<bool>(),
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3), 1..16),
    ) {
        let n = radii.len();
        let mut ring: Vec<Coord> = radii
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let a = turn + TAU * i as f64 / n as f64;
                Coord { x: centre.0 + r * a.cos(), y: centre.1 + r * a.sin() }
            })
            .collect();
        if clockwise {
            ring.reverse();
        }
        let rings = vec![ring];
        let small = travel::Router::small(&rings);
        let general = travel::Router::with_chunk(&rings, 4);
        prop_assert_eq!(small.layout(), general.layout());
        let ends = MoveEnds::new(&rings);
        for (a, b, kind) in moves {
            let (p, q) = (ends.point(a, kind), ends.point(b, kind));
            prop_assert_eq!(small.route(p, q), general.route(p, q));
            let from_edge = ends.point(a, 0);
            prop_assert_eq!(small.route(from_edge, q), general.route(from_edge, q));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// A region whose one ring the raw offset made (`Region::one_ring_left`) is
    /// counter-clockwise by `signed_area`, and the router told so (`Router::told`, its
    /// area not summed) has the layout (boxes, scale, side) of the one that sums it and
    /// routes every move as it does: random radial outlines of 3 to 24 vertices (reflex
    /// corners, arcs), moves between points on edges, vertices and points of the box.
    #[test]
    fn a_router_told_the_rings_side_is_the_router_that_sums_it(
        outer in prop::collection::vec(2.0f64..12.0, 3..24),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3), 1..12),
    ) {
        let shape = holed_radial(&outer, &[], turn, 2.5);
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        prop_assume!(region.one_ring_left());
        let rings = region.rings();
        prop_assert!(super::offset::signed_area(&rings[0]) > 0.0);
        let told = travel::Router::told(rings, true);
        let summed = travel::Router::new(rings);
        prop_assert_eq!(told.layout(), summed.layout());
        let ends = MoveEnds::new(rings);
        for (a, b, kind) in moves {
            let (p, q) = (ends.point(a, kind), ends.point(b, kind));
            prop_assert_eq!(told.route(p, q), summed.route(p, q));
            let from_edge = ends.point(a, 0);
            prop_assert_eq!(told.route(from_edge, q), summed.route(from_edge, q));
        }
    }
}

proptest! {
    /// The crossings sorted by `sort_crossings` (a pair by one comparison) are those the
    /// library's sort by line then x gives, to the bit: any count, lines and x repeated,
    /// zeros of both signs.
    #[test]
    fn crossings_sorted_as_the_librarys_sort(
        crossings in prop::collection::vec(
            (0i64..3, prop_oneof![Just(0.0f64), Just(-0.0), Just(1.5), -5.0f64..5.0]),
            0..6),
    ) {
        let mut fast = crossings.clone();
        straight::sort_crossings(&mut fast);
        let mut slow = crossings;
        slow.sort_unstable_by(|p, q| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1)));
        let bits = |v: &[(i64, f64)]| v.iter().map(|&(k, x)| (k, x.to_bits())).collect::<Vec<_>>();
        prop_assert_eq!(bits(&fast), bits(&slow));
    }
}

/// A region whose inset is one ring of at most 32 edges (the star's) gets the small
/// ring's router, which routes its layer's travels as the general router does.
#[test]
fn the_stars_travels_take_the_small_router() {
    let region = Region::new(&shapes::star(10.0, 4.5), W).unwrap();
    let rings = region.rings();
    assert_eq!(rings.len(), 1);
    assert!(rings[0].len() <= 32, "{}", rings[0].len());
    let small = travel::Router::new(rings);
    let general = travel::Router::with_chunk(rings, 4);
    assert_eq!(small.layout(), general.layout());
    let ends = MoveEnds::new(rings);
    for i in 0..rings[0].len() {
        let (p, q) = (ends.point((i, 0.3), 0), ends.point((i * 7 + 5, 0.6), 0));
        assert_eq!(small.route(p, q), general.route(p, q));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// A router that tells moves clear inside a small convex first ring (a convex outline
    /// with holes) by its edges' half-planes, without searching that ring, routes every
    /// move as the one that searches it: regular outlines of 3 to 8 edges with random
    /// holes and the holed square, moves in chains (as loops' travel) and not, between
    /// points on edges, vertices, of the box, of the box's diagonal, and points moved
    /// into the outline from its edges by a tenth of a nanometre to half a millimetre
    /// (either side of the test's margin, about 10⁻⁵ mm here).
    #[test]
    fn moves_clear_inside_a_convex_outline_are_the_searched_routes(
        sides in 3usize..=8,
        radius in 6.0f64..15.0,
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..30), 1..3),
        turn in 0.0f64..TAU,
        named in 0usize..4,
        points in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), 0u8..5, 0usize..7, any::<bool>()), 2..40),
    ) {
        let shape = match named {
            0 => shapes::holed_square(40.0, 10.0),
            _ => holed_radial(&vec![radius; sides], &holes, turn, 2.2),
        };
        let Ok(region) = Region::new(&shape, W) else {
            return Ok(());
        };
        let rings = region.rings();
        prop_assume!(rings.len() > 1);
        let outline = &rings[0];
        let ends = MoveEnds::new(rings);
        let point = |((at, t), kind, off): ((usize, f64), u8, usize)| match kind {
            3 => {
                let (lo, hi) = (ends.point((0, 0.0), 2), ends.point((1000, 1.0), 2));
                lo + (hi - lo) * t
            }
            4 => {
                // Into the outline from a point of one of its edges (it turns left).
                let n = outline.len();
                let (a, b) = (outline[at % n], outline[(at + 1) % n]);
                let e = b - a;
                let inward = Coord { x: -e.y, y: e.x } / (e.x * e.x + e.y * e.y).sqrt();
                let by = [1e-7, 8e-7, 5e-6, 1.6e-5, 3e-5, 1e-3, 0.5][off];
                a + e * t + inward * by
            }
            _ => ends.point((at, t), kind),
        };
        let deep = travel::Router::new(rings);
        let searched = travel::Router::new(rings).searching_every_ring();
        // The fast path is on for these outlines (convex, counter-clockwise, small), its
        // box for the square's (a rectangle).
        prop_assert!(deep.tells_deep_moves());
        prop_assert!(!searched.tells_deep_moves());
        if named == 0 {
            prop_assert!(deep.has_deep_box());
        }
        let edges_only = travel::Router::new(rings).without_deep_box();
        for pair in points.windows(2) {
            let (p, q) = (point((pair[0].0, pair[0].1, pair[0].2)), point((pair[1].0, pair[1].1, pair[1].2)));
            let looped = pair[1].3;
            let route = searched.route_on(p, q, looped);
            prop_assert_eq!(&deep.route_on(p, q, looped), &route);
            prop_assert_eq!(&edges_only.route_on(p, q, looped), &route);
        }
    }
}

/// The holed square's concentric loops' travel is told clear of the outline (each
/// move's ends well inside it; those missing the hole's box straight at once) and routed
/// as before: every move straight, the same with the outline searched; a move across the
/// hole is walked round it; and a move from outside the outline to inside, or out
/// beyond it, is not told clear (it is routed as the searching router routes it).
#[test]
fn the_holed_squares_travel_is_told_clear_of_its_outline() {
    let region = Region::new(&shapes::holed_square(40.0, 10.0), W).unwrap();
    let rings = region.rings();
    let deep = travel::Router::new(rings);
    assert!(deep.tells_deep_moves());
    let searched = travel::Router::new(rings).searching_every_ring();
    let moves = [
        (Coord { x: 18.8, y: 18.8 }, Coord { x: 16.8, y: 16.8 }),
        (Coord { x: -13.0, y: 9.6 }, Coord { x: -13.0, y: -9.6 }),
        // Across the hole: walked round it.
        (Coord { x: -13.0, y: 0.5 }, Coord { x: 13.0, y: 0.5 }),
        // From beyond the outline, and out beyond it: not clear of it.
        (Coord { x: 25.0, y: 0.0 }, Coord { x: 15.0, y: 0.0 }),
        (Coord { x: 15.0, y: 0.0 }, Coord { x: 25.0, y: 0.0 }),
    ];
    for (p, q) in moves {
        assert_eq!(deep.route_on(p, q, true), searched.route_on(p, q, true));
    }
    assert_eq!(
        deep.route(moves[0].0, moves[0].1),
        vec![moves[0].0, moves[0].1]
    );
    assert!(deep.route(moves[2].0, moves[2].1).len() > 2);
}
