//! The erosion's shortcuts against the general code they stand for: the same answers to
//! the bit on random regions (star-like outlines, with and without a hole).

use geo::{Coord, LineString, MultiPolygon, Polygon};
use proptest::prelude::*;

use super::*;

/// A star-like ring: `radii` (fractions of `size`) at even angles about `at`.
fn star_like(radii: &[f64], size: f64, at: Coord, clockwise: bool) -> LineString<f64> {
    let n = radii.len();
    let mut ring: Vec<Coord> = radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let a = if clockwise { -a } else { a };
            at + Coord {
                x: r * size * math::cos(a),
                y: r * size * math::sin(a),
            }
        })
        .collect();
    ring.push(ring[0]);
    LineString::new(ring)
}

/// An outline of `radii` about the origin, with a hole of `hole` radii (a sixth of the
/// outline's smallest radius at most, so that it stays inside) when there are any.
fn region(radii: &[f64], size: f64, hole: &[f64]) -> MultiPolygon<f64> {
    let outline = star_like(radii, size, Coord { x: 0.0, y: 0.0 }, false);
    let smallest = radii.iter().copied().fold(f64::INFINITY, f64::min);
    let holes = if hole.len() >= 3 {
        let scaled: Vec<f64> = hole.iter().map(|r| r * smallest / 6.0).collect();
        vec![star_like(&scaled, size, Coord { x: 0.0, y: 0.0 }, true)]
    } else {
        Vec::new()
    };
    MultiPolygon::new(vec![Polygon::new(outline, holes)])
}

/// Points to test `keep` at: anywhere about the region, and just inside and outside `d`
/// from its edges and vertices (where rounding decides).
fn probes(boundary: &Boundary, d: f64, picks: &[(f64, f64, f64)], size: f64) -> Vec<Coord> {
    let mut out = Vec::new();
    let sides = &boundary.sides;
    for &(s, t, u) in picks {
        out.push(Coord {
            x: (s - 0.5) * 2.4 * size,
            y: (t - 0.5) * 2.4 * size,
        });
        let side = &sides[((u * sides.len() as f64) as usize).min(sides.len() - 1)];
        let e = side.b - side.a;
        let len = math::hypot(e.x, e.y);
        if len == 0.0 {
            continue;
        }
        let normal = Coord {
            x: -e.y / len,
            y: e.x / len,
        };
        for scale in [1.0, 1.0 - 1e-9, 1.0 + 1e-9, 1.0 - 1e-12, -1.0, 0.5] {
            out.push(side.a + e * t + normal * (d * scale));
            out.push(side.a + normal * (d * scale));
        }
        // On the level of a vertex (the ray through it).
        out.push(Coord {
            x: side.a.x - (s - 0.5) * size,
            y: side.a.y,
        });
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// `keep` by runs of edges (far runs passed on one test, their ray crossings counted
    /// from their ends) answers as every edge tested in turn: random regions with and
    /// without a hole of many edges, points anywhere and a rounding from `d` off an edge.
    #[test]
    fn keep_by_runs_is_keep_edge_by_edge(
        radii in proptest::collection::vec(0.3f64..1.0, 3..40),
        hole in proptest::collection::vec(0.8f64..1.0, 0..70),
        size in 1.0f64..200.0,
        depth in 0.001f64..0.8,
        picks in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0), 1..12),
        arc in proptest::collection::vec((0.0f64..1.0, 0.9f64..1.0), 0..12),
    ) {
        let region = region(&radii, size, &hole);
        let eroder = Eroder::new(&region, 0.5);
        let d = depth * size;
        let mut points: Vec<(Coord, Option<Coord>)> =
            probes(&eroder.boundary, d, &picks, size).into_iter().map(|p| (p, None)).collect();
        // About the arcs' vertices, between their chords and the exact arc, some as the
        // middle of a chord of the arc (that arc not asked).
        for (i, &(turn, r)) in arc.iter().enumerate() {
            let fans = &eroder.boundary.arcs.fans;
            if let Some(&(b, ..)) = fans.get(i % fans.len().max(1)) {
                let a = std::f64::consts::TAU * turn;
                let p = b + Coord { x: math::cos(a), y: math::sin(a) } * (r * d);
                points.push((p, if i % 2 == 0 { Some(b) } else { None }));
            }
        }
        for (p, own) in points {
            prop_assert_eq!(
                keep(p, || own, &eroder.boundary, d),
                keep_edge_by_edge(p, own, &eroder.boundary, d),
                "at {:?}, d {}", p, d
            );
        }
    }
}

/// `convex` as it was: each edge worked out from its ends at every use.
fn convex_as_before(pts: &[Coord]) -> f64 {
    let n = pts.len();
    if n < 3 {
        return 0.0;
    }
    let edge = |i: usize| {
        let j = if i + 1 == n { 0 } else { i + 1 };
        pts[j] - pts[i]
    };
    let first = cross(edge(n - 1), edge(0));
    let sign = if first > 0.0 {
        1.0
    } else if first < 0.0 {
        -1.0
    } else {
        return 0.0;
    };
    let mut east = 0;
    let mut prev = edge(n - 1);
    for i in 0..n {
        let e = edge(i);
        if cross(prev, e) * sign <= 0.0 {
            return 0.0;
        }
        let passes = if sign > 0.0 {
            prev.y < 0.0 && e.y >= 0.0
        } else {
            prev.y > 0.0 && e.y <= 0.0
        };
        if passes {
            east += 1;
        }
        prev = e;
    }
    if east == 1 { sign } else { 0.0 }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// One pass for the turn and the bounds: the same turn as before and the same bounds
    /// as `travel::bounds`, on rings convex or nearly (radii jittered), either way round,
    /// some wound twice, some with a repeated or collinear point.
    #[test]
    fn convex_bounded_is_convex_and_bounds(
        radii in proptest::collection::vec(0.9f64..1.0, 3..24),
        at in (-50.0f64..50.0, -50.0f64..50.0),
        clockwise in proptest::bool::ANY,
        twice in proptest::bool::ANY,
        repeat in proptest::option::of(0usize..24),
        nan in proptest::option::of(0usize..24),
    ) {
        let n = radii.len();
        let mut pts: Vec<Coord> = (0..n * if twice { 2 } else { 1 })
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let a = if clockwise { -a } else { a };
                let r = 10.0 * radii[i % n];
                Coord { x: at.0 + r * math::cos(a), y: at.1 + r * math::sin(a) }
            })
            .collect();
        if let Some(k) = repeat {
            let k = k % pts.len();
            pts.insert(k, pts[k]);
        }
        // A NaN where a distance overflowed: passed over by the bounds, as by `min`.
        if let Some(k) = nan {
            let k = k % pts.len();
            pts[k].x = f64::NAN;
        }
        let (turn, (lo, hi)) = convex_bounded(&pts);
        prop_assert_eq!(turn, convex_as_before(&pts));
        if turn != 0.0 {
            prop_assert_eq!((lo, hi), crate::infill::travel::bounds(&pts));
        }
    }
}

/// The runs cover every edge once, each run's edges one ring's, end to start.
#[test]
fn runs_cover_each_ring_end_to_start() {
    let region = crate::infill::shapes::holed_square(40.0, 10.0);
    let eroder = Eroder::new(&region, 0.5);
    let b = &eroder.boundary;
    assert_eq!(b.sides.len(), 4 + 64);
    let mut next = 0;
    for run in &b.runs {
        assert_eq!(run.sides.start, next);
        next = run.sides.end;
        let sides = &b.sides[run.sides.clone()];
        assert!(sides.len() <= RUN);
        assert!(!sides.is_empty());
        assert!(sides.windows(2).all(|w| w[0].b == w[1].a));
        assert_eq!(
            (run.start, run.end),
            (sides[0].a.y, sides[sides.len() - 1].b.y)
        );
    }
    assert_eq!(next, b.sides.len());
    // The square's four edges one run, the hole's 64 eight.
    assert_eq!(b.runs.len(), 1 + 8);
    let star = Eroder::new(&crate::infill::shapes::star(10.0, 4.5), 0.5);
    assert_eq!(star.boundary.runs.len(), 1);
}

/// A convex ring: `radii` (near 1, so that it stays convex) times `size` about `at`,
/// starting at `phase` of a turn.
fn convex_ring(
    radii: &[f64],
    size: f64,
    at: (f64, f64),
    phase: f64,
    clockwise: bool,
) -> Vec<Coord> {
    let n = radii.len();
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * (i as f64 + phase) / n as f64;
            let a = if clockwise { -a } else { a };
            Coord {
                x: at.0 + size * radii[i] * math::cos(a),
                y: at.1 + size * radii[i] * math::sin(a),
            }
        })
        .collect()
}

/// A cut as bits: rings, segments, parameters and point.
type CutBits = ([usize; 2], [usize; 2], [u64; 2], [u64; 2]);

/// The cuts as bits, to compare two finders' to the bit.
fn cut_bits(cuts: &[Cut]) -> Vec<CutBits> {
    cuts.iter()
        .map(|c| {
            (
                c.ring,
                c.seg,
                [c.t[0].to_bits(), c.t[1].to_bits()],
                [c.at.x.to_bits(), c.at.y.to_bits()],
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// Convex rings that meet (an outline's offset and its holes' grown ones, holes
    /// crossing it and one another, some sharing a corner's height or width): the pairs'
    /// finder gives the sweep's cuts to the bit, in its order, and its tangencies.
    #[test]
    fn convex_pairs_cut_as_the_sweep(
        outline in proptest::collection::vec(0.97f64..1.0, 3..24),
        holes in proptest::collection::vec(
            (
                proptest::collection::vec(0.97f64..1.0, 3..70),
                0.05f64..1.2,
                (-1.2f64..1.2, -1.2f64..1.2),
                0.0f64..1.0,
            ),
            1..4,
        ),
        size in 1.0f64..100.0,
        phase in 0.0f64..1.0,
        snap in proptest::bool::ANY,
    ) {
        let mut raws = vec![Raw::of(convex_ring(&outline, size, (0.0, 0.0), phase, false))];
        for (radii, r, (x, y), phase) in &holes {
            let mut pts = convex_ring(radii, size * r, (x * size, y * size), *phase, true);
            if snap {
                // A hole's point on the outline's first point's height: touching boxes.
                pts[0].y = raws[0].pts[0].y;
            }
            raws.push(Raw::of(pts));
        }
        let mut turns = Vec::new();
        if apart(&raws, &mut turns) == Layout::Convex {
            let mut scratch = (Vec::new(), Vec::new(), Vec::new());
            let (mut fast, mut swept) = (Vec::new(), Vec::new());
            let found = convex_crossings(&raws, &turns, &mut scratch, &mut fast);
            let sweep = crossings(&raws, &mut Sweep::default(), &mut swept);
            prop_assert_eq!(found, Some(sweep));
            if sweep {
                prop_assert_eq!(cut_bits(&fast), cut_bits(&swept));
            }
        }
    }
}

/// The pairs' finder is asked where a hole's offset crosses the outline's: the holed
/// square's loops past the hole meeting the outline get their cuts from it.
#[test]
fn a_hole_crossing_the_outline_is_cut_by_pairs() {
    let region = crate::infill::shapes::holed_square(40.0, 10.0);
    let mut eroder = Eroder::new(&region, 0.5);
    let rings = eroder.rings(5.2).expect("cut, not declined");
    assert_eq!(apart(&eroder.raws, &mut eroder.turns), Layout::Convex);
    assert_eq!(eroder.cuts.len(), 8);
    // Four corner pieces, each made of two pieces of the outline's offset and one of the
    // hole's.
    assert_eq!(rings.len(), 4);
    let mut swept = Vec::new();
    assert!(crossings(&eroder.raws, &mut Sweep::default(), &mut swept));
    assert_eq!(cut_bits(&eroder.cuts), cut_bits(&swept));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A ring whose corners are all mitres is filled from its mitres in one pass: the
    /// same points to the bit as the corners read one by one, and the same rings, on
    /// convex outlines with and without a hole (their corners mitres) and star-like ones
    /// (tips and arcs: the general pass).
    #[test]
    fn mitres_fill_as_the_corners(
        radii in proptest::collection::vec(0.95f64..1.0, 3..40),
        hole in proptest::collection::vec(0.8f64..1.0, 0..70),
        size in 1.0f64..200.0,
        depths in proptest::collection::vec(0.001f64..0.8, 1..6),
    ) {
        let region = region(&radii, size, &hole);
        let mut eroder = Eroder::new(&region, 0.5);
        let mut general = Eroder::new(&region, 0.5);
        for depth in depths {
            let d = depth * size;
            let rings = eroder.rings(d);
            // The general pass: no ring's mitres listed.
            let _ = general.rings(d);
            for raw in &mut general.raws {
                raw.mitres.clear();
            }
            prop_assert_eq!(general.rings(d), rings, "by {}", d);
            for (fast, slow) in eroder.raws.iter().zip(&general.raws) {
                let bits = |pts: &[Coord]| -> Vec<(u64, u64)> {
                    pts.iter().map(|c| (c.x.to_bits(), c.y.to_bits())).collect()
                };
                prop_assert_eq!(bits(&fast.pts), bits(&slow.pts));
            }
        }
        prop_assert!(eroder.raws.iter().all(|r| r.mitres.len() == r.pts.len() || r.mitres.is_empty()));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// Cuts placed by segment come in the order the library's sort leaves them: random
    /// cuts on rings of random sizes, several on one segment, some at the same parameter
    /// (left to the library's sort), parameters of either sign and zero's.
    #[test]
    fn cuts_placed_by_segment_are_sorted_cuts(
        sizes in proptest::collection::vec(3usize..150, 1..10),
        picks in proptest::collection::vec(
            ((0usize..10, 0usize..150, -2i32..40), (0usize..10, 0usize..150, -2i32..40)),
            0..40,
        ),
    ) {
        let raws: Vec<Raw> = sizes
            .iter()
            .map(|&n| Raw::of(vec![Coord { x: 0.0, y: 0.0 }; n]))
            .collect();
        let side = |(r, s, t): (usize, usize, i32)| {
            let r = r % sizes.len();
            // Few parameters: ties happen; -0.0 and 0.0 told apart as `total_cmp` does.
            let t = if t == -2 { -0.0 } else { f64::from(t) / 39.0 };
            (r, s % sizes[r], t)
        };
        let cuts: Vec<Cut> = picks
            .iter()
            .map(|&(e, f)| {
                let (e, f) = (side(e), side(f));
                Cut { ring: [e.0, f.0], seg: [e.1, f.1], t: [e.2, f.2], at: Coord { x: 0.0, y: 0.0 } }
            })
            .collect();
        let mut placed = Vec::new();
        let mut scratch = (Vec::new(), Vec::new(), Vec::new());
        // Twice on the same buffers: the heads left from the first must not matter.
        for _ in 0..2 {
            place_cuts(&raws, &cuts, &mut placed, &mut scratch);
            let mut sorted = Vec::new();
            library_order(&cuts, &mut sorted);
            let bits = |h: &[(usize, usize, f64, usize)]| -> Vec<(usize, usize, u64, usize)> {
                h.iter().map(|&(r, s, t, id)| (r, s, t.to_bits(), id)).collect()
            };
            prop_assert_eq!(bits(&placed), bits(&sorted));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// `Raw::own` names the arc of every chord, after sharp tips are closed too (their
    /// points move up): each segment it names is a chord `d` from that vertex at both
    /// ends, and it names as many as the arcs have chords.
    #[test]
    fn each_chord_is_known_by_its_arc(
        radii in proptest::collection::vec(0.2f64..1.0, 3..16),
        hole in proptest::collection::vec(0.8f64..1.0, 0..12),
        size in 4.0f64..25.0,
        depth in 0.01f64..0.6,
    ) {
        let region = region(&radii, size, &hole);
        let mut eroder = Eroder::new(&region, 0.5);
        let d = depth * size;
        let _ = eroder.rings(d);
        for raw in &eroder.raws {
            let n = raw.pts.len();
            let mut named = 0;
            for i in 0..n {
                if let Some(b) = raw.own(i) {
                    named += 1;
                    for p in [raw.pts[i], raw.pts[(i + 1) % n]] {
                        let r = math::hypot((p - b).x, (p - b).y);
                        prop_assert!((r - d).abs() <= 1e-9 * (d + size), "{} from {:?}, not {}", r, b, d);
                    }
                }
            }
            prop_assert_eq!(named, raw.arcs.iter().map(|a| a.1).sum::<usize>());
        }
    }
}

/// The grid's cuts of one ring against the sweep's: the same answer (a tangency found by
/// both), and the same cuts to the bit in the same order.
fn ring_as_the_sweep(pts: Vec<Coord>) -> Result<(), TestCaseError> {
    let raws = vec![Raw::of(pts)];
    let (mut fast, mut swept) = (Vec::new(), Vec::new());
    let mut scratch = (Vec::new(), Vec::new(), Vec::new());
    let found = ring_crossings(&raws[0].pts, &mut scratch, &mut fast);
    let sweep = crossings(&raws, &mut Sweep::default(), &mut swept);
    prop_assert_eq!(found, Some(sweep));
    if sweep {
        prop_assert_eq!(cut_bits(&fast), cut_bits(&swept));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// One ring of 3 to 64 segments laid on the grid is cut as the sweep cuts it: rings
    /// about a centre with radii and angles jittered (crossing themselves where a radius
    /// is small or an angle runs back, some wound twice), or points anywhere in a box
    /// (crossing everywhere); some snapped to a coarse lattice (points repeated, segments
    /// touching, overlapping along a line, sharing a least `x`: the sweep's ties).
    #[test]
    fn one_ring_on_a_grid_is_cut_as_the_sweep(
        points in proptest::collection::vec(
            (0.05f64..1.0, -0.7f64..0.7, 0.0f64..1.0, 0.0f64..1.0),
            3..65,
        ),
        scattered in proptest::bool::ANY,
        twice in proptest::bool::ANY,
        size in 0.001f64..1000.0,
        at in (-100.0f64..100.0, -100.0f64..100.0),
        snap in proptest::option::of(2.0f64..12.0),
    ) {
        let n = points.len();
        let turns = if twice { 2.0 } else { 1.0 };
        let pts: Vec<Coord> = points
            .iter()
            .enumerate()
            .map(|(i, &(r, jitter, x, y))| {
                let (x, y) = if scattered {
                    (x - 0.5, y - 0.5)
                } else {
                    let a = std::f64::consts::TAU * turns * (i as f64 + jitter) / n as f64;
                    (r * math::cos(a), r * math::sin(a))
                };
                let (x, y) = match snap {
                    Some(k) => ((x * k).round() / k, (y * k).round() / k),
                    None => (x, y),
                };
                Coord { x: at.0 + size * x, y: at.1 + size * y }
            })
            .collect();
        ring_as_the_sweep(pts)?;
    }

    /// The raw rings of random star-like outlines' erosions (a star's loops pinching and
    /// their tips' swallowtails), each alone, are cut on the grid as by the sweep.
    #[test]
    fn eroded_rings_on_a_grid_are_cut_as_the_sweep(
        radii in proptest::collection::vec(0.2f64..1.0, 3..14),
        size in 1.0f64..50.0,
        depths in proptest::collection::vec(0.01f64..0.6, 1..6),
    ) {
        let region = region(&radii, size, &[]);
        let mut eroder = Eroder::new(&region, 0.5);
        for depth in depths {
            let _ = eroder.rings(depth * size);
            let pts = eroder.raws[0].pts.clone();
            if (3..=64).contains(&pts.len()) {
                ring_as_the_sweep(pts)?;
            }
        }
    }
}

/// The grid is asked only for one ring of 3 to 64 finite points; the sweep decides the
/// rest.
#[test]
fn the_grid_declines_what_it_is_not_for() {
    let ring = |n: usize| -> Vec<Coord> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * 3.0 * i as f64 / n as f64;
                Coord {
                    x: math::cos(a),
                    y: math::sin(a),
                }
            })
            .collect()
    };
    let mut scratch = (Vec::new(), Vec::new(), Vec::new());
    let mut cuts = Vec::new();
    assert_eq!(ring_crossings(&ring(65), &mut scratch, &mut cuts), None);
    assert_eq!(ring_crossings(&ring(2), &mut scratch, &mut cuts), None);
    for bad in [f64::NAN, f64::INFINITY] {
        let mut pts = ring(20);
        pts[7].y = bad;
        assert_eq!(ring_crossings(&pts, &mut scratch, &mut cuts), None);
    }
    // Bounds too wide to measure.
    let mut pts = ring(20);
    pts[3].x = -f64::MAX;
    pts[9].x = f64::MAX;
    assert_eq!(ring_crossings(&pts, &mut scratch, &mut cuts), None);
    // A ring wound three times crosses itself at every turn: found.
    assert_eq!(
        ring_crossings(&ring(64), &mut scratch, &mut cuts),
        Some(true)
    );
    assert!(!cuts.is_empty());
}

/// A star's loop where its arms pinch (one ring of 35 segments, 5 cuts at 20%) goes to
/// the grid, with the sweep's cuts.
#[test]
fn the_stars_pinched_loop_is_cut_on_the_grid() {
    let region = crate::infill::shapes::star(10.0, 4.5);
    let mut eroder = Eroder::new(&region, 0.5);
    let mut seen = false;
    for k in 1..40 {
        let d = 0.1 * k as f64;
        let _ = eroder.rings(d);
        let raws = &eroder.raws;
        if raws.len() == 1 && !star_shaped(&raws[0].pts) {
            let mut scratch = (Vec::new(), Vec::new(), Vec::new());
            let (mut fast, mut swept) = (Vec::new(), Vec::new());
            let found = ring_crossings(&raws[0].pts, &mut scratch, &mut fast);
            assert_eq!(
                found,
                Some(crossings(raws, &mut Sweep::default(), &mut swept))
            );
            assert_eq!(cut_bits(&fast), cut_bits(&swept));
            seen |= !fast.is_empty();
        }
    }
    assert!(seen);
}

/// A raw offset with its sharp tips closed as before: filled through each tip's vertex,
/// then each tip's three points replaced by its mitre afterwards (`Raw::close_tips`).
fn closed_afterwards(eroder: &Eroder, r: usize, d: f64) -> Raw {
    let corners = &eroder.corners[r];
    let mut raw = Raw::default();
    let check = d >= eroder.safes[r].0;
    raw.fill(corners, &eroder.boundary.arcs.directions, d, false, check);
    raw.tips.clear();
    let mut at = 0;
    for corner in corners {
        match corner {
            Corner::Mitre { .. } => at += 1,
            Corner::Tip { .. } => {
                raw.tips.push((at, None));
                at += 3;
            }
            Corner::Arc { inner, .. } => at += 2 + inner.len(),
        }
    }
    if !raw.tips.is_empty() {
        raw.close_tips();
    }
    raw
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// Sharp tips closed from the corners as the raw offset is filled are the tips
    /// closed afterwards: the same points to the bit, the same arcs and the same
    /// directions along, on star-like outlines (sharp tips, some two in a row) with and
    /// without a hole, at depths where the tips close, where they do not and where two
    /// tips' mitres come out of order.
    #[test]
    fn tips_closed_while_filling_are_tips_closed_after(
        radii in proptest::collection::vec(0.1f64..1.0, 3..12),
        hole in proptest::collection::vec(0.8f64..1.0, 0..8),
        scattered in proptest::option::of(
            proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 3..8),
        ),
        size in 1.0f64..50.0,
        depths in proptest::collection::vec(0.001f64..0.8, 1..6),
    ) {
        // Or an outline of points anywhere in a square (crossing itself, sharp tips in a
        // row: their mitres come out of order).
        let region = match scattered {
            Some(points) => {
                let mut ring: Vec<Coord> =
                    points.iter().map(|&(x, y)| Coord { x: x * size, y: y * size }).collect();
                ring.push(ring[0]);
                MultiPolygon::new(vec![Polygon::new(LineString::new(ring), Vec::new())])
            }
            None => region(&radii, size, &hole),
        };
        let mut eroder = Eroder::new(&region, 0.5);
        for depth in depths {
            let d = depth * size;
            let _ = eroder.rings(d);
            fills_as_closed_afterwards(&eroder, d)?;
        }
    }
}

/// Each of the eroder's raw offsets as filled for `d` is the one filled through its tips
/// and closed afterwards, to the bit.
fn fills_as_closed_afterwards(eroder: &Eroder, d: f64) -> Result<(), TestCaseError> {
    let bits = |pts: &[Coord]| -> Vec<(u64, u64)> {
        pts.iter().map(|c| (c.x.to_bits(), c.y.to_bits())).collect()
    };
    let along = |a: &[Option<Coord>]| -> Vec<Option<(u64, u64)>> {
        a.iter()
            .map(|c| c.map(|c| (c.x.to_bits(), c.y.to_bits())))
            .collect()
    };
    for r in 0..eroder.corners.len() {
        let before = closed_afterwards(eroder, r, d);
        let now = &eroder.raws[r];
        prop_assert_eq!(bits(&now.pts), bits(&before.pts), "by {}", d);
        prop_assert_eq!(along(&now.along), along(&before.along));
        prop_assert_eq!(&now.arcs, &before.arcs);
    }
    Ok(())
}

/// An outline crossing itself whose two sharp tips in a row have mitres out of order
/// along the edge between them at some depths, and in order at others: no tip closed
/// there, as before.
#[test]
fn tips_whose_mitres_come_out_of_order_stay_open() {
    let ring: Vec<Coord> = [
        (19.328, 10.66),
        (34.42, 25.184),
        (30.556, 17.996),
        (15.52, 26.66),
        (37.104, 7.652),
        (19.328, 10.66),
    ]
    .iter()
    .map(|&(x, y)| Coord { x, y })
    .collect();
    let region = MultiPolygon::new(vec![Polygon::new(LineString::new(ring), Vec::new())]);
    let mut eroder = Eroder::new(&region, 0.5);
    let (mut open, mut closed) = (0, 0);
    for k in 1..60 {
        let d = 0.25 * k as f64;
        let _ = eroder.rings(d);
        fills_as_closed_afterwards(&eroder, d).unwrap();
        let mut raw = Raw::default();
        let closing = raw.tip_mitres(&eroder.corners[0], d);
        if closing {
            closed += 1;
        } else if raw.tips.iter().any(|t| t.1.is_some()) {
            open += 1;
        }
    }
    assert!(open > 0 && closed > 0, "{open} {closed}");
}
