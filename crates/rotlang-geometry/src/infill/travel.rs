//! Travel moves that stay inside the region, as slicers route them ("avoid crossing
//! walls"): a straight move that would cross a hole, or leave a concave outline, goes
//! around along that ring instead, the shorter way.
//!
//! Plain square roots, not `hypot` (several times slower; coordinates are bounded by
//! `MAX_COORDINATE`, so nothing overflows).

use geo::Coord;

use super::offset::next;
use super::scratch;

thread_local! {
    /// A router's lists, kept from one layer to the next.
    static BOXES: std::cell::Cell<Vec<(Coord, Coord)>> = const { std::cell::Cell::new(Vec::new()) };
    static CUTS: std::cell::Cell<Vec<(f64, Cut)>> = const { std::cell::Cell::new(Vec::new()) };
    static PATH: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    static LENGTHS: std::cell::Cell<Vec<f64>> = const { std::cell::Cell::new(Vec::new()) };
    static AT: std::cell::Cell<Vec<(usize, usize)>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Edges per chunk: each ring's edges are taken in runs of this many consecutive ones,
/// each run with its bounding box, so that a move or a point far from a run skips it
/// whole (a round hole's 64 edges are 8 boxes, of which a move near it meets one or two).
const CHUNK: usize = 8;

/// Up to this many edges in all, a region's chunks hold half as many.
const SMALL: usize = 32;

/// From this many edges a ring's walk takes its way round from an arc where it can
/// (`shorter_way`): below, measuring the whole ring costs about as much.
const MEASURED: usize = 16;

/// The most edges a first ring (a convex outline) may have for its moves to be told
/// clear of it by its edges' half-planes (`Router::deep`): about a box's test per edge,
/// where its chunks' boxes would all meet a move inside (the ring's box holds every move).
const DEEP_EDGES: usize = 8;

/// Where a move crosses a ring./// Where a move crosses a ring.
#[derive(Clone, Copy, Debug)]
struct Cut {
    ring: usize,
    edge: usize,
    /// The fraction along the edge.
    u: f64,
    /// Met just beyond an end of the move (within a billionth of its length): not a
    /// crossing, only a sign of where that end lies (a line's end a rounding inside).
    near: bool,
}

/// The rings with their cumulative lengths, ready for many moves.
pub(crate) struct Router<'a> {
    rings: &'a [Vec<Coord>],
    /// Ring `r`'s cumulative lengths are `lengths[at[r].1..at[r].1 + n + 1]` (one flat
    /// list: one allocation, not one per ring), measured when a first move is walked
    /// around (most layers' moves are straight).
    lengths: std::cell::OnceCell<Vec<f64>>,
    /// The crossings of the move being routed, kept for the next.
    cuts: std::cell::Cell<Vec<(f64, Cut)>>,
    /// The route being built, kept for the next.
    path: std::cell::Cell<Vec<Coord>>,
    /// Per ring, its bounding box (a move or point outside it cannot cross it or be in
    /// it), then the boxes of its chunks of `CHUNK` edges, grown by a little slack
    /// (below): one list, ring `r`'s from `at[r].0`.
    boxes: Vec<(Coord, Coord)>,
    /// Where each ring's boxes and cumulative lengths start; empty for a single ring
    /// (both at 0: no list to allocate for most layers).
    at: Vec<(usize, usize)>,
    /// `CHUNK`, or (in tests) a ring's whole length: every edge tested, as before chunks.
    chunk: usize,
    /// Per ring, whether the region lies on its left (measured when first needed); for
    /// a single ring, in `left_one` (no list).
    left: std::cell::OnceCell<Vec<bool>>,
    left_one: std::cell::OnceCell<bool>,
    /// Whether a move that leaves a ring clearly inward is taken as inside without the
    /// even-odd test of its middle (off in tests, for the general path).
    fast: bool,
    /// Whether both fractions of every edge's crossing are divided out before either is
    /// tested (in tests: the general path the early test is compared with).
    divide_first: bool,
    /// Whether a walk projects the move's ends on the ring even where a crossing at the
    /// end says where they are (in tests: the general path).
    project_ends: bool,
    /// Whether an edge with both ends clearly on one side of a move's line is passed
    /// without its crossing's divisions (`hits`; off in tests, for the general path).
    sides: bool,
    /// Whether a walked move's middle, found clearly off every edge, answers for its
    /// stretch's middle nearby without a second `on_an_edge` (off in tests).
    reuse: bool,
    /// A billionth of a millimetre per millimetre of the rings' largest coordinate (the
    /// chunks' slack): the scale of `hits`' side test.
    unit: f64,
    /// Whether a walk's way round is taken from the arc the fewer edges span where that
    /// is certain (`shorter_way`; off in tests, for the cumulative lengths' answer).
    bound_ways: bool,
    /// Whether moves are told apart from every edge (`hits`), so that one touching none
    /// from `interior` is inside without the even-odd test (off in tests).
    chain: bool,
    /// The end of the last move found inside by the even-odd test of its middle (not on
    /// an edge) and touching no edge: a point inside the region, on no edge. The next
    /// move from there (a closed loop's, which ends where it starts) touching no edge is
    /// inside too.
    interior: std::cell::Cell<Option<Coord>>,
    /// Where a small convex first ring with other rings (a convex outline with holes)
    /// has its edges in `boxes` and how many (none otherwise): each as its start and its
    /// direction scaled to the margin (`deep_edges`). A move clear inside all of them
    /// crosses and touches none of them, and that ring's `hits` are not searched.
    deep: (usize, usize),
    /// A box inside which every point is clear inside all of those edges (its corners
    /// are): ring 0's box shrunk by two margins, where its corners are (a rectangle's,
    /// the holed square's outline); a point in it is told without the edges.
    deep_box: Option<(Coord, Coord)>,
}

/// Where `locate` finds a point.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Place {
    /// Within a nanometre of an edge (inside, for `inside`).
    OnEdge,
    /// Inside by the even-odd test, on no edge.
    In,
    Out,
}

/// The largest coordinate's size in the box `(lo, hi)`, or `largest` if larger (by
/// comparisons, as the boxes: the coordinates are finite).
fn largest_in((lo, hi): (Coord, Coord), mut largest: f64) -> f64 {
    for v in [lo.x, lo.y, hi.x, hi.y] {
        if v.abs() > largest {
            largest = v.abs();
        }
    }
    largest
}

/// How much a chunk's box is grown: a millionth of a nanometre per millimetre of the
/// largest coordinate, more than any rounding in the tests a chunk's box stands for, so
/// that skipping a chunk never skips an edge the test would have taken.
fn slack(largest: f64) -> f64 {
    1e-9 * (1.0 + largest)
}

impl<'a> Router<'a> {
    pub(crate) fn new(rings: &'a [Vec<Coord>]) -> Router<'a> {
        Router::told(rings, false)
    }

    /// [`Router::new`], told (`left`) that `rings` is one ring whose `signed_area` is
    /// known positive (`Region::one_ring_left`): a small one's area is then not summed
    /// (the answer that sum would give, to the bit: `offset_read` tested the same terms
    /// in the same order).
    pub(crate) fn told(rings: &'a [Vec<Coord>], left: bool) -> Router<'a> {
        // A small region (a star's or an L's inset, a few dozen edges, whose runs of 8
        // span most of it) in runs of 4: more of them missed by a move's box.
        let vertices: usize = rings.iter().map(Vec::len).sum();
        if rings.len() == 1 && (3..=SMALL).contains(&vertices) {
            return if left {
                Router::small_of::<false>(rings)
            } else {
                Router::small_of::<true>(rings)
            };
        }
        Router::with_chunk(rings, if vertices <= SMALL { CHUNK / 2 } else { CHUNK })
    }

    /// `with_chunk(rings, CHUNK / 2)` for a single ring of 3 to `SMALL` edges (a star's
    /// inset, an L's): the same boxes, made in one pass over the
    /// ring that also sums its signed area in `signed_area`'s order (edge by edge, the
    /// closing edge last: the same sum to the bit), so that which side the region lies
    /// on (`region_left`) is known without a second pass.
    #[cfg(test)]
    pub(crate) fn small(rings: &'a [Vec<Coord>]) -> Router<'a> {
        Router::small_of::<true>(rings)
    }

    /// [`Router::small`], the area summed only where `SUM` (else the ring is known
    /// counter-clockwise: `Router::told`).
    fn small_of<const SUM: bool>(rings: &'a [Vec<Coord>]) -> Router<'a> {
        const STEP: usize = CHUNK / 2;
        let r = &rings[0];
        // The ring's box first (set once its chunks are measured), as in `with_chunk`.
        let mut boxes = scratch::take(&BOXES);
        boxes.resize(1 + r.len().div_ceil(STEP), (Coord::zero(), Coord::zero()));
        let mut ring_box = bounds(&[]);
        // `signed_area`'s sum starts as `sum` does (from −0), each edge's term in turn.
        let mut twice = -0.0;
        // Chunk c holds edges c·STEP.. and vertices c·STEP..=(c + 1)·STEP, the last
        // wrapping to the first: each full chunk is its first vertex and the next STEP
        // (the same box as `with_chunk`'s, whose minimum and maximum do not depend on
        // the order but for the sign of a zero, which no use of a box tells apart).
        let mut a = r[0];
        let (full, rest) = r[1..].as_chunks::<STEP>();
        let mut count = 0;
        for next in full {
            let (mut lo, mut hi) = (a, a);
            for &b in next {
                crate::math::widen(&mut lo, &mut hi, b);
                if SUM {
                    twice += super::offset::cross(a, b);
                }
                a = b;
            }
            count += 1;
            boxes[count] = (lo, hi);
            crate::math::widen(&mut ring_box.0, &mut ring_box.1, lo);
            crate::math::widen(&mut ring_box.0, &mut ring_box.1, hi);
        }
        // The last chunk: the vertices left, then the closing edge to the first.
        let (mut lo, mut hi) = (a, a);
        for &b in rest.iter().chain(std::iter::once(&r[0])) {
            crate::math::widen(&mut lo, &mut hi, b);
            if SUM {
                twice += super::offset::cross(a, b);
            }
            a = b;
        }
        count += 1;
        boxes[count] = (lo, hi);
        crate::math::widen(&mut ring_box.0, &mut ring_box.1, lo);
        crate::math::widen(&mut ring_box.0, &mut ring_box.1, hi);
        let slack = slack(largest_in(ring_box, 0.0));
        for (lo, hi) in &mut boxes[1..=count] {
            *lo = *lo - Coord { x: slack, y: slack };
            *hi = *hi + Coord { x: slack, y: slack };
        }
        boxes[0] = ring_box;
        // Counter-clockwise (a positive area) is an outline, as `region_left` finds.
        let left_one = std::cell::OnceCell::from(!SUM || twice / 2.0 > 0.0);
        Router::assembled(rings, boxes, Vec::new(), STEP, left_one, slack)
    }

    /// A router with chunks of `chunk` edges (`usize::MAX`: one per ring).
    pub(crate) fn with_chunk(rings: &'a [Vec<Coord>], chunk: usize) -> Router<'a> {
        let vertices: usize = rings.iter().map(Vec::len).sum();
        // The router's lists are kept from one layer to the next (`scratch`).
        let mut chunks = scratch::take(&BOXES);
        chunks.reserve(vertices / chunk + 2 * rings.len());
        let mut at = Vec::new();
        if rings.len() > 1 {
            at = scratch::take(&AT);
            at.reserve(rings.len());
        }
        let mut largest: f64 = 0.0;
        let mut lengths_at = 0;
        for r in rings {
            let n = r.len();
            // The ring's box first, set once its chunks are measured.
            let ring_at = chunks.len();
            if rings.len() > 1 {
                at.push((ring_at, lengths_at));
            }
            lengths_at += n + 1;
            chunks.push((Coord::zero(), Coord::zero()));
            // Chunk c holds edges c·CHUNK.. (up to the ring's end), so vertices
            // c·CHUNK..=(c + 1)·CHUNK, the last wrapping to the first. Boxes by
            // comparisons, not `min`/`max` (which handle NaN, and cost several
            // instructions each): the coordinates are finite, the boxes are the same. The
            // ring's box grows with its chunks' (they hold every vertex).
            let mut ring_box = bounds(&[]);
            let mut from = 0;
            for edges in r.chunks(chunk) {
                let to = from + edges.len();
                let last = if to < n { r[to] } else { r[0] };
                let (mut lo, mut hi) = (last, last);
                for &c in edges {
                    crate::math::widen(&mut lo, &mut hi, c);
                }
                chunks.push((lo, hi));
                if lo.x < ring_box.0.x {
                    ring_box.0.x = lo.x;
                }
                if lo.y < ring_box.0.y {
                    ring_box.0.y = lo.y;
                }
                if hi.x > ring_box.1.x {
                    ring_box.1.x = hi.x;
                }
                if hi.y > ring_box.1.y {
                    ring_box.1.y = hi.y;
                }
                from = to;
            }
            largest = largest_in(ring_box, largest);
            chunks[ring_at] = ring_box;
        }
        let slack = slack(largest);
        let mut ring_at = 0;
        for r in rings {
            let count = r.len().div_ceil(chunk);
            for (lo, hi) in &mut chunks[ring_at + 1..ring_at + 1 + count] {
                *lo = *lo - Coord { x: slack, y: slack };
                *hi = *hi + Coord { x: slack, y: slack };
            }
            ring_at += 1 + count;
        }
        let mut router =
            Router::assembled(rings, chunks, at, chunk, std::cell::OnceCell::new(), slack);
        // (A single ring convex is a convex region, where nothing is routed.)
        if rings.len() > 1 {
            router.deep_edges(1e3 * slack);
        }
        router
    }

    /// Ring 0's edges appended to `boxes` where it is convex and counter-clockwise
    /// (`region::turns_left_once`) with at most `DEEP_EDGES` edges: each edge's start
    /// and its direction divided by `margin` times its length, so that a point's cross
    /// product with it is its distance from the edge's line in margins (within a few
    /// units in the last place). A move both of whose ends are more than a margin inside
    /// every edge's half-plane stays that far from every edge's line (the half-planes'
    /// distances are affine along it). `margin`: a millionth of a millimetre per
    /// millimetre of the largest coordinate (a thousand times the chunks' slack), above
    /// a nanometre (`on_edge`'s tolerance), above a billionth of any move's length (how
    /// far `hits` keeps a crossing beyond the move's ends) and far above the roundings
    /// of its fractions (about 10⁻¹⁵ of the coordinates): there `hits` would find no
    /// crossing of the ring, no edge it keeps as one the move may run along whose middle
    /// is on it, and no edge the move touches. The holed square's outline: every move of
    /// its loops is well inside it.
    fn deep_edges(&mut self, margin: f64) {
        let ring = &self.rings[0];
        let n = ring.len();
        if !(3..=DEEP_EDGES).contains(&n) || !super::region::turns_left_once(ring) {
            return;
        }
        let from = self.boxes.len();
        for (i, &a) in ring.iter().enumerate() {
            let e = ring[next(i, n)] - a;
            self.boxes
                .push((a, e / (margin * (e.x * e.x + e.y * e.y).sqrt())));
        }
        self.deep = (from, n);
        // Each point of a box is inside each edge's half-plane by at least the least of
        // its corners' distances (an affine function over the box): the corners tested.
        let (lo, hi) = self.ring_box(0);
        let shrink = Coord {
            x: 2.0 * margin,
            y: 2.0 * margin,
        };
        let (lo, hi) = (lo + shrink, hi - shrink);
        let corners = [
            lo,
            Coord { x: hi.x, y: lo.y },
            hi,
            Coord { x: lo.x, y: hi.y },
        ];
        if lo.x < hi.x && lo.y < hi.y && corners.iter().all(|&c| self.deep_edges_clear(c)) {
            self.deep_box = Some((lo, hi));
        }
    }

    /// Whether `p` is more than a margin inside each of ring 0's edges kept by
    /// `deep_edges` (by each edge: none kept, true).
    #[inline]
    fn deep_edges_clear(&self, p: Coord) -> bool {
        let (from, count) = self.deep;
        self.boxes[from..from + count]
            .iter()
            .all(|&(a, e)| cross(e, p - a) > 1.0)
    }

    /// Whether the box of the move from `p` to `q` misses the box of every ring but the
    /// first.
    #[inline]
    fn misses_holes(&self, p: Coord, q: Coord) -> bool {
        let (lo, hi) = move_box(p, q);
        (1..self.rings.len()).all(|r| {
            let (a, b) = self.ring_box(r);
            hi.x < a.x || lo.x > b.x || hi.y < a.y || lo.y > b.y
        })
    }

    /// Whether `p` and `q` are both more than a margin inside each of ring 0's edges
    /// kept by `deep_edges` (false where none is).
    #[inline]
    fn deep_inside(&self, p: Coord, q: Coord) -> bool {
        if let Some((lo, hi)) = self.deep_box {
            let within = |c: Coord| lo.x < c.x && c.x < hi.x && lo.y < c.y && c.y < hi.y;
            if within(p) && within(q) {
                return true;
            }
        }
        self.deep.1 > 0 && self.deep_edges_clear(p) && self.deep_edges_clear(q)
    }

    /// The router over `rings` with its `boxes` (each ring's, then its chunks' of `chunk`
    /// edges, these grown by `slack`), each ring's place in them (`at`, several rings
    /// only) and, where known, whether one ring has the region on its left; every
    /// shortcut on.
    fn assembled(
        rings: &'a [Vec<Coord>],
        boxes: Vec<(Coord, Coord)>,
        at: Vec<(usize, usize)>,
        chunk: usize,
        left_one: std::cell::OnceCell<bool>,
        slack: f64,
    ) -> Router<'a> {
        Router {
            rings,
            lengths: std::cell::OnceCell::new(),
            cuts: std::cell::Cell::new(scratch::take(&CUTS)),
            path: std::cell::Cell::new(scratch::take(&PATH)),
            boxes,
            at,
            chunk,
            left: std::cell::OnceCell::new(),
            left_one,
            fast: true,
            divide_first: false,
            project_ends: false,
            sides: true,
            reuse: true,
            unit: slack,
            bound_ways: true,
            chain: true,
            interior: std::cell::Cell::new(None),
            deep: (0, 0),
            deep_box: None,
        }
    }

    /// The same router without the inward-move shortcut (tests compare the two).
    #[cfg(test)]
    pub(crate) fn general(mut self) -> Router<'a> {
        self.fast = false;
        self
    }

    /// The same router testing every edge of a chunk a move's box meets for a crossing,
    /// wherever its ends lie (tests compare the two).
    #[cfg(test)]
    pub(crate) fn every_edge(mut self) -> Router<'a> {
        self.sides = false;
        self
    }

    /// The same router testing every stretch's middle for an edge, however near the
    /// move's middle found clearly off them all.
    #[cfg(test)]
    pub(crate) fn testing_every_middle(mut self) -> Router<'a> {
        self.reuse = false;
        self
    }

    /// The same router searching a convex first ring's edges for every move.
    #[cfg(test)]
    pub(crate) fn searching_every_ring(mut self) -> Router<'a> {
        self.deep = (0, 0);
        self.deep_box = None;
        self
    }

    /// Whether the first ring's moves may be told clear of it by its half-planes (tests).
    #[cfg(test)]
    pub(crate) fn tells_deep_moves(&self) -> bool {
        self.deep.1 > 0
    }

    /// Whether some of those are told by a box inside the first ring (tests).
    #[cfg(test)]
    pub(crate) fn has_deep_box(&self) -> bool {
        self.deep_box.is_some()
    }

    /// The same router telling moves clear of the first ring by its edges only.
    #[cfg(test)]
    pub(crate) fn without_deep_box(mut self) -> Router<'a> {
        self.deep_box = None;
        self
    }

    /// The same router testing every move's middle, wherever it starts.
    #[cfg(test)]
    pub(crate) fn unchained(mut self) -> Router<'a> {
        self.chain = false;
        self
    }

    /// The same router deciding every walk's way round by the ring's cumulative lengths.
    #[cfg(test)]
    pub(crate) fn measuring_ways(mut self) -> Router<'a> {
        self.bound_ways = false;
        self
    }

    /// `near_an_edge` and `on_an_edge` (tests).
    #[cfg(test)]
    pub(crate) fn near_and_on_an_edge(&self, p: Coord) -> (bool, bool) {
        (self.near_an_edge(p), self.on_an_edge(p))
    }

    /// How far from a point found clear of the edges another is answered for (tests).
    #[cfg(test)]
    pub(crate) const CLEAR: f64 = CLEAR;

    /// The same router projecting the move's ends on the ring before every walk.
    #[cfg(test)]
    pub(crate) fn projecting_ends(mut self) -> Router<'a> {
        self.project_ends = true;
        self
    }

    /// The same router dividing out both fractions of every edge's crossing before
    /// testing them.
    #[cfg(test)]
    pub(crate) fn dividing_first(mut self) -> Router<'a> {
        self.divide_first = true;
        self
    }

    /// Where a move crosses every ring, as (fraction along the move, ring, edge,
    /// fraction along the edge, near) with bits for exact comparison (tests).
    #[cfg(test)]
    pub(crate) fn crossings_of_move(
        &self,
        p: Coord,
        q: Coord,
    ) -> Vec<(u64, usize, usize, u64, bool)> {
        let mut out = Vec::new();
        for r in 0..self.rings.len() {
            let _ = self.hits::<false>(r, p, q, &mut out);
        }
        out.iter()
            .map(|(t, c)| (t.to_bits(), c.ring, c.edge, c.u.to_bits(), c.near))
            .collect()
    }

    /// Whether a move that crosses no ring inside it (`cuts`: where it meets the rings)
    /// starts or ends on an edge's middle and heads clearly into the region from it: then
    /// it is inside all along (it would have to cross a ring to leave), and the even-odd
    /// test of its middle is not needed. `Some(false)` where it heads clearly out of the
    /// region there: outside all along, so that test could only find its middle on an
    /// edge (`on_an_edge`). Any doubt (a vertex, a grazing move, two rings met at that
    /// end) answers `None`, for that test to decide.
    fn leaves_inward(&self, p: Coord, q: Coord, cuts: &[(f64, Cut)]) -> Option<bool> {
        let d = q - p;
        let d2 = d.x * d.x + d.y * d.y;
        for (at_p, from, to) in [(true, p, q), (false, q, p)] {
            let mut at_end = cuts
                .iter()
                .filter(|&&(t, _)| if at_p { t <= 1e-9 } else { t >= 1.0 - 1e-9 });
            let (Some(&(_, c)), None) = (at_end.next(), at_end.next()) else {
                continue;
            };
            if !(c.u > 1e-6 && c.u < 1.0 - 1e-6) {
                continue;
            }
            let ring = &self.rings[c.ring];
            let e = ring[next(c.edge, ring.len())] - ring[c.edge];
            let turn = cross(e, to - from);
            // Clearly off the edge's line: more than a thousandth of a radian.
            if turn * turn <= 1e-6 * (e.x * e.x + e.y * e.y) * d2 {
                continue;
            }
            return Some((turn > 0.0) == self.region_left(c.ring));
        }
        None
    }

    /// Whether the stretch before bound `k` of a move (`d` its direction; bound `k` is
    /// `cuts[k]`, the move's end past the last) runs into the region from a crossing at
    /// either of its ends: a crossing inside the move, alone there (no other within a
    /// billionth of the move), through an edge's middle and clearly across it, enters
    /// the region on one side of the edge; `Some(false)` where it runs out of the region
    /// from such a crossing (outside all along: the even-odd test could only find its
    /// middle on an edge, `on_an_edge`). `None` where in doubt, for the even-odd test of
    /// the stretch's middle to decide.
    fn enters(&self, cuts: &[(f64, Cut)], k: usize, d: Coord) -> Option<bool> {
        let d2 = d.x * d.x + d.y * d.y;
        let clean = |i: usize| {
            let (t, c) = cuts[i];
            t > 1e-9
                && t < 1.0 - 1e-9
                && c.u > 1e-6
                && c.u < 1.0 - 1e-6
                && (i == 0 || t - cuts[i - 1].0 > 1e-9)
                && (i + 1 == cuts.len() || cuts[i + 1].0 - t > 1e-9)
        };
        // The crossing the stretch starts at (moving along d), then the one it ends at
        // (moving back).
        for (i, sign) in [(k.wrapping_sub(1), 1.0), (k, -1.0)] {
            if i >= cuts.len() || !clean(i) {
                continue;
            }
            let c = cuts[i].1;
            let ring = &self.rings[c.ring];
            let e = ring[next(c.edge, ring.len())] - ring[c.edge];
            let turn = sign * cross(e, d);
            if turn * turn <= 1e-6 * (e.x * e.x + e.y * e.y) * d2 {
                continue;
            }
            return Some((turn > 0.0) == self.region_left(c.ring));
        }
        None
    }

    /// Whether `inside(p)` finds `p` on an edge (within a nanometre, in a ring's box): its
    /// answer for a point known to be outside by the crossings (a move or stretch that
    /// runs out of the region from a clean crossing), without the ray's crossings. The
    /// chunks it skips are those farther than a nanometre from `p`, where `on_edge`
    /// cannot hold (the test `inside` makes on every chunk it reads).
    fn on_an_edge(&self, p: Coord) -> bool {
        for (r, ring) in self.rings.iter().enumerate() {
            let (lo, hi) = self.ring_box(r);
            if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
                continue;
            }
            let n = ring.len();
            for (c, lo, hi) in self.boxes_of(r) {
                let near = p.x >= lo.x - 1e-6
                    && p.x <= hi.x + 1e-6
                    && p.y >= lo.y - 1e-6
                    && p.y <= hi.y + 1e-6;
                if near {
                    let edges = self.edges(n, c);
                    let mut b = ring[edges.start];
                    for i in edges {
                        let a = b;
                        b = ring[next(i, n)];
                        if on_edge(a, b, p) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }

    /// Whether `p` is within `CLEAR` more than a nanometre of an edge (rings' boxes
    /// grown by as much): where it is not, no point within `CLEAR / 2` of it is within
    /// a nanometre of one (the roundings, about 10⁻¹⁶ of the coordinates, are far
    /// below), and `on_an_edge` answers false there without its search.
    fn near_an_edge(&self, p: Coord) -> bool {
        const TOL: f64 = 1e-6 + CLEAR;
        for (r, ring) in self.rings.iter().enumerate() {
            let (lo, hi) = self.ring_box(r);
            if p.x < lo.x - CLEAR || p.x > hi.x + CLEAR || p.y < lo.y - CLEAR || p.y > hi.y + CLEAR
            {
                continue;
            }
            let n = ring.len();
            for (c, lo, hi) in self.boxes_of(r) {
                let near = p.x >= lo.x - TOL
                    && p.x <= hi.x + TOL
                    && p.y >= lo.y - TOL
                    && p.y <= hi.y + TOL;
                if near {
                    let edges = self.edges(n, c);
                    let mut b = ring[edges.start];
                    for i in edges {
                        let a = b;
                        b = ring[next(i, n)];
                        if within(a, b, p, TOL) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }

    /// Whether `m` (a move's middle) is on an edge the move runs parallel to (`cuts`
    /// holds those with a NaN `t`), where the even-odd test would find it: inside its
    /// ring's box and within a nanometre of the edge. Then that test answers "inside"
    /// (a point on an edge is), and need not be run.
    fn along_edge(&self, m: Coord, cuts: &[(f64, Cut)]) -> bool {
        cuts.iter().filter(|(t, _)| t.is_nan()).any(|&(_, c)| {
            let (lo, hi) = self.ring_box(c.ring);
            let ring = &self.rings[c.ring];
            !(m.x < lo.x || m.x > hi.x || m.y < lo.y || m.y > hi.y)
                && on_edge(ring[c.edge], ring[next(c.edge, ring.len())], m)
        })
    }

    /// Whether the region lies on ring `r`'s left: a counter-clockwise ring inside an even
    /// number of the others (an outline), or a clockwise one inside an odd number (a hole).
    fn region_left(&self, r: usize) -> bool {
        if self.rings.len() == 1 {
            // No other ring to be inside of: counter-clockwise is an outline.
            return *self
                .left_one
                .get_or_init(|| super::offset::signed_area(&self.rings[0]) > 0.0);
        }
        self.left.get_or_init(|| {
            self.rings
                .iter()
                .enumerate()
                .map(|(r, ring)| {
                    // Its sign only: the sum without a wrap test per vertex.
                    let area = super::offset::signed_area(ring);
                    let mut around = false;
                    for (s, other) in self.rings.iter().enumerate() {
                        let m = other.len();
                        if s != r {
                            for i in 0..m {
                                if super::clip::ray_crosses(other[i], other[next(i, m)], ring[0]) {
                                    around = !around;
                                }
                            }
                        }
                    }
                    (area > 0.0) != around
                })
                .collect()
        })[r]
    }

    /// Where ring `r`'s boxes and cumulative lengths start.
    #[inline]
    fn at(&self, r: usize) -> (usize, usize) {
        if self.at.is_empty() {
            (0, 0)
        } else {
            self.at[r]
        }
    }

    /// Ring `r`'s bounding box.
    #[inline]
    fn ring_box(&self, r: usize) -> (Coord, Coord) {
        self.boxes[self.at(r).0]
    }

    /// Ring `r`'s chunk boxes, with the range of edges each holds.
    #[inline]
    fn chunks(
        &self,
        r: usize,
    ) -> impl Iterator<Item = (std::ops::Range<usize>, Coord, Coord)> + '_ {
        let n = self.rings[r].len();
        let chunk = self.chunk;
        let count = n.div_ceil(chunk);
        let from = self.at(r).0 + 1;
        // Each chunk's edges from where the last ended (no multiplication, nothing to
        // saturate where a test's chunk is a whole ring).
        let mut start = 0;
        self.boxes[from..from + count].iter().map(move |&(lo, hi)| {
            let end = if n - start > chunk { start + chunk } else { n };
            let edges = start..end;
            start = end;
            (edges, lo, hi)
        })
    }

    /// Ring `r`'s chunk boxes with each one's index, its edges left to `edges` (for the
    /// chunks a caller reads: nothing worked out for those its boxes pass).
    #[inline]
    fn boxes_of(&self, r: usize) -> impl Iterator<Item = (usize, Coord, Coord)> + '_ {
        let count = self.rings[r].len().div_ceil(self.chunk);
        let from = self.at(r).0 + 1;
        self.boxes[from..from + count]
            .iter()
            .enumerate()
            .map(|(c, &(lo, hi))| (c, lo, hi))
    }

    /// The edges of chunk `c` of a ring of `n`: from c·chunk (below n, a later chunk
    /// existing only where `chunk` is less than n), `chunk` of them or to the ring's end.
    #[inline]
    fn edges(&self, n: usize, c: usize) -> std::ops::Range<usize> {
        let start = c * self.chunk;
        start..if n - start > self.chunk {
            start + self.chunk
        } else {
            n
        }
    }

    fn cumulative(&self, r: usize) -> &[f64] {
        let cumulative = self.lengths.get_or_init(|| {
            let vertices: usize = self.rings.iter().map(Vec::len).sum();
            let mut cumulative = scratch::take(&LENGTHS);
            cumulative.reserve(vertices + self.rings.len());
            // The same sums in the same order as edge by edge with `next`, by an extend
            // of exact length (no capacity test per push) over each vertex and the next,
            // then the closing edge.
            for ring in self.rings {
                let (Some(&first), Some(&last)) = (ring.first(), ring.last()) else {
                    cumulative.push(0.0);
                    continue;
                };
                // The ring's slots made first and written in place (the running sum in
                // a register, not a closure's captured place).
                let from = cumulative.len();
                cumulative.resize(from + ring.len() + 1, 0.0);
                let slots = &mut cumulative[from + 1..];
                let mut s = 0.0;
                for (slot, w) in slots.iter_mut().zip(ring.windows(2)) {
                    let e = w[1] - w[0];
                    s += (e.x * e.x + e.y * e.y).sqrt();
                    *slot = s;
                }
                let e = first - last;
                s += (e.x * e.x + e.y * e.y).sqrt();
                if let Some(end) = slots.last_mut() {
                    *end = s;
                }
            }
            cumulative
        });
        let from = self.at(r).1;
        &cumulative[from..from + self.rings[r].len() + 1]
    }

    /// The router's boxes (the ring's then its chunks', each as the bits of its corners,
    /// a zero's sign made one), its chunk, its side test's scale and which side of ring
    /// 0 the region lies on (tests compare `small` with `with_chunk`).
    #[cfg(test)]
    pub(crate) fn layout(&self) -> (Vec<[u64; 4]>, usize, u64, bool) {
        let bits = |v: f64| (v + 0.0).to_bits();
        let boxes = self
            .boxes
            .iter()
            .map(|(lo, hi)| [bits(lo.x), bits(lo.y), bits(hi.x), bits(hi.y)])
            .collect();
        (boxes, self.chunk, self.unit.to_bits(), self.region_left(0))
    }

    /// Ring `r`'s cumulative lengths (tests).
    #[cfg(test)]
    pub(crate) fn cumulative_lengths(&self, r: usize) -> Vec<f64> {
        self.cumulative(r).to_vec()
    }

    /// Where a move from `p` to `q` crosses ring `r`: the fraction along the move, and
    /// where on the ring (the edge and the fraction along it). Chunks whose box the
    /// move's box misses are skipped.
    ///
    /// Returns whether the move certainly touches no edge of the ring (`Clear`): every
    /// edge passed by its chunk's box or by its ends' sides, or found meeting the move's
    /// line clearly (a hundred-thousandth of a radian or more) beyond an end of the move
    /// or of the edge (a millionth of either's length, far above the roundings). Only
    /// worked out when `TRACK` asks for it (else `false`; a separate copy of the loop, so
    /// that moves not tracked pay nothing for it).
    #[inline(never)]
    fn hits<const TRACK: bool>(
        &self,
        r: usize,
        p: Coord,
        q: Coord,
        out: &mut Vec<(f64, Cut)>,
    ) -> bool {
        let ring = &self.rings[r];
        let n = ring.len();
        let d = q - p;
        let (lo, hi) = move_box(p, q);
        let moving = d.x != 0.0 || d.y != 0.0;
        // A move within a millionth of a radian of an edge's direction is kept as one
        // that may run along it (as an exactly parallel one is): a move between two line
        // ends on one edge is then found on it (`along_edge`) without the even-odd test
        // of its middle. First told by |denom| against a bound from the ring's box (no
        // edge is longer than its diagonal), then by the edge's own length.
        let d2 = d.x * d.x + d.y * d.y;
        let (lo_r, hi_r) = self.ring_box(r);
        let diagonal2 = (hi_r - lo_r).x * (hi_r - lo_r).x + (hi_r - lo_r).y * (hi_r - lo_r).y;
        let along = 1e-6 * (d2 * diagonal2).sqrt();
        // An edge whose ends are both farther than `beyond` on one side of the move's
        // line (`side`: the same products as the crossing's fraction along the edge, `u`'s
        // numerator negated) is not crossed: `u` would be negative, or 1 or more (the
        // edge's denominator, rounded, is at most the nearer end's side, far above the
        // roundings, which are about 10⁻¹⁶ of the coordinates where `beyond` is 10⁻⁹). It
        // could only be kept as an edge the move runs along (a NaN cut), whose middle
        // would be on it (`along_edge`): not so far from its line. Off for a move of no
        // length (every edge is "parallel" to it, and none is kept).
        let beyond = if self.sides {
            self.unit * (d.x.abs() + d.y.abs()) * (1.0 + p.x.abs() + p.y.abs())
        } else {
            f64::INFINITY
        };
        let side = |v: Coord| {
            let vp = v - p;
            d.x * vp.y - d.y * vp.x
        };
        let mut clear = TRACK;
        // Whether the lines of the move and of edge `e` (`denom` their cross product)
        // meet clearly beyond an end of either (`u` along the edge, `t` along the move):
        // clearly not parallel (a NaN is not), then a millionth past an end.
        let apart = |e: Coord, denom: f64, u: f64, t: f64| {
            let beyond = |f: f64| f < -1e-6 * (1.0 + f.abs()) || f > 1.0 + 1e-6 * (1.0 + f.abs());
            let crossing = denom * denom > 1e-10 * d2 * (e.x * e.x + e.y * e.y);
            crossing && (beyond(u) || beyond(t))
        };
        // The chunks' boxes read in a plain loop, each chunk's edges worked out only where
        // its box meets the move's (most are passed: a move meets one or two of a star's).
        let chunk = self.chunk;
        let from = self.at(r).0 + 1;
        for (c, &(a, b)) in self.boxes[from..from + n.div_ceil(chunk)]
            .iter()
            .enumerate()
        {
            if hi.x < a.x || lo.x > b.x || hi.y < a.y || lo.y > b.y {
                continue;
            }
            let edges = self.edges(n, c);
            // Each edge's end is the next one's start: carried, not read again.
            let mut b = ring[edges.start];
            let mut side_b = side(b);
            for i in edges {
                let a = b;
                let side_a = side_b;
                b = ring[next(i, n)];
                side_b = side(b);
                if (side_a > beyond && side_b > beyond) || (side_a < -beyond && side_b < -beyond) {
                    continue;
                }
                let e = b - a;
                let denom = d.x * e.y - d.y * e.x;
                if denom == 0.0 {
                    clear = false;
                    // Parallel: no crossing, but kept (t NaN, `near`) as an edge the
                    // move may run along (`along_edge`); a move of no length (every
                    // edge "parallel") keeps none.
                    if moving {
                        out.push((
                            f64::NAN,
                            Cut {
                                ring: r,
                                edge: i,
                                u: f64::NAN,
                                near: true,
                            },
                        ));
                    }
                    continue;
                }
                if self.fast
                    && denom.abs() <= along
                    && denom * denom <= 1e-12 * d2 * (e.x * e.x + e.y * e.y)
                {
                    out.push((
                        f64::NAN,
                        Cut {
                            ring: r,
                            edge: i,
                            u: f64::NAN,
                            near: true,
                        },
                    ));
                }
                let ap = a - p;
                // Most edges are missed beside their ends: told by where the move's line
                // meets the edge's, before the second division.
                let u = (ap.x * d.y - ap.y * d.x) / denom;
                if !self.divide_first && !(0.0..1.0).contains(&u) {
                    if TRACK && clear {
                        clear = apart(e, denom, u, (ap.x * e.y - ap.y * e.x) / denom);
                    }
                    continue;
                }
                let t = (ap.x * e.y - ap.y * e.x) / denom;
                if TRACK && clear {
                    // A crossing kept below is not apart (its `t` within a billionth).
                    clear = apart(e, denom, u, t);
                }
                if (0.0..1.0).contains(&u) && (-1e-9..=1.0 + 1e-9).contains(&t) {
                    out.push((
                        t,
                        Cut {
                            ring: r,
                            edge: i,
                            u,
                            near: !(0.0..=1.0).contains(&t),
                        },
                    ));
                }
            }
        }
        clear
    }

    /// The move from `p` to `q`: `[p, q]` when it stays inside, else each stretch that
    /// leaves the region (into a hole, or out of a concave outline) replaced by a walk
    /// along the ring it crossed, the shorter way round.
    pub(crate) fn route(&self, p: Coord, q: Coord) -> Vec<Coord> {
        self.route_on(p, q, false)
    }

    /// `route`, told whether the next move starts where this one ends (`q` starts a
    /// closed path): then whether this move touches an edge is worked out, for the next
    /// to be known inside without the even-odd test (`interior`).
    pub(crate) fn route_on(&self, p: Coord, q: Coord, looped: bool) -> Vec<Coord> {
        // No rings: a convex region, where every straight move stays inside.
        if self.rings.iter().any(|r| r.len() < 3) || self.rings.is_empty() {
            return vec![p, q];
        }
        // Clear inside a convex outline (`deep_inside`: no crossing of it, no edge of it
        // touched or within a nanometre) and missing every other ring's box (no
        // crossing, nothing touched, no point in a hole): inside all along, what the
        // even-odd test of its middle finds once the crossings are searched. Its end is
        // then a point inside and on no edge, for the next move (`interior`).
        let deep = self.deep.1 > 0 && self.deep_inside(p, q);
        if deep && self.misses_holes(p, q) {
            if self.chain {
                self.interior.set(Some(q));
            }
            return vec![p, q];
        }
        let mut cuts = self.cuts.take();
        cuts.clear();
        // Room for a few crossings at once (not grown from nothing, one at a time).
        cuts.reserve(16);
        let (lo, hi) = move_box(p, q);
        // Whether the move certainly touches no edge (a ring whose box it misses has none
        // it could touch).
        let track = self.chain && (looped || self.interior.get() == Some(p));
        let mut clear = track;
        for r in 0..self.rings.len() {
            let (a, b) = self.ring_box(r);
            if hi.x < a.x || lo.x > b.x || hi.y < a.y || lo.y > b.y {
                continue;
            }
            // Clear inside a convex first ring: no crossing of it, no edge touched.
            if r == 0 && deep {
                continue;
            }
            clear &= if track {
                self.hits::<true>(r, p, q, &mut cuts)
            } else {
                self.hits::<false>(r, p, q, &mut cuts)
            };
        }
        // A move touching no edge from a point known to be inside the region (and on no
        // edge) stays inside all along: what the even-odd test of its middle would find.
        if clear && self.interior.get() == Some(p) {
            self.interior.set(Some(q));
            self.cuts.set(cuts);
            return vec![p, q];
        }
        // The usual move, between two ends on a ring and across nothing: straight.
        let interior = |t: f64| t > 1e-9 && t < 1.0 - 1e-9;
        // Whether the move is known to run outside all along (but for its ends): out of
        // the region from one end, crossing nothing; then so is every stretch below.
        let mut outside = false;
        // The move's middle, when found clearly off every edge (`near_an_edge`).
        let mut clear_of: Option<Coord> = None;
        if !cuts.iter().any(|&(t, _)| interior(t)) {
            let straight = match self.fast.then(|| self.leaves_inward(p, q, &cuts)).flatten() {
                Some(true) => true,
                Some(false) => {
                    outside = true;
                    let m = (p + q) / 2.0;
                    if self.reuse && !self.near_an_edge(m) {
                        clear_of = Some(m);
                        false
                    } else {
                        self.on_an_edge(m)
                    }
                }
                None => {
                    self.fast && self.along_edge((p + q) / 2.0, &cuts) || {
                        let place = self.locate((p + q) / 2.0);
                        // Its middle inside by the even-odd test (on no edge), touching
                        // no edge: the whole move is inside, its end too.
                        if clear && place == Place::In {
                            self.interior.set(Some(q));
                        }
                        place != Place::Out
                    }
                }
            };
            if straight {
                self.cuts.set(cuts);
                return vec![p, q];
            }
        }
        // A move between two points of one ring (line ends lie on the inset's rings) may
        // find no crossing at all, its ends being on the ring: the middle of each
        // stretch decides whether it is inside.
        // Where each end of the move lies on a ring (a line's end on its edge, met just
        // beyond the move): a walk from there starts at that crossing, without
        // projecting the end on the ring (a search of every edge).
        let on_ring = |at_p: bool| {
            cuts.iter()
                .find(|&&(t, c)| c.near && if at_p { t <= 0.0 } else { t >= 1.0 })
                .map(|&(_, c)| c)
        };
        let (start, end) = if self.project_ends {
            (None, None)
        } else {
            (on_ring(true), on_ring(false))
        };
        cuts.retain(|c| !c.1.near);
        cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let at = |t: f64| if t >= 1.0 { q } else { p + (q - p) * t };
        let move_length = ((q - p).x * (q - p).x + (q - p).y * (q - p).y).sqrt();
        // Built in a buffer kept for the next move (walks grow it vertex by vertex), then
        // copied at its final length: one allocation per route, none to grow it.
        let mut out = self.path.take();
        out.clear();
        out.reserve(32);
        out.push(p);
        // The stretches between consecutive bounds: the move's ends and its crossings.
        let mut previous: (f64, Option<Cut>) = (0.0, None);
        let bounds = cuts
            .iter()
            .map(|&(t, c)| (t, Some(c)))
            .chain(std::iter::once((1.0, None)));
        for (k, (tb, rb)) in bounds.enumerate() {
            let (ta, ra) = std::mem::replace(&mut previous, (tb, rb));
            let (a, b) = (at(ta), at(tb));
            let straight = (tb - ta) * move_length < 1e-6
                || match if outside {
                    // The whole move runs outside: so does every stretch of it.
                    Some(false)
                } else if self.fast {
                    self.enters(&cuts, k, q - p)
                } else {
                    None
                } {
                    Some(true) => true,
                    Some(false) => {
                        let m = at((ta + tb) / 2.0);
                        // Within CLEAR / 2 of a middle clearly off every edge: off too.
                        match clear_of {
                            Some(c)
                                if (m.x - c.x).abs() <= CLEAR / 2.0
                                    && (m.y - c.y).abs() <= CLEAR / 2.0 =>
                            {
                                false
                            }
                            _ => self.on_an_edge(m),
                        }
                    }
                    None => self.inside(at((ta + tb) / 2.0)),
                };
            if straight {
                out.push(b);
                continue;
            }
            let r = ra
                .or(rb)
                .map_or_else(|| self.nearest(at((ta + tb) / 2.0)), |c| c.ring);
            // Where each end is on ring r: known for a crossing, else projected.
            let place = |cut: Option<Cut>, p: Coord| match cut {
                Some(c) if c.ring == r => {
                    let cumulative = self.cumulative(r);
                    let (s0, s1) = (cumulative[c.edge], cumulative[c.edge + 1]);
                    (c.edge, s0 + c.u * (s1 - s0))
                }
                _ => self.project(r, p),
            };
            let ends = (
                ra.or(if k == 0 { start } else { None }),
                rb.or(if k == cuts.len() { end } else { None }),
            );
            // Both ends crossings of ring r on two edges: the shorter way round is often
            // certain from the arc the fewer edges span, without the ring's lengths.
            let way = match ends {
                (Some(c0), Some(c1))
                    if self.bound_ways
                        && c0.ring == r
                        && c1.ring == r
                        && c0.edge != c1.edge
                        // Once measured (an earlier walk), the lengths answer at once; a
                        // ring of few edges (an L's) is measured about as fast.
                        && self.lengths.get().is_none()
                        && self.rings[r].len() >= MEASURED =>
                {
                    self.shorter_way(r, c0, c1)
                        .map(|forward| (c0.edge, c1.edge, forward))
                }
                _ => None,
            };
            match way {
                Some((i0, i1, forward)) => self.emit(r, i0, i1, forward, &mut out),
                None => self.walk(r, place(ends.0, a), place(ends.1, b), &mut out),
            }
            out.push(b);
        }
        self.cuts.set(cuts);
        out.dedup();
        let route = out.clone();
        self.path.set(out);
        route
    }

    /// Even-odd over every ring; a point on an edge (within a nanometre) counts as
    /// inside: a move along an edge (between two line ends on one side of the outline)
    /// stays on the boundary, and need not be walked around. A chunk none of whose edges
    /// can cross the ray to the right of `p` (all at or below it, all above it, or all to
    /// its left) has none of them tested for the ray, and one farther than a nanometre
    /// from `p` none for `on_edge` (which cannot hold there): the parity and the first
    /// edge `p` is on are those of every edge tested for both.
    pub(crate) fn inside(&self, p: Coord) -> bool {
        self.locate(p) != Place::Out
    }

    /// `inside`, telling a point on an edge (`OnEdge`) from one inside by the even-odd
    /// test (`In`: the parity is then exact, the point being farther than a nanometre
    /// from every edge that could sway it).
    #[inline(always)]
    fn locate(&self, p: Coord) -> Place {
        let mut inside = false;
        let band = (p.y - 2e-6, p.y + 2e-6);
        for (r, ring) in self.rings.iter().enumerate() {
            let (lo, hi) = self.ring_box(r);
            if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
                continue;
            }
            let n = ring.len();
            for (edges, lo, hi) in self.chunks(r) {
                let near = p.x >= lo.x - 1e-6
                    && p.x <= hi.x + 1e-6
                    && p.y >= lo.y - 1e-6
                    && p.y <= hi.y + 1e-6;
                let crossing = !(hi.y < p.y || lo.y > p.y || hi.x < p.x);
                let mut b = ring[edges.start];
                match (crossing, near) {
                    (false, false) => {}
                    (true, false) => {
                        for i in edges {
                            let a = b;
                            b = ring[next(i, n)];
                            if super::clip::ray_crosses(a, b, p) {
                                inside = !inside;
                            }
                        }
                    }
                    (false, true) => {
                        for i in edges {
                            let a = b;
                            b = ring[next(i, n)];
                            // As below: `on_edge` cannot hold.
                            if (a.y > band.1 && b.y > band.1) || (a.y < band.0 && b.y < band.0) {
                                continue;
                            }
                            if on_edge(a, b, p) {
                                return Place::OnEdge;
                            }
                        }
                    }
                    (true, true) => {
                        for i in edges {
                            let a = b;
                            b = ring[next(i, n)];
                            // Both ends more than two nanometres above `p`, or below:
                            // neither test can hold (the ray's edges reach its height;
                            // `on_edge`'s are within a nanometre of it, roundings far
                            // below the one left over).
                            if (a.y > band.1 && b.y > band.1) || (a.y < band.0 && b.y < band.0) {
                                continue;
                            }
                            if super::clip::ray_crosses(a, b, p) {
                                inside = !inside;
                            }
                            if on_edge(a, b, p) {
                                return Place::OnEdge;
                            }
                        }
                    }
                }
            }
        }
        if inside { Place::In } else { Place::Out }
    }

    /// `inside` as it was: every edge of a chunk near `p` or that may cross its ray
    /// tested for both the ray and `on_edge` (tests compare the two).
    #[cfg(test)]
    pub(crate) fn inside_each_edge(&self, p: Coord) -> bool {
        let mut inside = false;
        for (r, ring) in self.rings.iter().enumerate() {
            let (lo, hi) = self.ring_box(r);
            if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
                continue;
            }
            let n = ring.len();
            for (edges, lo, hi) in self.chunks(r) {
                let near = p.x >= lo.x - 1e-6
                    && p.x <= hi.x + 1e-6
                    && p.y >= lo.y - 1e-6
                    && p.y <= hi.y + 1e-6;
                if !near && (hi.y < p.y || lo.y > p.y || hi.x < p.x) {
                    continue;
                }
                let mut b = ring[edges.start];
                for i in edges {
                    let a = b;
                    b = ring[next(i, n)];
                    if super::clip::ray_crosses(a, b, p) {
                        inside = !inside;
                    }
                    if on_edge(a, b, p) {
                        return true;
                    }
                }
            }
        }
        inside
    }

    /// The ring nearest to `p` (of one ring, that one: nothing to measure).
    fn nearest(&self, p: Coord) -> usize {
        if self.rings.len() == 1 {
            return 0;
        }
        (0..self.rings.len())
            .map(|r| {
                let (i, _) = self.project(r, p);
                let ring = &self.rings[r];
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                (r, segment_distance(p, a, b))
            })
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .map_or(0, |(r, _)| r)
    }

    /// Where `p` projects on ring `r`: (edge index, distance along the ring). A chunk
    /// whose box is farther than the nearest edge found so far is skipped (its edges are
    /// all farther, by more than the box's slack).
    fn project(&self, r: usize, p: Coord) -> (usize, f64) {
        let (ring, cumulative) = (&self.rings[r], self.cumulative(r));
        let n = ring.len();
        let mut best = (f64::INFINITY, 0, 0.0);
        for (edges, lo, hi) in self.chunks(r) {
            let dx = (lo.x - p.x).max(p.x - hi.x).max(0.0);
            let dy = (lo.y - p.y).max(p.y - hi.y).max(0.0);
            if dx * dx + dy * dy > best.0 {
                continue;
            }
            for i in edges {
                let (a, b) = (ring[i], ring[next(i, n)]);
                let e = b - a;
                let len2 = e.x * e.x + e.y * e.y;
                let u = if len2 > 0.0 {
                    (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let c = a + e * u;
                // Squared: the nearest is the same, without a root per edge.
                let d = (p - c).x * (p - c).x + (p - c).y * (p - c).y;
                if d < best.0 {
                    best = (
                        d,
                        i,
                        cumulative[i] + u * (cumulative[i + 1] - cumulative[i]),
                    );
                }
            }
        }
        (best.1, best.2)
    }

    /// The vertices of ring `r` between two of its points (edge, distance along the ring),
    /// the shorter way, appended to `walk`.
    fn walk(
        &self,
        r: usize,
        (i0, s0): (usize, f64),
        (i1, s1): (usize, f64),
        walk: &mut Vec<Coord>,
    ) {
        let n = self.rings[r].len();
        let perimeter = self.cumulative(r)[n];
        let forward = (s1 - s0).rem_euclid(perimeter);
        if forward <= perimeter - forward {
            if !(i0 == i1 && s1 >= s0) {
                self.emit(r, i0, i1, true, walk);
            }
        } else if !(i0 == i1 && s1 <= s0) {
            self.emit(r, i0, i1, false, walk);
        }
    }

    /// The vertices of ring `r` from edge `i0` to edge `i1`, forward (the vertices after
    /// `i0`'s start up to `i1`'s) or back (from `i0`'s start down to `i1`'s end).
    #[inline(never)]
    fn emit(&self, r: usize, i0: usize, i1: usize, forward: bool, walk: &mut Vec<Coord>) {
        let ring = &self.rings[r];
        let n = ring.len();
        if forward {
            let mut i = next(i0, n);
            for _ in 0..n {
                walk.push(ring[i]);
                if i == i1 {
                    break;
                }
                i = next(i, n);
            }
        } else {
            let mut i = i0;
            for _ in 0..n {
                walk.push(ring[i]);
                i = if i == 0 { n - 1 } else { i - 1 };
                if i == i1 {
                    break;
                }
            }
        }
    }

    /// Which way round ring `r` is the shorter from crossing `c0` to crossing `c1` (on
    /// two different edges), when that is certain without the ring's cumulative lengths:
    /// the arc of fewer edges is measured, and is the shorter where it is less than the
    /// ring's box's diagonal (the perimeter is at least twice that) by more than any
    /// rounding of `walk`'s sums, and longer than that rounding (no wrap). `Some(true)`:
    /// forward. `None` where in doubt: `walk` measures.
    fn shorter_way(&self, r: usize, c0: Cut, c1: Cut) -> Option<bool> {
        let ring = &self.rings[r];
        let n = ring.len();
        let (i0, i1) = (c0.edge, c1.edge);
        let (lo, hi) = self.ring_box(r);
        let size = hi - lo;
        // The box's diagonal, at most half the perimeter (less a rounding): a closed ring
        // runs across its box and back both ways, at least twice its width in x and its
        // height in y, so its length is at least twice the diagonal.
        let diagonal = (size.x * size.x + size.y * size.y).sqrt();
        let half = diagonal * (1.0 - 1e-12);
        // `walk`'s sums err by about n ulps of the perimeter, at most n edges each no
        // longer than the box's diagonal; this arc's by n ulps of itself: both far below.
        let k = n as f64 + 2.0;
        let margin = 1e-14 * k * k * diagonal;
        let bound = |arc: f64| arc * (1.0 + 1e-14 * k) + margin;
        let length = |i: usize| {
            let e = ring[next(i, n)] - ring[i];
            (e.x * e.x + e.y * e.y).sqrt()
        };
        // The arc one way, summed edge by edge, given up (`None`) once it reaches the
        // box's diagonal.
        let arc = |forward: bool| {
            let mut arc;
            if forward {
                arc = (1.0 - c0.u) * length(i0) + c1.u * length(i1);
                let mut i = next(i0, n);
                while i != i1 && bound(arc) < half {
                    arc += length(i);
                    i = next(i, n);
                }
            } else {
                arc = c0.u * length(i0) + (1.0 - c1.u) * length(i1);
                let mut i = if i0 == 0 { n - 1 } else { i0 - 1 };
                while i != i1 && bound(arc) < half {
                    arc += length(i);
                    i = if i == 0 { n - 1 } else { i - 1 };
                }
            }
            (arc > margin && bound(arc) < half).then_some(forward)
        };
        // The way of fewer edges (it may be the longer, round a notch's many short arc
        // edges: then in doubt).
        let steps = if i1 > i0 { i1 - i0 } else { i1 + n - i0 };
        arc(steps <= n - steps)
    }
}

impl Drop for Router<'_> {
    /// The lists go back to the pool for the next layer's router.
    fn drop(&mut self) {
        scratch::give(&BOXES, std::mem::take(&mut self.boxes));
        scratch::give(&AT, std::mem::take(&mut self.at));
        scratch::give(&CUTS, self.cuts.take());
        scratch::give(&PATH, self.path.take());
        if let Some(lengths) = self.lengths.take() {
            scratch::give(&LENGTHS, lengths);
        }
    }
}

/// A move's box, its lowest and highest corner, by comparisons (not `min`/`max`, which
/// handle NaN at several instructions each): a move's ends are finite, and a move with a
/// NaN end crosses nothing either way (its fractions are NaN), so the box only says
/// which rings and chunks are tested.
#[inline]
fn move_box(p: Coord, q: Coord) -> (Coord, Coord) {
    let (x0, x1) = if p.x < q.x { (p.x, q.x) } else { (q.x, p.x) };
    let (y0, y1) = if p.y < q.y { (p.y, q.y) } else { (q.y, p.y) };
    (Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 })
}

/// How far beyond a nanometre `near_an_edge` looks: a tenth of a nanometre, far above
/// the roundings of a point (about 10⁻¹⁶ of its coordinates) and above how far the
/// middle of a stretch of a move that crosses nothing lies from the move's (its ends
/// are within a billionth of the move's length of the move's: a hundredth of a
/// nanometre on a 10 mm move). A stretch's middle farther than `CLEAR / 2` is searched.
const CLEAR: f64 = 1e-7;

/// `on_edge` within `tol` (the same tests).
#[inline]
fn within(a: Coord, b: Coord, p: Coord, tol: f64) -> bool {
    if (p.y >= a.y - tol || p.y >= b.y - tol)
        && (p.y <= a.y + tol || p.y <= b.y + tol)
        && (p.x >= a.x - tol || p.x >= b.x - tol)
        && (p.x <= a.x + tol || p.x <= b.x + tol)
    {
        let e = b - a;
        let c = cross(e, p - a);
        return c * c <= tol * tol * (e.x * e.x + e.y * e.y);
    }
    false
}

/// Whether `p` is on the edge from `a` to `b` within a nanometre (a millionth of a
/// millimetre): within that of the edge's box, by comparisons with each end
/// (`min(a, b) − 1e-6` is the lesser of `a − 1e-6` and `b − 1e-6`), and of its line.
#[inline]
fn on_edge(a: Coord, b: Coord, p: Coord) -> bool {
    const NM: f64 = 1e-6;
    if (p.y >= a.y - NM || p.y >= b.y - NM)
        && (p.y <= a.y + NM || p.y <= b.y + NM)
        && (p.x >= a.x - NM || p.x >= b.x - NM)
        && (p.x <= a.x + NM || p.x <= b.x + NM)
    {
        let e = b - a;
        let c = cross(e, p - a);
        return c * c <= NM * NM * (e.x * e.x + e.y * e.y);
    }
    false
}

fn cross(a: Coord, b: Coord) -> f64 {
    a.x * b.y - a.y * b.x
}

fn segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    crate::math::segment_distance2(p, a, b).sqrt()
}

pub(crate) fn length(path: &[Coord]) -> f64 {
    path.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            (d.x * d.x + d.y * d.y).sqrt()
        })
        .sum()
}

/// The bounding box of a ring: its lowest and highest corner.
pub(crate) fn bounds(ring: &[Coord]) -> (Coord, Coord) {
    ring.iter().fold(
        (
            Coord {
                x: f64::INFINITY,
                y: f64::INFINITY,
            },
            Coord {
                x: f64::NEG_INFINITY,
                y: f64::NEG_INFINITY,
            },
        ),
        |(lo, hi), c| {
            (
                Coord {
                    x: lo.x.min(c.x),
                    y: lo.y.min(c.y),
                },
                Coord {
                    x: hi.x.max(c.x),
                    y: hi.y.max(c.y),
                },
            )
        },
    )
}
