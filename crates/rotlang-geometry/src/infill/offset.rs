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
    let raw = raw_rings(region, d, arc)?;
    Some(raw.polygons())
}

/// The rings of [`raw_inset`], open (no closing point), as `Region` keeps them: every
/// polygon's outline, then every polygon's holes in the same order.
#[derive(Clone, Debug, Default)]
pub(crate) struct RawRings {
    pub rings: Vec<Vec<Coord>>,
    /// How many of `rings` are outlines (one per polygon).
    pub outlines: usize,
    /// How many holes each polygon has; empty when none has any (no allocation).
    pub holes: Vec<usize>,
    /// `area()`, where the offset measured it as it went (one outline without holes).
    pub measured: Option<f64>,
}

impl RawRings {
    /// The polygons, each ring closed (copies: `raw_rings` is what a layer reads).
    pub(crate) fn polygons(&self) -> MultiPolygon<f64> {
        polygons(&self.rings, self.outlines, &self.holes)
    }

    /// [`RawRings::polygons`] made of the rings themselves (each closed in place), not
    /// copies.
    pub(crate) fn into_polygons(self) -> MultiPolygon<f64> {
        let closed = |mut ring: Vec<Coord>| {
            ring.push(ring[0]);
            LineString::new(ring)
        };
        let mut rings = self.rings;
        let mut hole = self.outlines;
        let out = (0..self.outlines)
            .map(|i| {
                let count = self.holes.get(i).copied().unwrap_or(0);
                let interiors = rings[hole..hole + count]
                    .iter_mut()
                    .map(|r| closed(std::mem::take(r)))
                    .collect();
                hole += count;
                Polygon::new(closed(std::mem::take(&mut rings[i])), interiors)
            })
            .collect();
        MultiPolygon::new(out)
    }

    /// The area of the polygons, to the bit as geo's `unsigned_area` of [`polygons`]
    /// (`Region::area`, which densities are measured against), without making them.
    pub(crate) fn area(&self) -> f64 {
        if let Some(area) = self.measured {
            return area;
        }
        let mut hole = self.outlines;
        let mut total = 0.0;
        for i in 0..self.outlines {
            let count = self.holes.get(i).copied().unwrap_or(0);
            total += polygon_area(&self.rings[i], &self.rings[hole..hole + count]);
            hole += count;
        }
        total
    }
}

/// Open rings as `Region` keeps them (`outlines` outlines, then each polygon's holes,
/// `holes[i]` of them, none where `holes` is empty) made polygons, each ring closed.
pub(crate) fn polygons(
    rings: &[Vec<Coord>],
    outlines: usize,
    holes: &[usize],
) -> MultiPolygon<f64> {
    let closed = |ring: &Vec<Coord>| {
        let mut c = Vec::with_capacity(ring.len() + 1);
        c.extend_from_slice(ring);
        c.push(ring[0]);
        LineString::new(c)
    };
    let mut hole = outlines;
    let out = (0..outlines)
        .map(|i| {
            let count = holes.get(i).copied().unwrap_or(0);
            let interiors = rings[hole..hole + count].iter().map(closed).collect();
            hole += count;
            Polygon::new(closed(&rings[i]), interiors)
        })
        .collect();
    MultiPolygon::new(out)
}

/// geo's unsigned area of a polygon (`Polygon::signed_area().abs()`) from open rings.
pub(crate) fn polygon_area(exterior: &[Coord], holes: &[Vec<Coord>]) -> f64 {
    let area = geo_ring_area(exterior);
    let is_negative = area < 0.0;
    let area = holes
        .iter()
        .fold(area.abs(), |total, h| total - geo_ring_area(h).abs());
    (if is_negative { -area } else { area }).abs()
}

/// geo's signed area of an open ring closed (`get_linestring_area`): the determinants
/// of its edges shifted by the first point, the same terms in the same order.
pub(crate) fn geo_ring_area(open: &[Coord]) -> f64 {
    // The closed ring has `open.len() + 1` points: fewer than 3 is no area.
    if open.len() < 2 {
        return 0.0;
    }
    let shift = open[0];
    let mut prev = open[1] - shift;
    let mut sum = 0.0;
    for &point in &open[2..] {
        let shifted = point - shift;
        sum += prev.x * shifted.y - prev.y * shifted.x;
        prev = shifted;
    }
    // The closing point, the first shifted: (0, 0).
    let shifted = open[0] - shift;
    sum += prev.x * shifted.y - prev.y * shifted.x;
    sum / 2.0
}

/// [`raw_inset`]'s rings without its polygons: what a layer's `Region` reads.
pub(crate) fn raw_rings(region: &MultiPolygon<f64>, d: f64, arc: f64) -> Option<RawRings> {
    raw_rings_stepped(region, d, ArcStep::new(arc))
}

/// [`raw_rings`] with the round corners' step made already (`Region` keeps the last
/// nozzle's).
pub(crate) fn raw_rings_stepped(
    region: &MultiPolygon<f64>,
    d: f64,
    step: ArcStep,
) -> Option<RawRings> {
    raw_rings_known(region, d, step, None)
}

/// [`raw_rings_stepped`] with the first outline's signed area known where the region
/// is clean (`Survey::first_area`): that ring is read in place without a second look.
pub(crate) fn raw_rings_known(
    region: &MultiPolygon<f64>,
    d: f64,
    step: ArcStep,
    first_area: Option<f64>,
) -> Option<RawRings> {
    // The commonest region, one outline and no hole (a star, an L): read in place when
    // it needs no cleaning and turns the right way, offset into the ring kept.
    if let [polygon] = &region.0[..]
        && polygon.interiors().is_empty()
    {
        let pts = match first_area {
            Some(area) => inside_left_known(&polygon.exterior().0, true, area)?,
            None => inside_left_cow(&polygon.exterior().0, true)?,
        };
        // Both proofs are sound; the cheaper first: the pairwise one for a few edges (an
        // L's six have nine pairs, and its mean is its reflex corner, where the one-pass
        // proof declines), the one pass over the inset for more (a star's ten have 35),
        // made as the inset is read for its area.
        let few = pts.len() <= 6;
        let (exterior, read) = offset_read(&pts, d, step, (!few).then(|| mean(&pts)))?;
        if exterior.len() > MAX_POINTS {
            return None;
        }
        let pairwise = || clear_of_crossings(std::slice::from_ref(&pts), d);
        let clear = if few {
            pairwise() || star_clear(&exterior, mean(&pts))
        } else {
            read.star || pairwise()
        };
        if !clear && crossings(std::slice::from_ref(&exterior)) {
            return None;
        }
        // The list from the pool a dropped `Region` gave it back to (`scratch`).
        let mut rings = super::scratch::take(&RINGS);
        rings.push(exterior);
        return Some(RawRings {
            rings,
            outlines: 1,
            holes: Vec::new(),
            measured: Some(read.area),
        });
    }
    // Every ring, outlines and holes (each outline followed by its holes): the crossing
    // check needs them all. The rings as offset (inside on the left) too: most regions
    // are proved clear of crossings on them, without the sweep over the offset's edges.
    let count = region.0.iter().map(|p| 1 + p.interiors().len()).sum();
    let mut rings: Vec<Vec<Coord>> = Vec::with_capacity(count);
    let mut originals: Vec<std::borrow::Cow<'_, [Coord]>> = Vec::with_capacity(count);
    let mut total = 0;
    for polygon in &region.0 {
        let pts = inside_left_cow(&polygon.exterior().0, true)?;
        let exterior = offset_points(&pts, d, step, true)?;
        originals.push(pts);
        total += exterior.len();
        rings.push(exterior);
        let outline = rings.len() - 1;
        for hole in polygon.interiors() {
            let pts = inside_left_cow(&hole.0, false)?;
            let hole = offset_points(&pts, d, step, false)?;
            originals.push(pts);
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
    if !clear_of_crossings(&originals, d) && crossings(&rings) {
        return None;
    }
    // Outlines first, then holes, moved (not copied) out of the list.
    let outlines = region.0.len();
    let mut ordered = Vec::with_capacity(count);
    let mut at = 0;
    for polygon in &region.0 {
        ordered.push(std::mem::take(&mut rings[at]));
        at += 1 + polygon.interiors().len();
    }
    let mut at = 0;
    for polygon in &region.0 {
        let holes = polygon.interiors().len();
        ordered.extend(rings[at + 1..at + 1 + holes].iter_mut().map(std::mem::take));
        at += 1 + holes;
    }
    let holes = if region.0.iter().any(|p| !p.interiors().is_empty()) {
        region.0.iter().map(|p| p.interiors().len()).collect()
    } else {
        Vec::new()
    };
    Some(RawRings {
        rings: ordered,
        outlines,
        holes,
        measured: None,
    })
}

/// [`inside_left`] borrowing the ring where that is the same: a ring with no repeated
/// point in a row (its closing point aside) that already turns the asked way (most
/// regions) is read where it is, not copied.
pub(crate) fn inside_left_cow(
    ring: &[Coord],
    exterior: bool,
) -> Option<std::borrow::Cow<'_, [Coord]>> {
    let open = match ring {
        [first, .., last] if first == last => &ring[..ring.len() - 1],
        _ => ring,
    };
    let as_is =
        open.len() >= 3 && open.first() != open.last() && open.windows(2).all(|w| w[0] != w[1]);
    if as_is {
        let area = signed_area(open);
        if area == 0.0 {
            return None;
        }
        if (area > 0.0) == exterior {
            return Some(std::borrow::Cow::Borrowed(open));
        }
    }
    inside_left(ring, exterior).map(std::borrow::Cow::Owned)
}

/// [`inside_left_cow`] of a ring known clean (no point repeated in a row, its closing
/// point its first) whose signed area is `area`.
pub(crate) fn inside_left_known(
    ring: &[Coord],
    exterior: bool,
    area: f64,
) -> Option<std::borrow::Cow<'_, [Coord]>> {
    let open = &ring[..ring.len().saturating_sub(1)];
    if open.len() >= 3 {
        if area == 0.0 {
            return None;
        }
        if (area > 0.0) == exterior {
            return Some(std::borrow::Cow::Borrowed(open));
        }
    }
    inside_left(ring, exterior).map(std::borrow::Cow::Owned)
}

/// How a round corner's points are placed: turned from one moved edge's end toward the
/// next's start by a fixed step (one sine and cosine per region, not an arc tangent and a
/// sine and cosine per corner), the last chord taking what is left. The step is `arc /
/// 1.2` and what is left is more than a fifth of a step, so that every chord spans at
/// most `arc` (the sagitta bound the arc step was chosen for) and none is a sliver.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ArcStep {
    sin: f64,
    cos: f64,
    /// The cosine of a fifth of a step: a point closer than that to the corner's last
    /// is not placed.
    last_cos: f64,
}

impl ArcStep {
    /// A placeholder (no step), for a cache not yet filled.
    pub(crate) const NONE: ArcStep = ArcStep {
        sin: 0.0,
        cos: 1.0,
        last_cos: 1.0,
    };

    pub(crate) fn new(arc: f64) -> ArcStep {
        let step = arc / 1.2;
        let (sin, cos) = math::sin_cos(step);
        ArcStep {
            sin,
            cos,
            last_cos: math::cos(step / 5.0),
        }
    }
}

/// The points strictly between `b + nu·d` and `b + nv·d` of the round corner about `b`
/// turning clockwise (right) from the unit normal `nu` to `nv`, by `step`.
#[inline]
pub(crate) fn arc_points(
    b: Coord,
    nu: Coord,
    nv: Coord,
    d: f64,
    step: ArcStep,
    out: &mut Vec<Coord>,
) {
    let mut w = nu;
    // A corner turns by less than half a turn: a few steps (the bound is only a guard).
    for _ in 0..64 {
        w = Coord {
            x: w.x * step.cos + w.y * step.sin,
            y: w.y * step.cos - w.x * step.sin,
        };
        // Past `nv` (it is no longer clockwise of w), or within a fifth of a step of it.
        if cross(w, nv) >= 0.0 || w.x * nv.x + w.y * nv.y >= step.last_cos {
            break;
        }
        put(out, b + w * d);
    }
}

/// Whether the raw offset by `d` of these rings (as offset: distinct points, inside on
/// the left) is sure not to cross itself, so that the sweep need not look. Each piece of
/// the offset lies within `d` of what it was moved from (a moved edge, kept to its
/// direction, within `d` of its edge; a round corner's chords within `d` of its vertex),
/// so pieces from features more than `2d` apart cannot meet. That covers every two edges
/// that share no vertex, and every piece against a round corner at a vertex that is not
/// its edge's (with four edges or more, one of the vertex's two edges shares no vertex
/// with it), and two round corners not at the ends of one edge. What is left cannot
/// meet: a moved edge and the next lie on lines that cross only at their mitre, or
/// beyond both their ends at a round corner; a round corner's chords stay on the
/// circle's side of its tangents; the two round corners at the ends of an edge lie
/// behind its start and beyond its end along it. `false` (the sweep decides) for a ring
/// of three edges, and past 64 edges in all (the pairs grow as their square).
pub(crate) fn clear_of_crossings<R: AsRef<[Coord]>>(rings: &[R], d: f64) -> bool {
    let total: usize = rings.iter().map(|r| r.as_ref().len()).sum();
    if total > 64 || rings.iter().any(|r| r.as_ref().len() < 4) {
        return false;
    }
    let reach = 2.0 * d;
    // A millionth more than 2d, squared: far above the offset's rounding.
    let reach2 = reach * reach * (1.0 + 1e-6);
    // Every edge once, with its box and squared length (a list kept between layers).
    let mut edges = super::scratch::take(&EDGES);
    edges.reserve(total);
    for ring in rings {
        let ring = ring.as_ref();
        let n = ring.len();
        for i in 0..n {
            let (p, q) = (ring[i], ring[next(i, n)]);
            let e = q - p;
            edges.push(Edge {
                p,
                q,
                lo: Coord {
                    x: if p.x < q.x { p.x } else { q.x },
                    y: if p.y < q.y { p.y } else { q.y },
                },
                hi: Coord {
                    x: if p.x < q.x { q.x } else { p.x },
                    y: if p.y < q.y { q.y } else { p.y },
                },
                len2: e.x * e.x + e.y * e.y,
            });
        }
    }
    let mut from = 0;
    for ring in rings {
        let n = ring.as_ref().len();
        for i in 0..n {
            let e = &edges[from + i];
            // The edges after it, but not its neighbours in its ring: the next (unless it
            // is the last, whose next is the first, met before) and, for the first, the
            // last.
            let start = from + i + if i + 1 < n { 2 } else { 1 };
            let skip = if i == 0 { from + n - 1 } else { usize::MAX };
            let (lo, hi) = (e.lo, e.hi);
            for (l, f) in (start..).zip(&edges[start.min(edges.len())..]) {
                if f.lo.x - hi.x > reach
                    || lo.x - f.hi.x > reach
                    || f.lo.y - hi.y > reach
                    || lo.y - f.hi.y > reach
                    || l == skip
                {
                    continue;
                }
                // One edge wholly on one side of the other's line, farther than 2d from
                // it; else the distance itself.
                if !(beyond(e.p, e.q, e.len2, f.p, f.q, reach2)
                    || beyond(f.p, f.q, f.len2, e.p, e.q, reach2)
                    || apart(e.p, e.q, f.p, f.q, reach2))
                {
                    super::scratch::give(&EDGES, edges);
                    return false;
                }
            }
        }
        from += n;
    }
    super::scratch::give(&EDGES, edges);
    true
}

/// Whether a ring is sure not to cross or touch itself because it winds once around
/// `c` (any point: the mean of the points it was offset from), which lies clearly on the
/// left of every edge: seen from `c`, every edge turns the same way, so the angle grows
/// all along the ring, and one turn in all (one edge goes up across `c`'s level: with `c`
/// on their left, those that go up cross to its right and those that go down to its
/// left) puts no two of its points on one ray. Each edge's side is told by a margin far
/// above the rounding of its cross product (a few 1e-16 of its two terms), so that it
/// holds for the ring's exact coordinates. A star's or a rounded convex part's inset
/// passes in one pass over its points, without the pairwise check.
pub(crate) fn star_clear(ring: &[Coord], c: Coord) -> bool {
    let n = ring.len();
    if n < 3 {
        return false;
    }
    let mut up = 0;
    let mut a = ring[n - 1];
    for &b in ring {
        let (e, f) = (b - a, c - a);
        let (s, t) = (e.x * f.y, e.y * f.x);
        if s - t <= 1e-12 * (s.abs() + t.abs()) {
            return false;
        }
        if a.y <= c.y && b.y > c.y {
            up += 1;
        }
        a = b;
    }
    up == 1
}

/// The mean of a ring's points.
pub(crate) fn mean(ring: &[Coord]) -> Coord {
    let mut sum = Coord::zero();
    for p in ring {
        sum = sum + *p;
    }
    sum / ring.len().max(1) as f64
}

/// An edge of `clear_of_crossings`, with its box and squared length.
#[derive(Clone, Copy)]
struct Edge {
    p: Coord,
    q: Coord,
    lo: Coord,
    hi: Coord,
    len2: f64,
}

thread_local! {
    /// A one-ring `Region`'s ring and list of rings, given back when it is dropped and
    /// taken by the next raw offset (a layer's region filled once).
    pub(crate) static RING: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    pub(crate) static RINGS: std::cell::Cell<Vec<Vec<Coord>>> = const { std::cell::Cell::new(Vec::new()) };
    /// `clear_of_crossings`' edges, kept between layers.
    static EDGES: std::cell::Cell<Vec<Edge>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Whether `r` and `s` are both on the same side of the line through `p` and `q` (`len2`
/// its squared length), farther than `√reach2` from it.
#[inline]
pub(crate) fn beyond(p: Coord, q: Coord, len2: f64, r: Coord, s: Coord, reach2: f64) -> bool {
    let e = q - p;
    let (cr, cs) = (cross(e, r - p), cross(e, s - p));
    let bound = reach2 * len2;
    cr * cr > bound && cs * cs > bound && (cr > 0.0) == (cs > 0.0)
}

/// Whether the segments `pq` and `rs` are farther apart than `√reach2`: no crossing, and
/// every end far from the other segment.
#[inline]
pub(crate) fn apart(p: Coord, q: Coord, r: Coord, s: Coord, reach2: f64) -> bool {
    !segments_meet(p, q, r, s)
        && farther(p, r, s, reach2)
        && farther(q, r, s, reach2)
        && farther(r, p, q, reach2)
        && farther(s, p, q, reach2)
}

/// Whether `p` is farther than `√reach2` from the segment `ab` (squared, no root).
#[inline]
fn farther(p: Coord, a: Coord, b: Coord, reach2: f64) -> bool {
    let e = b - a;
    let f = p - a;
    let t = e.x * f.x + e.y * f.y;
    let len2 = e.x * e.x + e.y * e.y;
    if t <= 0.0 {
        f.x * f.x + f.y * f.y > reach2
    } else if t >= len2 {
        let g = p - b;
        g.x * g.x + g.y * g.y > reach2
    } else {
        let c = cross(e, f);
        c * c > reach2 * len2
    }
}

/// One ring moved `d` toward the region's inside (`exterior`: the ring is an outline,
/// else a hole), without its closing point; `None` when an edge turns around or the ring
/// turns inside out.
#[cfg(test)]
pub(crate) fn offset_ring(ring: &[Coord], d: f64, arc: f64, exterior: bool) -> Option<Vec<Coord>> {
    let pts = inside_left(ring, exterior)?;
    offset_points(&pts, d, ArcStep::new(arc), exterior)
}

/// `offset_ring` of a ring already turned by `inside_left` (so its area is positive for
/// an outline, negative for a hole: not measured again).
fn offset_points(pts: &[Coord], d: f64, step: ArcStep, exterior: bool) -> Option<Vec<Coord>> {
    let out = moved_points(pts, d, step)?;
    let moved = signed_area(&out);
    if moved == 0.0 || (moved > 0.0) != exterior {
        return None;
    }
    Some(out)
}

/// What one pass over an outline's offset reads of it: geo's area of it alone (as
/// [`polygon_area`]) and whether it is proved clear of crossings by [`star_clear`].
pub(crate) struct Read {
    pub area: f64,
    pub star: bool,
}

/// `offset_points` of an outline, its signed area, geo's area and (about `centre`, if
/// given; else `false`) `star_clear` taken in one pass over it, each sum in its own
/// order.
pub(crate) fn offset_read(
    pts: &[Coord],
    d: f64,
    step: ArcStep,
    centre: Option<Coord>,
) -> Option<(Vec<Coord>, Read)> {
    let out = moved_points(pts, d, step)?;
    let (twice_moved, twice_geo, star) = match centre {
        Some(c) => read_ring::<true>(&out, c),
        None => read_ring::<false>(&out, Coord::zero()),
    };
    // `offset_points`' test, on the same sum.
    let moved = twice_moved / 2.0;
    if moved == 0.0 || moved.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    // `polygon_area` of the ring alone: the magnitude of geo's signed area.
    let area = (twice_geo / 2.0).abs();
    Some((out, Read { area, star }))
}

/// A ring's `signed_area` (doubled: its sign is what is asked), `geo_ring_area`'s sum
/// (doubled) and, with `STAR`, `star_clear(ring, c)`, in one pass: each term as those
/// make it, summed in their order.
#[inline(always)]
fn read_ring<const STAR: bool>(ring: &[Coord], c: Coord) -> (f64, f64, bool) {
    let (first, second) = (ring[0], ring[1]);
    // `signed_area`: each point and the next, then the closing edge. `geo_ring_area`:
    // the determinants of the points shifted by the first, from the second on.
    let mut sum = -0.0 + cross(first, second);
    let mut geo = 0.0;
    let mut prev = second - first;
    // `star_clear`: every edge with `c` clearly on its left, and one going up across it.
    let (mut clear, mut up) = (true, 0u32);
    let mut edge = |a: Coord, b: Coord| {
        let (e, f) = (b - a, c - a);
        let (s, t) = (e.x * f.y, e.y * f.x);
        clear &= s - t > 1e-12 * (s.abs() + t.abs());
        up += u32::from(a.y <= c.y && b.y > c.y);
    };
    if STAR {
        edge(first, second);
    }
    let mut a = second;
    for &b in &ring[2..] {
        sum += cross(a, b);
        let shifted = b - first;
        geo += prev.x * shifted.y - prev.y * shifted.x;
        prev = shifted;
        if STAR {
            edge(a, b);
        }
        a = b;
    }
    sum += cross(a, first);
    // The closing point shifted by itself: (0, 0), its term as geo makes it.
    let zero = Coord::<f64>::zero();
    geo += prev.x * zero.y - prev.y * zero.x;
    if STAR {
        edge(a, first);
    }
    (sum, geo, STAR && clear && up == 1)
}

/// Each vertex moved `d` to the left of its edges (convex corners mitred, reflex ones
/// round), without the closing point; `None` when an edge turns around.
fn moved_points(pts: &[Coord], d: f64, step: ArcStep) -> Option<Vec<Coord>> {
    let n = pts.len();
    // Coordinates are bounded (MAX_COORDINATE): a plain square root, not `hypot`.
    let unit = |e: Coord| e / (e.x * e.x + e.y * e.y).sqrt();
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    // Room for the arcs (a few points per reflex corner) and the closing point the
    // polygon adds: a star's ring is not grown twice. From the pool a dropped `Region`
    // gave its ring back to (`scratch`).
    let mut out = super::scratch::take(&RING);
    out.reserve(3 * n + 1);
    // Each vertex's moved point(s) run from `end` (where the edge before it ends) to
    // `start` (where the edge after it starts); edge i runs from vertex i's start to
    // vertex i+1's end and must keep its direction (`e`, from pts[i] to pts[i+1]):
    // checked as each vertex is moved.
    let last = pts[0] - pts[n - 1];
    let mut previous_start = Coord::zero();
    let turns_around = |e: Coord, from: Coord, to: Coord| {
        let f = to - from;
        e.x * f.x + e.y * f.y <= 0.0
    };
    // Each edge's direction once: the corner after it takes it as the one before.
    let mut u = unit(last);
    let mut before = last;
    let mut b = pts[0];
    for i in 0..n {
        let c = if i + 1 < n { pts[i + 1] } else { pts[0] };
        let e = c - b;
        let v = unit(e);
        let (nu, nv) = (left(u), left(v));
        let turn = cross(u, v);
        let dot = u.x * v.x + u.y * v.y;
        let (start, end) = if turn >= 0.0 || dot > 1.0 - 1e-12 {
            // Convex (or straight): the mitre, where both moved edges meet.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            if k <= 1e-9 {
                return None;
            }
            let p = b + (nu + nv) * (d / k);
            put(&mut out, p);
            (p, p)
        } else {
            // Reflex: an arc about the vertex from one moved edge's end to the next's start.
            let end = b + nu * d;
            put(&mut out, end);
            arc_points(b, nu, nv, d, step, &mut out);
            let start = b + nv * d;
            put(&mut out, start);
            (start, end)
        };
        if i > 0 && turns_around(before, previous_start, end) {
            return None;
        }
        previous_start = start;
        before = e;
        u = v;
        b = c;
    }
    // Vertex 0's end is the ring's first point.
    if turns_around(last, previous_start, out[0]) {
        return None;
    }
    Some(out)
}

/// `out.push(p)` with its growing out of the way (`cold_push`): the loop that moves a
/// ring's vertices keeps its values in registers rather than about a call.
#[inline(always)]
fn put(out: &mut Vec<Coord>, p: Coord) {
    if out.len() < out.capacity() {
        out.push(p);
    } else {
        cold_push(out, p);
    }
}

#[cold]
#[inline(never)]
fn cold_push(out: &mut Vec<Coord>, p: Coord) {
    out.push(p);
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

#[inline]
pub(crate) fn cross(a: Coord, b: Coord) -> f64 {
    a.x * b.y - a.y * b.x
}

pub(crate) fn signed_area(ring: &[Coord]) -> f64 {
    // The same terms in the same order as `cross(ring[i], ring[next(i, n)])` over i (so
    // the same sum to the bit), without a wrap test per vertex: each point and the
    // next, then the closing edge.
    let (Some(&first), Some(&last)) = (ring.first(), ring.last()) else {
        return 0.0;
    };
    (ring.windows(2).map(|w| cross(w[0], w[1])).sum::<f64>() + cross(last, first)) / 2.0
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
    let unit = |e: Coord| e / (e.x * e.x + e.y * e.y).sqrt();
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
            let end = out.len();
            out.push(b + nu * d);
            arc_points(b, nu, nv, d, ArcStep::new(arc), &mut out);
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
