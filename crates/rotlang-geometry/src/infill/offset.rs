//! The inward offset of any region (concave outlines and holes included) where it keeps
//! its shape: every edge moved inward by `d`, convex corners mitred, reflex corners an arc
//! about the vertex. That raw offset *is* the erosion by a disc of radius `d` as long as no
//! edge turns around and no two of its edges cross (then no part of the region pinched
//! off or vanished, and no grown hole met the outline or another hole); both are checked,
//! and `None` is returned otherwise, for geo's general buffer to do it. Most layers of
//! most parts (an L, a star, a bracket with holes, a slicer's mesh section at a half-nozzle
//! inset) pass, at a hundredth of the buffer's cost.

use crate::math;
use geo::{Coord, LineString, MultiPolygon, Polygon};

/// Rings longer than this go to the buffer: the crossing check sorts the edges and sweeps,
/// but a pathological ring (a comb) could still make it quadratic.
const MAX_POINTS: usize = 20_000;

/// The erosion of `region` by `d` (arcs in steps of at most `arc` radians), or `None`
/// where the raw offset is not it.
pub(crate) fn raw_inset(region: &MultiPolygon<f64>, d: f64, arc: f64) -> Option<MultiPolygon<f64>> {
    // Every ring, outlines and holes (each outline followed by its holes): the crossing
    // check needs them all, the polygons are built after it by moving them.
    let mut rings: Vec<Vec<Coord>> =
        Vec::with_capacity(region.0.iter().map(|p| 1 + p.interiors().len()).sum());
    let mut total = 0;
    for polygon in &region.0 {
        let exterior = offset_ring(&polygon.exterior().0, d, arc, true)?;
        total += exterior.len();
        rings.push(exterior);
        let outline = rings.len() - 1;
        for hole in polygon.interiors() {
            let hole = offset_ring(&hole.0, d, arc, false)?;
            total += hole.len();
            // A grown hole that swallowed the whole shrunk outline crosses nothing: each
            // hole must lie inside the outline.
            if hole.first().is_none_or(|&p| !inside(&rings[outline], p)) {
                return None;
            }
            rings.push(hole);
        }
        if total > MAX_POINTS {
            return None;
        }
    }
    // Islands shrink apart and never meet; an outline inside another polygon's hole is
    // another matter, left to the crossing check as well.
    if crossings(&rings) {
        return None;
    }
    let closed = |mut ring: Vec<Coord>| {
        ring.push(ring[0]);
        LineString::new(ring)
    };
    let mut rings = rings.into_iter();
    let out = region
        .0
        .iter()
        .map(|polygon| polygon.interiors().len())
        .filter_map(|holes| {
            let exterior = closed(rings.next()?);
            let interiors = rings.by_ref().take(holes).map(closed).collect();
            Some(Polygon::new(exterior, interiors))
        })
        .collect();
    Some(MultiPolygon::new(out))
}

/// One ring moved `d` toward the region's inside (`exterior`: the ring is an outline,
/// else a hole), without its closing point; `None` when an edge turns around or the ring
/// turns inside out.
pub(crate) fn offset_ring(ring: &[Coord], d: f64, arc: f64, exterior: bool) -> Option<Vec<Coord>> {
    let pts = inside_left(ring, exterior)?;
    let n = pts.len();
    let unit = |e: Coord| e / math::hypot(e.x, e.y);
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    // Room for the arcs and the closing point the polygon adds.
    let mut out = Vec::with_capacity(n + n / 2 + 1);
    // Each vertex's moved point(s) run from `end` (where the edge before it ends) to
    // `start` (where the edge after it starts); edge i runs from vertex i's start to
    // vertex i+1's end and must keep its direction: checked as each vertex is moved
    // (vertex 0's (start, end) kept for the last edge), no list of them.
    let mut first = (0, 0);
    let mut previous_start = 0;
    let turns_around = |out: &[Coord], from: usize, to: usize, i: usize, j: usize| {
        let e = pts[j] - pts[i];
        let f = out[to] - out[from];
        e.x * f.x + e.y * f.y <= 0.0
    };
    // Each edge's direction once: the corner after it takes it as the one before.
    let mut u = unit(pts[0] - pts[n - 1]);
    for i in 0..n {
        let b = pts[i];
        let c = if i + 1 < n { pts[i + 1] } else { pts[0] };
        let v = unit(c - b);
        let (nu, nv) = (left(u), left(v));
        let turn = cross(u, v);
        let dot = u.x * v.x + u.y * v.y;
        let (start, end) = if turn >= 0.0 || dot > 1.0 - 1e-12 {
            // Convex (or straight): the mitre, where both moved edges meet.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            if k <= 1e-9 {
                return None;
            }
            let at = (out.len(), out.len());
            out.push(b + (nu + nv) * (d / k));
            at
        } else {
            // Reflex: an arc about the vertex from one moved edge's end to the next's start.
            let angle = math::atan2(turn, dot); // negative: turning right
            let steps = (-angle / arc).ceil().max(1.0) as usize;
            let end = out.len();
            out.push(b + nu * d);
            let (s, c) = math::sin_cos(angle / steps as f64);
            let mut w = nu;
            for _ in 1..steps {
                w = Coord {
                    x: w.x * c - w.y * s,
                    y: w.x * s + w.y * c,
                };
                out.push(b + w * d);
            }
            let at = (out.len(), end);
            out.push(b + nv * d);
            at
        };
        if i == 0 {
            first = (start, end);
        } else if turns_around(&out, previous_start, end, i - 1, i) {
            return None;
        }
        previous_start = start;
        u = v;
    }
    if turns_around(&out, previous_start, first.1, n - 1, 0) {
        return None;
    }
    let moved = signed_area(&out);
    if moved == 0.0 || (moved > 0.0) != (signed_area(&pts) > 0.0) {
        return None;
    }
    Some(out)
}

/// Whether `p` is inside the ring (even-odd).
fn inside(ring: &[Coord], p: Coord) -> bool {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (ring[i], ring[next(i, n)]);
        if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
            inside = !inside;
        }
    }
    inside
}

/// Whether any two edges of the rings cross or touch, other than neighbours at their
/// shared vertex: a sweep over the edges sorted by their left end.
pub(crate) fn crossings(rings: &[Vec<Coord>]) -> bool {
    // Sorted by left end through keys that carry each edge's x and y extent and where it
    // is (ring, index): the sweep's inner loop reads them in order, and looks an edge's
    // ends up only when two boxes overlap.
    #[derive(Clone, Copy)]
    struct Key {
        ax: f64,
        bx: f64,
        ylo: f64,
        yhi: f64,
        ring: u32,
        index: u32,
    }
    let mut order: Vec<Key> = Vec::with_capacity(rings.iter().map(Vec::len).sum());
    for (r, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for i in 0..n {
            let (a, b) = ends(ring, i);
            order.push(Key {
                ax: a.x,
                bx: b.x,
                ylo: a.y.min(b.y),
                yhi: a.y.max(b.y),
                ring: r as u32,
                index: i as u32,
            });
        }
    }
    // A small ring's keys by insertion (the sweep's answer does not depend on how ties
    // are ordered); a large one's by the library's sort.
    if order.len() <= 48 {
        // Each key held aside while the larger ones before it move up one (a copy each,
        // not a swap): the same order as swapping it down.
        for i in 1..order.len() {
            let key = order[i];
            let mut j = i;
            while j > 0 && order[j - 1].ax > key.ax {
                order[j] = order[j - 1];
                j -= 1;
            }
            order[j] = key;
        }
    } else {
        order.sort_unstable_by(|p, q| p.ax.total_cmp(&q.ax));
    }
    for (k, e) in order.iter().enumerate() {
        for f in &order[k + 1..] {
            if f.ax > e.bx {
                break;
            }
            if f.yhi < e.ylo || f.ylo > e.yhi {
                continue;
            }
            if e.ring == f.ring {
                let n = rings[e.ring as usize].len() as u32;
                if next(e.index as usize, n as usize) == f.index as usize
                    || next(f.index as usize, n as usize) == e.index as usize
                {
                    continue;
                }
            }
            let (ea, eb) = ends(&rings[e.ring as usize], e.index as usize);
            let (fa, fb) = ends(&rings[f.ring as usize], f.index as usize);
            if segments_meet(ea, eb, fa, fb) {
                return true;
            }
        }
    }
    false
}

/// Edge `i` of a ring, its ends ordered left to right (by x, then y).
#[inline]
fn ends(ring: &[Coord], i: usize) -> (Coord, Coord) {
    let (a, b) = (ring[i], ring[next(i, ring.len())]);
    if (a.x, a.y) <= (b.x, b.y) {
        (a, b)
    } else {
        (b, a)
    }
}

pub(crate) fn segments_meet(p: Coord, q: Coord, r: Coord, s: Coord) -> bool {
    let d1 = cross(q - p, r - p);
    let d2 = cross(q - p, s - p);
    let d3 = cross(s - r, p - r);
    let d4 = cross(s - r, q - r);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    // Touching or collinear overlap: treated as meeting (the buffer decides).
    let on = |a: Coord, b: Coord, c: Coord, d: f64| {
        d == 0.0
            && c.x >= a.x.min(b.x)
            && c.x <= a.x.max(b.x)
            && c.y >= a.y.min(b.y)
            && c.y <= a.y.max(b.y)
    };
    on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4)
}

/// A ring's distinct points without its closing one, turned so the region's inside is on
/// the left (`exterior`: an outline, counter-clockwise; else a hole, clockwise); `None`
/// for a ring of no area. What every ring offset starts from.
pub(crate) fn inside_left(ring: &[Coord], exterior: bool) -> Option<Vec<Coord>> {
    let mut pts: Vec<Coord> = ring.to_vec();
    pts.dedup();
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    let area = signed_area(&pts);
    if pts.len() < 3 || area == 0.0 {
        return None;
    }
    if (area > 0.0) != exterior {
        pts.reverse();
    }
    Some(pts)
}

/// The index after `i` round a ring of `n` (a comparison, not the integer division of
/// `%`, in the loops over every edge).
#[inline]
pub(crate) fn next(i: usize, n: usize) -> usize {
    if i + 1 >= n { 0 } else { i + 1 }
}

pub(crate) fn cross(a: Coord, b: Coord) -> f64 {
    a.x * b.y - a.y * b.x
}

pub(crate) fn signed_area(ring: &[Coord]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| cross(ring[i], ring[next(i, n)]))
        .sum::<f64>()
        / 2.0
}

/// The ring offset with each vertex's (start, end) listed and every edge's direction
/// checked after: what `offset_ring` checks vertex by vertex (tests compare the two).
#[cfg(test)]
pub(crate) fn offset_ring_listed(
    ring: &[Coord],
    d: f64,
    arc: f64,
    exterior: bool,
) -> Option<Vec<Coord>> {
    let pts = inside_left(ring, exterior)?;
    let n = pts.len();
    let unit = |e: Coord| e / math::hypot(e.x, e.y);
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    // Room for the arcs and the closing point the polygon adds.
    let mut out = Vec::with_capacity(n + n / 2 + 1);
    // For every original edge i (from pts[i]), where its offset starts and ends in `out`.
    // One list of (start, end) per vertex: its moved point(s) run from `end` (where the
    // edge before it ends) to `start` (where the edge after it starts).
    let mut at: Vec<(usize, usize)> = Vec::with_capacity(n);
    // Each edge's direction once: the corner after it takes it as the one before.
    let mut u = unit(pts[0] - pts[n - 1]);
    for i in 0..n {
        let b = pts[i];
        let c = if i + 1 < n { pts[i + 1] } else { pts[0] };
        let v = unit(c - b);
        let (nu, nv) = (left(u), left(v));
        let turn = cross(u, v);
        let dot = u.x * v.x + u.y * v.y;
        if turn >= 0.0 || dot > 1.0 - 1e-12 {
            // Convex (or straight): the mitre, where both moved edges meet.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            if k <= 1e-9 {
                return None;
            }
            at.push((out.len(), out.len()));
            out.push(b + (nu + nv) * (d / k));
        } else {
            // Reflex: an arc about the vertex from one moved edge's end to the next's start.
            let angle = math::atan2(turn, dot); // negative: turning right
            let steps = (-angle / arc).ceil().max(1.0) as usize;
            let end = out.len();
            out.push(b + nu * d);
            let (s, c) = math::sin_cos(angle / steps as f64);
            let mut w = nu;
            for _ in 1..steps {
                w = Coord {
                    x: w.x * c - w.y * s,
                    y: w.x * s + w.y * c,
                };
                out.push(b + w * d);
            }
            at.push((out.len(), end));
            out.push(b + nv * d);
        }
        u = v;
    }
    // Edge i runs from vertex i's start to vertex i+1's end: it must keep its direction.
    for i in 0..n {
        let (p, q) = (out[at[i].0], out[at[next(i, n)].1]);
        let e = pts[next(i, n)] - pts[i];
        let f = q - p;
        if e.x * f.x + e.y * f.y <= 0.0 {
            return None;
        }
    }
    let moved = signed_area(&out);
    if moved == 0.0 || (moved > 0.0) != (signed_area(&pts) > 0.0) {
        return None;
    }
    Some(out)
}
