//! How fast an erosion's perimeter drops at the region's mitred corners, for
//! concentric's test that part of the region ended between two loops (`concentric.rs`:
//! where it did, a middle ring fills the band left). That test expected an offset to
//! shrink each outline's perimeter by 2π per unit of distance, which is true of rounded
//! corners. A convex corner stays sharp in an erosion (its mitre): there the perimeter
//! drops by `2·tan(θ/2)` per unit, θ the corner's turn, not θ. The star's five 45° tips
//! drop 12.4 spacings a step more than 2π (18.6 in all): the test took that for a part
//! ending at every step, and made a middle ring (an erosion, and every point of it
//! measured) that printed nothing, 85k of the star's 157k instructions a layer at 40%.
//!
//! Only corners whose own middle stretch is short are counted: about a corner of inside
//! angle α, the middle ring (half a spacing s past the last loop) has its mitre M at
//! `c = s/(2·sin(α/2))` from the next loop's mitre I, and a point P of it t along an
//! edge from M is `|P − I|² = t² − 2tc·cos(α/2) + c²` from I (nearer the next loop's
//! edges, s/2, where its foot falls on them). It is far from the next loop (over ¾ s,
//! `uncovered`) for `t < c·cos(α/2) − sqrt(c²·cos²(α/2) − c² + (¾s)²)`, a stretch of
//! under 1.5 spacings on both sides of M where `sin α > 2/3` (α over 41.8°): with the
//! middle points half a spacing apart and stretches under a spacing left out, such a
//! stretch prints a piece of a spacing at most, or nothing (the star's tips, 1.28
//! spacings, printed nothing at any density). A sharper tip leaves a stretch worth a
//! line (a 30° tip's is 2.6 spacings): it is not counted, and its drop makes the middle
//! ring as before.

use geo::{Coord, MultiPolygon};

/// The largest `tan(θ/2)` counted, θ a corner's turn: the turn `π − asin(2/3)`, an
/// inside angle of 41.8° (the module's doc: a blunter corner's own middle stretch is
/// under 1.5 spacings). `sin θ / (1 + cos θ)` with `sin θ = 2/3`, `cos θ = −√5/3`:
/// `2 / (3 − √5) = (3 + √5) / 2`.
const SHARPEST: f64 = 2.618_033_988_749_895;

/// What the region's convex corners still present at `depth` (the distance eroded from
/// the region itself) add to an erosion's perimeter drop, per unit of distance, beyond
/// the turn that 2π counts: the sum of `2·tan(θ/2) − θ` over them ([`corners`] lists
/// them; this is for one distance).
#[cfg(test)]
pub(crate) fn excess(region: &MultiPolygon<f64>, depth: f64) -> f64 {
    let mut list = Vec::new();
    corners(region, &mut list);
    excess_at(&list, depth)
}

/// [`excess`] from the corners [`corners`] listed.
pub(crate) fn excess_at(corners: &[(f64, f64)], depth: f64) -> f64 {
    corners
        .iter()
        .filter(|&&(until, _)| depth < until)
        .map(|&(_, excess)| excess)
        .sum()
}

/// Each convex corner of the region no sharper than [`SHARPEST`] allows, into `out` (emptied first): the distance until
/// which it is there, and its `2·tan(θ/2) − θ`.
///
/// A corner is there while both its edges are: an edge moved in by `depth` is shorter
/// by `depth·(tan(θ₀/2) + tan(θ₁/2))`, its ends' convex turns (a reflex end, drawn as an
/// arc about its vertex, shortens it by nothing), and it is gone past its length over
/// that rate. A tip eaten by another part of the region (a hole's loops meeting it)
/// still counts: the drop test's margin, not more.
///
/// Each ring is read with the region on its left (outlines counter-clockwise, holes
/// clockwise, whatever the ring's own order); a ring with no area adds nothing. Only a
/// convex corner and its edges are measured (a round hole's many reflex corners cost a
/// product each).
pub(crate) fn corners(region: &MultiPolygon<f64>, out: &mut Vec<(f64, f64)>) {
    out.clear();
    for polygon in &region.0 {
        let exterior = std::iter::once((polygon.exterior(), true));
        for (ring, outline) in exterior.chain(polygon.interiors().iter().map(|r| (r, false))) {
            ring_corners(&ring.0, outline, out);
        }
    }
}

/// [`corners`] of one ring (closed or not).
fn ring_corners(ring: &[Coord], outline: bool, out: &mut Vec<(f64, f64)>) {
    let pts = match ring {
        [first, .., last] if first == last => &ring[..ring.len() - 1],
        _ => ring,
    };
    let n = pts.len();
    if n < 3 {
        return;
    }
    // Twice the signed area (the shoelace), each point and the next, then the closing.
    let area = pts
        .windows(2)
        .map(|w| w[0].x * w[1].y - w[0].y * w[1].x)
        .sum::<f64>()
        + (pts[n - 1].x * pts[0].y - pts[n - 1].y * pts[0].x);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    // +1 where the ring runs with the region on its left.
    let side = if (area > 0.0) == outline { 1.0 } else { -1.0 };
    // Corner i is at point i, between edge i − 1 and edge i.
    let at = |i: usize| {
        pts[if i >= 2 * n {
            i - 2 * n
        } else if i >= n {
            i - n
        } else {
            i
        }]
    };
    let edge = |i: usize| at(i + 1) - at(i);
    // (A plain square root, not `hypot`: no length of a region nears overflowing, and
    // the drop test's margin is four spacings.)
    let length = |e: Coord| (e.x * e.x + e.y * e.y).sqrt();
    // tan(θ/2) = sin θ / (1 + cos θ) of the turn from `u` to `v`, both scaled by the
    // edges' lengths; 0 where not convex (an arc moves no edge's end along it).
    let tan = |u: Coord, v: Coord| {
        let sin = side * (u.x * v.y - u.y * v.x);
        if sin <= 0.0 {
            0.0
        } else {
            sin / (length(u) * length(v) + (u.x * v.x + u.y * v.y))
        }
    };
    // Until when an edge is there, its ends' `tan(θ/2)` given.
    let until = |length: f64, t0: f64, t1: f64| {
        let rate = t0 + t1;
        if rate > 0.0 {
            length / rate
        } else {
            f64::INFINITY
        }
    };
    // Each corner's turn from the edge before, kept from the corner before (a reflex
    // corner costs a product and a comparison); a convex one asks its neighbours'.
    let mut u = edge(n - 1);
    for i in 0..n {
        let v = edge(i);
        let sin = side * (u.x * v.y - u.y * v.x);
        let t = if sin > 0.0 { tan(u, v) } else { 0.0 };
        let before = u;
        u = v;
        if t <= 0.0 || t > SHARPEST {
            continue;
        }
        let (ahead, behind) = (edge(i + 1), edge(i + 2 * n - 2));
        let there =
            until(length(before), tan(behind, before), t).min(until(length(v), t, tan(v, ahead)));
        // 2·tan(θ/2) − θ, θ = 2·atan(tan(θ/2)).
        let excess = 2.0 * (t - atan(t));
        if excess.is_finite() && there > 0.0 {
            out.push((there, excess));
        }
    }
}

/// `atan t` for `0 ≤ t ≤ SHARPEST` in plain arithmetic, to some 1e-9: halved twice
/// (`atan t = 2·atan(t / (1 + sqrt(1 + t²)))`, to 0.31 at most), then its series to the
/// 19th power. (libm's `atan2` was 200 instructions a corner, a twentieth of the star's
/// layer's test; the drop test's margin is four spacings.)
fn atan(t: f64) -> f64 {
    let half = |x: f64| x / (1.0 + (1.0 + x * x).sqrt());
    let x = half(half(t));
    let x2 = x * x;
    // 1 − x²/3 + x⁴/5 − …, to x¹⁸/19, by Horner's rule from the last term.
    let series = [17.0, 15.0, 13.0, 11.0, 9.0, 7.0, 5.0, 3.0, 1.0]
        .iter()
        .fold(1.0 / 19.0, |acc, &k| 1.0 / k - x2 * acc);
    4.0 * x * series
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{LineString, MultiPolygon, Polygon};
    use std::f64::consts::PI;

    fn region(outline: &[(f64, f64)], holes: &[&[(f64, f64)]]) -> MultiPolygon<f64> {
        let ring = |pts: &[(f64, f64)]| LineString::from(pts.to_vec());
        MultiPolygon(vec![Polygon::new(
            ring(outline),
            holes.iter().map(|h| ring(h)).collect(),
        )])
    }

    #[test]
    fn a_squares_corners_add_two_less_a_half_turn_each() {
        let square = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        let expected = 4.0 * (2.0 - PI / 2.0);
        assert!((excess(&region(&square, &[]), 1.0) - expected).abs() < 1e-12);
        // Clockwise, the same square.
        let mut cw = square;
        cw.reverse();
        assert!((excess(&region(&cw, &[]), 1.0) - expected).abs() < 1e-12);
        // Past half its side every edge is gone.
        assert_eq!(excess(&region(&square, &[]), 5.0), 0.0);
    }

    #[test]
    fn a_holes_corners_are_reflex_and_add_nothing() {
        let square = [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)];
        let hole = [(15.0, 15.0), (25.0, 15.0), (25.0, 25.0), (15.0, 25.0)];
        let alone = excess(&region(&square, &[]), 1.0);
        assert!((excess(&region(&square, &[&hole]), 1.0) - alone).abs() < 1e-12);
    }

    /// An isosceles triangle with its tip of `tip` degrees at the origin, 10 high.
    fn triangle(tip: f64) -> (MultiPolygon<f64>, f64) {
        let h = 10.0;
        let half = h * (tip / 2.0).to_radians().tan();
        // The inscribed circle's radius: every edge gone past it, none before.
        let r = half * h / (half + (h * h + half * half).sqrt());
        (region(&[(0.0, 0.0), (h, -half), (h, half)], &[]), r)
    }

    fn t(turn: f64) -> f64 {
        2.0 * (turn / 2.0).tan() - turn
    }

    #[test]
    fn a_tip_counts_until_its_edges_are_eaten() {
        let (tri, r) = triangle(50.0);
        let all = t(PI - 50f64.to_radians()) + 2.0 * t(PI - 65f64.to_radians());
        let got = excess(&tri, 0.1);
        assert!((got - all).abs() < 1e-9, "{got} vs {all}");
        assert!((excess(&tri, r * 0.999) - all).abs() < 1e-9);
        assert_eq!(excess(&tri, r * 1.001), 0.0);
    }

    /// A tip sharper than 41.8° is not counted (its middle stretch is worth a line), the
    /// corners beside it are; 42° is.
    #[test]
    fn a_tip_sharper_than_41_8_degrees_is_not_counted() {
        let (tri, r) = triangle(30.0);
        let blunt = 2.0 * t(PI - 75f64.to_radians());
        assert!((excess(&tri, 0.1) - blunt).abs() < 1e-9);
        assert!((excess(&tri, r * 0.999) - blunt).abs() < 1e-9);
        let (tri, _) = triangle(41.0);
        assert!((excess(&tri, 0.1) - 2.0 * t(PI - 69.5f64.to_radians())).abs() < 1e-9);
        let (tri, _) = triangle(42.0);
        let all = t(PI - 42f64.to_radians()) + 2.0 * t(PI - 69f64.to_radians());
        assert!((excess(&tri, 0.1) - all).abs() < 1e-9);
        // The bound: sin α = 2/3.
        assert!(((PI - 2.0 * SHARPEST.atan()).sin() - 2.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_plain_arctangent_is_the_librarys() {
        for i in 0..=10_000 {
            let t = SHARPEST * f64::from(i) / 10_000.0;
            assert!((atan(t) - t.atan()).abs() < 1e-9, "{t}");
        }
    }

    #[test]
    fn a_short_edge_takes_its_corners_with_it() {
        // A rectangle 10 × 1 with its right end cut by a short bevel: at depth 0.3 the
        // bevel's edge (0.2 long, two 45° turns) is gone, the other corners stay.
        let shape = [(0.0, 0.0), (9.8, 0.0), (10.0, 0.2), (10.0, 1.0), (0.0, 1.0)];
        let right = 3.0 * t(PI / 2.0);
        let early = excess(&region(&shape, &[]), 0.01);
        assert!(
            (early - (right + 2.0 * t(PI / 4.0))).abs() < 1e-9,
            "{early}"
        );
        // The bevel is 0.28 long and shortens by 2·tan(22.5°) = 0.83 per unit: gone at
        // 0.34, and its two corners with it. The three right angles stay (the shortest
        // of their edges, the left end, 1 long and shortened by 2 per unit, until 0.5).
        let late = excess(&region(&shape, &[]), 0.4);
        assert!((late - right).abs() < 1e-9, "{late}");
        assert_eq!(excess(&region(&shape, &[]), 0.6), 0.0);
    }
}
