//! Lightning's tree against the general path: every polyline clipped, every segment
//! clipped on its own.

use super::*;
use crate::infill::clip::Edges;
use crate::infill::shapes;
use geo::{LineString, MultiPolygon, Polygon};
use proptest::prelude::*;
use std::f64::consts::TAU;

const W: f64 = 0.4;

/// A ring of `radii.len()` vertices at those distances from `centre`, evenly turned
/// (counter-clockwise; clockwise for a hole).
fn radial(radii: &[f64], turn: f64, centre: Coord, hole: bool) -> LineString<f64> {
    let n = radii.len();
    let mut points: Vec<Coord> = radii
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let (s, c) = math::sin_cos(turn + TAU * i as f64 / n as f64);
            centre + Coord { x: r * c, y: r * s }
        })
        .collect();
    if hole {
        points.reverse();
    }
    LineString::from(points)
}

fn region_of(radii: &[f64], hole: Option<&[f64]>, turn: f64) -> Region {
    let holes = hole
        .map(|h| vec![radial(h, -turn, Coord { x: 0.3, y: 0.2 }, true)])
        .unwrap_or_default();
    let shape = MultiPolygon::new(vec![Polygon::new(
        radial(radii, turn, Coord::zero(), false),
        holes,
    )]);
    Region::new(&shape, W).unwrap()
}

/// The tree's pieces as `tree` hands them out.
fn tree_pieces(region: &Region, theta: f64, spacing: f64) -> Vec<Vec<Coord>> {
    let centre = region.centre();
    let mut edges = Edges::new(region.rings(), &frame(centre));
    let mut out = Vec::new();
    tree(
        region,
        &Outlines::new(region, theta),
        centre,
        spacing,
        &mut edges,
        |p| out.push(p.to_vec()),
    );
    out
}

/// The general path: each of `lines` clipped, in the frame, back in world coordinates.
fn clipped(region: &Region, lines: &[Vec<Coord>]) -> Vec<Vec<Coord>> {
    let frame = frame(region.centre());
    let mut edges = Edges::new(region.rings(), &frame);
    let mut out = Vec::new();
    for line in lines {
        let local: Vec<Coord> = line.iter().map(|&p| frame.to_local(p)).collect();
        edges.clip_each(&local, |piece| {
            out.push(piece.iter().map(|&q| frame.to_world(q)).collect())
        });
    }
    out
}

fn total(paths: &[Vec<Coord>]) -> f64 {
    paths.iter().map(|p| length_of(p)).sum()
}

fn length_of(p: &[Coord]) -> f64 {
    p.windows(2).map(|w| length(w[1] - w[0])).sum()
}

/// The tree's polylines are the branches' three segments (start to tip, two twigs from
/// the fork): the same line printed, in two paths per branch, not three.
fn check_same_line(region: &Region, theta: f64, spacing: f64) -> Result<(), TestCaseError> {
    let centre = region.centre();
    let polylines = branches(region, centre, theta, spacing);
    let segments: Vec<Vec<Coord>> = polylines
        .chunks_exact(2)
        .flat_map(|pair| {
            let ([p, fork, left], [tip, _, right]) = (pair[0], pair[1]);
            [vec![p, tip], vec![fork, left], vec![fork, right]]
        })
        .collect();
    let pieces = tree_pieces(region, theta, spacing);
    let (a, b) = (total(&pieces), total(&clipped(region, &segments)));
    prop_assert!((a - b).abs() <= 1e-9 * b.max(1.0), "{a} against {b}");
    // The fast path (no clipping in a convex region) gives what clipping gives, but for
    // the pieces of no length that clipping leaves where a branch starts on an edge (which
    // `Region::fill` drops as slivers) and the last bits of the frame's round trip.
    let general: Vec<Vec<Coord>> = clipped(
        region,
        &polylines.iter().map(|p| p.to_vec()).collect::<Vec<_>>(),
    )
    .into_iter()
    .filter(|p| length_of(p) > 1e-9)
    .collect();
    let ours: Vec<&Vec<Coord>> = pieces.iter().filter(|p| length_of(p) > 1e-9).collect();
    prop_assert_eq!(ours.len(), general.len());
    for (a, b) in ours.iter().zip(&general) {
        prop_assert_eq!(a.len(), b.len());
        for (p, q) in a.iter().zip(b) {
            prop_assert!(length(*p - *q) < 1e-9, "{p:?} against {q:?}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Star-like regions, convex (equal radii) or not, with a hole or none, any angle and
    /// spacing: the tree's pieces are its polylines clipped, and print the length its
    /// segments clipped one by one print.
    #[test]
    fn tree_is_its_segments_clipped(
        radii in prop::collection::vec(2.0f64..15.0, 3..14),
        hole in prop::collection::vec(0.5f64..1.5, 3..8),
        holed in any::<bool>(),
        convex in any::<bool>(),
        turn in 0.0f64..TAU,
        theta in 0.0f64..TAU,
        spacing in 0.8f64..16.0,
    ) {
        let radii = if convex { vec![radii[0]; radii.len()] } else { radii };
        let region = region_of(&radii, holed.then_some(&hole[..]), turn);
        check_same_line(&region, theta, spacing)?;
    }
}

/// The compared shapes at their first spacings for 10, 20 and 40%.
#[test]
fn compared_shapes_print_their_segments() {
    for shape in [
        shapes::square(20.0),
        shapes::circle(10.0),
        shapes::holed_square(40.0, 10.0),
        shapes::star(10.0, 4.5),
        shapes::l_shape(20.0),
    ] {
        let region = Region::new(&shape, W).unwrap();
        for rho in [0.1, 0.2, 0.4] {
            check_same_line(&region, 45f64.to_radians(), 2.0 * W / rho).unwrap();
        }
    }
}

/// The turns' sines and cosines written as constants are `math::sin_cos`'s, to the bit;
/// whether two spacings make the same tree is whether their branch counts are equal.
#[test]
fn turn_constants_are_the_computed_ones() {
    for (angle, turn) in [
        (10f64, EVEN),
        (-10.0, ODD),
        (45.0, LEFT_TWIG),
        (-45.0, RIGHT_TWIG),
    ] {
        let (s, c) = crate::math::sin_cos(angle.to_radians());
        assert_eq!(
            (s.to_bits(), c.to_bits()),
            (turn.0.to_bits(), turn.1.to_bits()),
            "{angle}"
        );
    }
    for shape in [
        shapes::star(10.0, 4.5),
        shapes::l_shape(20.0),
        shapes::holed_square(40.0, 10.0),
    ] {
        let region = Region::new(&shape, 0.4).unwrap();
        for (a, b) in [(1.0, 1.1), (4.0, 4.02), (2.0, 8.0), (3.3, 3.3)] {
            assert_eq!(
                same_counts(&region, a, b),
                counts(&region, a) == counts(&region, b)
            );
        }
    }
}

/// A layer's lists are kept between layers (`scratch`): the L's and the star's lightning
/// filled again, after other layers filled with other trees, is the same to the bit.
#[test]
fn layers_with_kept_lists_are_the_same() {
    use crate::infill::{Params, Pattern};
    let bits = |t: &crate::infill::Toolpaths| -> Vec<Vec<[u64; 2]>> {
        t.polylines
            .iter()
            .chain(&t.travels)
            .map(|l| l.0.iter().map(|p| [p.x.to_bits(), p.y.to_bits()]).collect())
            .collect()
    };
    let shapes = [shapes::l_shape(20.0), shapes::star(10.0, 4.5)];
    let regions: Vec<Region> = shapes.iter().map(|s| Region::new(s, W).unwrap()).collect();
    let layer = |region: &Region, density: f64| {
        let params = Params::new(Pattern::Lightning, density, W);
        bits(&region.fill(&params).unwrap())
    };
    let first: Vec<_> = regions.iter().map(|r| layer(r, 0.1)).collect();
    for density in [0.4, 0.05, 0.2] {
        for region in &regions {
            layer(region, density);
        }
        for (region, first) in regions.iter().zip(&first) {
            assert_eq!(&layer(region, 0.1), first);
        }
    }
}

/// The outlines' starts and perimeters found once for a layer serve both of its trees:
/// a tree built with those found for another spacing (and the other tree of the layer
/// built before it) is, to the bit, the tree built with its own.
#[test]
fn trees_sharing_the_outlines_are_the_trees_on_their_own() {
    for shape in [
        shapes::star(10.0, 4.5),
        shapes::l_shape(20.0),
        shapes::holed_square(40.0, 10.0),
        shapes::circle(10.0),
    ] {
        let region = Region::new(&shape, 0.4).unwrap();
        let centre = region.centre();
        for theta in [0.0, 0.8, 2.5, 4.0] {
            let shared = Outlines::new(&region, theta);
            let mut edges = Edges::new(region.rings(), &frame(centre));
            for spacing in [8.0, 5.3, 2.0] {
                let mut first = Vec::new();
                tree(&region, &shared, centre, spacing, &mut edges, |p| {
                    first.push(p.to_vec())
                });
                let mut second = Vec::new();
                lightning_of(&region, &shared, centre, spacing, &mut edges, &mut second);
                let fresh = tree_pieces(&region, theta, spacing);
                let mut own = Vec::new();
                lightning(&region, centre, theta, spacing, &mut edges, &mut own);
                assert!(!fresh.is_empty());
                assert_eq!(first, fresh);
                assert_eq!(second, own);
                assert_eq!(second, fresh);
            }
        }
    }
}

proptest! {
    /// The outlines' direction from one `sin_cos` is `cos` and `sin` apart, to the bit,
    /// at any angle the layer's θ may be (reduced to a turn, and beyond).
    #[test]
    fn sin_cos_is_sin_and_cos(theta in prop_oneof![0.0f64..TAU, -1e3f64..1e3, Just(0.0), Just(TAU)]) {
        let (s, c) = crate::math::sin_cos(theta);
        prop_assert_eq!(s.to_bits(), crate::math::sin(theta).to_bits());
        prop_assert_eq!(c.to_bits(), crate::math::cos(theta).to_bits());
    }
}

proptest! {
    /// `farthest` (each projection found once) is the vertex `Iterator::max_by` over the
    /// projections picks, ties included (whole coordinates and axis directions make
    /// many: the last of equals), and 0 for an empty ring.
    #[test]
    fn farthest_is_max_by_of_the_projections(
        ring in prop::collection::vec((-3i32..4, -3i32..4), 0..12),
        direction in prop_oneof![
            Just((1.0f64, 0.0f64)),
            Just((0.0, -1.0)),
            Just((0.6, 0.8)),
            (-1.0f64..1.0, -1.0f64..1.0),
        ],
    ) {
        let ring: Vec<Coord> = ring
            .into_iter()
            .map(|(x, y)| Coord { x: x as f64, y: y as f64 })
            .collect();
        let direction = Coord { x: direction.0, y: direction.1 };
        let wanted = (0..ring.len())
            .max_by(|&i, &j| dot(ring[i], direction).total_cmp(&dot(ring[j], direction)))
            .unwrap_or(0);
        prop_assert_eq!(farthest(&ring, direction), wanted);
    }
}
