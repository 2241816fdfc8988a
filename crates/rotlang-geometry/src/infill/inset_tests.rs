//! The inset's fast paths against the general ones: round corners placed by a fixed
//! rotation, and the crossing sweep skipped where the rings are proved clear of it.

use super::offset;
use super::shapes;
use geo::Coord;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

/// A star-like ring: vertex i at `radii[i]` in direction `turn + i·2π/n`, about `centre`.
fn radial(radii: &[f64], turn: f64, centre: Coord) -> Vec<Coord> {
    let n = radii.len() as f64;
    radii
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let a = turn + i as f64 * TAU / n;
            centre
                + Coord {
                    x: r * a.cos(),
                    y: r * a.sin(),
                }
        })
        .collect()
}

/// Rings (each a list of points).
type Rings = Vec<Vec<Coord>>;

/// The rings of a region as the inset offsets them, and their offsets by `d` (`None`
/// where an offset declines).
fn offsets(rings: &[(Vec<Coord>, bool)], d: f64) -> Option<(Rings, Rings)> {
    let mut originals = Vec::new();
    let mut moved = Vec::new();
    for (ring, exterior) in rings {
        originals.push(offset::inside_left(ring, *exterior)?);
        moved.push(offset::offset_ring(ring, d, 0.45, *exterior)?);
    }
    Some((originals, moved))
}

#[test]
fn the_compared_shapes_are_proved_clear_at_half_a_nozzle() {
    for (name, region) in [
        ("star", shapes::star(10.0, 4.5)),
        ("L", shapes::l_shape(20.0)),
    ] {
        let ring = (region.0[0].exterior().0.clone(), true);
        let (originals, moved) = offsets(&[ring], 0.2).expect("an offset");
        assert!(offset::clear_of_crossings(&originals, 0.2), "{name}");
        assert!(!offset::crossings(&moved), "{name}");
    }
}

/// A slot narrower than 2d: its sides' offsets cross, and the proof declines (the sweep
/// finds the crossing).
#[test]
fn a_narrow_slot_is_left_to_the_sweep() {
    let slot = vec![
        Coord { x: 0.0, y: 0.0 },
        Coord { x: 10.0, y: 0.0 },
        Coord { x: 10.0, y: 10.0 },
        Coord { x: 5.2, y: 10.0 },
        Coord { x: 5.2, y: 2.0 },
        Coord { x: 4.8, y: 2.0 },
        Coord { x: 4.8, y: 10.0 },
        Coord { x: 0.0, y: 10.0 },
    ];
    let (originals, moved) = offsets(&[(slot.clone(), true)], 1.0).expect("an offset");
    assert!(!offset::clear_of_crossings(&originals, 1.0));
    assert!(offset::crossings(&moved));
    // Two sides 0.4 apart at an inset of 0.19: clear, and no crossing.
    let (originals, moved) = offsets(&[(slot, true)], 0.19).expect("an offset");
    assert!(offset::clear_of_crossings(&originals, 0.19));
    assert!(!offset::crossings(&moved));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Wherever the rings are proved clear, the sweep over their offsets finds no
    /// crossing: star-like outlines with star-like holes (some overlapping the outline or
    /// each other), some rings scrambled so that they cross themselves, insets from a
    /// twentieth of a millimetre to 3 mm.
    #[test]
    fn rings_proved_clear_have_no_crossing(
        outline in prop::collection::vec(2.0f64..12.0, 4..24),
        holes in prop::collection::vec(
            (prop::collection::vec(0.3f64..3.0, 4..10), -6.0f64..6.0, -6.0f64..6.0), 0..3),
        turn in 0.0f64..TAU,
        scramble in any::<bool>(),
        d in 0.05f64..3.0,
    ) {
        let mut outer = radial(&outline, turn, Coord::zero());
        if scramble {
            for pair in outer.chunks_exact_mut(2).step_by(3) {
                pair.swap(0, 1);
            }
        }
        let mut rings = vec![(outer, true)];
        for (radii, x, y) in &holes {
            let mut hole = radial(radii, turn, Coord { x: *x, y: *y });
            hole.reverse();
            rings.push((hole, false));
        }
        if let Some((originals, moved)) = offsets(&rings, d)
            && offset::clear_of_crossings(&originals, d)
        {
            prop_assert!(!offset::crossings(&moved));
        }
    }

    /// A round corner's points, turned by a fixed step: on the circle, in order from one
    /// moved edge's end to the next's start, no chord spanning more than the arc step (so
    /// none strays from the arc more than the step allows), and no more chords than equal
    /// steps of `arc / 1.2` would make.
    #[test]
    fn round_corners_by_a_fixed_step_stay_on_the_arc(
        from in 0.0f64..TAU,
        angle in 0.001f64..(PI - 0.001),
        d in 0.01f64..5.0,
        arc in 0.1f64..0.8,
        b in (-100.0f64..100.0, -100.0f64..100.0),
    ) {
        let b = Coord { x: b.0, y: b.1 };
        let nu = Coord { x: from.cos(), y: from.sin() };
        let nv = Coord { x: (from - angle).cos(), y: (from - angle).sin() };
        let mut points = vec![b + nu * d];
        offset::arc_points(b, nu, nv, d, offset::ArcStep::new(arc), &mut points);
        points.push(b + nv * d);
        let chords = points.len() - 1;
        prop_assert!(chords as f64 <= (angle / (arc / 1.2)).ceil() + 1e-9, "{chords} chords");
        let mut turned = 0.0;
        for w in points.windows(2) {
            let (p, q) = (w[0] - b, w[1] - b);
            prop_assert!(((q.x * q.x + q.y * q.y).sqrt() - d).abs() <= 1e-9 * d.max(1.0));
            // Clockwise, by at most the arc step.
            let step = -(p.x * q.y - p.y * q.x).atan2(p.x * q.x + p.y * q.y);
            prop_assert!(step > 0.0 && step <= arc + 1e-9, "a chord of {step} rad");
            turned += step;
        }
        prop_assert!((turned - angle).abs() < 1e-9);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Travel's crossings, each edge told missed by where the move's line meets it before
    /// the second division, are the crossings found dividing both first, to the bit: moves between points on the
    /// inset's rings (line ends), its vertices and anywhere in its box, on star-like
    /// outlines with holes (moves along edges and of no length included). And the routes
    /// walked from where a move's end meets a ring are those walked from its projection.
    #[test]
    fn crossings_told_before_dividing_are_the_divided_ones(
        outer in prop::collection::vec(4.0f64..15.0, 6..30),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..12), 0..3),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0), (0usize..1000, 0.0f64..1.0), 0u8..3, 0u8..3), 1..24),
    ) {
        let shape = super::tests::holed_radial(&outer, &holes, turn, 2.2);
        let region = super::Region::new(&shape, 0.4).unwrap();
        let rings = region.rings();
        let ends = super::tests::MoveEnds::new(rings);
        let point = |at, kind| ends.point(at, kind);
        let edges = &ends.edges;
        let told = super::travel::Router::new(rings);
        let projecting = super::travel::Router::new(rings).projecting_ends();
        let divided = super::travel::Router::new(rings).dividing_first();
        for (a, b, ka, kb) in moves {
            let (p, q) = (point(a, ka), point(b, kb));
            let (i, _) = a;
            let (e0, e1) = edges[i % edges.len()];
            for (from, to) in [(p, q), (q, p), (p, p), (e0, e1), (p, e1)] {
                prop_assert_eq!(told.crossings_of_move(from, to), divided.crossings_of_move(from, to));
                prop_assert_eq!(told.route(from, to), divided.route(from, to));
                // A walk from a move's end where it meets the ring is the walk from its
                // projection on the ring.
                prop_assert_eq!(told.route(from, to), projecting.route(from, to));
            }
        }
    }
}

proptest! {
    /// The signed area summed point by point with the closing edge last is the indexed
    /// sum (`i` and `(i + 1) % n`) to the bit, on rings of any size, empty ones included.
    #[test]
    fn signed_area_without_wrapping_is_the_indexed_sum(
        ring in prop::collection::vec((-1e3f64..1e3, -1e3f64..1e3), 0..40),
    ) {
        let ring: Vec<Coord> = ring.into_iter().map(|(x, y)| Coord { x, y }).collect();
        let n = ring.len();
        let indexed = (0..n)
            .map(|i| offset::cross(ring[i], ring[(i + 1) % n]))
            .sum::<f64>()
            / 2.0;
        let area = offset::signed_area(&ring);
        prop_assert!(area.to_bits() == indexed.to_bits() || (area == 0.0 && indexed == 0.0));
    }
}

/// The region's inset as `Region` kept it before its rings were read from the raw
/// offset directly: the polygons of `raw_inset`, their rings opened, outlines first, and
/// geo's area of them.
fn rings_and_area_of(inset: &geo::MultiPolygon<f64>) -> (Rings, f64) {
    use geo::Area;
    let open = |ring: &geo::LineString<f64>| {
        let mut c = ring.0.clone();
        if c.len() > 1 && c.first() == c.last() {
            c.pop();
        }
        c
    };
    let mut rings: Rings = inset.0.iter().map(|p| open(p.exterior())).collect();
    for p in &inset.0 {
        rings.extend(p.interiors().iter().map(open));
    }
    (rings, inset.unsigned_area())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// The raw offset's rings as a layer reads them (outline rings borrowed where they
    /// need no cleaning and turn the right way, outlines first, the area without the
    /// polygons) are `raw_inset`'s polygons opened, to the bit, and its area is geo's; a
    /// region's inset made from them when asked is `raw_inset`. Outlines turning either
    /// way, with a repeated point or not, with up to two holes and a second island.
    #[test]
    fn raw_rings_are_the_raw_inset(
        outer in prop::collection::vec(4.0f64..12.0, 3..24),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..10), 0..3),
        island in prop::option::of(prop::collection::vec(1.0f64..3.0, 3..8)),
        turn in 0.0f64..TAU,
        clockwise in any::<bool>(),
        repeat in prop::option::of(0usize..30),
        d in 0.05f64..0.6,
    ) {
        let mut region = super::tests::holed_radial(&outer, &holes, turn, 3.0);
        if clockwise {
            region.0[0].exterior_mut(|ring| ring.0.reverse());
        }
        if let Some(i) = repeat {
            region.0[0].exterior_mut(|ring| {
                let i = i % (ring.0.len() - 1);
                ring.0.insert(i, ring.0[i]);
            });
        }
        if let Some(radii) = island {
            let ring = super::tests::radial_ring(&radii, turn, Coord { x: 30.0, y: 0.0 }, false);
            region.0.push(geo::Polygon::new(ring, vec![]));
        }
        let raw = offset::raw_rings(&region, d, 0.45);
        let inset = offset::raw_inset(&region, d, 0.45);
        prop_assert_eq!(raw.is_some(), inset.is_some());
        if let (Some(raw), Some(inset)) = (raw, inset) {
            let (rings, area) = rings_and_area_of(&inset);
            prop_assert_eq!(&raw.rings, &rings);
            prop_assert_eq!(raw.outlines, inset.0.len());
            prop_assert_eq!(raw.area().to_bits(), area.to_bits());
            prop_assert_eq!(&raw.polygons(), &inset);
            prop_assert_eq!(&raw.into_polygons(), &inset);
        }
        for polygon in &region.0 {
            let ring = &polygon.exterior().0;
            for exterior in [true, false] {
                prop_assert_eq!(
                    offset::inside_left_cow(ring, exterior).map(|c| c.into_owned()),
                    offset::inside_left(ring, exterior)
                );
            }
        }
        // A layer's region reads the rings so: the same rings, area and (when asked)
        // inset as the polygons gave.
        let cleaned = super::region::clean(&region);
        let layer = super::Region::new(&region, 2.0 * d);
        let inset = offset::raw_inset(&cleaned, d, super::region::arc_step(d));
        if let (Ok(layer), Some(inset)) = (layer, inset)
            && super::region::convex_inset(&cleaned, d, 0.45).is_none()
        {
            let (rings, area) = rings_and_area_of(&inset);
            prop_assert_eq!(layer.rings(), &rings[..]);
            prop_assert_eq!(layer.area().to_bits(), area.to_bits());
            prop_assert_eq!(layer.inset(), &inset);
        }
    }
}

/// The round corners' step kept for the last half nozzle is the one computed for it,
/// nozzles alternating; the same region's rings come out the same either way.
#[test]
fn arc_step_kept_for_the_last_nozzle_is_the_computed_one() {
    let star = shapes::star(10.0, 4.5);
    for d in [0.2, 0.2, 0.3, 0.2, 0.05, 0.05, 0.6] {
        let (arc, step) = super::region::arc_and_step(d);
        assert_eq!(arc.to_bits(), super::region::arc_step(d).to_bits(), "{d}");
        let fresh = offset::raw_rings(&star, d, arc).unwrap().rings;
        assert_eq!(
            offset::raw_rings_stepped(&star, d, step).unwrap().rings,
            fresh,
            "{d}"
        );
    }
}

/// A one-ring region gives its lists back to the raw offset's pools when dropped, and the
/// next region's inset is made in them: regions built one after another (each dropping
/// the last, shapes of more and fewer points in turn) have the rings, area and fill of
/// each built while the others live.
#[test]
fn regions_built_in_a_dropped_regions_lists_are_the_fresh_ones() {
    let shapes = [
        shapes::star(10.0, 4.5),
        shapes::l_shape(20.0),
        shapes::star(30.0, 2.0),
        shapes::holed_square(40.0, 10.0),
        shapes::l_shape(5.0),
    ];
    let params = super::Params::new(super::Pattern::Triangles, 0.2, 0.4).angle(30.0);
    let alive: Vec<super::Region> = shapes
        .iter()
        .map(|s| super::Region::new(s, 0.4).unwrap())
        .collect();
    for _ in 0..2 {
        for (shape, fresh) in shapes.iter().zip(&alive) {
            let region = super::Region::new(shape, 0.4).unwrap();
            assert_eq!(region.rings(), fresh.rings());
            assert_eq!(region.area().to_bits(), fresh.area().to_bits());
            assert_eq!(
                super::fill(shape, &params).unwrap(),
                fresh.fill(&params).unwrap()
            );
        }
    }
}

/// The one-pass proof (`star_clear`): the star's inset winds once around its centre and
/// passes; the L's, around the mean of its corners (its reflex corner, behind the round
/// corner's chords), declines; a pentagram (every edge turning the same way about its
/// centre, but twice round) and a bow tie decline, and the sweep finds their crossings.
#[test]
fn one_turn_about_a_point_proves_a_ring_clear() {
    let star = shapes::star(10.0, 4.5);
    let (originals, moved) =
        offsets(&[(star.0[0].exterior().0.clone(), true)], 0.2).expect("an offset");
    assert!(offset::star_clear(&moved[0], offset::mean(&originals[0])));
    let l = shapes::l_shape(20.0);
    let (originals, moved) =
        offsets(&[(l.0[0].exterior().0.clone(), true)], 0.2).expect("an offset");
    assert!(!offset::star_clear(&moved[0], offset::mean(&originals[0])));
    let pentagram = radial(&[5.0; 5], 0.3, Coord::zero());
    let pentagram: Vec<Coord> = (0..5).map(|i| pentagram[(2 * i) % 5]).collect();
    assert!(!offset::star_clear(&pentagram, Coord::zero()));
    assert!(offset::crossings(&[pentagram]));
    let bow_tie = vec![
        Coord { x: 0.0, y: 0.0 },
        Coord { x: 4.0, y: 4.0 },
        Coord { x: 4.0, y: 0.0 },
        Coord { x: 0.0, y: 4.0 },
    ];
    assert!(!offset::star_clear(&bow_tie, Coord { x: 2.0, y: 1.0 }));
    assert!(offset::crossings(&[bow_tie]));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// Wherever a ring is proved clear in one pass, the sweep finds no crossing: star-like
    /// rings (some scrambled, crossing themselves, some wound twice) and their offsets,
    /// about points near and far from their centre.
    #[test]
    fn rings_proved_clear_in_one_pass_have_no_crossing(
        radii in prop::collection::vec(0.5f64..12.0, 3..24),
        turn in 0.0f64..TAU,
        scramble in 0usize..3,
        d in 0.05f64..3.0,
        c in (-3.0f64..3.0, -3.0f64..3.0),
    ) {
        let mut ring = radial(&radii, turn, Coord::zero());
        if scramble == 1 {
            for pair in ring.chunks_exact_mut(2).step_by(3) {
                pair.swap(0, 1);
            }
        } else if scramble == 2 && ring.len() % 2 == 1 {
            // Every second point: twice round the centre.
            let n = ring.len();
            ring = (0..n).map(|i| ring[(2 * i) % n]).collect();
        }
        let c = Coord { x: c.0, y: c.1 };
        if offset::star_clear(&ring, c) {
            prop_assert!(!offset::crossings(std::slice::from_ref(&ring)));
        }
        if let Some(moved) = offset::offset_ring(&ring, d, 0.45, true)
            && offset::star_clear(&moved, c)
        {
            prop_assert!(!offset::crossings(&[moved]));
        }
    }
}

/// The former convex inset (before its rings were kept open and its corners tested as
/// they grew): each ring copied by `convex_ring`, each hole grown with the mitre's reach
/// computed at every corner, each grown point tested inside the outline.
fn former_convex_inset(
    region: &geo::MultiPolygon<f64>,
    d: f64,
    arc: f64,
) -> Option<geo::MultiPolygon<f64>> {
    use super::region::{convex_ring, inset_kept, inside_convex, separated};
    use geo::{BooleanOps, LineString, MultiPolygon, Polygon};
    let grow = |ring: &[Coord]| -> Option<Vec<Coord>> {
        let kept = convex_ring(ring)?;
        let n = kept.len();
        let normal = |a: Coord, b: Coord| {
            let e = b - a;
            let len = crate::math::hypot(e.x, e.y);
            Coord {
                x: e.y / len,
                y: -e.x / len,
            }
        };
        let mut out = Vec::new();
        let (arc_cos, half_arc_cos) = (crate::math::cos(arc), crate::math::cos(arc / 2.0));
        let mut n0 = normal(kept[n - 1], kept[0]);
        for i in 0..n {
            let (b, c) = (kept[i], kept[(i + 1) % n]);
            let n1 = normal(b, c);
            let (sin, cos) = (offset::cross(n0, n1), n0.x * n1.x + n0.y * n1.y);
            let steps = if sin >= 0.0 && cos >= arc_cos {
                1
            } else {
                (crate::math::atan2(sin, cos).max(0.0) / arc)
                    .ceil()
                    .max(1.0) as usize
            };
            if steps == 1 && cos > 0.0 {
                let half_cos = ((1.0 + cos) / 2.0).sqrt();
                if 1.0 / half_cos - 1.0 <= 1.0 - half_arc_cos {
                    out.push(b + (n0 + n1) * (d / (1.0 + cos)));
                    n0 = n1;
                    continue;
                }
            }
            out.push(b + n0 * d);
            if steps > 1 {
                let turn = crate::math::atan2(sin, cos).max(0.0) / steps as f64;
                let (s, c) = crate::math::sin_cos(turn);
                let mut v = n0;
                for _ in 1..steps {
                    v = Coord {
                        x: v.x * c - v.y * s,
                        y: v.x * s + v.y * c,
                    };
                    out.push(b + v * d);
                }
            }
            out.push(b + n1 * d);
            n0 = n1;
        }
        Some(out)
    };
    let closed = |mut ring: Vec<Coord>| {
        ring.push(ring[0]);
        LineString::new(ring)
    };
    let mut out = Vec::new();
    for polygon in &region.0 {
        let exterior = inset_kept(&convex_ring(&polygon.exterior().0)?, d);
        let mut holes = Vec::new();
        for hole in polygon.interiors() {
            holes.push(grow(&hole.0)?);
        }
        if exterior.is_empty() {
            continue;
        }
        let apart = holes
            .iter()
            .all(|h| h.iter().all(|&p| inside_convex(&exterior, p)))
            && holes
                .iter()
                .enumerate()
                .all(|(i, a)| holes[i + 1..].iter().all(|b| separated(a, b)));
        if apart {
            out.push(Polygon::new(
                closed(exterior),
                holes.into_iter().map(closed).collect(),
            ));
        } else {
            let outer = Polygon::new(closed(exterior), vec![]);
            let grown: Vec<Polygon<f64>> = holes
                .into_iter()
                .map(|h| Polygon::new(closed(h), vec![]))
                .collect();
            let grown = if grown.len() > 1 {
                geo::unary_union(&grown)
            } else {
                MultiPolygon::new(grown)
            };
            out.extend(outer.difference(&grown).0);
        }
    }
    Some(MultiPolygon::new(out))
}

/// A convex ring: `n` points on an ellipse at angles spread by `jitter`, about `centre`,
/// clockwise for a hole; one point repeated or a straight corner inserted at `extra`.
fn convex_ring_of(
    n: usize,
    radii: (f64, f64),
    turn: f64,
    jitter: &[f64],
    centre: Coord,
    clockwise: bool,
    extra: Option<(usize, bool)>,
) -> geo::LineString<f64> {
    let mut pts: Vec<Coord> = (0..n)
        .map(|i| {
            let a = turn + (i as f64 + 0.45 * jitter[i % jitter.len()]) * TAU / n as f64;
            centre
                + Coord {
                    x: radii.0 * a.cos(),
                    y: radii.1 * a.sin(),
                }
        })
        .collect();
    if let Some((at, repeat)) = extra {
        let i = at % n;
        let p = if repeat {
            pts[i]
        } else {
            (pts[i] + pts[(i + 1) % n]) / 2.0
        };
        pts.insert(i + 1, p);
    }
    if clockwise {
        pts.reverse();
    }
    pts.push(pts[0]);
    geo::LineString::new(pts)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// The convex inset with its rings kept open, its holes' corners tested as they grow
    /// (read either way round), the mitre told by the least cosine that takes one and
    /// the holes told inside the outline by their boxes is the former one to the bit:
    /// convex outlines (squares, ellipses, a triangle) turning either way with up to
    /// three convex holes (some meeting the outline or each other), an island, a
    /// repeated point or a straight corner; insets from a twentieth of a millimetre to
    /// 4 mm. A region of these made for a layer has the former inset's rings (outlines
    /// first), area and polygons.
    #[test]
    fn convex_rings_are_the_former_convex_inset(
        outer in (3usize..40, 5.0f64..20.0, 5.0f64..20.0),
        jitter in prop::collection::vec(-1.0f64..1.0, 1..8),
        holes in prop::collection::vec(
            (3usize..70, 0.3f64..6.0, -12.0f64..12.0, -12.0f64..12.0, any::<bool>()), 0..4),
        island in any::<bool>(),
        turn in 0.0f64..TAU,
        clockwise in any::<bool>(),
        extra in prop::option::of((0usize..80, any::<bool>(), 0usize..4)),
        d in 0.05f64..4.0,
        arc in prop::sample::select(vec![0.2, 0.45, 0.5, 0.8]),
    ) {
        let (n, rx, ry) = outer;
        let extra_at = |ring: usize| extra.and_then(|(at, repeat, r)| (r == ring).then_some((at, repeat)));
        let exterior = convex_ring_of(n, (rx, ry), turn, &jitter, Coord::zero(), clockwise, extra_at(0));
        let interiors = holes
            .iter()
            .enumerate()
            .map(|(i, &(m, r, x, y, round))| {
                let radii = if round { (r, r) } else { (r, 0.6 * r) };
                convex_ring_of(m, radii, turn, &jitter, Coord { x, y }, !clockwise, extra_at(i + 1))
            })
            .collect();
        let mut region = geo::MultiPolygon::new(vec![geo::Polygon::new(exterior, interiors)]);
        if island {
            let far = convex_ring_of(5, (3.0, 2.0), turn, &jitter, Coord { x: 60.0, y: 5.0 }, false, None);
            region.0.push(geo::Polygon::new(far, vec![]));
        }
        let former = former_convex_inset(&region, d, arc);
        prop_assert_eq!(super::region::convex_inset(&region, d, arc), former.clone());
        // A layer's region (inset by half its nozzle, at that nozzle's arc step).
        let step = super::region::arc_step(d);
        if let (Ok(layer), Some(inset)) = (super::Region::new(&region, 2.0 * d), former_convex_inset(&super::region::clean(&region), d, step)) {
            let (rings, area) = rings_and_area_of(&inset);
            let rings: Rings = rings.into_iter().filter(|r| r.len() >= 3).collect();
            prop_assert_eq!(layer.rings(), &rings[..]);
            prop_assert_eq!(layer.area().to_bits(), area.to_bits());
            prop_assert_eq!(layer.inset(), &inset);
        }
    }

    /// The least cosine that takes a mitre tells every corner as the reach computed at
    /// the corner does: random cosines, and those next to the least, for rooms of the
    /// arc steps a nozzle gives.
    #[test]
    fn least_mitre_cosine_tells_each_corner(
        arc in 0.2f64..0.8,
        cos in -1.0f64..1.0,
    ) {
        let room = 1.0 - crate::math::cos(arc / 2.0);
        let from = super::region::mitre_from(room);
        prop_assert!(super::region::mitre_fits(from, room));
        let below = f64::from_bits(from.to_bits() - 1);
        prop_assert!(!super::region::mitre_fits(below, room));
        let near = f64::from_bits(from.to_bits().wrapping_add((cos.to_bits() % 64).wrapping_sub(32)));
        for c in [cos, near, 1.0, 1.0 + f64::EPSILON, f64::MIN_POSITIVE] {
            prop_assert_eq!(c >= from, c > 0.0 && super::region::mitre_fits(c, room), "{}", c);
        }
    }

    /// One pass over the points finds the bounds, whether the region is clean
    /// (`is_clean`), its first outline's area (to the bit) and the first coordinate out
    /// of range, as the former checks did: rings with a repeated point or not, a value
    /// out of range or not.
    #[test]
    fn survey_is_the_former_checks(
        outer in prop::collection::vec(4.0f64..12.0, 3..24),
        holes in prop::collection::vec(prop::collection::vec(0.5f64..1.5, 3..10), 0..3),
        turn in 0.0f64..TAU,
        repeat in prop::option::of(0usize..30),
        bad in prop::option::of((0usize..60, any::<bool>(), prop::sample::select(vec![f64::NAN, f64::INFINITY, -f64::INFINITY, 2e6, -1.5e6]))),
    ) {
        let mut region = super::tests::holed_radial(&outer, &holes, turn, 3.0);
        if let Some(i) = repeat {
            region.0[0].exterior_mut(|ring| {
                let i = i % (ring.0.len() - 1);
                ring.0.insert(i, ring.0[i]);
            });
        }
        if let Some((i, y, v)) = bad {
            region.0[0].exterior_mut(|ring| {
                let i = i % ring.0.len();
                if y { ring.0[i].y = v } else { ring.0[i].x = v }
            });
        }
        let (mut min, mut max) = (
            Coord { x: f64::INFINITY, y: f64::INFINITY },
            Coord { x: f64::NEG_INFINITY, y: f64::NEG_INFINITY },
        );
        let mut first_bad = None;
        for p in &region.0 {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                for c in &ring.0 {
                    for v in [c.x, c.y] {
                        if first_bad.is_none() && !(v.is_finite() && v.abs() <= super::MAX_COORDINATE) {
                            first_bad = Some(v);
                        }
                    }
                    crate::math::widen(&mut min, &mut max, *c);
                }
            }
        }
        match (super::region::survey(&region), first_bad) {
            (Err(super::Error::Coordinate(v)), Some(b)) => prop_assert_eq!(v.to_bits(), b.to_bits()),
            (Ok(found), None) => {
                prop_assert_eq!((found.min, found.max), (min, max));
                let clean = super::region::is_clean(&region);
                prop_assert_eq!(found.clean, clean);
                let first = offset::signed_area(&region.0[0].exterior().0);
                prop_assert_eq!(found.first_area.map(f64::to_bits), clean.then_some(first.to_bits()));
            }
            (got, want) => prop_assert!(false, "{:?} against {:?}", got.map(|_| ()), want),
        }
    }
}

/// A ring whose corners all turn left but which winds twice (a pentagram's points taken
/// every second one) is no convex ring, as outline or as hole, as before; a square with
/// a square hole (edges with no x component) is one.
#[test]
fn rings_wound_twice_have_no_convex_inset() {
    let five = radial(&[6.0; 5], 0.3, Coord::zero());
    let mut pentagram: Vec<Coord> = (0..5).map(|i| five[(2 * i) % 5]).collect();
    pentagram.push(pentagram[0]);
    let square = shapes::square(40.0).0[0].exterior().clone();
    let mut hole = pentagram.clone();
    hole.reverse();
    for region in [
        geo::MultiPolygon::new(vec![geo::Polygon::new(
            geo::LineString::new(pentagram),
            vec![],
        )]),
        geo::MultiPolygon::new(vec![geo::Polygon::new(
            square,
            vec![geo::LineString::new(hole)],
        )]),
    ] {
        assert!(former_convex_inset(&region, 0.2, 0.45).is_none());
        assert!(super::region::convex_inset(&region, 0.2, 0.45).is_none());
    }
    // Edges with no x component (a square's sides, a hole's) turn the count as before.
    let mut hole = shapes::square(10.0).0[0].exterior().clone();
    hole.0.reverse();
    let boxed = geo::MultiPolygon::new(vec![geo::Polygon::new(
        shapes::square(40.0).0[0].exterior().clone(),
        vec![hole],
    )]);
    let former = former_convex_inset(&boxed, 0.2, 0.45);
    assert!(former.is_some());
    assert_eq!(super::region::convex_inset(&boxed, 0.2, 0.45), former);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// An outline's offset read in one pass (its area's sign, geo's area of it, the
    /// one-pass proof about a point) is `offset_points`, `polygon_area` and `star_clear`
    /// taken apart, to the bit: star-like rings (some scrambled, some wound twice) about
    /// points near and far. A clean ring whose area is known is read in place as
    /// `inside_left_cow` reads it.
    #[test]
    fn outline_read_in_one_pass_is_read_apart(
        radii in prop::collection::vec(0.5f64..12.0, 3..24),
        turn in 0.0f64..TAU,
        scramble in 0usize..3,
        d in 0.05f64..3.0,
        c in (-3.0f64..3.0, -3.0f64..3.0),
        exterior in any::<bool>(),
    ) {
        let mut ring = radial(&radii, turn, Coord::zero());
        if scramble == 1 {
            for pair in ring.chunks_exact_mut(2).step_by(3) {
                pair.swap(0, 1);
            }
        } else if scramble == 2 && ring.len() % 2 == 1 {
            let n = ring.len();
            ring = (0..n).map(|i| ring[(2 * i) % n]).collect();
        }
        let c = Coord { x: c.0, y: c.1 };
        let step = offset::ArcStep::new(0.45);
        if let Some(pts) = offset::inside_left(&ring, true) {
            let apart = offset::offset_ring(&pts, d, 0.45, true);
            for centre in [Some(c), None] {
                let read = offset::offset_read(&pts, d, step, centre);
                prop_assert_eq!(read.as_ref().map(|r| &r.0), apart.as_ref());
                if let (Some((moved, read)), Some(_)) = (read, &apart) {
                    let area = offset::polygon_area(&moved, &[]);
                    prop_assert_eq!(read.area.to_bits(), area.to_bits());
                    prop_assert_eq!(read.star, centre.is_some() && offset::star_clear(&moved, c));
                }
            }
        }
        let mut closed = ring.clone();
        closed.push(ring[0]);
        let area = offset::signed_area(&closed);
        if closed.windows(2).all(|w| w[0] != w[1]) {
            prop_assert_eq!(
                offset::inside_left_known(&closed, exterior, area),
                offset::inside_left_cow(&closed, exterior)
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// A ring found turning clearly both ways has no convex ring, either way round (so
    /// the convex inset is not tried): star-like rings, convex ones, with a repeated
    /// point or a straight corner; and a convex one is never found so.
    #[test]
    fn rings_turning_both_ways_are_not_convex(
        radii in prop::collection::vec(1.0f64..12.0, 3..24),
        turn in 0.0f64..TAU,
        round in any::<bool>(),
        extra in prop::option::of((0usize..30, any::<bool>())),
    ) {
        let mut ring = if round {
            let jitter: Vec<f64> = radii.iter().map(|r| r / 12.0 - 0.5).collect();
            convex_ring_of(radii.len(), (radii[0], radii[0] * 0.7), turn, &jitter, Coord::zero(), false, extra).0
        } else {
            let mut r = radial(&radii, turn, Coord::zero());
            r.push(r[0]);
            r
        };
        for _ in 0..2 {
            let open = &ring[..ring.len() - 1];
            if super::region::turns_both_ways(open) {
                prop_assert!(super::region::convex_ring(&ring).is_none());
                prop_assert!(!round);
            }
            ring.reverse();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Regions with holes built one after another on a thread, each dropped before the
    /// next (their rings' lists then come from the ones given back), have the rings of
    /// the same regions built each on a new thread (nothing given back yet): squares of
    /// random sizes with round holes of random radii and vertex counts, holed squares.
    #[test]
    fn regions_built_from_the_lists_given_back_are_the_same(
        regions in prop::collection::vec((8.0f64..40.0, 0.1f64..0.4, 3usize..70, any::<bool>()), 1..6),
    ) {
        let shape = |&(side, hole, sides, named): &(f64, f64, usize, bool)| {
            if named {
                shapes::holed_square(40.0, 10.0)
            } else {
                let h = side / 2.0;
                let ring = |points: Vec<(f64, f64)>| {
                    geo::LineString::from(points)
                };
                let hole = (0..sides)
                    .map(|i| {
                        let a = TAU * i as f64 / sides as f64;
                        (hole * side * a.cos(), -hole * side * a.sin())
                    })
                    .collect();
                geo::MultiPolygon::new(vec![geo::Polygon::new(
                    ring(vec![(-h, -h), (h, -h), (h, h), (-h, h)]),
                    vec![ring(hole)],
                )])
            }
        };
        let rings_of = |r: &(f64, f64, usize, bool)| {
            super::Region::new(&shape(r), 0.4).map(|region| region.rings().to_vec())
        };
        for r in &regions {
            let fresh = std::thread::scope(|s| s.spawn(|| rings_of(r)).join().unwrap());
            let reused = rings_of(r);
            prop_assert_eq!(reused.is_ok(), fresh.is_ok());
            if let (Ok(a), Ok(b)) = (reused, fresh) {
                prop_assert_eq!(a, b);
            }
        }
    }

    /// The outline a region keeps (for concentric loops) is the region as given, to
    /// the bit, where its one polygon without holes is copied into the lists an earlier
    /// region gave back: random star-like outlines of 3 to 80 points one after another
    /// (each taking the last one's lists, longer or shorter), some with a point repeated
    /// (cleaned: then what a region built on a new thread keeps), some with a hole, some
    /// two polygons (cloned).
    #[test]
    fn outlines_kept_in_the_lists_given_back_are_the_regions(
        outlines in prop::collection::vec(
            (prop::collection::vec(4.0f64..15.0, 3..80), 0.0f64..TAU, 0u8..4),
            1..8,
        ),
    ) {
        for (radii, turn, kind) in &outlines {
            let mut points = radial(radii, *turn, Coord::zero());
            if *kind == 1 {
                points.insert(1, points[1]);
            }
            let polygon = |points: Vec<Coord>, holes| geo::Polygon::new(geo::LineString::new(points), holes);
            let hole = || {
                let mut h = radial(&[1.0, 1.0, 1.0, 1.0], 0.3, Coord::zero());
                h.reverse();
                geo::LineString::new(h)
            };
            let region = geo::MultiPolygon::new(match kind {
                2 => vec![polygon(points, vec![hole()])],
                3 => vec![
                    polygon(points, vec![]),
                    polygon(radial(&[1.0, 1.0, 1.0], 0.0, Coord { x: 40.0, y: 0.0 }), vec![]),
                ],
                _ => vec![polygon(points, vec![])],
            });
            let kept = |region: &geo::MultiPolygon<f64>| {
                super::Region::build(region, 0.4, true).map(|r| r.outline().clone())
            };
            let fresh = std::thread::scope(|s| s.spawn(|| kept(&region)).join().unwrap());
            let reused = kept(&region);
            prop_assert_eq!(reused.is_ok(), fresh.is_ok());
            if let (Ok(a), Ok(b)) = (reused, fresh) {
                let bits = |m: &geo::MultiPolygon<f64>| {
                    m.0.iter()
                        .map(|p| {
                            std::iter::once(p.exterior())
                                .chain(p.interiors())
                                .map(|r| r.0.iter().map(|c| (c.x.to_bits(), c.y.to_bits())).collect::<Vec<_>>())
                                .collect::<Vec<_>>()
                        })
                        .collect::<Vec<_>>()
                };
                prop_assert_eq!(bits(&a), bits(&b));
                if *kind != 1 {
                    prop_assert_eq!(bits(&a), bits(&region));
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// A move `Region::clear_inside` proves inside is the straight move the router
    /// over the inset's rings gives (the fast router and the general one): random
    /// star-like outlines (the raw offset's one ring), moves between random points of
    /// the region's box and points of the inset a little (0 to 1.5 mm) in from it, many
    /// of them passing within half a nozzle of the outline.
    #[test]
    fn moves_proved_inside_from_the_outline_are_the_routers_straight_moves(
        radii in prop::collection::vec(4.0f64..15.0, 5..30),
        turn in 0.0f64..TAU,
        moves in prop::collection::vec(
            ((0usize..1000, 0.0f64..1.0, 0.0f64..1.5, any::<bool>()),
             (0usize..1000, 0.0f64..1.0, 0.0f64..1.5, any::<bool>())),
            1..24,
        ),
    ) {
        let shape = geo::MultiPolygon::new(vec![geo::Polygon::new(
            geo::LineString::new(radial(&radii, turn, Coord::zero())),
            vec![],
        )]);
        let Ok(region) = super::Region::build(&shape, 0.4, true) else {
            return Ok(());
        };
        let rings = region.rings();
        prop_assume!(rings.len() == 1 && region.one_ring_left());
        let ring = &rings[0];
        let n = ring.len();
        let centre = offset::mean(ring);
        // A point of the inset's edge `at` moved `inward` towards the centre, or a point
        // of the box.
        let point = |(at, along, inward, boxed): (usize, f64, f64, bool)| {
            if boxed {
                let (lo, hi) = (region.min, region.max);
                Coord { x: lo.x + (hi.x - lo.x) * along, y: lo.y + (hi.y - lo.y) * inward / 1.5 }
            } else {
                let (a, b) = (ring[at % n], ring[(at + 1) % n]);
                let p = a + (b - a) * along;
                let to = centre - p;
                let length = (to.x * to.x + to.y * to.y).sqrt();
                if length > 0.0 { p + to * (inward / length) } else { p }
            }
        };
        let fast = super::travel::Router::told(rings, true);
        let general = super::travel::Router::new(rings).general();
        for (a, b) in moves {
            let (p, q) = (point(a), point(b));
            if region.clear_inside(p, q) {
                prop_assert_eq!(fast.route(p, q), vec![p, q]);
                prop_assert_eq!(general.route(p, q), vec![p, q]);
            }
        }
    }
}
