//! A layer's region, inset by half a nozzle, ready to be filled many times.

use crate::math;
use geo::{Area, BooleanOps, Buffer, Coord, LineString, MultiPolygon, Polygon};

use super::{Error, MAX_COORDINATE};
// Where they were (`super::region::cross`): ring helpers the offset shares.
use super::offset::{ArcStep, RawRings, next};
pub(crate) use super::offset::{cross, signed_area};

/// The infill area of a layer: the region inset by half a nozzle.
#[derive(Clone, Debug)]
pub struct Region {
    /// The inset area: made from `rings` when first asked where the raw offset made
    /// them (a layer filled once, by `infill::fill`, never asks), else kept as made.
    inset: std::sync::OnceLock<MultiPolygon<f64>>,
    /// How many holes each polygon of the inset has, to make it from `rings` (empty when
    /// none has any, or when it was kept as made).
    holes: Vec<usize>,
    /// The region as given, without degenerate rings: concentric loops are offset from
    /// it (it has fewer vertices than the inset, whose holes have grown arcs).
    outline: MultiPolygon<f64>,
    /// Its rings (outlines and holes) without the repeated closing point.
    pub(super) rings: Vec<Vec<Coord>>,
    /// How many of `rings` are outlines (they come first).
    outlines: usize,
    /// The bounding box of the region as given (the object centre is its centre).
    pub(super) min: Coord,
    pub(super) max: Coord,
    pub(super) area: f64,
    nozzle: f64,
    /// One convex outline, no hole: every straight travel stays inside, none is routed.
    pub(super) convex: bool,
    /// Whether `rings` (one ring) goes back to the raw offset's pools when dropped.
    pooled: bool,
    /// Whether `rings` (made by the convex offset, with holes) goes back to its pools
    /// when dropped: the list, the outline and the first hole.
    pooled_convex: bool,
}

/// The squared length of the edge from `a` to `b`.
fn edge_len2(a: Coord, b: Coord) -> f64 {
    let e = b - a;
    e.x * e.x + e.y * e.y
}

/// A copy of `region` (the outline concentric loops are offset from), the same to the
/// bit: one polygon without holes (a star's, an L's) in the lists `OUTLINE_POLYGONS` and
/// `OUTLINE_RING` a dropped region gave back (`Region::drop`), no allocation; any other
/// region cloned.
fn copied(region: &MultiPolygon<f64>) -> MultiPolygon<f64> {
    match &region.0[..] {
        [polygon] if polygon.interiors().is_empty() => {
            let mut ring = super::scratch::take(&OUTLINE_RING);
            ring.extend_from_slice(&polygon.exterior().0);
            let mut polygons = super::scratch::take(&OUTLINE_POLYGONS);
            polygons.push(Polygon::new(LineString::new(ring), Vec::new()));
            MultiPolygon::new(polygons)
        }
        _ => region.clone(),
    }
}

thread_local! {
    /// A region's copy of its one polygon (`copied`), given back when it is dropped,
    /// for the next layer's.
    static OUTLINE_POLYGONS: std::cell::Cell<Vec<Polygon<f64>>> =
        const { std::cell::Cell::new(Vec::new()) };
    static OUTLINE_RING: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
}

impl Region {
    /// Insets `region` by half of `nozzle`. Coordinates must be finite and within
    /// ±[`MAX_COORDINATE`] mm; rings with fewer than three points or no area are ignored.
    pub fn new(region: &MultiPolygon<f64>, nozzle: f64) -> Result<Region, Error> {
        Region::build(region, nozzle, true)
    }

    /// The region, keeping the outline as given (`Region::outline`, which concentric
    /// loops are offset from) only if `keep_outline`: a layer filled once with another
    /// pattern (`infill::fill`) neither copies nor frees it. Its inset is the same.
    pub(crate) fn build(
        region: &MultiPolygon<f64>,
        nozzle: f64,
        keep_outline: bool,
    ) -> Result<Region, Error> {
        if !(0.01..=10.0).contains(&nozzle) {
            return Err(Error::Nozzle(nozzle));
        }
        let Survey {
            mut min,
            mut max,
            clean: as_is,
            first_area,
            first_turns_both_ways,
        } = survey(region)?;
        // A region with nothing to clean (no repeated point, no degenerate ring: most)
        // is read where it is, not copied (or copied whole, where the outline is kept),
        // its first outline's area known.
        let cleaned = match (keep_outline, as_is) {
            (false, true) => std::borrow::Cow::Borrowed(region),
            (true, true) => std::borrow::Cow::Owned(copied(region)),
            _ => std::borrow::Cow::Owned(clean(region)),
        };
        let (arc, step) = arc_and_step(nozzle / 2.0);
        // Which offset made the inset says, most of the time, whether it is convex (see
        // `convex` below) without testing its ring again. The raw offset's rings are kept
        // as they are (open, outlines first), its polygons made only if asked.
        let Inset {
            inset,
            rings,
            outlines,
            holes,
            area,
            made_by,
        } = if let Some(convex) = (!first_turns_both_ways)
            .then(|| convex_rings_built(&cleaned, nozzle / 2.0, arc, first_area))
            .flatten()
        {
            match convex {
                // Kept open as made: the polygons only if asked, as the raw offset's.
                ConvexInset::Rings(raw) => Inset {
                    inset: std::sync::OnceLock::new(),
                    area: raw.area(),
                    rings: raw.rings,
                    outlines: raw.outlines,
                    holes: raw.holes,
                    made_by: Offset::Convex,
                },
                ConvexInset::Polygons(inset) => Inset::of_polygons(inset, Offset::Convex),
            }
        } else if let Some(raw) =
            super::offset::raw_rings_known(&cleaned, nozzle / 2.0, step, first_area)
        {
            Inset {
                inset: std::sync::OnceLock::new(),
                area: raw.area(),
                rings: raw.rings,
                outlines: raw.outlines,
                holes: raw.holes,
                made_by: Offset::Raw,
            }
        } else if cleaned.0.is_empty() {
            Inset::of_polygons(cleaned.as_ref().clone(), Offset::Buffer)
        } else {
            Inset::of_polygons(cleaned.buffer(-nozzle / 2.0), Offset::Buffer)
        };
        if !min.x.is_finite() {
            min = Coord::zero();
            max = Coord::zero();
        }
        // The exact inset of one convex outline without holes is convex (its edges are the
        // outline's, moved); the raw offset was only tried because some ring has a reflex
        // vertex, which its inset keeps (an arc, or the same turn); a convex outline whose
        // grown holes met it may be left concave, and the buffer's result is tested.
        let convex = rings.len() == 1
            && outlines == 1
            && match made_by {
                Offset::Convex if cleaned.0.len() == 1 && cleaned.0[0].interiors().is_empty() => {
                    true
                }
                Offset::Raw => false,
                _ => convex_ring(&rings[0]).is_some(),
            };
        // The raw offset's one ring came from its pools (`offset::RING`): given back
        // when the region is dropped. A ring made otherwise is freed as made (held in the
        // pool, where no offset takes it, it would only keep the allocator from reusing
        // its memory for the next layer's).
        let pooled = made_by == Offset::Raw && rings.len() == 1;
        // The convex offset's rings with holes (a holed plate's) came from its pools
        // (`KEPT_EXTERIOR`, `KEPT_HOLE`, `offset::RINGS`): given back too. (One convex
        // ring alone is freed as made, as above.)
        let pooled_convex = made_by == Offset::Convex && rings.len() > 1;
        Ok(Region {
            convex,
            pooled,
            pooled_convex,
            inset,
            holes,
            outline: if keep_outline {
                cleaned.into_owned()
            } else {
                MultiPolygon::new(Vec::new())
            },
            rings,
            outlines,
            min,
            max,
            area,
            nozzle,
        })
    }

    /// The inset area the infill covers.
    /// The region as given, degenerate rings dropped.
    pub fn outline(&self) -> &MultiPolygon<f64> {
        &self.outline
    }

    pub fn inset(&self) -> &MultiPolygon<f64> {
        self.inset
            .get_or_init(|| super::offset::polygons(&self.rings, self.outlines, &self.holes))
    }

    /// The area of the inset (mm²): what densities are measured against.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The nozzle this region was inset for.
    pub fn nozzle(&self) -> f64 {
        self.nozzle
    }

    /// The centre of the region's bounding box (the pattern centre of `Centring::Object`).
    pub fn centre(&self) -> Coord {
        (self.min + self.max) / 2.0
    }

    /// One convex outline and no hole.
    pub(crate) fn is_convex(&self) -> bool {
        self.convex
    }

    /// Whether `clear_inside` may prove a move inside: the inset made by the raw offset
    /// as one ring (`pooled`: a star's, an L's) from the outline kept.
    pub(crate) fn proves_inside(&self) -> bool {
        self.pooled && !self.outline.0.is_empty()
    }

    /// Whether the straight move from `p` to `q` is sure to stay inside the inset, proved
    /// from the outline kept (the region as given, a few edges) rather than by the
    /// router over the inset's rings: it passes farther than half a nozzle (and a
    /// margin) from every edge of the outline, so it crosses none and lies inside or
    /// outside it all along, and its middle is inside (even-odd). Then every point of
    /// it is in the erosion of the region by half a nozzle, which the raw offset holds
    /// (its moved edges and mitres are the erosion's, its round corners' chords cut
    /// inside their arcs, towards the vertex: the inset takes in more than the erosion,
    /// never less), and farther than the margin from each of the inset's edges (every
    /// point of those lies within half a nozzle of the outline: a moved edge's points
    /// half a nozzle from their edge, between its ends, the offset declining an edge
    /// that turns around; a round corner's within it of its vertex): the router would find
    /// no crossing, no edge within the nanometre it tests, and its middle inside, and
    /// answer the straight move. The margin (a tenth of a micrometre, and a hundred
    /// millionth of the largest coordinate, the move's ends' included) is far above the
    /// roundings of the offset and of the router's tests and above how far beyond the
    /// move's ends the router takes an edge's crossing as the end's (a billionth of the
    /// move's length), and far below a concentric loop's distance from the inset.
    /// `false` where `proves_inside` does not hold, or nothing proves it.
    pub(crate) fn clear_inside(&self, p: Coord, q: Coord) -> bool {
        if !self.proves_inside() {
            return false;
        }
        let mut largest: f64 = 1.0;
        for v in [
            self.min.x, self.min.y, self.max.x, self.max.y, p.x, p.y, q.x, q.y,
        ] {
            if v.abs() > largest {
                largest = v.abs();
            }
        }
        let reach = self.nozzle / 2.0 + 1e-4 + 1e-8 * largest;
        let reach2 = reach * reach;
        let (lo, hi) = (
            Coord {
                x: if p.x < q.x { p.x } else { q.x } - reach,
                y: if p.y < q.y { p.y } else { q.y } - reach,
            },
            Coord {
                x: if p.x < q.x { q.x } else { p.x } + reach,
                y: if p.y < q.y { q.y } else { p.y } + reach,
            },
        );
        let m = (p + q) / 2.0;
        let len2 = edge_len2(p, q);
        let mut inside = false;
        for polygon in &self.outline.0 {
            for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
                for w in ring.0.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    // The ray to the right of the middle (the half-open rule).
                    if (a.y <= m.y) != (b.y <= m.y)
                        && a.x + (m.y - a.y) * (b.x - a.x) / (b.y - a.y) > m.x
                    {
                        inside = !inside;
                    }
                    // An edge whose box is farther than the reach from the move's in x or
                    // y is farther from the move; else its distance is measured.
                    let beside = (a.x < lo.x && b.x < lo.x)
                        || (a.x > hi.x && b.x > hi.x)
                        || (a.y < lo.y && b.y < lo.y)
                        || (a.y > hi.y && b.y > hi.y);
                    // Most edges near the move's box are told far by the sides of the
                    // move's line (both ends beyond the reach on one side), or of
                    // theirs; the others by the distance between the two segments.
                    let far = beside
                        || super::offset::beyond(p, q, len2, a, b, reach2)
                        || super::offset::beyond(a, b, edge_len2(a, b), p, q, reach2)
                        || super::offset::apart(p, q, a, b, reach2);
                    if !far {
                        return false;
                    }
                }
            }
        }
        inside
    }

    /// Whether the inset is one ring that the raw offset proved counter-clockwise by
    /// `signed_area`'s own sum (`offset_read` keeps a ring only where that sum is
    /// positive): the side a router over it finds, known without summing it again.
    pub(crate) fn one_ring_left(&self) -> bool {
        self.pooled && self.rings.len() == 1
    }

    /// The rings of the inset: outlines first, then holes.
    pub(crate) fn rings(&self) -> &[Vec<Coord>] {
        &self.rings
    }

    pub(crate) fn outlines(&self) -> &[Vec<Coord>] {
        &self.rings[..self.outlines.min(self.rings.len())]
    }
}

impl Drop for Region {
    /// A one-ring region's lists (the commonest: a star's, an L's inset) go back to the
    /// raw offset's pools for the next layer's (`scratch`): two allocations and frees
    /// fewer per layer filled once.
    fn drop(&mut self) {
        if self.pooled && self.rings.len() == 1 {
            let ring = self.rings.pop().unwrap_or_default();
            super::scratch::give(&super::offset::RING, ring);
            super::scratch::give(&super::offset::RINGS, std::mem::take(&mut self.rings));
        }
        // The outline kept as `copied` made it (one polygon without holes): its lists
        // back to their pools (any other outline's are freed).
        if let [polygon] = &self.outline.0[..]
            && polygon.interiors().is_empty()
        {
            let mut polygons = std::mem::take(&mut self.outline.0);
            if let Some(polygon) = polygons.pop() {
                super::scratch::give(&OUTLINE_RING, polygon.into_inner().0.0);
            }
            super::scratch::give(&OUTLINE_POLYGONS, polygons);
        }
        if self.pooled_convex {
            let mut rings = std::mem::take(&mut self.rings);
            let mut each = rings.drain(..rings.len().min(2));
            let (outline, hole) = (each.next(), each.next());
            drop(each);
            super::scratch::give(&KEPT_EXTERIOR, outline.unwrap_or_default());
            super::scratch::give(&KEPT_HOLE, hole.unwrap_or_default());
            super::scratch::give(&super::offset::RINGS, rings);
        }
    }
}

/// A region's inset as it is kept: its polygons (if made), its rings open, outlines
/// first, how many holes each polygon has, its area and which offset made it.
struct Inset {
    inset: std::sync::OnceLock<MultiPolygon<f64>>,
    rings: Vec<Vec<Coord>>,
    outlines: usize,
    holes: Vec<usize>,
    area: f64,
    made_by: Offset,
}

impl Inset {
    /// The inset as polygons (the convex offset's or the buffer's): kept, with its rings
    /// opened (rings of fewer than three points dropped).
    fn of_polygons(inset: MultiPolygon<f64>, made_by: Offset) -> Inset {
        let mut rings = Vec::with_capacity(inset.0.iter().map(|p| 1 + p.interiors().len()).sum());
        for p in &inset.0 {
            rings.push(open_ring(p.exterior()));
        }
        let outlines = rings.len();
        for p in &inset.0 {
            rings.extend(p.interiors().iter().map(open_ring));
        }
        rings.retain(|r| r.len() >= 3);
        Inset {
            area: inset.unsigned_area(),
            inset: std::sync::OnceLock::from(inset),
            rings,
            outlines,
            holes: Vec::new(),
            made_by,
        }
    }
}

/// Which offset made a region's inset.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Offset {
    Convex,
    Raw,
    Buffer,
}

/// `arc_step(d)` and its `ArcStep`, kept for the last `d` (a slicer's layers share one
/// nozzle): an arc cosine, a sine and two cosines not computed again for every layer.
pub(crate) fn arc_and_step(d: f64) -> (f64, ArcStep) {
    thread_local! {
        static LAST: std::cell::Cell<(f64, f64, ArcStep)> =
            const { std::cell::Cell::new((f64::NAN, 0.0, ArcStep::NONE)) };
    }
    let (last, arc, step) = LAST.with(std::cell::Cell::get);
    if last == d {
        return (arc, step);
    }
    let arc = arc_step(d);
    let step = ArcStep::new(arc);
    LAST.with(|cell| cell.set((d, arc, step)));
    (arc, step)
}

/// The angle step (radians) of the arcs of an inset by `d`: chords that stray at most
/// 5 µm from the arc (`d·(1 − cos(step/2))`), at least 0.2 rad, at most 0.8. At half a
/// 0.4 mm nozzle that is 0.45 rad: a star's reflex corner gets 4 chords instead of 10, and
/// every line family, clip and travel route after has fewer edges to test.
pub(crate) fn arc_step(d: f64) -> f64 {
    const CHORD: f64 = 0.005;
    if d <= CHORD {
        return 0.8;
    }
    (2.0 * math::acos(1.0 - CHORD / d)).clamp(0.2, 0.8)
}

/// The region moved inward by `d` mm (the erosion by a disc; what walls leave to the
/// infill): the fast exact offsets where they apply, geo's buffer otherwise.
pub fn inset(region: &MultiPolygon<f64>, d: f64) -> MultiPolygon<f64> {
    let cleaned = clean(region);
    if cleaned.0.is_empty() || d.is_nan() || d <= 0.0 {
        return cleaned;
    }
    convex_inset(&cleaned, d, 0.2)
        .or_else(|| super::offset::raw_inset(&cleaned, d, 0.2))
        .unwrap_or_else(|| cleaned.buffer(-d))
}

/// What one pass over a region's points finds: its bounding box (infinite where it has
/// no point), whether it is clean (`is_clean`: no ring repeats a point in a row, every
/// ring has three points or more and some area) and, where it is, its first outline's
/// signed area (`signed_area`'s, the same sum: its closing edge adds nothing).
pub(crate) struct Survey {
    pub(crate) min: Coord,
    pub(crate) max: Coord,
    pub(crate) clean: bool,
    pub(crate) first_area: Option<f64>,
    /// Where it is clean and its first outline has no holes, whether that outline turns
    /// clearly left at some corner and clearly right at another (`convex_ring`'s test):
    /// it is no convex ring, either way round.
    pub(crate) first_turns_both_ways: bool,
}

/// [`Survey`] of a region, every coordinate checked finite and within
/// ±[`MAX_COORDINATE`] (the first value out of range looked for again only when some is).
pub(crate) fn survey(region: &MultiPolygon<f64>) -> Result<Survey, Error> {
    let rings = || {
        region
            .0
            .iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
    };
    let mut min = Coord {
        x: f64::INFINITY,
        y: f64::INFINITY,
    };
    let mut max = Coord {
        x: f64::NEG_INFINITY,
        y: f64::NEG_INFINITY,
    };
    let (mut within, mut clean) = (true, true);
    let mut first_area = None;
    for ring in rings() {
        let c = &ring.0;
        let Some((&head, rest)) = c.split_first() else {
            clean = false;
            continue;
        };
        math::widen(&mut min, &mut max, head);
        // `signed_area`'s terms in its order: each point and the next, the closing edge.
        let (mut sum, mut last, mut repeated) = (-0.0, head, false);
        for &p in rest {
            math::widen(&mut min, &mut max, p);
            repeated |= p == last;
            sum += cross(last, p);
            last = p;
        }
        let area = (sum + cross(last, head)) / 2.0;
        // Every coordinate is in some term of the sum (each point's with the next's): a
        // NaN or an infinity leaves it NaN or infinite (a finite value beyond the range
        // is told by the bounds).
        within &= area.is_finite();
        clean &= !repeated && c.len() >= 3 && area != 0.0;
        if first_area.is_none() {
            first_area = Some(area);
        }
    }
    let bound = MAX_COORDINATE;
    within &= -bound <= min.x && max.x <= bound && -bound <= min.y && max.y <= bound;
    // (An empty region is looked at again, and nothing found.)
    if !within {
        for ring in rings() {
            for c in ring.coords() {
                for v in [c.x, c.y] {
                    if !(v.is_finite() && v.abs() <= MAX_COORDINATE) {
                        return Err(Error::Coordinate(v));
                    }
                }
            }
        }
    }
    // Only a clean region's, read where it is: its first ring closed (as a polygon's
    // are), so its open ring's area is this one.
    let first = region
        .0
        .first()
        .filter(|_| clean)
        .filter(|p| p.exterior().0.first() == p.exterior().0.last());
    Ok(Survey {
        min,
        max,
        clean,
        first_area: first_area.filter(|_| first.is_some()),
        // Asked of an outline without holes (a star's, an L's), where the raw offset
        // follows at once.
        first_turns_both_ways: first.is_some_and(|p| {
            let c = &p.exterior().0;
            p.interiors().is_empty() && turns_both_ways(&c[..c.len() - 1])
        }),
    })
}

/// Whether an open ring turns clearly left at some corner and clearly right at another,
/// as `convex_ring_copied` tells a corner (a corner at a repeated point turns neither
/// way): then it has a reflex vertex whichever way it is turned. Told at the first
/// corner that turns the other way (a star's second).
pub(crate) fn turns_both_ways(ring: &[Coord]) -> bool {
    let n = ring.len();
    if n < 3 {
        return false;
    }
    let (mut left, mut right) = (false, false);
    let mut u = ring[0] - ring[n - 1];
    for i in 0..n {
        let c = if i + 1 < n { ring[i + 1] } else { ring[0] };
        let v = c - ring[i];
        let cross = cross(u, v);
        let scale2 = (u.x * u.x + u.y * u.y) * (v.x * v.x + v.y * v.y);
        if cross * cross > 1e-24 * scale2 {
            left |= cross > 0.0;
            right |= cross < 0.0;
            if left && right {
                return true;
            }
        }
        u = v;
    }
    false
}

/// Whether `clean` would return the region as it is: every ring without a repeated
/// point in a row, of three points or more and some area (a polygon's rings are closed).
/// (`Region::build` asks it of `survey`.)
#[cfg(test)]
pub(crate) fn is_clean(region: &MultiPolygon<f64>) -> bool {
    region.0.iter().all(|p| {
        std::iter::once(p.exterior())
            .chain(p.interiors())
            .all(|ring| {
                let c = &ring.0;
                c.len() >= 3 && c.windows(2).all(|w| w[0] != w[1]) && signed_area(c) != 0.0
            })
    })
}

/// The region without degenerate rings, every ring closed.
pub(crate) fn clean(region: &MultiPolygon<f64>) -> MultiPolygon<f64> {
    let keep = |ring: &LineString<f64>| {
        let mut c: Vec<Coord> = ring.0.clone();
        c.dedup();
        (c.len() >= 3 && signed_area(&c) != 0.0).then(|| LineString::new(c))
    };
    MultiPolygon::new(
        region
            .0
            .iter()
            .filter_map(|p| {
                let exterior = keep(p.exterior())?;
                let holes = p.interiors().iter().filter_map(keep).collect();
                Some(Polygon::new(exterior, holes))
            })
            .collect(),
    )
}

fn open_ring(ring: &LineString<f64>) -> Vec<Coord> {
    let mut c = ring.0.clone();
    if c.len() > 1 && c.first() == c.last() {
        c.pop();
    }
    c
}

/// The inward offset by `d` of a region whose outlines and holes are all convex (most
/// layers of most parts: a box, a tube, a plate with round holes), without geo's general
/// buffer, which is about a hundred times slower: each outline is clipped by its edges'
/// half-planes moved inward (exact), each hole grows by `d` with round corners (arcs in
/// steps of at most `arc` radians). Where grown holes stay inside the shrunk outline and
/// apart, that is the offset; where they meet it or each other, the shrunk outline minus
/// the grown holes by geo's boolean difference (still exact: eroding `A ∖ H` by a disc is
/// eroding `A` less `H` dilated). `None` when some ring is not convex.
pub(crate) fn convex_inset(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
) -> Option<MultiPolygon<f64>> {
    Some(match convex_rings(region, d, arc)? {
        ConvexInset::Rings(rings) => rings.into_polygons(),
        ConvexInset::Polygons(polygons) => polygons,
    })
}

/// [`convex_inset`] as a layer keeps it.
pub(crate) enum ConvexInset {
    /// Every polygon's grown holes inside its shrunk outline and apart (most): the rings
    /// open as made, outlines first, no polygon made.
    Rings(RawRings),
    /// Some grown hole met the outline or another hole: the polygons, some by geo's
    /// boolean difference.
    Polygons(MultiPolygon<f64>),
}

/// [`convex_inset`]'s rings as a layer keeps them where no grown hole meets anything.
pub(crate) fn convex_rings(region: &MultiPolygon<f64>, d: f64, arc: f64) -> Option<ConvexInset> {
    convex_rings_known(region, d, arc, None)
}

/// [`convex_rings`] with the first outline's signed area known (`Survey::first_area`).
/// [`convex_rings_known`] for a region being built, whose rings (where it has holes)
/// are taken from the lists its drop gives back.
#[inline(always)]
fn convex_rings_built(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
    first_area: Option<f64>,
) -> Option<ConvexInset> {
    let holed = region.0.len() > 1 || region.0.first().is_some_and(|p| !p.interiors().is_empty());
    let mut kept = super::scratch::take(&KEPT_POLYGONS);
    // (Two copies: an offset's without the pools compiles as it did without them.)
    let inset = if holed {
        convex_rings_in::<true>(region, d, arc, first_area, &mut kept)
    } else {
        convex_rings_in::<false>(region, d, arc, first_area, &mut kept)
    };
    super::scratch::give(&KEPT_POLYGONS, kept);
    inset
}

pub(crate) fn convex_rings_known(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
    first_area: Option<f64>,
) -> Option<ConvexInset> {
    // Per polygon kept its holes and whether they lie apart: a list kept between layers.
    let mut kept = super::scratch::take(&KEPT_POLYGONS);
    let inset = convex_rings_in::<false>(region, d, arc, first_area, &mut kept);
    super::scratch::give(&KEPT_POLYGONS, kept);
    inset
}

/// [`convex_rings_known`] with its list of the polygons kept; `POOLS`: whether its
/// list of rings, its first outline and its first hole are taken from the lists a
/// region with holes gives back when dropped (a region's being built: one kept by an
/// offset that is not given back would be taken from the pool for nothing).
fn convex_rings_in<const POOLS: bool>(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
    first_area: Option<f64>,
    kept: &mut Vec<(usize, bool)>,
) -> Option<ConvexInset> {
    // Allocated once a first outline is found convex: most concave layers are turned
    // down at their first ring, with nothing to free. Each polygon's outline then its
    // holes.
    let mut rings: Vec<Vec<Coord>> = Vec::new();
    // A reversed ring's copy, kept between layers (taken once one is needed).
    let mut buffer = Vec::new();
    let result = (|| {
        let mut known = first_area;
        for polygon in &region.0 {
            let exterior = if POOLS && rings.is_empty() {
                convex_ring_inset::<true>(&polygon.exterior().0, d, &mut buffer, known.take())?
            } else {
                convex_ring_inset::<false>(&polygon.exterior().0, d, &mut buffer, known.take())?
            };
            if rings.capacity() == 0 {
                let count = region.0.iter().map(|p| 1 + p.interiors().len()).sum();
                // The list kept between layers where one of a region with holes was
                // given back (`Region`'s drop).
                if POOLS {
                    rings = super::scratch::take(&super::offset::RINGS);
                }
                rings.reserve_exact(count);
                kept.reserve(region.0.len());
            }
            let first = rings.len();
            rings.push(exterior);
            // Each grown hole inside the shrunk outline (told from its box where that
            // can be).
            let corners = Corners::of(arc);
            let mut inside = true;
            for hole in polygon.interiors() {
                let (grown, lo, hi) = if POOLS && rings.len() == 1 {
                    grow_hole::<true>(&hole.0, d, arc, corners)?
                } else {
                    grow_hole::<false>(&hole.0, d, arc, corners)?
                };
                inside = inside && inside_convex_all(&rings[first], &grown, lo, hi);
                rings.push(grown);
            }
            let exterior = &rings[first];
            if exterior.is_empty() {
                rings.truncate(first);
                continue;
            }
            let holes = &rings[first + 1..];
            let apart = inside
                && holes
                    .iter()
                    .enumerate()
                    .all(|(i, a)| holes[i + 1..].iter().all(|b| separated(a, b)));
            kept.push((holes.len(), apart));
        }
        Some(())
    })();
    super::scratch::give(&KEPT, buffer);
    result?;
    let outlines = kept.len();
    let any_holes = kept.iter().any(|&(holes, _)| holes > 0);
    if kept.iter().all(|&(_, apart)| apart) {
        // Outlines first (one polygon's already are), then the holes, moved (not copied).
        let rings = if outlines <= 1 {
            rings
        } else {
            let mut ordered = Vec::with_capacity(rings.len());
            let mut at = 0;
            for &(holes, _) in kept.iter() {
                ordered.push(std::mem::take(&mut rings[at]));
                at += 1 + holes;
            }
            let mut at = 0;
            for &(holes, _) in kept.iter() {
                ordered.extend(rings[at + 1..at + 1 + holes].iter_mut().map(std::mem::take));
                at += 1 + holes;
            }
            ordered
        };
        return Some(ConvexInset::Rings(RawRings {
            rings,
            outlines,
            holes: if any_holes {
                kept.iter().map(|&(holes, _)| holes).collect()
            } else {
                Vec::new()
            },
            measured: None,
        }));
    }
    let closed = |mut ring: Vec<Coord>| {
        ring.reserve_exact(1);
        ring.push(ring[0]);
        LineString::new(ring)
    };
    let mut out = Vec::with_capacity(outlines);
    let mut rings = rings.into_iter();
    for &(holes, apart) in kept.iter() {
        let exterior = rings.next()?;
        let holes: Vec<Vec<Coord>> = rings.by_ref().take(holes).collect();
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
            // Grown holes may overlap: their union first (a multi-polygon's overlaps would
            // otherwise cancel out).
            let grown = if grown.len() > 1 {
                geo::unary_union(&grown)
            } else {
                MultiPolygon::new(grown)
            };
            out.extend(outer.difference(&grown).0);
        }
    }
    Some(ConvexInset::Polygons(MultiPolygon::new(out)))
}

thread_local! {
    /// `convex_rings_known`'s list of the polygons kept, kept between layers.
    static KEPT_POLYGONS: std::cell::Cell<Vec<(usize, bool)>> =
        const { std::cell::Cell::new(Vec::new()) };
    /// `convex_view`'s reversed copy of a ring, kept between layers.
    static KEPT: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    /// A convex outline's inset and a first grown hole of a region with holes, given
    /// back by the region when dropped, for the next layer's.
    static KEPT_EXTERIOR: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    static KEPT_HOLE: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
}

/// A ring's points without the closing repeat, counter-clockwise, collinear and repeated
/// vertices dropped; `None` when it has a reflex vertex.
pub(crate) fn convex_ring(ring: &[Coord]) -> Option<Vec<Coord>> {
    if has_reflex_corner(ring) {
        return None;
    }
    convex_ring_copied(ring)
}

/// `convex_ring` on a copy, every corner tested.
pub(crate) fn convex_ring_copied(ring: &[Coord]) -> Option<Vec<Coord>> {
    let mut pts: Vec<Coord> = ring.to_vec();
    if pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    pts.dedup();
    if signed_area(&pts) < 0.0 {
        pts.reverse();
    }
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let mut kept = Vec::with_capacity(n);
    // Each vertex with the one before and after (no `%` per vertex: an integer division).
    let mut a = pts[n - 1];
    for i in 0..n {
        let b = pts[i];
        let c = if i + 1 < n { pts[i + 1] } else { pts[0] };
        let (u, v) = (b - a, c - b);
        let cross = cross(u, v);
        // |cross| against 1e-12·|u|·|v|, squared (no square root per vertex).
        let scale2 = (u.x * u.x + u.y * u.y) * (v.x * v.x + v.y * v.y);
        let significant = cross * cross > 1e-24 * scale2;
        if significant && cross < 0.0 {
            return None; // a reflex vertex: not convex
        }
        if significant && cross > 0.0 {
            kept.push(b);
        }
        a = b;
    }
    // A ring that winds more than once has no reflex vertex either: its edges' direction
    // turns through more than a full turn, so their x components change sign more than
    // twice.
    let n = kept.len();
    if n < 3 {
        return None;
    }
    let signs = (0..n)
        .map(|i| (if i + 1 < n { kept[i + 1] } else { kept[0] } - kept[i]).x)
        .filter(|&x| x != 0.0)
        .map(|x| x > 0.0);
    let mut changes = 0;
    let mut first = None;
    let mut last = None;
    for s in signs {
        if last.is_some_and(|l| l != s) {
            changes += 1;
        }
        first.get_or_insert(s);
        last = Some(s);
    }
    if first != last {
        changes += 1;
    }
    (changes <= 2).then_some(kept)
}

/// Whether the ring (closing point or not) has a corner that `convex_ring` calls reflex,
/// found without copying it: a star's or an L's outline is turned down before any
/// allocation. Corners next to a repeated point, and rings of more than 32 points, are
/// left to `convex_ring` (its copy drops the repeat, which may change the corner), so
/// `false` is not a verdict of convexity.
fn has_reflex_corner(ring: &[Coord]) -> bool {
    let open = match ring {
        [first, .., last] if first == last => &ring[..ring.len() - 1],
        _ => ring,
    };
    let n = open.len();
    // A long ring (a round hole) is most likely convex: its copy is tested once, not
    // scanned twice.
    if !(3..=32).contains(&n) {
        return false;
    }
    // Turned as `convex_ring` turns it: counter-clockwise unless the area is negative.
    let sign = if signed_area(open) < 0.0 { -1.0 } else { 1.0 };
    let mut a = open[n - 2];
    let mut b = open[n - 1];
    for &c in open {
        if a != b && b != c {
            let (u, v) = (b - a, c - b);
            let cross = sign * cross(u, v);
            let scale2 = (u.x * u.x + u.y * u.y) * (v.x * v.x + v.y * v.y);
            if cross < 0.0 && cross * cross > 1e-24 * scale2 {
                return true;
            }
        }
        a = b;
        b = c;
    }
    false
}

/// What `convex_ring` keeps of a ring, read where it is where that is the ring itself
/// (every corner turning left clearly, no repeated point: most convex rings), or its
/// copy in `buffer` (turned round, or with points dropped); `None` when it has a reflex
/// vertex, as `convex_ring`. `area`: its signed area, where known.
pub(crate) fn convex_view<'a>(
    ring: &'a [Coord],
    buffer: &'a mut Vec<Coord>,
    area: Option<f64>,
) -> Option<&'a [Coord]> {
    let open = match ring {
        [first, .., last] if first == last => &ring[..ring.len() - 1],
        _ => ring,
    };
    let mut reversed = false;
    // A repeated point only adds a zero term to the area: it is `convex_ring`'s, and so
    // is the turn it gives the ring.
    // (`area`: the ring's signed area where it is known already.)
    let verdict = if open.len() >= 3 {
        reversed = area.unwrap_or_else(|| signed_area(open)) < 0.0;
        if reversed {
            if buffer.capacity() == 0 {
                *buffer = super::scratch::take(&KEPT);
            }
            buffer.clear();
            buffer.extend(open.iter().rev());
            every_corner_kept(buffer)
        } else {
            every_corner_kept(open)
        }
    } else {
        Kept::Unsure
    };
    match verdict {
        Kept::All if reversed => Some(&buffer[..]),
        Kept::All => Some(open),
        Kept::Reflex => None,
        Kept::Unsure => {
            let kept = convex_ring_copied(ring)?;
            buffer.clear();
            buffer.extend_from_slice(&kept);
            Some(&buffer[..])
        }
    }
}

/// `convex_ring_copied`'s verdict on a ring already turned counter-clockwise.
enum Kept {
    /// Every corner turns left clearly, the ring winds once: all kept, none dropped.
    All,
    /// A corner turns right clearly (wherever repeated points are), or the ring winds
    /// more than once with every corner kept: not convex.
    Reflex,
    /// Some corner is straight or at a repeated point: `convex_ring_copied` decides.
    Unsure,
}

/// Whether an open ring turns left clearly at every corner and winds once (a convex
/// ring, counter-clockwise): `every_corner_kept`'s verdict that it keeps every corner.
pub(crate) fn turns_left_once(ring: &[Coord]) -> bool {
    ring.len() >= 3 && matches!(every_corner_kept(ring), Kept::All)
}

/// `convex_ring_copied`'s corner tests on an open ring turned counter-clockwise, with
/// nothing copied: what it keeps when no corner is dropped.
fn every_corner_kept(pts: &[Coord]) -> Kept {
    let n = pts.len();
    // `convex_ring_copied` counts how often the edges' x components change sign (zeros
    // skipped, round the ring): twice a turn. Where every corner turns left clearly
    // (each by less than half a turn, the edges' direction growing all along), an edge
    // with no x component lies between a positive and a negative one, so the turns are
    // the edges whose x is positive after one whose x is not (the last edge before the
    // first).
    let mut ups = 0u32;
    let mut u = pts[0] - pts[n - 1];
    let mut u2 = u.x * u.x + u.y * u.y;
    for i in 0..n {
        let b = pts[i];
        let c = if i + 1 < n { pts[i + 1] } else { pts[0] };
        let v = c - b;
        let v2 = v.x * v.x + v.y * v.y;
        match left_corner(u, u2, v, v2) {
            Ok(up) => ups += u32::from(up),
            Err(kept) => return kept,
        }
        u = v;
        u2 = v2;
    }
    if ups <= 1 { Kept::All } else { Kept::Reflex }
}

/// The corner from edge `u` to edge `v` (their squared lengths `u2`, `v2`) of a ring
/// that should turn left clearly at every corner: `Err` where it does not (straight or
/// at a repeated point: `Unsure`; turning right: `Reflex`), else whether the edges' x
/// component turns positive there (one of `every_corner_kept`'s counted turns).
#[inline(always)]
fn left_corner(u: Coord, u2: f64, v: Coord, v2: f64) -> Result<bool, Kept> {
    let cross = cross(u, v);
    if cross * cross <= 1e-24 * (u2 * v2) {
        return Err(Kept::Unsure);
    }
    if cross < 0.0 {
        return Err(Kept::Reflex);
    }
    Ok(u.x <= 0.0 && v.x > 0.0)
}

/// The exact inward offset of one convex ring: empty when it is thinner than `2d`.
/// (`POOLED`: its list taken from the one a region with holes gives back.)
fn convex_ring_inset<const POOLED: bool>(
    ring: &[Coord],
    d: f64,
    buffer: &mut Vec<Coord>,
    area: Option<f64>,
) -> Option<Vec<Coord>> {
    let kept = convex_view(ring, buffer, area)?;
    Some(inset_kept_in::<POOLED>(kept, d))
}

/// The exact inward offset of a ring as `convex_ring` keeps it.
#[cfg(test)]
pub(crate) fn inset_kept(kept: &[Coord], d: f64) -> Vec<Coord> {
    inset_kept_in::<false>(kept, d)
}

/// [`inset_kept`], its mitred list taken from the one a region with holes gives back
/// where `POOLED`.
fn inset_kept_in<const POOLED: bool>(kept: &[Coord], d: f64) -> Vec<Coord> {
    let n = kept.len();
    if let Some(mitred) = mitred_inset::<POOLED>(kept, d) {
        return mitred;
    }
    // Some edge vanishes: the intersection of the edges' half-planes, each moved inward by
    // d, clipping the ring by each in turn.
    let mut out = kept.to_vec();
    let mut next = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (a, b) = (kept[i], kept[super::offset::next(i, n)]);
        let dir = b - a;
        let len = math::hypot(dir.x, dir.y);
        // Inside: to the left of the edge, at least d from its line.
        let side = |p: Coord| cross(dir, p - a) / len - d;
        next.clear();
        for j in 0..out.len() {
            let (p, q) = (out[j], out[(j + 1) % out.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                next.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                next.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        std::mem::swap(&mut out, &mut next);
        if out.len() < 3 {
            return Vec::new();
        }
    }
    if signed_area(&out) <= 0.0 {
        return Vec::new();
    }
    out
}

/// The inset of a counter-clockwise convex ring by `d` where no edge vanishes: each vertex
/// moves along its bisector to the point `d` from both its edges (O(n), where clipping by
/// every half-plane is O(n²)); `None` when some edge would turn around.
fn mitred_inset<const POOLED: bool>(ring: &[Coord], d: f64) -> Option<Vec<Coord>> {
    let n = ring.len();
    let unit = |e: Coord| e / (e.x * e.x + e.y * e.y).sqrt();
    // Room for the closing point the polygon adds (a list kept between layers where a
    // region with holes gave one back).
    let mut out = if POOLED {
        let mut out = super::scratch::take(&KEPT_EXTERIOR);
        out.reserve_exact(n + 1);
        out
    } else {
        Vec::with_capacity(n + 1)
    };
    for i in 0..n {
        let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[next(i, n)]);
        let (u, v) = (unit(b - a), unit(c - b));
        // The inward normals (left of each edge) and their mitre.
        let (nu, nv) = (Coord { x: -u.y, y: u.x }, Coord { x: -v.y, y: v.x });
        let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
        if k <= 1e-9 {
            return None;
        }
        out.push(b + (nu + nv) * (d / k));
    }
    for i in 0..n {
        let (a, b) = (ring[i], ring[next(i, n)]);
        let (p, q) = (out[i], out[next(i, n)]);
        let (e, f) = (b - a, q - p);
        if e.x * f.x + e.y * f.y <= 0.0 {
            return None;
        }
    }
    Some(out)
}

/// How `grow` turns a hole's corners for an arc step: the cosine of the step (a corner
/// turning by less takes no arc), and the least cosine of a corner's turn whose mitre
/// lies no farther out than a chord cuts in (`1/cos(α/2) − 1 ≤ 1 − cos(arc/2)`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corners {
    arc_cos: f64,
    mitre_from: f64,
}

impl Corners {
    /// Kept for the last step (a slicer's layers share one): two cosines and the search
    /// below not made again for every ring grown.
    pub(crate) fn of(arc: f64) -> Corners {
        thread_local! {
            static LAST: std::cell::Cell<(f64, Corners)> = const {
                std::cell::Cell::new((f64::NAN, Corners { arc_cos: 0.0, mitre_from: 0.0 }))
            };
        }
        let (last, corners) = LAST.with(std::cell::Cell::get);
        if last == arc {
            return corners;
        }
        let corners = Corners {
            arc_cos: math::cos(arc),
            mitre_from: mitre_from(1.0 - math::cos(arc / 2.0)),
        };
        LAST.with(|cell| cell.set((arc, corners)));
        corners
    }
}

/// Whether a corner turning by `cos` (positive) takes one mitre point: its mitre strays
/// `1/cos(α/2) − 1` beyond the moved edges, no more than `room`. Each step of it is a
/// correctly rounded operation, each monotonic, so the answer flips once as `cos` grows:
/// at `mitre_from(room)`.
pub(crate) fn mitre_fits(cos: f64, room: f64) -> bool {
    let half_cos = ((1.0 + cos) / 2.0).sqrt();
    1.0 / half_cos - 1.0 <= room
}

/// The least positive `cos` for which `mitre_fits(cos, room)` (infinite where none):
/// a binary search over the doubles' bit patterns, which the positive ones keep in order.
pub(crate) fn mitre_from(room: f64) -> f64 {
    let (mut lo, mut hi) = (1u64, f64::MAX.to_bits());
    if !mitre_fits(f64::MAX, room) {
        return f64::INFINITY;
    }
    // `hi` fits, `lo - 1` (zero) is outside the search: the least that fits is in lo..=hi.
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if mitre_fits(f64::from_bits(mid), room) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    f64::from_bits(lo)
}

/// A ring as `convex_ring` keeps it grown outward by `d`: each edge moved out, each
/// corner an arc of radius `d` about its vertex, with its points on the arc (so the
/// chords cut in by at most `d·(1 − cos(arc/2))`), or where the corner turns by little,
/// the mitre (out by no more).
fn grow_kept(kept: &[Coord], d: f64, arc: f64, corners: Corners) -> Vec<Coord> {
    let mut out = Vec::with_capacity(2 * kept.len() + 1);
    grow::<false>(kept.len(), |i| kept[i], d, arc, corners, &mut out);
    out
}

/// A hole grown outward by `d` (as `grow_kept` of `convex_ring`), read where it is,
/// either way round, its corners tested as it grows; with its box. `None` when it has a
/// reflex vertex.
/// (`POOLED`: its list taken from the one a region with holes gives back.)
fn grow_hole<const POOLED: bool>(
    ring: &[Coord],
    d: f64,
    arc: f64,
    corners: Corners,
) -> Option<(Vec<Coord>, Coord, Coord)> {
    let open = match ring {
        [first, .., last] if first == last => &ring[..ring.len() - 1],
        _ => ring,
    };
    let n = open.len();
    if n >= 3 {
        // Room for a round hole's points (one mitre a corner), a small allocation's
        // size for a 64-gon; a sharper hole's arcs grow it. (The ring is kept open: the
        // polygons, if asked, are made afresh.)
        // (A list kept between layers where a region with holes gave one back.)
        let mut out = if POOLED {
            let mut out = super::scratch::take(&KEPT_HOLE);
            out.reserve_exact(n);
            out
        } else {
            Vec::with_capacity(n)
        };
        // Counter-clockwise, as `convex_ring` turns it (a repeated point adds nothing).
        let verdict = if signed_area(open) < 0.0 {
            grow::<true>(n, |i| open[n - 1 - i], d, arc, corners, &mut out)
        } else {
            grow::<true>(n, |i| open[i], d, arc, corners, &mut out)
        };
        match verdict {
            Kept::All => {
                let (lo, hi) = bounds(&out);
                return Some((out, lo, hi));
            }
            Kept::Reflex => return None,
            Kept::Unsure => {}
        }
    }
    let out = grow_kept(&convex_ring_copied(ring)?, d, arc, corners);
    let (lo, hi) = bounds(&out);
    Some((out, lo, hi))
}

/// A ring's bounding box.
fn bounds(ring: &[Coord]) -> (Coord, Coord) {
    let (mut lo, mut hi) = (ring[0], ring[0]);
    for &p in &ring[1..] {
        math::widen(&mut lo, &mut hi, p);
    }
    (lo, hi)
}

/// The growth of `grow_kept` of the `n` points `at(0..n)` (counter-clockwise) into
/// `out`. With `CHECK`, each corner is tested as `every_corner_kept` tests it, and its
/// verdict returned (the points grown are then `grow_kept`'s only for `Kept::All`).
#[inline(always)]
fn grow<const CHECK: bool>(
    n: usize,
    at: impl Fn(usize) -> Coord,
    d: f64,
    arc: f64,
    corners: Corners,
    out: &mut Vec<Coord>,
) -> Kept {
    // Each edge's normal once (the corner before and the corner after it share it).
    let normal = |e: Coord| {
        let len = math::hypot(e.x, e.y);
        Coord {
            x: e.y / len,
            y: -e.x / len,
        }
    };
    let a = at(n - 1);
    let mut b = at(0);
    let mut u = b - a;
    let mut u2 = u.x * u.x + u.y * u.y;
    let mut n0 = normal(u);
    // How often the edges' x components turn from negative (or zero) to positive:
    // `every_corner_kept`'s count of turns.
    let mut ups = 0u32;
    for i in 0..n {
        let c = if i + 1 < n { at(i + 1) } else { at(0) };
        let v = c - b;
        if CHECK {
            let v2 = v.x * v.x + v.y * v.y;
            match left_corner(u, u2, v, v2) {
                Ok(up) => ups += u32::from(up),
                Err(kept) => return kept,
            }
            u = v;
            u2 = v2;
        }
        let n1 = normal(v);
        let (sin, cos) = (cross(n0, n1), n0.x * n1.x + n0.y * n1.y);
        // Most corners of a round hole turn by less than `arc`: their two ends only, no
        // trigonometry; sharper ones in equal steps, each the last rotated.
        let steps = if sin >= 0.0 && cos >= corners.arc_cos {
            1
        } else {
            (math::atan2(sin, cos).max(0.0) / arc).ceil().max(1.0) as usize
        };
        // A corner turning by little (a round hole's) gets one mitre point, no farther out
        // than a chord cuts in (`mitre_fits`, told by the least cosine that does): half
        // the vertices of a 64-gon hole, for every pattern's clipping and routing after.
        if steps == 1 && cos >= corners.mitre_from {
            let k = 1.0 + cos;
            out.push(b + (n0 + n1) * (d / k));
        } else {
            out.push(b + n0 * d);
            if steps > 1 {
                let (s, c) = math::sin_cos(math::atan2(sin, cos).max(0.0) / steps as f64);
                let mut w = n0;
                for _ in 1..steps {
                    w = Coord {
                        x: w.x * c - w.y * s,
                        y: w.x * s + w.y * c,
                    };
                    out.push(b + w * d);
                }
            }
            out.push(b + n1 * d);
        }
        n0 = n1;
        b = c;
    }
    if CHECK && ups > 1 {
        return Kept::Reflex;
    }
    Kept::All
}

/// Whether every point of `ring` is strictly inside the counter-clockwise convex ring
/// `outer` (`inside_convex` of each), told where it can be from the corners of the
/// ring's box: each clearly inside every edge (by a margin far above the rounding of
/// the cross products over the whole box, whose smallest value over the box is at a
/// corner), then so is every point of the box, by the test's own arithmetic too.
fn inside_convex_all(outer: &[Coord], ring: &[Coord], lo: Coord, hi: Coord) -> bool {
    let corners = [
        lo,
        Coord { x: hi.x, y: lo.y },
        hi,
        Coord { x: lo.x, y: hi.y },
    ];
    let n = outer.len();
    let boxed = (0..n).all(|i| {
        let (a, b) = (outer[i], outer[next(i, n)]);
        let e = b - a;
        // The smallest cross product at a corner, and the largest sum of its terms'
        // magnitudes (at a corner too: each term's magnitude is convex over the box).
        let (mut least, mut scale) = (f64::INFINITY, 0.0f64);
        for &c in &corners {
            let f = c - a;
            let (s, t) = (e.x * f.y, e.y * f.x);
            least = least.min(s - t);
            scale = scale.max(s.abs() + t.abs());
        }
        // (and clear of the products' underflow).
        least > 1e-12 * scale + 1e-280
    });
    boxed || ring.iter().all(|&p| inside_convex(outer, p))
}

/// Whether `p` is strictly inside the counter-clockwise convex ring.
pub(crate) fn inside_convex(ring: &[Coord], p: Coord) -> bool {
    let n = ring.len();
    (0..n).all(|i| cross(ring[next(i, n)] - ring[i], p - ring[i]) > 0.0)
}

/// Whether two counter-clockwise convex rings are apart: some edge of one has the whole
/// other strictly on its outer side.
pub(crate) fn separated(a: &[Coord], b: &[Coord]) -> bool {
    let outside = |r: &[Coord], s: &[Coord]| {
        let n = r.len();
        (0..n).any(|i| {
            let (p, q) = (r[i], r[next(i, n)]);
            s.iter().all(|&x| cross(q - p, x - p) < 0.0)
        })
    };
    outside(a, b) || outside(b, a)
}
