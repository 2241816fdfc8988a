//! Concentric loops: each loop the region's erosion (by `loops::Eroder`, prepared once for
//! every loop of the layer), the later of two loops giving way where they come close, and
//! a middle loop's stretches where part of the region ended between two loops.
//!
//! Where the time went (callgrind, star and holed square at 10–40%): before, each loop
//! re-oriented the region's rings and rebuilt their corners, every piece of a cut offset was
//! built before it was tested, the test keeping loops apart measured each point against
//! every segment of every earlier loop, and the erosion past the last loop was computed in
//! full to find it empty. The answers are the same to the bit (`concentric_tests.rs`
//! checks them against the former code on random shapes).
//!
//! Then (the middle rings' stretches, a third to a half of a star's or a holed square's
//! layer outside the erosions): each point is asked first of the segment the point before
//! was near (`Hint`), a middle segment or a run of one near a covered segment all along is
//! kept as one point, a hole's loop is measured against the outline's only where a segment
//! of it comes near, and the middle ring's points lie half a spacing apart, not a quarter
//! (`MIDDLE_STEP`, the one change of the output).
//!
//! Then (a star's layer at 10%, one loop: 21.8k → 19.4k instructions, the same output):
//! the thread's pool used in its box (moving the eroder out and back copied it eight
//! times), the convex inset not asked of a region known concave, the last lone loop moved
//! out, the loops' ring list reused, and the eroder's preparation without a division or a
//! `ceil` call per corner.
//!
//! Then (the holed square's middle rings at 10%: 234.8k → 226.0k instructions a layer,
//! the same output): a run of middle points near two last loops is found so from each
//! loop's hint, walking a few segments nearer, before all their segments grown by two
//! spacings are gathered; the last loops' segments are gathered only when the covered
//! ones do not decide a run; a middle stretch is measured before it is copied; a middle
//! segment's point count by a square root, `hypot` only where the quotient is near a
//! whole number. Tried and dropped (more instructions on the holed square at 20–40% or
//! the star): hints for the last loops per point and per middle segment; deciding runs
//! by chunks of a ring's segments with their bounds; every middle point from bounds on
//! its distance to each ring carried from the point before (a 1-Lipschitz walk); the
//! whole middle ring shown near two loops before it is measured (it holds on the holed
//! square at 10% only: 226k → 214k there, 419k → 432k and 549k → 585k at 20 / 40%).
//!
//! Then (the holed square's meeting steps, where the hole's loops meet the outline's:
//! their middle ring printed nothing and cost a third of the layer at 10%): the middle
//! ring is not made where no point of it can be far (`nothing_far`: the last loops uncut,
//! these cut only where two rings meet, every convex corner of 85° or more, no arc of
//! chords), the same output: instructions a layer 201k → 109k, 368k → 265k and 478k →
//! 362k at 10 / 20 / 40%.
//!
//! Then (the star's middle rings: every step of its loops took the tips' drop for a part
//! ending, and made a middle ring that printed nothing, 85k of its 157k instructions a
//! layer at 40%): the drop test counts the region's convex corners, which stay sharp
//! (`mitres`), where a corner's own middle stretch is under 1.5 spacings. Star concentric
//! 20 / 40% 62.9k / 156.6k → 41.2k / 56.6k; the comparison's paths the same to the bit.

use std::cell::Cell;
use std::f64::consts::{PI, TAU};

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{Buffer, Coord, MultiPolygon};

use crate::infill::Region;
use crate::infill::curves::mitres;
use crate::infill::loops::{Cutting, Eroder};
use crate::infill::region::ConvexInset;
use crate::infill::travel::bounds;
use crate::math;

/// Loops at `(k + ½)·spacing` inside the inset outline (and around its holes), each
/// starting at its farthest vertex in direction θ and closed.
pub(crate) fn concentric(region: &Region, theta: f64, spacing: f64, out: &mut Vec<Vec<Coord>>) {
    let direction = Coord {
        x: math::cos(theta),
        y: math::sin(theta),
    };
    let outline = region.outline();
    let mut pool = POOL.try_with(Cell::take).ok().flatten().unwrap_or_default();
    // Its buffers used where they are in the box: moving them out and back in copied
    // the eroder's and the scratch's some forty vectors eight times a layer.
    let Pool {
        eroder: spare,
        scratch,
        last: last_loops,
        mitres: corners,
    } = &mut *pool;
    let mut eroder = Shrink::new(outline, spare, known_concave(region));
    // Each loop offset from the inset itself, not from the previous loop: offsets of
    // offsets pile up the arcs at reflex corners.
    // The previous loops' distance, (perimeter, outline rings − hole rings), and how
    // they were cut.
    let mut previous: Option<(f64, f64, f64, Cutting)> = None;
    // The region's convex corners, listed where a drop is first asked of them.
    let mut mitres = Mitres {
        region,
        corners,
        listed: false,
    };
    // The previous loops themselves (closed rings).
    last_loops.clear();
    for k in 0.. {
        let mut d = (k as f64 + 0.5) * spacing;
        // From the region itself: the inset's offset by d is its offset by w/2 + d.
        let mut current = eroder.shrink(region.nozzle() / 2.0 + d);
        // A region thinner than a spacing still gets one loop, as far in as it can be.
        while k == 0 && current.rings.is_empty() && d > region.nozzle() / 4.0 {
            d /= 2.0;
            current = eroder.shrink(region.nozzle() / 2.0 + d);
        }
        let shape = perimeter(&current);
        // Where part of the region ended between the last loops and these (an L's arm),
        // a band up to two spacings wide would stay empty: its middle gets the pieces of
        // a loop half a spacing further in that no loop here is near. (Not where the
        // whole region ends: a last loop there costs more density than the gap.)
        // Offsets shrink each outline's perimeter by 2π per unit (and grow each hole's),
        // and by more at each convex corner still there, which stays sharp
        // (`mitres::excess`: a star's tips): a larger drop says a part ended.
        if let Some((d0, length, turns, before)) = previous {
            let expected = TAU * spacing * turns;
            if !current.rings.is_empty()
                && length - shape.0 > expected + 4.0 * spacing
                && !skipped(nothing_far(
                    (before, current.cutting),
                    eroder.corners(),
                    d - d0,
                    spacing,
                ))
                // (Asked last: the corners are listed only here, and a round hole has
                // many.)
                && length - shape.0 > expected + (d - d0) * mitres.excess(d0) + 4.0 * spacing
            {
                #[cfg(test)]
                MADE.with(|n| n.set(n.get() + 1));
                let middle = eroder.shrink(region.nozzle() / 2.0 + d0 + spacing / 2.0);
                uncovered(&middle, &current, last_loops, spacing, scratch, out);
            }
        }
        if current.rings.is_empty() {
            break;
        }
        previous = Some((d, shape.0, shape.1, current.cutting));
        // No point of the region is farther in than the largest disc these loops hold:
        // when it is narrower than the step to the next loop, that loop is empty, and its
        // erosion (the dearest, every offset crossing itself) is not worth computing.
        let step = (k as f64 + 1.5) * spacing - d;
        let deep = region.nozzle() / 2.0 + d;
        let mut room = room(&current, shape.0, deep);
        // A piece not round (a holed square's corner, between the outline and the grown
        // hole) holds a disc smaller than its area says (a triangle's by a third at most
        // for any but slivers): asked of its hull too where the area leaves it in doubt
        // by less than half a step (a round one's bounds agree: not asked).
        if (step..1.5 * step).contains(&room) {
            room = room.min(hull_room(&current, deep, step, &mut scratch.dense));
        }
        last_loops.clear();
        let mut rings = current.rings;
        for ring in rings.drain(..) {
            let mut pts = ring;
            if pts.len() > 1 && pts.first() == pts.last() {
                pts.pop();
            }
            if pts.len() < 3 {
                continue;
            }
            // The last of the farthest (as `max_by`), each point measured once.
            let along = |a: Coord| a.x * direction.x + a.y * direction.y;
            let mut start = 0;
            let mut top = along(pts[0]);
            for (i, &p) in pts.iter().enumerate().skip(1) {
                let x = along(p);
                if x.total_cmp(&top).is_ge() {
                    (start, top) = (i, x);
                }
            }
            pts.rotate_left(start);
            pts.push(pts[0]);
            last_loops.push(pts);
        }
        eroder.recycle(rings);
        // The last loops are not read again: a lone one is moved out, not copied.
        let last = room < step;
        apart(last_loops, last, 0.75 * spacing, scratch, out);
        if last {
            break;
        }
    }
    // Kept for the next layer on this thread, unless a huge region made them huge.
    if scratch.dense.capacity() + scratch.flags.capacity() < POOLED_POINTS {
        last_loops.clear();
        if eroder
            .eroder
            .as_ref()
            .is_some_and(|e| e.capacity() >= POOLED_POINTS)
        {
            *eroder.eroder = None;
        }
        // During the thread's teardown the pool may be gone: the buffers are freed.
        let _ = POOL.try_with(|p| p.set(Some(pool)));
    }
}

/// The region's convex corners for the drop test (`mitres::excess_at`), listed where
/// it first asks (most layers never do: no drop passes 2π's first).
struct Mitres<'a> {
    region: &'a Region,
    corners: &'a mut Vec<(f64, f64)>,
    listed: bool,
}

impl Mitres<'_> {
    /// What the corners still there at the loops `d` in add to a drop, per unit.
    fn excess(&mut self, d: f64) -> f64 {
        if !self.listed {
            mitres::corners(self.region.outline(), self.corners);
            self.listed = true;
        }
        mitres::excess_at(self.corners, self.region.nozzle() / 2.0 + d)
    }
}

/// The buffers of one layer's loops, kept for the next layer on the same thread: a
/// layer's loops allocated some forty vectors and grew most of them by doubling (a tenth
/// of the L's layer). Never anything computed: each layer's region is prepared afresh.
#[derive(Default)]
struct Pool {
    eroder: Option<Eroder>,
    scratch: Scratch,
    last: Vec<Vec<Coord>>,
    /// The region's convex corners (`mitres::corners`).
    mitres: Vec<(f64, f64)>,
}

/// Buffers with room for more points than this are let go rather than kept (a few MB
/// at most stay with a thread; a layer that large spends far more than its allocations).
const POOLED_POINTS: usize = 1 << 16;

thread_local! {
    static POOL: Cell<Option<Box<Pool>>> = const { Cell::new(None) };
}

/// The radius of the largest disc inside rings that bound (approximately) the erosion
/// by `d`, or more: a disc inside an outline ring covers no more than its area. Arcs are
/// drawn in steps of 0.5 rad (a chord or a mitre strays 3.2% of `d` from the exact
/// boundary): the rings are widened by 4% of `d` all round for it, or, where the eroder
/// made them, by a quarter more than its reflex mitres stray outside their exact arcs
/// (`Eroder::stray`; its chords stray inside, taking in more, not less). A star's
/// reflex corners are arcs: its rings need no widening, and its last erosion at 40%,
/// empty, is not made (8 erosions a layer → 7).
fn room(loops: &Loops, length: f64, d: f64) -> f64 {
    let area = loops.largest.unwrap_or_else(|| {
        loops
            .rings
            .iter()
            .map(|r| twice_area(r).abs() / 2.0)
            .fold(0.0, f64::max)
    });
    let widen = widening(loops, d);
    ((area + length * widen + PI * widen * widen) / PI).sqrt()
}

/// How far `room` and `hull_room` widen the rings for what they may miss of the exact
/// erosion by `d`: a quarter more than the eroder's reflex mitres stray (`Eroder::stray`),
/// else 4% of `d` (any chord or mitre of a 0.5 rad step).
fn widening(loops: &Loops, d: f64) -> f64 {
    loops.stray.map_or(0.04, |s| (1.25 * s).min(0.04)) * d + 1e-6
}

/// Another bound on the room of `room`: a disc inside a convex ring has a radius of at
/// most twice its area over its perimeter (the disc's centre sees every edge at least
/// its radius away: the ring's area, summed as triangles from the centre, is at least
/// the radius times half the perimeter), and a disc inside a ring lies inside its hull.
/// The rings, short of the exact erosion by `stray·d` at most at reflex mitres (no more
/// than `room`'s widening), hold the exact erosion's discs less that much: it is added.
/// `hull` is working room.
/// Past `step` it stops: a ring whose own twice area over perimeter (no more than its
/// hull's) reaches `step` answers at once.
fn hull_room(loops: &Loops, d: f64, step: f64, hull: &mut Vec<Coord>) -> f64 {
    let widen = widening(loops, d);
    let mut most = 0.0f64;
    for ring in &loops.rings {
        // The hull's area is the ring's or more, its perimeter the ring's or less.
        let (mut area, mut length) = (0.0, 0.0);
        for w in ring.windows(2) {
            let e = w[1] - w[0];
            area += w[0].x * w[1].y - w[1].x * w[0].y;
            length += (e.x * e.x + e.y * e.y).sqrt();
        }
        // (A NaN answers too: nothing proved.)
        let bound = area.abs() / length + widen;
        if bound >= step || bound.is_nan() {
            return f64::INFINITY;
        }
        // The hull by the monotone chain: points sorted by x then y, the lower chain then
        // the upper, each turning left only.
        let pts = match ring.split_last() {
            Some((last, rest)) if Some(last) == rest.first() => rest,
            _ => &ring[..],
        };
        hull.clear();
        hull.extend_from_slice(pts);
        hull.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let n = hull.len();
        if n < 3 {
            continue;
        }
        let mut k = 0;
        let turn = |o: Coord, a: Coord, b: Coord| (a - o).x * (b - o).y - (a - o).y * (b - o).x;
        // In place: the chain written over the sorted points (k ≤ i always), the upper
        // half read from a copy of the points past the lower chain's end.
        let sorted = hull.clone();
        for &p in &sorted {
            while k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0.0 {
                k -= 1;
            }
            hull[k] = p;
            k += 1;
        }
        let lower = k + 1;
        for &p in sorted.iter().rev().skip(1) {
            while k >= lower && turn(hull[k - 2], hull[k - 1], p) <= 0.0 {
                k -= 1;
            }
            if k < hull.len() {
                hull[k] = p;
            } else {
                hull.push(p);
            }
            k += 1;
        }
        // hull[..k] closes on its first point.
        let (mut area, mut length) = (0.0, 0.0);
        for w in hull[..k].windows(2) {
            area += w[0].x * w[1].y - w[1].x * w[0].y;
            length += math::hypot((w[1] - w[0]).x, (w[1] - w[0]).y);
        }
        if !(length > 0.0 && area.is_finite()) {
            return f64::INFINITY;
        }
        most = most.max(area.abs() / length);
    }
    most + widen
}

/// The region's erosion by `d` (from the region itself, as the loops make it) and the
/// room `room` gives it, with `hull_room`'s, `None` where it is empty (for the tests).
#[cfg(test)]
pub(super) fn room_at(region: &Region, d: f64) -> Option<(f64, f64)> {
    let mut spare = None;
    let mut shrink = Shrink::new(region.outline(), &mut spare, known_concave(region));
    let loops = shrink.shrink(d);
    if loops.rings.is_empty() {
        return None;
    }
    let length = perimeter(&loops).0;
    let mut hull = Vec::new();
    Some((
        room(&loops, length, d),
        hull_room(&loops, d, f64::INFINITY, &mut hull),
    ))
}

/// The middle ring's points lie this many spacings apart at most: a middle stretch ends
/// this near where the region is first covered. A quarter before: every point measured
/// (most of them near a loop) cost a star's or a holed square's layer a tenth of its time
/// at 20–40%, and the half moves a stretch's ends by less than half a spacing (density of
/// the Polyslice comparison's holed square and L at 20% 0.1–0.2 points lower, largest gap
/// the same; the star, circle and square unchanged to the bit).
pub(super) const MIDDLE_STEP: f64 = 0.5;

/// Reused from one loop to the next: flags, dense points, the segments and candidates.
#[derive(Default)]
struct Scratch {
    flags: Vec<bool>,
    dense: Vec<Coord>,
    segments: Segments,
    last: Segments,
    near: Near,
    near_last: Near,
    /// Each last loop's segment a run was last found near all along (`Disc`).
    last_hints: Vec<Option<u32>>,
    /// How much the last loops' hints are trusted to find a run near two (`far`): up
    /// by one for each run near two, down by one for each the hints missed.
    trust: i32,
}

/// Rings with their bounds.
pub(super) type Bounded<'a> = Vec<(&'a [Coord], (Coord, Coord))>;

/// A segment near a run of points: its ends, and where it is (its ring, and its index
/// there), to be asked first for the next points ([`Hint`]).
#[derive(Clone, Copy)]
struct Candidate {
    a: Coord,
    b: Coord,
    at: Hint,
}

/// A segment of closed rings: the ring's index and the segment's there.
#[derive(Clone, Copy, PartialEq, Debug)]
struct Hint {
    ring: u32,
    seg: u32,
}

/// How many consecutive points share one gathering of near segments: a ring's points lie
/// close together, so a run's bounds are small and few segments pass them. Four, not
/// eight, since the middle ring's points lie half a spacing apart: a run of eight was
/// rarely decided whole (`together`, `hinted_both`), and measured (callgrind) 4 gave the
/// star at 40% 214k → 205k, the holed square at 20% 482k → 472k (3 and 5 were each worse
/// on one of them).
const RUN: usize = 4;

/// The segments of some rings with their bounds grown by `r` (and a margin for rounding:
/// a segment whose grown bounds miss a point is farther than `r` from it), ring by ring.
#[derive(Default)]
struct Segments {
    /// Each ring's grown bounds and its range in `grown`.
    rings: Vec<(Coord, Coord, std::ops::Range<usize>)>,
    grown: Vec<(Coord, Coord, Candidate)>,
}

impl Segments {
    fn build(&mut self, rings: &Bounded, r: f64) {
        let reach = Coord {
            x: r + 1e-9,
            y: r + 1e-9,
        };
        self.rings.clear();
        self.grown.clear();
        for (index, &(ring, (lo, hi))) in rings.iter().enumerate() {
            let first = self.grown.len();
            self.grown
                .extend(ring.windows(2).enumerate().map(|(seg, w)| {
                    let (a, b) = (w[0], w[1]);
                    let lo = Coord {
                        x: a.x.min(b.x),
                        y: a.y.min(b.y),
                    };
                    let hi = Coord {
                        x: a.x.max(b.x),
                        y: a.y.max(b.y),
                    };
                    let at = Hint {
                        ring: index as u32,
                        seg: seg as u32,
                    };
                    (lo - reach, hi + reach, Candidate { a, b, at })
                }));
            self.rings
                .push((lo - reach, hi + reach, first..self.grown.len()));
        }
    }

    /// The segments of rings before `before` that may be within `r` of a point of
    /// `lo..hi`.
    fn gather(&self, lo: Coord, hi: Coord, before: usize, out: &mut Near) {
        out.cands.clear();
        out.groups.clear();
        let meets = |a: Coord, b: Coord| a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y;
        for (ring, (a, b, range)) in self.rings.iter().take(before).enumerate() {
            if meets(*a, *b) {
                let first = out.cands.len();
                out.cands.extend(
                    self.grown[range.clone()]
                        .iter()
                        .filter(|(a, b, _)| meets(*a, *b))
                        .map(|&(_, _, c)| c),
                );
                if out.cands.len() > first {
                    out.groups.push((ring, first..out.cands.len()));
                }
            }
        }
    }
}

/// The segments gathered near a run of points, ring by ring: a ring's bounds are
/// tested once per point, and a ring found near is not searched further.
#[derive(Default)]
struct Near {
    cands: Vec<Candidate>,
    /// Each ring with candidates, and their range in `cands`.
    groups: Vec<(usize, std::ops::Range<usize>)>,
}

impl Near {
    /// The candidates of each ring whose bounds (as `within` decides it) come within `r`
    /// of `p`.
    fn rings<'a>(
        &'a self,
        rings: &'a Bounded,
        p: Coord,
        r: f64,
    ) -> impl Iterator<Item = &'a [Candidate]> + 'a {
        self.groups
            .iter()
            .filter(move |(ring, _)| in_bounds(rings[*ring].1, p, r))
            .map(|(_, range)| &self.cands[range.clone()])
    }
}

/// A candidate within `r` of `p`, if any (its ring's bounds first, then the segment,
/// measured exactly as `within` measured it).
fn near_any(rings: &Bounded, near: &Near, p: Coord, r: f64) -> Option<Hint> {
    near.rings(rings, p, r)
        .find_map(|cands| cands.iter().find(|c| segment_within(c.a, c.b, p, r)))
        .map(|c| c.at)
}

/// Whether `p` is within `r` of the segment `hint` or of one of its next neighbours on
/// its ring (of the rings before `before`); `hint` becomes the one found. Consecutive
/// points of a loop, or of a middle ring, run alongside the same few segments of the ring
/// they are near: most are found here without gathering any (a point's answer is the
/// same: any segment within `r`, its ring's bounds first as `within` asked them).
fn hinted(rings: &Bounded, hint: &mut Option<Hint>, before: usize, p: Coord, r: f64) -> bool {
    let Some(h) = *hint else {
        return false;
    };
    let (ring, bounds) = rings[h.ring as usize];
    if h.ring as usize >= before || !in_bounds(bounds, p, r) {
        return false;
    }
    next_to(ring, h, hint, |s, e| segment_within(s, e, p, r))
}

/// Whether both `a` and `b` are within `r` of one segment: `hint` or one of its next
/// neighbours (as [`hinted`]).
fn hinted_both(rings: &Bounded, hint: &mut Option<Hint>, a: Coord, b: Coord, r: f64) -> bool {
    let Some(h) = *hint else {
        return false;
    };
    let (ring, bounds) = rings[h.ring as usize];
    // Both ends within `r` of the ring's bounds first (a cheap no where the hint's ring is
    // elsewhere: the middle ring passing from one covered ring to the next).
    if !in_bounds(bounds, a, r) || !in_bounds(bounds, b, r) {
        return false;
    }
    next_to(ring, h, hint, |s, e| {
        segment_within(s, e, a, r) && segment_within(s, e, b, r)
    })
}

/// Whether the segment `h` of the closed `ring`, or one of its next neighbours (after,
/// before, two after, in that order), passes `test`; `hint` becomes the first that does.
#[inline(always)]
fn next_to(
    ring: &[Coord],
    h: Hint,
    hint: &mut Option<Hint>,
    test: impl Fn(Coord, Coord) -> bool,
) -> bool {
    let n = ring.len() - 1;
    let seg = h.seg as usize;
    for k in [seg, seg + 1, seg + n - 1, seg + 2] {
        let k = k % n;
        if test(ring[k], ring[k + 1]) {
            *hint = Some(Hint {
                ring: h.ring,
                seg: k as u32,
            });
            return true;
        }
    }
    false
}

/// Whether `p` is within `r` of segments of two different rings.
fn near_two(rings: &Bounded, near: &Near, p: Coord, r: f64) -> bool {
    near.rings(rings, p, r)
        .filter(|cands| cands.iter().any(|c| segment_within(c.a, c.b, p, r)))
        .nth(1)
        .is_some()
}

/// The loops of one distance, each less its stretches within `gap` of an earlier one.
/// Where an outline's loop and a hole's approach (the band between them narrower than
/// a spacing, before their offsets meet), both would be printed side by side, down to a
/// fraction of a spacing apart: the later gives way to the earlier there.
fn apart(
    loops: &mut [Vec<Coord>],
    last: bool,
    gap: f64,
    scratch: &mut Scratch,
    out: &mut Vec<Vec<Coord>>,
) {
    // One loop gives way to none (the layer's last: moved, not copied).
    if let [only] = loops {
        out.push(if last {
            std::mem::take(only)
        } else {
            only.clone()
        });
        return;
    }
    let loops = &*loops;
    let all: Bounded = loops.iter().map(|l| (l.as_slice(), bounds(l))).collect();
    let mut filed = false;
    for (j, ring) in loops.iter().enumerate() {
        let (lo, hi) = all[j].1;
        // An earlier loop with a segment whose bounds come within `gap` of this one's (a
        // hole's loop inside an outline's: the outline's bounds hold it, its segments
        // pass it by).
        // (With a margin for rounding: a point within `gap` of a segment is inside its
        // bounds grown by `gap`.)
        let reach = gap * (1.0 + 1e-9) + 1e-12;
        let meets = |a: Coord, b: Coord| {
            a.x - reach <= hi.x && b.x + reach >= lo.x && a.y - reach <= hi.y && b.y + reach >= lo.y
        };
        let near = all[..j].iter().any(|&(earlier, (a, b))| {
            meets(a, b)
                && earlier.windows(2).any(|w| {
                    let (a, b) = (w[0], w[1]);
                    meets(
                        Coord {
                            x: a.x.min(b.x),
                            y: a.y.min(b.y),
                        },
                        Coord {
                            x: a.x.max(b.x),
                            y: a.y.max(b.y),
                        },
                    )
                })
        });
        if !near {
            out.push(ring.clone());
            continue;
        }
        if !filed {
            scratch.segments.build(&all, gap);
            filed = true;
        }
        scratch.flags.clear();
        let mut hint = None;
        for run in ring.chunks(RUN) {
            // The points the hint does not find near are measured against the segments
            // gathered near their run.
            let start = scratch.flags.len();
            let mut open = false;
            for &p in run {
                // Past a point the hint missed, the run is gathered anyway.
                let near = !open && hinted(&all, &mut hint, j, p, gap);
                scratch.flags.push(!near);
                open |= !near;
            }
            if !open {
                continue;
            }
            let (lo, hi) = bounds(run);
            scratch.segments.gather(lo, hi, j, &mut scratch.near);
            for (flag, &p) in scratch.flags[start..].iter_mut().zip(run) {
                if *flag && let Some(h) = near_any(&all, &scratch.near, p, gap) {
                    *flag = false;
                    hint = Some(h);
                }
            }
        }
        runs(ring, &scratch.flags, out);
    }
}

/// Whether the points of `a` then `b` make a line `spacing` long or more (the sum of
/// its segments' `hypot`s, in order, until it reaches `spacing`).
pub(super) fn long_enough(a: &[Coord], b: &[Coord], spacing: f64) -> bool {
    let mut length = 0.0;
    let mut points = a.iter().chain(b);
    let Some(mut previous) = points.next().copied() else {
        return false;
    };
    points.any(|&p| {
        let e = p - previous;
        previous = p;
        length += math::hypot(e.x, e.y);
        length >= spacing
    })
}

/// How many points a middle segment `e` long gets, `step` apart at most:
/// `⌈|e| / step⌉` (in 1..=1000), `|e|` by `hypot`. A plain square root (a fraction of its
/// time) differs from it by a few units in the last place: where the quotient is not
/// that near a whole number, its ceiling is the same.
pub(super) fn steps(e: Coord, step: f64) -> usize {
    let q = (e.x * e.x + e.y * e.y).sqrt() / step;
    let f = q - q.floor();
    let q = if q < 1e6 && f > 1e-6 && f < 1.0 - 1e-6 {
        q
    } else {
        math::hypot(e.x, e.y) / step
    };
    (q.ceil() as usize).clamp(1, 1000)
}

/// Whether `p` is within `r` of the bounds `(lo, hi)` (as `within` decides it).
pub(super) fn in_bounds((lo, hi): (Coord, Coord), p: Coord, r: f64) -> bool {
    !(p.x < lo.x - r || p.x > hi.x + r || p.y < lo.y - r || p.y > hi.y + r)
}

/// Whether `p` is within `r` of the segment `a`–`b`.
pub(super) fn segment_within(a: Coord, b: Coord, p: Coord, r: f64) -> bool {
    math::segment_distance2(p, a, b) <= r * r
}

/// The runs of a closed ring's vertices whose flag is set (the whole ring when all are),
/// each of two points or more (copied a run at a time).
pub(super) fn runs(pts: &[Coord], flags: &[bool], out: &mut Vec<Vec<Coord>>) {
    runs_kept(pts, flags, out, |_, _| true);
}

/// The runs of [`runs`] that `keep` keeps, asked of each run's points (in one or two
/// slices, where it passes the ring's end) before it is copied.
pub(super) fn runs_kept(
    pts: &[Coord],
    flags: &[bool],
    out: &mut Vec<Vec<Coord>>,
    keep: impl Fn(&[Coord], &[Coord]) -> bool,
) {
    // None flagged (most middle rings): nothing to read.
    if !flags.contains(&true) {
        return;
    }
    if flags.iter().all(|&f| f) {
        if keep(pts, &[]) {
            out.push(pts.to_vec());
        }
        return;
    }
    // Read from an unflagged vertex so that no run wraps: vertices start + 1 ..= start + n
    // (the last is the unflagged one again), a run ended by the next unflagged vertex.
    let n = pts.len().saturating_sub(1);
    let Some(start) = (0..n).find(|&i| !flags[i]) else {
        return;
    };
    let mut piece: Vec<Coord> = Vec::new();
    let mut from = start + 1;
    while from <= start + n {
        let flagged = |k: usize| flags[if k >= n { k - n } else { k }];
        if !flagged(from) {
            from += 1;
            continue;
        }
        let mut to = from;
        while to < start + n && flagged(to + 1) {
            to += 1;
        }
        if to > from {
            // from..=to, in at most two slices where it passes the ring's end.
            let (a, b): (&[Coord], &[Coord]) = if to < n {
                (&pts[from..=to], &[])
            } else if from >= n {
                (&pts[from - n..=to - n], &[])
            } else {
                (&pts[from..n], &pts[..=to - n])
            };
            if keep(a, b) {
                // Its size known: one allocation (a run through the ring's end grew it
                // twice).
                piece.reserve_exact(a.len() + b.len());
                piece.extend_from_slice(a);
                piece.extend_from_slice(b);
                out.push(std::mem::take(&mut piece));
            }
        }
        from = to + 1;
    }
}

/// The total length of a region's rings, and its outline rings less its hole rings.
fn perimeter(area: &Loops) -> (f64, f64) {
    let length = area
        .rings
        .iter()
        .map(|ring| {
            // A plain square root, not `hypot` (a fraction of its time): no length comes
            // near overflowing, and the last bit it may differ by changes a comparison of
            // the sum (the heuristics' thresholds, `room`) only at its exact threshold.
            ring.windows(2)
                .map(|w| {
                    let e = w[1] - w[0];
                    (e.x * e.x + e.y * e.y).sqrt()
                })
                .sum::<f64>()
        })
        .sum();
    (length, area.turns)
}

/// The stretches of `middle`'s rings farther than ¾ `spacing` from every ring of
/// `covered`, and farther than two spacings from every loop of `last` but the nearest
/// (the one each middle stretch lies half a spacing inside of): where two loops of `last`
/// close in on each other from both sides (an outline's and a hole's, about to meet),
/// each side's middle stretch would be a second line in a band that wants less than two.
fn uncovered(
    middle: &Loops,
    covered: &Loops,
    last: &[Vec<Coord>],
    spacing: f64,
    scratch: &mut Scratch,
    out: &mut Vec<Vec<Coord>>,
) {
    let gap = 0.75 * spacing;
    let covered: Bounded = covered
        .rings
        .iter()
        .map(|r| (r.as_slice(), bounds(r)))
        .collect();
    let last: Bounded = last.iter().map(|r| (r.as_slice(), bounds(r))).collect();
    scratch.segments.build(&covered, gap);
    // Near two of one loop is never asked: with one loop none of its segments is filed.
    if last.len() > 1 {
        scratch.last.build(&last, 2.0 * spacing);
    } else {
        scratch.last.build(&Vec::new(), 2.0 * spacing);
    }
    scratch.last_hints.clear();
    scratch.last_hints.resize(last.len(), None);
    scratch.trust = TRUST;
    // Inside `gap` by more than rounding: a segment of the middle ring whose both ends
    // are this near one covered segment lies that near it all along (the distance to a
    // segment is convex along a line), so none of its points is far.
    let inner = gap * (1.0 - 1e-9);
    // The points not decided whole, each measured (`far`), their flags appended.
    let measure = |points: &[Coord], hint: &mut Option<Hint>, scratch: &mut Scratch| {
        far(points, &covered, &last, gap, spacing, hint, scratch);
    };
    // The covered segment the last point (or segment) was found near.
    let mut hint = None;
    for ring in &middle.rings {
        // Points every half spacing at least (`MIDDLE_STEP`): a ring cut from the raw
        // offset has long edges, and a stretch is kept from vertex to vertex.
        // Out of the scratch while `far` writes the flags there.
        let mut dense = std::mem::take(&mut scratch.dense);
        dense.clear();
        scratch.flags.clear();
        // The points not flagged yet start here (measured in runs of 8 across segments).
        let mut pending = 0;
        for w in ring.windows(2) {
            let e = w[1] - w[0];
            let steps = steps(e, MIDDLE_STEP * spacing);
            let point = |i: usize| w[0] + e * (i as f64 / steps as f64);
            // All near one covered segment: none far. Asked first of the segments the
            // last points were near (no gathering), then, for a segment of a few points
            // or more, of those near its bounds.
            let all = if hinted_both(&covered, &mut hint, w[0], w[1], inner) {
                Some(false)
            } else if !(4..2 * RUN).contains(&steps) {
                None
            } else {
                let (lo, hi) = bounds(w);
                scratch
                    .segments
                    .gather(lo, hi, usize::MAX, &mut scratch.near);
                if let Some(c) = scratch.near.cands.iter().find(|c| {
                    segment_within(c.a, c.b, w[0], inner) && segment_within(c.a, c.b, w[1], inner)
                }) {
                    hint = Some(c.at);
                    Some(false)
                } else if scratch.near.cands.is_empty() && {
                    // No covered segment near the segment's bounds (nor last loops'
                    // segments, where two are asked for): all far.
                    scratch
                        .last
                        .gather(lo, hi, usize::MAX, &mut scratch.near_last);
                    scratch.near_last.cands.is_empty()
                } {
                    Some(true)
                } else {
                    None
                }
            };
            if let Some(flag) = all {
                // The points before it, not decided yet, are measured first.
                measure(&dense[pending..], &mut hint, scratch);
                if flag {
                    dense.extend((0..steps).map(point));
                    scratch.flags.resize(dense.len(), true);
                } else {
                    // None of its points is in a stretch: its first stands for all (a
                    // stretch is cut by one point not far as by many).
                    dense.push(w[0]);
                    scratch.flags.push(false);
                }
                pending = dense.len();
                continue;
            }
            if steps < 2 * RUN {
                dense.extend((0..steps).map(point));
                // Measured as whole runs gather (the hint then follows the ring).
                let whole = pending + (dense.len() - pending) / RUN * RUN;
                if whole > pending {
                    measure(&dense[pending..whole], &mut hint, scratch);
                    pending = whole;
                }
                continue;
            }
            // The points of a long segment in runs: a run (a straight stretch) whose
            // ends are both near one covered segment is near it all along (its first
            // point stands for it, as above); the others measured.
            for from in (0..steps).step_by(RUN) {
                let to = (from + RUN).min(steps);
                if hinted_both(&covered, &mut hint, point(from), point(to - 1), inner) {
                    measure(&dense[pending..], &mut hint, scratch);
                    dense.push(point(from));
                    scratch.flags.push(false);
                } else {
                    dense.extend((from..to).map(point));
                    measure(&dense[pending..], &mut hint, scratch);
                }
                pending = dense.len();
            }
        }
        dense.extend(ring.last().copied());
        measure(&dense[pending..], &mut hint, scratch);
        // A stretch shorter than a spacing (a star's tip) leaves no gap worth a line. Its
        // length summed only until it reaches a spacing (sums of lengths only grow, so the
        // answer is the whole sum's); measured before it is copied out.
        runs_kept(&dense, &scratch.flags, out, |a, b| {
            long_enough(a, b, spacing)
        });
        scratch.dense = dense;
    }
}

/// Appends to `scratch.flags` whether each point is farther than `gap` from every
/// covered ring (exactly: within is `<=`) and near at most one of the last loops.
fn far(
    points: &[Coord],
    covered: &Bounded,
    last: &Bounded,
    gap: f64,
    spacing: f64,
    hint: &mut Option<Hint>,
    scratch: &mut Scratch,
) {
    for run in points.chunks(RUN) {
        // Most points lie near the covered segments the point before was near: not far,
        // and nothing gathered. The others are measured against the segments gathered
        // near their run.
        let start = scratch.flags.len();
        let mut open = false;
        for &p in run {
            // Past a point the hint missed, the run is gathered anyway: not asked again.
            let near = !open && hinted(covered, hint, usize::MAX, p, gap);
            scratch.flags.push(!near);
            open |= !near;
        }
        if !open {
            continue;
        }
        let (lo, hi) = bounds(run);
        scratch
            .segments
            .gather(lo, hi, usize::MAX, &mut scratch.near);
        if scratch.near.cands.is_empty() && last.len() < 2 {
            // Nothing near the run: all of it far (as flagged).
            continue;
        }
        // With two last loops or more (an outline's and a hole's), a run is mostly near
        // one of them and far from the others all along: decided once, not per point;
        // first against the covered segments, the last loops' gathered only if that does
        // not decide it (most of them, grown by two spacings, meet every run).
        let disc = Disc::new(lo, hi);
        let decided = if last.len() >= 2 {
            match disc.covered(&scratch.near, gap) {
                None => Some(false),
                // Near the segments of two last loops the run before was near (or the
                // ones nearest them): none far, nothing gathered.
                // (Asked while it answers more often than not: where the runs are not
                // near two loops, as in a part's corner, it is not worth asking.)
                Some(_)
                    if scratch.trust > 0
                        && if disc.near_two_hinted(last, &mut scratch.last_hints, spacing) {
                            scratch.trust = (scratch.trust + 1).min(TRUST);
                            true
                        } else {
                            scratch.trust -= 1;
                            false
                        } =>
                {
                    Some(false)
                }
                Some(apart) => {
                    scratch
                        .last
                        .gather(lo, hi, usize::MAX, &mut scratch.near_last);
                    let (flag, two) =
                        disc.last(apart, &scratch.near_last, spacing, &mut scratch.last_hints);
                    // A run the hints could have answered: ask them again.
                    if two {
                        scratch.trust = (scratch.trust + 1).min(TRUST);
                    }
                    flag
                }
            }
        } else {
            scratch
                .last
                .gather(lo, hi, usize::MAX, &mut scratch.near_last);
            None
        };
        if let Some(flag) = decided {
            for f in &mut scratch.flags[start..] {
                *f &= flag;
            }
            continue;
        }
        for (flag, &p) in scratch.flags[start..].iter_mut().zip(run) {
            if !*flag {
                continue;
            }
            if let Some(h) = near_any(covered, &scratch.near, p, gap) {
                *flag = false;
                *hint = Some(h);
            } else {
                *flag = !near_two(last, &scratch.near_last, p, 2.0 * spacing);
            }
        }
    }
}

/// A run of points in the bounds `lo..hi`, for the answer `far` gives all of them where
/// it is the same for all. Every point of the run lies within `rho` of the bounds'
/// centre, so a segment within `r − rho` of the centre is within `r` of each point, and
/// one farther than `r + rho` is within `r` of none; both with a margin far above the
/// rounding of the distances (a run's points lie half a spacing apart along the middle
/// ring at most: most runs are wholly near a last loop, and most far from the others).
pub(super) struct Disc {
    centre: Coord,
    rho: f64,
}

/// How far a last loop's hint walks along it (`Disc::near_two_hinted`): a run of four
/// middle points half a spacing apart moves along a loop by a few of its segments.
const WALK: usize = 4;

/// The most trust the last loops' hints earn (`Scratch::trust`): as many misses in a row
/// stop them being asked.
const TRUST: i32 = 1;

impl Disc {
    pub(super) fn new(lo: Coord, hi: Coord) -> Disc {
        let half = (hi - lo) / 2.0;
        Disc {
            centre: (lo + hi) / 2.0,
            rho: (half.x * half.x + half.y * half.y).sqrt(),
        }
    }

    fn distance(&self, c: &Candidate) -> f64 {
        self.distance_to(c.a, c.b)
    }

    /// The distance from the centre to the segment `a`–`b`.
    fn distance_to(&self, a: Coord, b: Coord) -> f64 {
        math::segment_distance2(self.centre, a, b).sqrt()
    }

    /// Within `r − rho` (inner) and `r + rho` (outer), with the margin.
    fn band(&self, r: f64) -> (f64, f64) {
        let margin = 1e-9 * (r + self.rho) + 1e-12;
        (r - self.rho - margin, r + self.rho + margin)
    }

    /// Whether every point is within two spacings of one segment of each of two last
    /// loops, each found from its hint (`hints`, a segment per loop) by walking along
    /// the loop while the segments come nearer the centre: consecutive runs lie near the
    /// same stretch of each loop, so most runs near two are decided without gathering
    /// (a yes is `last`'s; a no decides nothing). The hints move to the nearest found.
    pub(super) fn near_two_hinted(
        &self,
        last: &Bounded,
        hints: &mut [Option<u32>],
        spacing: f64,
    ) -> bool {
        let (inner2, _) = self.band(2.0 * spacing);
        if inner2 <= 0.0 || hints.iter().flatten().nth(1).is_none() {
            return false;
        }
        // Squared distances: the margin in `inner2` is far above their rounding.
        let within = inner2 * inner2;
        let c = self.centre;
        let mut found = 0;
        for (&(ring, bounds), hint) in last.iter().zip(hints.iter_mut()) {
            let Some(seg) = *hint else {
                continue;
            };
            // A loop whose bounds are that far from the centre has no segment near.
            if !in_bounds(bounds, c, inner2) {
                continue;
            }
            let n = ring.len() - 1;
            let at = |k: usize| math::segment_distance2(c, ring[k], ring[k + 1]);
            let (mut k, mut d) = (seg as usize, at(seg as usize));
            if d >= within {
                // Forward while nearer, else backward while nearer (a few segments).
                let next = |k: usize| if k + 1 == n { 0 } else { k + 1 };
                let back = |k: usize| if k == 0 { n - 1 } else { k - 1 };
                let (mut j, mut e) = (next(k), at(next(k)));
                let forward = e < d;
                if !forward {
                    (j, e) = (back(k), at(back(k)));
                }
                let mut steps = 0;
                while e < d && steps < WALK {
                    (k, d) = (j, e);
                    j = if forward { next(k) } else { back(k) };
                    e = at(j);
                    steps += 1;
                }
                *hint = Some(k as u32);
            }
            if d < within {
                found += 1;
                if found == 2 {
                    return true;
                }
            }
        }
        false
    }

    /// `None` where every point is within `gap` of one covered segment (of `near`, those
    /// gathered near the run: none far), else whether every covered segment is farther
    /// than `gap` from every point.
    fn covered(&self, near: &Near, gap: f64) -> Option<bool> {
        let (inner, outer) = self.band(gap);
        let mut apart = true;
        for c in &near.cands {
            let d = self.distance(c);
            if d < inner {
                return None;
            }
            apart &= d > outer;
        }
        Some(apart)
    }

    /// The answer for every point, given whether the covered segments are apart from
    /// all of them (`near_last`: the last loops' segments gathered near the run).
    /// And whether every point is near two last loops (their segments found are the
    /// hints).
    fn last(
        &self,
        apart: bool,
        near_last: &Near,
        spacing: f64,
        hints: &mut [Option<u32>],
    ) -> (Option<bool>, bool) {
        let (inner2, outer2) = self.band(2.0 * spacing);
        let (mut within, mut touched) = (0, 0);
        for (_, range) in &near_last.groups {
            let mut all = false;
            let mut some = false;
            for c in &near_last.cands[range.clone()] {
                let d = self.distance(c);
                if d < inner2 {
                    all = true;
                    some = true;
                    // The next run asks it first (`near_two_hinted`).
                    hints[c.at.ring as usize] = Some(c.at.seg);
                    break;
                }
                some |= d <= outer2;
            }
            within += usize::from(all);
            touched += usize::from(some);
        }
        // Near two last loops, every point: none far.
        if within >= 2 {
            return (Some(false), true);
        }
        // No covered segment near any point, and at most one last loop near: all far.
        if apart && touched <= 1 {
            return (Some(true), false);
        }
        (None, false)
    }
}

/// Whether the region's outline is one polygon without holes that the exact convex
/// inset declines at every distance (it has a reflex corner): the region's own inset
/// was made from that outline (`Region::outline`, kept as cleaned) by the convex inset
/// where it could, and such an inset, not empty, is one convex ring: a region of one
/// holeless polygon, not empty and not convex, had its convex inset declined. The first
/// loop then does not ask it again (some 280 instructions of a star's layer of 23k).
pub(super) fn known_concave(region: &Region) -> bool {
    let outline = region.outline();
    !region.is_convex()
        && !region.outlines().is_empty()
        && outline.0.len() == 1
        && outline.0[0].interiors().is_empty()
}

/// Whether no point of the middle ring (half a spacing past the last loops) can be far
/// from the loops `step` past them (`uncovered`), by how the two erosions were cut
/// (`cutting`: the last loops' and these) and the region's corners (`Eroder::corners`):
/// its middle ring is not made.
///
/// The last loops uncut, these cut only where two rings' raw offsets cross, one spacing
/// on: each point p of the middle ring lies on a region ring's raw offset, and the point
/// q of that ring's raw offset half a spacing further in (along the normal, or at a
/// convex corner's mitre) is within `apex` spacings of it: half a spacing along an edge
/// or at a reflex mitre, `½·sqrt(2/k)` from mitre to mitre at a convex corner
/// (`k = 1 − cos α`), under 0.74 (the test's ¾ less a margin) for a corner of 85° or
/// more. Where q is kept, p is near these loops. Where q was cut away, it lies within a
/// spacing of another ring's last loop (nearer that ring than a loop's distance: its last
/// loop lies a spacing less out from it), so p lies within `apex + 1` spacings of that
/// loop and `apex` of its own ring's: near two last loops, which no stretch is. Either
/// way none is far. Uncut both (no part ended, no ring met another), the same without the
/// second case.
///
/// Not where a reflex corner is an arc of chords. The first random shapes that found
/// stretches past this bound with arcs (a pentagon with an octagonal hole) were the
/// eroder leaving out real pieces (its keep test measured the exact arc, not the chords
/// drawn; it measures the chords now), but with that fixed, random outlines with square
/// holes still find middle stretches here: the bound is not shown for chords, and is not
/// taken. A reflex mitre lies outside its arc: a point outside another ring's raw offset
/// is as far from that ring as the distance, and a piece kept is on the erosion.
/// (The holed square's meeting steps at 10, 20 and 40%: a third of its layer at 10%.)
fn nothing_far(
    (before, now): (Cutting, Cutting),
    corners: Option<(f64, bool)>,
    step: f64,
    spacing: f64,
) -> bool {
    let Some((k, arcs)) = corners else {
        return false;
    };
    if arcs || before != Cutting::None || now == Cutting::Other || step > spacing * (1.0 + 1e-9) {
        return false;
    }
    // (A sharp tip's k is 0, a NaN none: not blunt.)
    if k.is_nan() || k <= 0.0 {
        return false;
    }
    let apex = 0.5 * (2.0 / k).sqrt();
    apex < 0.74
}

/// `nothing_far`'s answer, counted where it is yes (for the tests: that it was asked
/// and taken).
fn skipped(yes: bool) -> bool {
    #[cfg(test)]
    SKIPPED.with(|n| n.set(n.get() + usize::from(yes)));
    yes
}

#[cfg(test)]
thread_local! {
    /// How many middle rings `nothing_far` left out on this thread.
    pub(super) static SKIPPED: Cell<usize> = const { Cell::new(0) };
    /// How many middle rings were made on this thread.
    pub(super) static MADE: Cell<usize> = const { Cell::new(0) };
}

/// A region's rings (closed), and its outline rings less its hole rings.
struct Loops {
    rings: Vec<Vec<Coord>>,
    turns: f64,
    /// The largest ring's area where it was measured already (for `room`).
    largest: Option<f64>,
    /// How far the rings' reflex mitres stray outside the exact erosion, per unit of
    /// distance, where the eroder made them (for `room`).
    stray: Option<f64>,
    /// How the eroder cut them (`Cutting::Other` where it did not make them).
    cutting: Cutting,
}

impl Loops {
    /// Rings the eroder did not make (a convex inset's, the buffer's): nothing measured
    /// as they were made, their cutting not known.
    fn unmeasured(turns: f64, rings: Vec<Vec<Coord>>) -> Loops {
        Loops {
            rings,
            turns,
            largest: None,
            stray: None,
            cutting: Cutting::Other,
        }
    }
}

/// Twice a closed ring's signed area (counter-clockwise positive).
fn twice_area(ring: &[Coord]) -> f64 {
    ring.windows(2)
        .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
        .sum()
}

/// The loops' offsets of one region: arcs in steps of 0.5 rad (not geo's 0.2): the loops
/// are far from the outline, and a third of the vertices makes the offset three times
/// quicker. Where the region is not convex, the raw offset cut where it crosses itself
/// (`loops::Eroder`, prepared once for all the loops): parts pinching off and holes
/// meeting the outline cost no polygon rebuilt.
struct Shrink<'a> {
    area: &'a MultiPolygon<f64>,
    holes: bool,
    /// Set once the exact convex inset declined (without holes it declines a region with
    /// a reflex corner, whatever the distance): not asked again for the later loops.
    concave: bool,
    /// Made (or an earlier layer's reset) at the first loop that needs it (a convex
    /// region never does), in the thread's pool.
    eroder: &'a mut Option<Eroder>,
    ready: bool,
}

impl<'a> Shrink<'a> {
    fn new(
        area: &'a MultiPolygon<f64>,
        spare: &'a mut Option<Eroder>,
        concave: bool,
    ) -> Shrink<'a> {
        Shrink {
            area,
            holes: area.0.iter().any(|p| !p.interiors().is_empty()),
            concave,
            eroder: spare,
            ready: false,
        }
    }

    /// The eroder of this region, prepared at the first call.
    fn eroder(&mut self) -> &mut Eroder {
        if !self.ready {
            self.ready = true;
            match self.eroder {
                Some(e) => e.reset(self.area, 0.5),
                None => *self.eroder = Some(Eroder::new(self.area, 0.5)),
            }
        }
        self.eroder.as_mut().expect("made above")
    }

    /// The region's corners (`Eroder::corners`), where the eroder was made.
    fn corners(&self) -> Option<(f64, bool)> {
        self.eroder
            .as_ref()
            .filter(|_| self.ready)
            .map(|e| e.corners())
    }

    /// The list of an erosion's rings, emptied, back for the next erosion's.
    fn recycle(&mut self, rings: Vec<Vec<Coord>>) {
        if let Some(e) = self.eroder {
            e.recycle(rings);
        }
    }

    fn shrink(&mut self, d: f64) -> Loops {
        let area = self.area;
        let holes = self.holes;
        // A convex region without holes: its exact inset is cheapest. With holes, that
        // inset takes geo's boolean difference once a hole meets the outline.
        let convex = if holes || self.concave {
            None
        } else {
            match crate::infill::region::convex_rings(area, d, 0.5) {
                // Its rings as made, each closed in place: no polygon made, taken apart
                // and copied again (a square's layer at 10 / 20 / 40%: 16.2k / 24.5k /
                // 44.5k → 13.8k / 19.2k / 33.7k instructions). Without holes, one outline
                // a polygon: in the polygons' order.
                Some(ConvexInset::Rings(raw)) if raw.holes.is_empty() => {
                    let mut rings = raw.rings;
                    for ring in &mut rings {
                        if let Some(&first) = ring.first() {
                            ring.push(first);
                        }
                    }
                    return Loops::unmeasured(rings.len() as f64, rings);
                }
                Some(ConvexInset::Rings(raw)) => Some(raw.into_polygons()),
                Some(ConvexInset::Polygons(polygons)) => Some(polygons),
                None => None,
            }
        };
        self.concave |= !holes && convex.is_none();
        if convex.is_none()
            && let Some(rings) = self.eroder().rings(d)
        {
            // Each ring's area once, for its turn and for `room` (the same sums).
            let mut largest = 0.0;
            let turns = rings
                .iter()
                .map(|r| {
                    let twice = twice_area(r);
                    largest = f64::max(largest, twice.abs() / 2.0);
                    twice.signum()
                })
                .sum();
            return Loops {
                rings,
                turns,
                largest: Some(largest),
                stray: self.eroder.as_ref().map(|e| e.stray()),
                cutting: self.eroder.as_ref().map_or(Cutting::Other, |e| e.cutting()),
            };
        }
        let polygons = convex.unwrap_or_else(|| {
            if holes && let Some(inset) = crate::infill::region::convex_inset(area, d, 0.5) {
                return inset;
            }
            area.buffer_with_style(BufferStyle::new(-d).line_join(LineJoin::Round(0.5)))
        });
        Loops::unmeasured(
            polygons
                .0
                .iter()
                .map(|p| 1.0 - p.interiors().len() as f64)
                .sum(),
            polygons
                .0
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .map(|r| r.0.clone())
                .collect(),
        )
    }
}
