//! The boundary of a region's erosion by `d` as closed rings, for concentric loops, where
//! parts pinch off or a grown hole meets the outline: the raw offset of every ring (edges
//! moved by `d`, convex corners mitred, reflex corners an arc about the vertex) is cut
//! where it crosses itself or another ring's, and the pieces that stay `d` from the
//! boundary are chained back into rings. "`d` from the boundary" is measured as the raw
//! offsets are drawn (`keep`): about a reflex corner drawn as an arc of chords, a point is
//! near only inside the chords, not inside the exact arc, or a piece of another ring with
//! its middle between the two was dropped though no raw offset crossed it. The erosion's
//! boundary is made of exactly those pieces; no polygon is rebuilt, which is what made
//! geo's buffer and boolean difference cost 10–40 µs a loop. `None` where the offset touches itself without crossing (a
//! tangency), a chain does not close, or a stretch run backwards (an edge event) is not
//! cut off as a whole swallowtail: the buffer decides then.

use crate::math;
use geo::{Coord, MultiPolygon};

use super::offset::{cross, inside_left_cow};

/// More raw segments than this go to the buffer (the crossing sweep could go quadratic).
const MAX_SEGMENTS: usize = 20_000;

/// The rings (closed: first point = last) bounding the erosion of `region` by `d`, arcs in
/// steps of at most `arc` radians, each with the inside on its left (outlines
/// counter-clockwise, holes clockwise). Empty when nothing is left. (Concentric prepares
/// an [`Eroder`] once for all its loops; the tests ask for one distance at a time.)
#[cfg(test)]
pub(crate) fn eroded_rings(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
) -> Option<Vec<Vec<Coord>>> {
    Eroder::new(region, arc).rings(d)
}

/// A region prepared for eroding it by many distances (concentric's loops): what does not
/// depend on the distance (each ring oriented, its corners' normals and kinds, the arcs'
/// directions) is worked out once, and the buffers are reused from one distance to the
/// next. Every raw point is computed from the same numbers as before, so the rings are the
/// same to the bit as a fresh `eroded_rings`.
pub(crate) struct Eroder {
    /// Every edge of the region as given with its bounds, in runs with theirs, for the
    /// test that a piece is `d` away (the bounds do not depend on `d`: worked out once).
    boundary: Boundary,
    /// Each ring's corners (rings that cannot be oriented are left out, as before).
    corners: Vec<Vec<Corner>>,
    /// Each ring's distance below which no segment of its raw offset runs backwards, and
    /// how many points its raw offset has (before its tips are closed).
    safes: Vec<(f64, usize)>,
    /// Reused by `prepare`: a ring's edge directions.
    units: Vec<Coord>,
    /// Whether the raw rings' buffers were sized for these corners.
    sized: bool,
    /// Reused: the raw offsets, the crossing sweep's edges, each ring's cuts.
    raws: Vec<Raw>,
    sweep: Sweep,
    here: Vec<(usize, usize, f64, usize)>,
    /// Reused by `place_cuts`: the segments cut, each one's last cut, each cut's next.
    counts: (Vec<u64>, Vec<u32>, Vec<u32>),
    cuts: Vec<Cut>,
    turns: Vec<(f64, (Coord, Coord))>,
    /// Reused by `convex_crossings`: the cuts found and their places in the sweep's order,
    /// and the larger ring's chunks' boxes.
    ranked: Pairs,
    /// Reused by the chaining: the piece leaving each cut, and the pieces used.
    chained: (Vec<usize>, Vec<bool>),
    /// Reused: the kept pieces, their points one after another.
    pieces: Vec<Piece>,
    points: Vec<Coord>,
    /// A list of rings given back (`recycle`), empty: the next erosion's rings go in it.
    spare: Vec<Vec<Coord>>,
    /// Whether sharp tips are closed at their mitre (`Raw::close_tips`); the tests turn
    /// it off to compare with the tips cut.
    close: bool,
    /// How far a reflex corner's mitre lies beyond its exact arc, per unit of the
    /// distance eroded, at most (0 with none): `stray`.
    mitre_stray: f64,
    /// The least `k` of the region's convex corners' mitres (`1 − cos α` for an inside
    /// angle α), 0 with a sharp tip, and whether any reflex corner is drawn as an arc:
    /// `corners`.
    bluntest: f64,
    arcs: bool,
    /// How the last erosion's rings were cut from the raw offsets: `cutting`.
    cutting: Cutting,
}

/// How an erosion's rings came from the raw offsets of the region's rings.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Cutting {
    /// Uncut: each ring a raw offset whole, each kept, no edge run backwards.
    None,
    /// Cut only where two different rings' raw offsets cross (a hole's meeting the
    /// outline's), no ring crossing itself, no uncut ring left out and no edge run
    /// backwards.
    Between,
    /// Anything else (a ring crossing itself, an edge event, or not known).
    Other,
}

/// A corner of a ring, as its raw offset needs it.
enum Corner {
    /// One point `b + m·d/k` (a convex corner's mitre, or a reflex corner within one arc
    /// step).
    Mitre { b: Coord, m: Coord, k: f64 },
    /// A sharp tip: through the vertex.
    Tip { b: Coord, nu: Coord, nv: Coord },
    /// A reflex corner's arc: `b + nu·d`, `b + w·d` for each inner direction, `b + nv·d`.
    Arc {
        b: Coord,
        nu: Coord,
        nv: Coord,
        inner: std::ops::Range<usize>,
    },
}

impl Eroder {
    pub(crate) fn new(region: &MultiPolygon<f64>, arc: f64) -> Eroder {
        let mut eroder = Eroder {
            boundary: Boundary::default(),
            corners: Vec::new(),
            safes: Vec::new(),
            units: Vec::new(),
            sized: false,
            raws: Vec::new(),
            sweep: Sweep::default(),
            here: Vec::new(),
            counts: (Vec::new(), Vec::new(), Vec::new()),
            cuts: Vec::new(),
            turns: Vec::new(),
            ranked: (Vec::new(), Vec::new(), Vec::new()),
            chained: (Vec::new(), Vec::new()),
            spare: Vec::new(),
            pieces: Vec::new(),
            points: Vec::new(),
            close: true,
            mitre_stray: 0.0,
            bluntest: f64::INFINITY,
            arcs: false,
            cutting: Cutting::Other,
        };
        eroder.reset(region, arc);
        eroder
    }

    /// Prepared for another region (the next layer's), its buffers kept: an eroder made
    /// afresh for each layer allocated some twenty vectors and grew them by doubling.
    pub(crate) fn reset(&mut self, region: &MultiPolygon<f64>, arc: f64) {
        let boundary = &mut self.boundary;
        boundary.sides.clear();
        boundary.runs.clear();
        boundary.arcs.fans.clear();
        boundary.arcs.directions.clear();
        self.safes.clear();
        self.mitre_stray = 0.0;
        self.bluntest = f64::INFINITY;
        self.arcs = false;
        self.cutting = Cutting::Other;
        // The sweep's order is kept: the next layer's region is most often the same or
        // close (any permutation of as many edges would do; another size starts afresh).
        self.sized = false;
        let mut used = 0;
        for polygon in &region.0 {
            for (i, ring) in std::iter::once(polygon.exterior())
                .chain(polygon.interiors())
                .enumerate()
            {
                let first = boundary.sides.len();
                boundary.sides.extend(ring.0.windows(2).map(|w| {
                    let (a, b) = (w[0], w[1]);
                    Side {
                        a,
                        b,
                        lo: Coord {
                            x: a.x.min(b.x),
                            y: a.y.min(b.y),
                        },
                        hi: Coord {
                            x: a.x.max(b.x),
                            y: a.y.max(b.y),
                        },
                    }
                }));
                boundary.split(first);
                if used == self.corners.len() {
                    self.corners.push(Vec::new());
                }
                let corners = &mut self.corners[used];
                if let Some(safe) = prepare(
                    &ring.0,
                    arc,
                    i == 0,
                    &mut boundary.arcs.directions,
                    corners,
                    &mut self.units,
                    (&mut self.mitre_stray, &mut self.bluntest, &mut self.arcs),
                ) {
                    used += 1;
                    self.safes.push(safe);
                    boundary.arcs.add(corners);
                } else {
                    // A ring left out: the cutting says nothing of the region's.
                    self.bluntest = 0.0;
                }
            }
        }
        self.corners.truncate(used);
        let arcs = &mut self.boundary.arcs;
        if !arcs.fans.is_empty() {
            arcs.deep = math::cos(arc / 2.0);
        }
        arcs.sorted = arcs.fans.len() > FEW_ARCS;
        if arcs.sorted {
            arcs.fans
                .sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
        }
    }

    /// A list of rings emptied, kept for the next erosion's (one allocation and free
    /// fewer a loop).
    pub(crate) fn recycle(&mut self, mut rings: Vec<Vec<Coord>>) {
        rings.clear();
        if rings.capacity() <= 64 {
            self.spare = rings;
        }
    }

    /// How far the rings' area may fall short of the exact erosion's, as a distance per
    /// unit of the distance eroded: a reflex corner within one arc step is drawn as its
    /// mitre, which lies beyond the exact arc (`sqrt(2 / (1 + cos φ)) − 1` for a turn φ:
    /// the rings miss a sliver of the erosion there). Nothing else does: an arc's chords
    /// cut inside the exact arc, towards its vertex, which takes in more than the erosion,
    /// a convex corner's mitre is exact, and a tip's stretch through its vertex is cut
    /// away. 0 where no reflex corner is a mitre (a star's).
    pub(crate) fn stray(&self) -> f64 {
        self.mitre_stray
    }

    /// The region's corners as the middle ring's test needs them: the least `k` of its
    /// convex corners' mitres (`1 − cos α`, α the inside angle; 0 where one is a sharp
    /// tip), and whether a reflex corner is drawn as an arc of chords.
    pub(crate) fn corners(&self) -> (f64, bool) {
        (self.bluntest, self.arcs)
    }

    /// How the last erosion's rings were cut from the raw offsets (`Cutting::Other`
    /// where it gave none).
    pub(crate) fn cutting(&self) -> Cutting {
        self.cutting
    }

    /// How many points its largest buffers hold room for (a pool lets a huge one go).
    pub(crate) fn capacity(&self) -> usize {
        self.points.capacity() + self.boundary.sides.capacity() + self.sweep.edges.capacity()
    }

    /// The same eroder with sharp tips run through the vertex and cut, as before tips
    /// were closed (for the tests).
    #[cfg(test)]
    pub(crate) fn cutting_tips(mut self) -> Eroder {
        self.close = false;
        self
    }

    /// The rings bounding the erosion by `d` (as [`eroded_rings`]).
    pub(crate) fn rings(&mut self, d: f64) -> Option<Vec<Vec<Coord>>> {
        self.cutting = Cutting::Other;
        // Each raw ring's size is known from its corners: the buffers are made once at
        // their size (growing them by doubling was a tenth of a star's layer).
        if !self.sized {
            self.raws.resize_with(self.corners.len(), Raw::default);
            let mut total = 0;
            for (raw, &(_, n)) in self.raws.iter_mut().zip(&self.safes) {
                total += n;
                // (`reserve` counts from the length: the vectors are emptied first.)
                raw.pts.clear();
                raw.pts.reserve(n);
                raw.along.clear();
                raw.along.reserve(n);
            }
            for (raw, corners) in self.raws.iter_mut().zip(&self.corners) {
                raw.shape(corners);
            }
            self.sized = true;
            self.sweep.edges.clear();
            self.sweep.edges.reserve(total);
            self.sweep.order.reserve(total);
            self.sweep.sorted.clear();
            self.sweep.sorted.reserve(total);
            self.points.clear();
            self.points.reserve(2 * total);
        }
        for ((raw, corners), &(safe, _)) in self.raws.iter_mut().zip(&self.corners).zip(&self.safes)
        {
            raw.fill(
                corners,
                &self.boundary.arcs.directions,
                d,
                self.close,
                d >= safe,
            );
        }
        if self.raws.iter().map(|r| r.pts.len()).sum::<usize>() > MAX_SEGMENTS {
            return None;
        }
        let raws = &self.raws;
        // Convex rings nested or apart cross nothing (a holed square's loops until the
        // outline's meet the hole's), nor does one ring star-shaped about its centre (a
        // star's or an L's loops until they pinch): no sweep.
        let cuts = &mut self.cuts;
        cuts.clear();
        // One ring is uncut where it is star-shaped or convex: the first asked first (a
        // star's loops until they pinch are, and are not convex: one pass, not two).
        let layout = if raws.len() == 1 && star_shaped(&raws[0].pts) {
            Layout::Apart
        } else {
            apart(raws, &mut self.turns)
        };
        let uncut = layout == Layout::Apart;
        if !uncut {
            // Rings each convex (a hole's grown offset meeting the outline's) cross only
            // one another: their pairs alone are looked at, not the sweep's every edge. One
            // ring of a few dozen segments (a star's loops where they pinch) is laid on a grid.
            let found = match layout {
                Layout::Convex => convex_crossings(raws, &self.turns, &mut self.ranked, cuts),
                _ if raws.len() == 1 => ring_crossings(&raws[0].pts, &mut self.ranked, cuts),
                _ => None,
            };
            if !found.unwrap_or_else(|| crossings(raws, &mut self.sweep, cuts)) {
                return None;
            }
        }
        let cuts = &*cuts;
        let mut cutting = if raws.iter().any(|r| r.check) {
            Cutting::Other
        } else if cuts.is_empty() {
            Cutting::None
        } else if cuts.iter().all(|c| c.ring[0] != c.ring[1]) {
            Cutting::Between
        } else {
            Cutting::Other
        };
        // Every cut twice (once on each ring it is on), grouped by ring, in order along it.
        place_cuts(raws, cuts, &mut self.here, &mut self.counts);
        // Cut every raw ring at its crossings into pieces; keep those `d` from the boundary.
        // A piece is tested before it is built: most are cut away.
        let boundary = &self.boundary;
        let (pieces, points) = (&mut self.pieces, &mut self.points);
        pieces.clear();
        points.clear();
        let mut from = 0;
        for (r, raw) in raws.iter().enumerate() {
            let n = raw.pts.len();
            let to = from + self.here[from..].iter().take_while(|h| h.0 == r).count();
            let here = &self.here[from..to];
            from = to;
            if here.is_empty() {
                // The whole ring, closed: its point m and m + 1 (n is the first again).
                let m = (n + 1 - 2) / 2;
                let mid = (raw.pts[m] + raw.pts[(m + 1) % n]) / 2.0;
                let kept = keep(mid, || raw.own(m), boundary, d);
                // A region's one ring, uncut, run round the wrong way (inside on its
                // right): a simple curve turned inside out where edges ran backwards; no
                // point of it is on the erosion (the L's arms gone, its corner too small).
                let inverted = raws.len() == 1
                    && raw.check
                    && (0..n).any(|i| raw.reversed(i))
                    && (0..n)
                        .map(|i| cross(raw.pts[i], raw.pts[if i + 1 == n { 0 } else { i + 1 }]))
                        .sum::<f64>()
                        < 0.0;
                if !inverted && undecided(raw, 0, n - 1, |i| raw.pts[i % n], kept, boundary, d) {
                    return None;
                }
                // A whole ring left out (inside another ring's raw offset though the two
                // do not cross): not a cutting `Cutting` vouches for.
                if !kept {
                    cutting = Cutting::Other;
                }
                if kept && !inverted {
                    let first = points.len();
                    points.extend_from_slice(&raw.pts);
                    points.push(raw.pts[0]);
                    pieces.push(Piece {
                        pts: first..points.len(),
                        from: usize::MAX,
                        to: usize::MAX,
                    });
                }
                continue;
            }
            for k in 0..here.len() {
                let (_, s0, t0, id0) = here[k];
                let (_, s1, t1, id1) = here[(k + 1) % here.len()];
                let wraps = k + 1 == here.len();
                // The raw points between the cuts: s0 + 1 ..= s1 (all around when s1 = s0).
                let count = if s1 == s0 && t1 > t0 && !wraps {
                    0
                } else {
                    let c = (s1 + n - s0) % n;
                    if c == 0 { n } else { c }
                };
                let point = |i: usize| {
                    if i == 0 {
                        cuts[id0].at
                    } else if i <= count {
                        // s0 + i < 2n: one wrap at most (no division per point).
                        let j = s0 + i;
                        raw.pts[if j >= n { j - n } else { j }]
                    } else {
                        cuts[id1].at
                    }
                };
                let m = count / 2;
                let mid = (point(m) + point(m + 1)) / 2.0;
                // Segment m of the piece is raw segment s0 + m (it starts inside s0).
                let kept = keep(mid, || raw.own((s0 + m) % n), boundary, d);
                if undecided(raw, s0, count, point, kept, boundary, d) {
                    return None;
                }
                if kept {
                    let first = points.len();
                    points.extend((0..count + 2).map(point));
                    pieces.push(Piece {
                        pts: first..points.len(),
                        from: id0,
                        to: id1,
                    });
                }
            }
        }
        let rings = std::mem::take(&mut self.spare);
        let rings = chain(pieces, points, cuts.len(), &mut self.chained, rings);
        if rings.is_some() {
            self.cutting = cutting;
        }
        rings
    }
}

/// One ring's raw offset: its points (not closed), and what its segments run along.
#[derive(Default)]
struct Raw {
    pts: Vec<Coord>,
    /// Each arc of chords: its first point, how many chords follow, and its vertex (a
    /// piece's middle on a chord is not inside that arc's chords: `keep` need not ask).
    arcs: Vec<(usize, usize, Coord)>,
    /// For the segment from each point that runs along an edge of the ring (from a
    /// corner's last point to the next corner's first), that edge's direction: the
    /// segment is reversed (an edge event passed) where it points against it.
    along: Vec<Option<Coord>>,
    /// Whether a segment may run backwards at this distance (`along` is worth asking).
    check: bool,
    /// Reused by `fill`: where each sharp tip's three points start, and each tip's mitre
    /// (where its two moved edges cross).
    tips: Vec<(usize, Option<Coord>)>,
    /// Where every corner is a mitre (a holed square's rings): each one's vertex, mitre
    /// direction and its length's divisor, read in one tight pass, and its `along`,
    /// which does not depend on the distance (made once for the corners by `shape`,
    /// copied by `fill`).
    mitres: Vec<(Coord, Coord, f64)>,
    shape: Vec<Option<Coord>>,
    /// Whether a corner is a sharp tip (made once for the corners by `shape`).
    tipped: bool,
}

impl Raw {
    /// A raw ring of these points, as `fill` leaves one (no arcs, every segment checked;
    /// for the tests).
    #[cfg(test)]
    fn of(pts: Vec<Coord>) -> Raw {
        Raw {
            along: vec![None; pts.len()],
            check: true,
            pts,
            tips: Vec::new(),
            arcs: Vec::new(),
            shape: Vec::new(),
            mitres: Vec::new(),
            tipped: false,
        }
    }

    /// For a ring whose corners are all mitres, the mitres and its `along` (`shape`: the
    /// direction of each edge from its corner to the next), which do not depend on the
    /// distance; nothing for another ring. And whether any corner is a sharp tip.
    fn shape(&mut self, corners: &[Corner]) {
        self.tipped = false;
        self.mitres.clear();
        let along = &mut self.shape;
        along.clear();
        for (i, corner) in corners.iter().enumerate() {
            match *corner {
                Corner::Mitre { b, m, k } => self.mitres.push((b, m, k)),
                _ => {
                    self.mitres.clear();
                    self.tipped = corners[i..].iter().any(|c| matches!(c, Corner::Tip { .. }));
                    return;
                }
            }
        }
        for (i, &(b, ..)) in self.mitres.iter().enumerate() {
            let next = self.mitres[if i + 1 == self.mitres.len() { 0 } else { i + 1 }].0;
            along.push(Some(next - b));
        }
    }

    /// The raw offset by `d` of a ring's corners (`shape` made for them).
    fn fill(&mut self, corners: &[Corner], directions: &[Coord], d: f64, close: bool, check: bool) {
        self.pts.clear();
        self.tips.clear();
        self.arcs.clear();
        self.check = check;
        self.along.clear();
        if !self.mitres.is_empty() && self.mitres.len() == corners.len() {
            // Its points in one tight pass.
            if check {
                self.along.extend_from_slice(&self.shape);
            }
            self.pts
                .extend(self.mitres.iter().map(|&(b, m, k)| b + m * (d / k)));
            return;
        }
        // Sharp tips closed at their mitres (`tip_mitres`), known from the corners before
        // any point is written: each closed tip one point, not three moved up later.
        let closing = close && self.tipped && self.tip_mitres(corners, d);
        let mut tips = 0;
        for corner in corners {
            match *corner {
                Corner::Mitre { b, m, k } => {
                    self.pts.push(b + m * (d / k));
                }
                Corner::Tip { b, nu, nv } => {
                    let mitre = if closing { self.tips[tips].1 } else { None };
                    tips += 1;
                    match mitre {
                        Some(x) => self.pts.push(x),
                        None => self.pts.extend([b + nu * d, b, b + nv * d]),
                    }
                }
                Corner::Arc {
                    b,
                    nu,
                    nv,
                    ref inner,
                } => {
                    self.arcs.push((self.pts.len(), inner.len() + 1, b));
                    self.pts.push(b + nu * d);
                    for &w in &directions[inner.clone()] {
                        self.pts.push(b + w * d);
                    }
                    self.pts.push(b + nv * d);
                }
            }
        }
        // Only where an edge may have run backwards (past the ring's safe distance): the
        // segment from each corner's last point runs along the edge to the next corner
        // (a closed tip's one point too).
        if check {
            let vertex = |c: &Corner| match *c {
                Corner::Mitre { b, .. } | Corner::Tip { b, .. } | Corner::Arc { b, .. } => b,
            };
            let mut tips = 0;
            for (i, corner) in corners.iter().enumerate() {
                let points = match corner {
                    Corner::Mitre { .. } => 1,
                    Corner::Tip { .. } => {
                        let closed = closing && self.tips[tips].1.is_some();
                        tips += 1;
                        if closed { 1 } else { 3 }
                    }
                    Corner::Arc { inner, .. } => 2 + inner.len(),
                };
                let next = vertex(&corners[if i + 1 == corners.len() { 0 } else { i + 1 }]);
                self.along.extend(std::iter::repeat_n(None, points - 1));
                self.along.push(Some(next - vertex(corner)));
            }
        }
    }

    /// Each sharp tip's mitre (into `tips`: its corner and where the moved edges on
    /// either side cross, where they cross properly), and whether the tips are closed
    /// there: each tip's three points (through the vertex) replaced by its mitre, where
    /// it has one: the stretch through the vertex between them is nearer the boundary
    /// than `d` and would be cut away there. A ring whose only crossings were its tips'
    /// then needs no cutting and chaining (a star's loops until its tips close up: a
    /// third of its layer at 10%). None is closed where no tip's edges cross, or two
    /// tips' mitres come out of order along the edge between them (an edge event: the
    /// general cutting decides). The moved edges' ends are worked out from the corners
    /// as `fill` writes them (the same points to the bit).
    fn tip_mitres(&mut self, corners: &[Corner], d: f64) -> bool {
        self.tips.clear();
        let n = corners.len();
        let first = |c: &Corner| match *c {
            Corner::Mitre { b, m, k } => b + m * (d / k),
            Corner::Tip { b, nu, .. } | Corner::Arc { b, nu, .. } => b + nu * d,
        };
        let last = |c: &Corner| match *c {
            Corner::Mitre { b, m, k } => b + m * (d / k),
            Corner::Tip { b, nv, .. } | Corner::Arc { b, nv, .. } => b + nv * d,
        };
        for (j, corner) in corners.iter().enumerate() {
            if let Corner::Tip { b, nu, nv } = *corner {
                let p = last(&corners[if j == 0 { n - 1 } else { j - 1 }]);
                let q = first(&corners[if j + 1 == n { 0 } else { j + 1 }]);
                self.tips
                    .push((j, proper_crossing((p, b + nu * d), (b + nv * d, q))));
            }
        }
        if self.tips.iter().all(|t| t.1.is_none()) {
            return false;
        }
        // Two tips in a row: their mitres in order along the edge between them.
        let count = self.tips.len();
        for i in 0..count {
            let (j, x) = self.tips[i];
            let (k, y) = self.tips[if i + 1 == count { 0 } else { i + 1 }];
            if let (Some(x), Some(y)) = (x, y)
                && k == if j + 1 == n { 0 } else { j + 1 }
            {
                let e = first(&corners[k]) - last(&corners[j]);
                let m = y - x;
                if m.x * e.x + m.y * e.y <= 0.0 {
                    return false;
                }
            }
        }
        true
    }

    /// The vertex of the arc whose chord is the segment from point `i`, if it is one.
    fn own(&self, i: usize) -> Option<Coord> {
        // The first arc ending past `i` (one after another where there are few).
        let k = if self.arcs.len() <= FEW_ARCS {
            self.arcs.iter().position(|a| i < a.0 + a.1)?
        } else {
            self.arcs.partition_point(|a| a.0 + a.1 <= i)
        };
        let &(first, _, b) = self.arcs.get(k)?;
        (first <= i).then_some(b)
    }

    /// Whether the segment from point `i` runs against the edge it was moved from.
    fn reversed(&self, i: usize) -> bool {
        let n = self.pts.len();
        self.check
            && self.along[i].is_some_and(|e| {
                let s = self.pts[if i + 1 == n { 0 } else { i + 1 }] - self.pts[i];
                s.x * e.x + s.y * e.y < 0.0
            })
    }

    /// The tips of a ring filled without closing them closed afterwards, as `fill` did
    /// before it closed them from the corners (the tests compare the two): each tip's
    /// three points become its mitre, the points after it moved up. `tips` as `fill`
    /// left them before: each tip's first point, and its mitre unknown.
    #[cfg(test)]
    fn close_tips(&mut self) {
        let n = self.pts.len();
        let pts = &self.pts;
        for tip in self.tips.iter_mut() {
            let at = tip.0;
            let p = pts[if at == 0 { n - 1 } else { at - 1 }];
            let (a, b) = (pts[at], pts[at + 2]);
            let q = pts[if at + 3 == n { 0 } else { at + 3 }];
            tip.1 = proper_crossing((p, a), (b, q));
        }
        if self.tips.iter().all(|t| t.1.is_none()) {
            return;
        }
        // Two tips in a row: their mitres in order along the edge between them.
        let count = self.tips.len();
        for i in 0..count {
            let (at, x) = self.tips[i];
            // (A tip's three points end before n: at + 3 is n at most.)
            let (next, y) = self.tips[if i + 1 == count { 0 } else { i + 1 }];
            if let (Some(x), Some(y)) = (x, y)
                && next == if at + 3 == n { 0 } else { at + 3 }
            {
                let e = pts[next] - pts[at + 2];
                let m = y - x;
                if m.x * e.x + m.y * e.y <= 0.0 {
                    return;
                }
            }
        }
        // In place: each closed tip's three points become its mitre, the rest move up.
        let check = self.check;
        let (pts, along) = (&mut self.pts, &mut self.along);
        let (mut to, mut from) = (0, 0);
        for &(at, x) in &self.tips {
            for i in from..at {
                pts[to] = pts[i];
                if check {
                    along[to] = along[i];
                }
                to += 1;
            }
            if let Some(x) = x {
                // On along the edge out of the tip, as the tip's last point was.
                pts[to] = x;
                if check {
                    along[to] = along[at + 2];
                }
                to += 1;
            } else {
                for i in at..at + 3 {
                    pts[to] = pts[i];
                    if check {
                        along[to] = along[i];
                    }
                    to += 1;
                }
            }
            from = at + 3;
        }
        for i in from..n {
            pts[to] = pts[i];
            if check {
                along[to] = along[i];
            }
            to += 1;
        }
        pts.truncate(to);
        if check {
            along.truncate(to);
        }
        // Each arc moved up two points for each tip closed before it.
        let mut closed = 0;
        let mut tips = self.tips.iter().peekable();
        for arc in self.arcs.iter_mut() {
            while let Some(&&(at, x)) = tips.peek() {
                if at > arc.0 {
                    break;
                }
                closed += usize::from(x.is_some());
                tips.next();
            }
            arc.0 -= 2 * closed;
        }
    }
}

/// Every cut twice into `here` (once on each ring it is on: ring, segment, parameter and
/// the cut), sorted by ring, segment and parameter (`f64::total_cmp`), as the library's
/// unstable sort of them leaves them. Placed by segment: each cut segment marked in a
/// bit set (its cuts listed from it), the marks read in order, each segment's few cuts
/// by parameter (the library's sort of a star's 30 cost 1.7k instructions, a count of
/// every segment's cuts 2k on the holed square's 68 segments). Where two have the same
/// ring, segment and parameter (three segments through one point), the unstable sort's
/// order of them is its own: it is asked.
#[inline(never)]
fn place_cuts(
    raws: &[Raw],
    cuts: &[Cut],
    here: &mut Vec<(usize, usize, f64, usize)>,
    (marks, heads, next): &mut (Vec<u64>, Vec<u32>, Vec<u32>),
) {
    here.clear();
    if cuts.is_empty() {
        return;
    }
    // Each ring's first segment among all the rings' (few rings: a small array, else the
    // library's sort; the library's sort too for a handful of cuts, which it places by
    // insertion more cheaply).
    let mut bases = [0usize; 9];
    if raws.len() >= bases.len() || cuts.len() <= 5 {
        return library_order(cuts, here);
    }
    for (r, raw) in raws.iter().enumerate() {
        bases[r + 1] = bases[r] + raw.pts.len();
    }
    let total = bases[raws.len()];
    marks.clear();
    marks.resize(total.div_ceil(64), 0);
    if heads.len() < total {
        heads.resize(total, 0);
    }
    // Each segment's cuts as a list (entry `2·id + side`); a head is read only where its
    // mark is set, so the heads are never cleared.
    next.clear();
    next.resize(2 * cuts.len(), u32::MAX);
    for (id, c) in cuts.iter().enumerate() {
        for side in 0..2 {
            let g = bases[c.ring[side]] + c.seg[side];
            let (word, bit) = (g / 64, 1u64 << (g % 64));
            let entry = (2 * id + side) as u32;
            if marks[word] & bit != 0 {
                next[entry as usize] = heads[g];
            }
            marks[word] |= bit;
            heads[g] = entry;
        }
    }
    for (w, &word) in marks.iter().enumerate() {
        let mut left = word;
        while left != 0 {
            let g = w * 64 + left.trailing_zeros() as usize;
            left &= left - 1;
            let first = here.len();
            let mut entry = heads[g];
            while entry != u32::MAX {
                let (id, side) = (entry as usize / 2, entry as usize % 2);
                let c = &cuts[id];
                let x = (c.ring[side], c.seg[side], c.t[side], id);
                // By parameter among this segment's (insertion: most have one).
                let mut j = here.len();
                here.push(x);
                while j > first {
                    match here[j - 1].2.total_cmp(&x.2) {
                        std::cmp::Ordering::Greater => {
                            here[j] = here[j - 1];
                            j -= 1;
                        }
                        std::cmp::Ordering::Equal => return library_order(cuts, here),
                        std::cmp::Ordering::Less => break,
                    }
                }
                here[j] = x;
                entry = next[entry as usize];
            }
        }
    }
}

/// [`place_cuts`] by the library's unstable sort, as before.
fn library_order(cuts: &[Cut], here: &mut Vec<(usize, usize, f64, usize)>) {
    here.clear();
    for (id, c) in cuts.iter().enumerate() {
        here.push((c.ring[0], c.seg[0], c.t[0], id));
        here.push((c.ring[1], c.seg[1], c.t[1], id));
    }
    here.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.total_cmp(&b.2)));
}

/// `xlo` as an integer that sorts as `f64::total_cmp` does (the sweep's key).
fn sort_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// Where segment `e` crosses segment `f` properly (each strictly on both sides of the
/// other), computed as the crossing sweep computes it (and as the reference closes a tip,
/// `e` the segment into it: the same point to the bit).
fn proper_crossing(e: (Coord, Coord), f: (Coord, Coord)) -> Option<Coord> {
    let (p, r) = (e.1 - e.0, f.1 - f.0);
    let d1 = cross(p, f.0 - e.0);
    let d2 = cross(p, f.1 - e.0);
    let d3 = cross(r, e.0 - f.0);
    let d4 = cross(r, e.1 - f.0);
    let proper = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
    (proper(d1, d2) && proper(d3, d4)).then(|| e.0 + p * (d3 / (d3 - d4)))
}

struct Piece {
    /// Its points' range in the points of all pieces.
    pts: std::ops::Range<usize>,
    /// The cuts it starts and ends at (`usize::MAX`: a whole ring).
    from: usize,
    to: usize,
}

/// Where two raw segments cross: ring, segment and parameter on each, and the point.
#[derive(Clone, Copy)]
struct Cut {
    ring: [usize; 2],
    seg: [usize; 2],
    t: [f64; 2],
    at: Coord,
}

/// A ring's corners toward the region's inside (`exterior`: an outline) into `out`, the
/// inner directions of its arcs appended to `directions`, and the distance below which
/// no edge of its raw offset runs backwards, with the number of its raw offset's points;
/// `None` where it cannot be oriented.
fn prepare(
    ring: &[Coord],
    arc: f64,
    exterior: bool,
    directions: &mut Vec<Coord>,
    out: &mut Vec<Corner>,
    units: &mut Vec<Coord>,
    (mitre_stray, bluntest, arcs): (&mut f64, &mut f64, &mut bool),
) -> Option<(f64, usize)> {
    // The ring itself where it is clean and turns the right way (a copy otherwise).
    let pts = inside_left_cow(ring, exterior)?;
    let first = directions.len();
    let n = pts.len();
    let unit = |e: Coord| e / math::hypot(e.x, e.y);
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    // Each edge's direction once (edge i runs from point i to i + 1).
    // (No division per edge: the last edge closes the ring.)
    units.clear();
    units.extend(pts.windows(2).map(|w| unit(w[1] - w[0])));
    if n > 0 {
        units.push(unit(pts[0] - pts[n - 1]));
    }
    out.clear();
    out.reserve(n);
    let cos_arc = math::cos(arc);
    // The points of tips and arcs beyond one a corner.
    let mut extra = 0;
    for i in 0..n {
        let b = pts[i];
        let (u, v) = (units[if i == 0 { n - 1 } else { i - 1 }], units[i]);
        let (nu, nv) = (left(u), left(v));
        let turn = cross(u, v);
        let dot = u.x * v.x + u.y * v.y;
        if turn >= 0.0 || dot > 1.0 - 1e-12 {
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            if k >= 0.5 {
                // The mitre, where both moved edges meet.
                *bluntest = bluntest.min(k);
                out.push(Corner::Mitre { b, m: nu + nv, k });
            } else {
                // A sharp tip: its mitre would be far away; through the vertex instead
                // (that stretch is nearer the boundary than `d`, and is cut away).
                *bluntest = 0.0;
                out.push(Corner::Tip { b, nu, nv });
                extra += 2;
            }
        } else if dot >= cos_arc {
            // A reflex corner within one step (a round hole's): the mitre, which strays
            // outside the arc no more than a chord inside it, and is one point, not two.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            // `b + m·d/k` lies `d·sqrt(2 / k)` from the vertex (|m|² = 2k).
            *mitre_stray = f64::max(*mitre_stray, (2.0 / k).sqrt() - 1.0);
            out.push(Corner::Mitre { b, m: nu + nv, k });
        } else {
            let angle = math::atan2(turn, dot);
            *arcs = true;
            let steps = steps(-angle / arc);
            let start = directions.len();
            // One step has no inner direction (and needs no sine).
            let (s, co) = if steps > 1 {
                math::sin_cos(angle / steps as f64)
            } else {
                (0.0, 1.0)
            };
            let mut w = nu;
            for _ in 1..steps {
                w = Coord {
                    x: w.x * co - w.y * s,
                    y: w.x * s + w.y * co,
                };
                directions.push(w);
            }
            out.push(Corner::Arc {
                b,
                nu,
                nv,
                inner: start..directions.len(),
            });
            extra += 1;
        }
    }
    // Edge i (from corner i to i + 1) moved by `d` runs from the foot of corner i's last
    // point to that of corner i + 1's first: shorter by `d` times the mitres' slants along
    // it (a tip's and an arc's points stand square on it), backwards past length / rate.
    let slant = |c: &Corner, e: Coord| match *c {
        Corner::Mitre { m, k, .. } => (m.x * e.x + m.y * e.y) / k,
        _ => 0.0,
    };
    let mut safe = f64::INFINITY;
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        let e = units[i];
        let rate = slant(&out[i], e) - slant(&out[j], e);
        if rate > 0.0 {
            let length = (pts[j] - pts[i]).x * e.x + (pts[j] - pts[i]).y * e.y;
            safe = safe.min(length / rate);
        }
    }
    // One point a mitre, three a tip, two an arc and its inner directions.
    let points = out.len() + extra + directions.len() - first;
    // Well inside the rounding of the points' own test.
    Some((safe * (1.0 - 1e-6), points))
}

/// `x.ceil().max(1.0) as usize` without the call `ceil` is here (no SSE4.1 assumed): an
/// arc's steps (`x` is positive, or NaN: one step).
fn steps(x: f64) -> usize {
    let whole = x as usize;
    if (whole as f64) < x {
        whole.saturating_add(1)
    } else {
        whole.max(1)
    }
}

/// An edge of the region as given, with its bounds.
#[derive(Clone, Copy)]
struct Side {
    a: Coord,
    b: Coord,
    lo: Coord,
    hi: Coord,
}

/// Edges per run of the boundary: a point far from a run passes its edges on one test.
const RUN: usize = 8;

/// The region's edges as given, and the same in runs of [`RUN`] consecutive ones
/// of a ring (each ring's edges one after another, each edge's end the next's start).
#[derive(Default)]
pub(super) struct Boundary {
    sides: Vec<Side>,
    runs: Vec<Run>,
    /// The reflex corners drawn as arcs of chords, where a point is near the boundary
    /// only inside the chords (`Arcs::covers`).
    arcs: Arcs,
}

/// Every reflex corner drawn as an arc of chords (`Corner::Arc`): its vertex, the
/// directions of its first and last points from it and the range of its inner ones in
/// `directions` (the unit directions of every arc's inner points, which its raw offset
/// is drawn with).
#[derive(Default)]
struct Arcs {
    fans: Vec<(Coord, Coord, Coord, std::ops::Range<usize>)>,
    directions: Vec<Coord>,
    /// Whether `fans` is sorted by vertex (more than [`FEW_ARCS`]: looked up by halves).
    sorted: bool,
    /// The cosine of half the arc step (no chord spans more): within `deep·d` of its
    /// vertex a point is inside an arc's chords if it lies in the arc's wedge.
    deep: f64,
}

/// Arcs up to this many are looked up one after another.
const FEW_ARCS: usize = 16;

impl Arcs {
    /// The arcs of these corners (a ring's) added.
    fn add(&mut self, corners: &[Corner]) {
        for corner in corners {
            if let Corner::Arc {
                b,
                nu,
                nv,
                ref inner,
            } = *corner
            {
                self.fans.push((b, nu, nv, inner.clone()));
            }
        }
    }

    /// Where `v` is the vertex of an arc of chords: whether `p` lies inside the polygon
    /// its chords make with it (the vertex, `v + nu·d`, `v + w·d`…, `v + nv·d`), by more
    /// than a rounding. `None` at any other vertex.
    ///
    /// This is the rule [`keep`] measures a point by at such a vertex, not the exact
    /// distance `d` about it: the raw offsets are drawn with the chords, and their
    /// crossings are found on the chords, so a point between the chords and the exact arc
    /// is on the far side of the raw offset drawn there. Measured by the exact arc, a
    /// piece of another ring with its middle in that sliver was dropped whole though no
    /// raw offset crossed it (most of it on the erosion). Only a point whose foot on an
    /// edge is that vertex asks: a point past the vertex but outside its arc's wedge is
    /// nearer the other edge at the vertex than the vertex itself, which decides.
    #[inline(never)]
    fn covers(&self, v: Coord, p: Coord, d: f64) -> Option<bool> {
        let from = if self.sorted {
            self.fans
                .partition_point(|(b, ..)| b.x.total_cmp(&v.x).then(b.y.total_cmp(&v.y)).is_lt())
        } else {
            0
        };
        let mut found = None;
        for &(b, nu, nv, ref inner) in &self.fans[from..] {
            if b != v {
                if self.sorted {
                    break;
                }
                continue;
            }
            let inside = self.chords_cover(nu, &self.directions[inner.clone()], nv, p - v, d);
            found = Some(found == Some(true) || inside);
        }
        found
    }

    /// Whether `x` (from an arc's vertex) lies inside the polygon of the vertex and the
    /// chords between the ends `w·d` of the directions `nu`, `inner`…, `nv` (turning
    /// clockwise), by more than `1e-9·d` (a point on a chord is not: a chord's own piece
    /// is measured on it).
    fn chords_cover(&self, nu: Coord, inner: &[Coord], nv: Coord, x: Coord, d: f64) -> bool {
        let mut u = nu;
        for &v in inner.iter().chain(std::iter::once(&nv)) {
            // The sector between `u` and `v` (at most half a turn: both tests hold only
            // inside it).
            if cross(u, x) <= 0.0 && cross(x, v) <= 0.0 {
                let (a, e) = (u * d, (v - u) * d);
                // The vertex is on the chord's right: inside where `x` is too.
                let side = cross(e, x - a);
                let margin = 1e-9 * d;
                return side < 0.0 && side * side > margin * margin * (e.x * e.x + e.y * e.y);
            }
            u = v;
        }
        false
    }
}

/// A run of consecutive edges of a ring: its bounds, the height where it starts and
/// where it ends (the ray east of a point crosses a run wholly east of it an odd number
/// of times exactly when the point's height is between those, as the per-edge test
/// counts), and a margin over the rounding of that test's crossing abscissa.
struct Run {
    sides: std::ops::Range<usize>,
    lo: Coord,
    hi: Coord,
    start: f64,
    end: f64,
    slack: f64,
}

impl Boundary {
    /// The edges from `first` on (one ring's) split into runs; a ring of up to twice
    /// [`RUN`] edges one run (a star's ten: runs would only add their tests).
    fn split(&mut self, first: usize) {
        let step = if self.sides.len() - first <= 2 * RUN {
            2 * RUN
        } else {
            RUN
        };
        let mut from = first;
        while from < self.sides.len() {
            let to = (from + step).min(self.sides.len());
            let sides = &self.sides[from..to];
            let (mut lo, mut hi) = (sides[0].lo, sides[0].hi);
            for s in &sides[1..] {
                lo = Coord {
                    x: lo.x.min(s.lo.x),
                    y: lo.y.min(s.lo.y),
                };
                hi = Coord {
                    x: hi.x.max(s.hi.x),
                    y: hi.y.max(s.hi.y),
                };
            }
            // The crossing abscissa `a.x + (p.y - a.y)·(b.x - a.x)/(b.y - a.y)` is off by
            // a few roundings of the coordinates at most: far less than this.
            let size = lo.x.abs().max(hi.x.abs()).max(lo.y.abs()).max(hi.y.abs());
            self.runs.push(Run {
                sides: from..to,
                lo,
                hi,
                start: sides[0].a.y,
                end: sides[sides.len() - 1].b.y,
                slack: 1e-12 * (1.0 + size),
            });
            from = to;
        }
    }
}

/// How the raw rings lie (`apart`'s answer).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Layout {
    /// Each strictly convex and simple, each pair apart or nested: nothing to cut.
    Apart,
    /// Each strictly convex and simple (none crosses or touches itself), some two meet.
    Convex,
    /// Some ring not strictly convex.
    Other,
}

/// Whether the raw rings are each strictly convex and simple, and each pair apart (bounds
/// that do not meet) or one strictly inside the other: then nothing crosses or touches,
/// and the sweep would find no cut. `turns` is reused: each ring's turn and bounds (all
/// of them unless `Other`).
fn apart(raws: &[Raw], turns: &mut Vec<(f64, (Coord, Coord))>) -> Layout {
    turns.clear();
    for r in raws {
        // Most rings that fail fail here, at their first reflex turn.
        let (turn, bounds) = convex_bounded(&r.pts);
        if turn == 0.0 {
            return Layout::Other;
        }
        turns.push((turn, bounds));
    }
    for i in 0..raws.len() {
        for j in i + 1..raws.len() {
            let ((ti, bi), (tj, bj)) = (turns[i], turns[j]);
            if !meets(bi, bj) {
                continue;
            }
            if !inside(&raws[j].pts, bj, &raws[i].pts, ti)
                && !inside(&raws[i].pts, bi, &raws[j].pts, tj)
            {
                return Layout::Convex;
            }
        }
    }
    Layout::Apart
}

/// Whether two closed boxes meet.
#[inline]
fn meets((a, b): (Coord, Coord), (c, e): (Coord, Coord)) -> bool {
    !(b.x < c.x || e.x < a.x || b.y < c.y || e.y < a.y)
}

/// Whether a ring turns counter-clockwise about the mean of its points strictly all
/// along (each edge by a margin over rounding) and once round: then every ray from that
/// centre meets it once, so it is simple, crossing and touching nothing (the sweep would
/// find no cut). A star's raw offset is, until its tips close up; where the centre is
/// not in a ring's kernel (an L's) the sweep decides as before.
fn star_shaped(pts: &[Coord]) -> bool {
    let n = pts.len();
    if n < 3 {
        return false;
    }
    let sum = pts.iter().fold(Coord { x: 0.0, y: 0.0 }, |s, &p| s + p);
    let centre = sum / n as f64;
    let mut east = 0usize;
    // Each point's offset from the centre and its size once, carried to the next edge.
    let mut a = pts[0] - centre;
    let mut size = a.x.abs() + a.y.abs();
    for &q in pts[1..].iter().chain(&pts[..1]) {
        let b = q - centre;
        let next = b.x.abs() + b.y.abs();
        let turn = cross(a, b);
        // Not above the margin, or NaN (one comparison).
        if turn.partial_cmp(&(1e-9 * (size * next))) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        // Turning counter-clockwise by less than a half turn, an edge from below the
        // centre to above it passes the ray east of it.
        east += usize::from(a.y < 0.0 && b.y >= 0.0);
        (a, size) = (b, next);
    }
    east == 1
}

/// `1.0` for a strictly convex simple counter-clockwise ring, `-1.0` clockwise, `0.0`
/// otherwise: every turn strictly the same way, and the edges' direction passing east
/// once (turns each under a half turn: it goes round once).
#[cfg(test)]
fn convex(pts: &[Coord]) -> f64 {
    convex_bounded(pts).0
}

/// [`convex`]'s turn, and where it is not 0 the ring's bounds (as `travel::bounds`, found
/// in the same pass).
fn convex_bounded(pts: &[Coord]) -> (f64, (Coord, Coord)) {
    let zero = Coord { x: 0.0, y: 0.0 };
    let n = pts.len();
    if n < 3 {
        return (0.0, (zero, zero));
    }
    let first = cross(pts[0] - pts[n - 1], pts[1] - pts[0]);
    let bounds = if first > 0.0 {
        turning::<true>(pts)
    } else if first < 0.0 {
        turning::<false>(pts)
    } else {
        None
    };
    match bounds {
        Some(b) => (if first > 0.0 { 1.0 } else { -1.0 }, b),
        None => (0.0, (zero, zero)),
    }
}

/// The bounds of a ring turning strictly counter-clockwise (`CCW`; else clockwise) at
/// every corner and going round once; `None` otherwise. One pass over the points, each
/// edge once (`convex` worked out each edge twice and the bounds in a pass of their own).
fn turning<const CCW: bool>(pts: &[Coord]) -> Option<(Coord, Coord)> {
    let n = pts.len();
    // Every point is some step's `b` (the first at the last step).
    let (mut lo, mut hi) = super::travel::bounds(&[]);
    let mut prev = pts[0] - pts[n - 1];
    let mut a = pts[0];
    let mut east = 0;
    // Each point after the first, then the first again (a slice's iterator and one more
    // step: an inclusive range with a test per point cost a third more).
    let mut step = |b: Coord| {
        let e = b - a;
        let t = cross(prev, e);
        // (`t·sign <= 0` as before: NaN passes.)
        if if CCW { t <= 0.0 } else { t >= 0.0 } {
            return false;
        }
        let passes = if CCW {
            prev.y < 0.0 && e.y >= 0.0
        } else {
            prev.y > 0.0 && e.y <= 0.0
        };
        // Past east a second time, it goes round more than once: not convex, told there,
        // not at the end (a star's loop drawn as a pentagram turned inside out, halfway
        // round).
        if passes {
            if east == 1 {
                return false;
            }
            east = 1;
        }
        // The same extremes as `f64::min`/`max` (a zero's sign aside, which no test of
        // the bounds tells apart), as `math::widen` finds them, but by selects: a
        // comparison and a move each (a NaN never taken), no branch.
        lo.x = if b.x < lo.x { b.x } else { lo.x };
        hi.x = if b.x > hi.x { b.x } else { hi.x };
        lo.y = if b.y < lo.y { b.y } else { lo.y };
        hi.y = if b.y > hi.y { b.y } else { hi.y };
        prev = e;
        a = b;
        true
    };
    for &b in &pts[1..] {
        if !step(b) {
            return None;
        }
    }
    if !step(pts[0]) {
        return None;
    }
    (east == 1).then_some((lo, hi))
}

/// Whether every point of `pts` (within the bounds `lo..hi`) is strictly inside the
/// strictly convex ring `ring` (turning `turn`: its inside is on the left when 1, on the
/// right when −1). Where the bounds' corners are inside it by far more than a rounding,
/// so is every point (a convex ring holds the hull of what it holds: a hole's raw offset
/// tested against an outline's four corners on its four corners, not its every point).
fn inside(pts: &[Coord], (lo, hi): (Coord, Coord), ring: &[Coord], turn: f64) -> bool {
    let n = ring.len();
    let corners = [
        lo,
        Coord { x: hi.x, y: lo.y },
        hi,
        Coord { x: lo.x, y: hi.y },
    ];
    let clear = (0..n).all(|i| {
        let (a, b) = (ring[i], ring[if i + 1 == n { 0 } else { i + 1 }]);
        let e = b - a;
        let reach = corners
            .iter()
            .map(|&c| (c.x - a.x).abs() + (c.y - a.y).abs())
            .fold(0.0, f64::max);
        let margin = 1e-9 * (e.x.abs() + e.y.abs()) * reach;
        corners.iter().all(|&c| cross(e, c - a) * turn > margin)
    });
    clear
        || pts.iter().all(|&p| {
            (0..n).all(|i| {
                let (a, b) = (ring[i], ring[if i + 1 == n { 0 } else { i + 1 }]);
                cross(b - a, p - a) * turn > 0.0
            })
        })
}

/// The crossing sweep's buffers: the edges as built, their sort keys, and their bounds
/// in that order.
#[derive(Default)]
struct Sweep {
    edges: Vec<Edge>,
    order: Vec<(i64, u32)>,
    sorted: Vec<Bounds>,
}

/// A raw segment in the crossing sweep.
#[derive(Clone, Copy)]
struct Edge {
    a: Coord,
    b: Coord,
    ring: u32,
    seg: u32,
    /// The segment after it on its ring (neighbours meet without crossing).
    next: u32,
}

/// A raw segment's bounds and place, in the sweep's order: what its inner loop reads for
/// every pair (the segment's ends only where two boxes meet and they are not neighbours).
#[derive(Clone, Copy)]
struct Bounds {
    xlo: f64,
    xhi: f64,
    ylo: f64,
    yhi: f64,
    /// The segment in `Sweep::edges`.
    at: u32,
    ring: u32,
    seg: u32,
    next: u32,
}

/// A segment's bounds: for finite ends by comparisons (the same as `f64::min`/`max`
/// as far as comparisons tell, of two equal zeros either; `min` and `max` cost the
/// sweep's bounds twice as much), else by `min` and `max` (a NaN gives way).
#[inline]
fn extent(a: f64, b: f64, finite: bool) -> (f64, f64) {
    if !finite {
        (a.min(b), a.max(b))
    } else if b < a {
        (b, a)
    } else {
        (a, b)
    }
}

/// Every proper crossing between the raw rings' segments (neighbours excepted); `None`
/// where two touch without crossing. (Not inlined: inlined into `rings` it cost a holed
/// square's layer 2k instructions more.)
#[inline(never)]
fn crossings(raws: &[Raw], sweep: &mut Sweep, cuts: &mut Vec<Cut>) -> bool {
    let Sweep {
        edges,
        order,
        sorted,
    } = sweep;
    edges.clear();
    let total: usize = raws.iter().map(|r| r.pts.len()).sum();
    // The keys are renewed in place where the order is reused (below).
    let reuse = order.len() == total;
    if !reuse {
        order.clear();
    }
    let mut finite = true;
    for (r, raw) in raws.iter().enumerate() {
        let n = raw.pts.len();
        for i in 0..n {
            let next = if i + 1 == n { 0 } else { i + 1 };
            let (a, b) = (raw.pts[i], raw.pts[next]);
            // (0 for a finite coordinate, NaN for any other: one test for both.)
            finite &= (a.x - a.y) * 0.0 == 0.0;
            if !reuse {
                order.push((sort_key(a.x.min(b.x)), edges.len() as u32));
            }
            edges.push(Edge {
                a,
                b,
                ring: r as u32,
                seg: i as u32,
                next: next as u32,
            });
        }
    }
    // By `xlo` in `total_cmp`'s order, compared as integers, ties in the order built: the
    // small (key, index) pairs are sorted, not the edges, then the edges' bounds are laid
    // out in that order once (the inner loop reads nothing else for most pairs).
    // The pairs are distinct (the index breaks ties), so every sort gives the one order.
    // A ring's raw offset has as many edges at every distance: the previous loop's order,
    // its keys renewed, is nearly sorted (edges move little from one loop to the next),
    // and insertion sorts it in a few passes; where it is not, a full sort takes over.
    if reuse {
        for entry in order.iter_mut() {
            let e = &edges[entry.1 as usize];
            entry.0 = sort_key(e.a.x.min(e.b.x));
        }
        if !insertion_sort(order, 4 * edges.len() + 64) {
            order.sort_unstable();
        }
    } else {
        // A few dozen pairs by insertion (half the library sort's instructions on a
        // star's first loop), more by the library's sort.
        if order.len() > 48 || !insertion_sort(order, usize::MAX) {
            order.sort_unstable();
        }
    }
    sorted.clear();
    // (A loop, not `extend` over a mapped iterator: that was a call costing a sixth of
    // the sweep.)
    for &(_, i) in order.iter() {
        let e = edges[i as usize];
        let ((xlo, xhi), (ylo, yhi)) = (extent(e.a.x, e.b.x, finite), extent(e.a.y, e.b.y, finite));
        sorted.push(Bounds {
            xlo,
            xhi,
            ylo,
            yhi,
            at: i,
            ring: e.ring,
            seg: e.seg,
            next: e.next,
        });
    }
    let boxes = &*sorted;
    for (i, eb) in boxes.iter().enumerate() {
        let (xhi, ylo, yhi) = (eb.xhi, eb.ylo, eb.yhi);
        for fb in &boxes[i + 1..] {
            if fb.xlo > xhi {
                break;
            }
            if fb.yhi < ylo || fb.ylo > yhi {
                continue;
            }
            if eb.ring == fb.ring && (eb.next == fb.seg || fb.next == eb.seg || eb.seg == fb.seg) {
                continue;
            }
            let (e, f) = (&edges[eb.at as usize], &edges[fb.at as usize]);
            match meet((e.a, e.b), (f.a, f.b)) {
                Meet::Cut(t, u, at) => cuts.push(Cut {
                    ring: [e.ring as usize, f.ring as usize],
                    seg: [e.seg as usize, f.seg as usize],
                    t: [t, u],
                    at,
                }),
                Meet::Touch => return false,
                Meet::Not => {}
            }
        }
    }
    true
}

/// What two raw segments whose boxes meet do.
enum Meet {
    /// Neither crosses nor touches the other.
    Not,
    /// They cross properly: at `t` along `e`, `u` along `f`, at this point.
    Cut(f64, f64, Coord),
    /// They touch or overlap without crossing: a tangency.
    Touch,
}

/// The sweep's test of two segments `e` (the first in its order) and `f`: both finders
/// compute every cut from the same numbers.
#[inline(always)]
fn meet(e: (Coord, Coord), f: (Coord, Coord)) -> Meet {
    let (ea, eb, fa, fb) = (e.0, e.1, f.0, f.1);
    let (p, r) = (eb - ea, fb - fa);
    let d1 = cross(p, fa - ea);
    let d2 = cross(p, fb - ea);
    let d3 = cross(r, ea - fa);
    let d4 = cross(r, eb - fa);
    let proper = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
    if proper(d1, d2) && proper(d3, d4) {
        let t = d3 / (d3 - d4);
        let u = d1 / (d1 - d2);
        Meet::Cut(t, u, ea + p * t)
    } else if d1 == 0.0 || d2 == 0.0 || d3 == 0.0 || d4 == 0.0 {
        // Touching or collinear (their boxes overlap): a tangency.
        let on = |a: Coord, b: Coord, c: Coord| {
            c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
        };
        if (d1 == 0.0 && on(ea, eb, fa))
            || (d2 == 0.0 && on(ea, eb, fb))
            || (d3 == 0.0 && on(fa, fb, ea))
            || (d4 == 0.0 && on(fa, fb, eb))
        {
            Meet::Touch
        } else {
            Meet::Not
        }
    } else {
        Meet::Not
    }
}

/// A segment's place in the sweep's order: its key (`xlo`) and its index among all the
/// rings' segments (ties in the order built); a cut's, its two segments' in that order.
type Rank = ((i64, u32), (i64, u32));

/// [`convex_crossings`]'s buffers: the cuts found and their places in the sweep's order,
/// and the larger ring's chunks' boxes.
type Pairs = (Vec<(Rank, u32)>, Vec<Cut>, Vec<(Coord, Coord)>);

/// Segments per chunk of the larger ring in [`convex_crossings`]: a segment whose box
/// misses a chunk's passes its segments on one test.
const CHUNK: usize = 8;

/// [`crossings`] where every ring is strictly convex and simple (`apart` found them so,
/// `turns` their bounds): no ring crosses or touches itself, so only two rings' segments
/// can meet, and only where the rings' bounds do. The segments of the smaller ring of
/// each such pair are tested against chunks of the larger's, then segment by segment
/// where a chunk's box meets; each pair whose boxes meet is tested as the sweep tests it
/// (the segment first in the sweep's order as `e`), and the cuts are put in the order the
/// sweep finds them. `None` (the sweep decides) where a coordinate is not finite.
#[inline(never)]
fn convex_crossings(
    raws: &[Raw],
    turns: &[(f64, (Coord, Coord))],
    (ranked, found, chunks): &mut Pairs,
    cuts: &mut Vec<Cut>,
) -> Option<bool> {
    ranked.clear();
    found.clear();
    let mut base = 0u32;
    let mut bases = [0u32; 8];
    if raws.len() > bases.len() {
        return None;
    }
    // (0 for a finite coordinate, NaN for any other, as in the sweep.)
    let mut finite = true;
    for (r, raw) in raws.iter().enumerate() {
        bases[r] = base;
        base += raw.pts.len() as u32;
        for &c in &raw.pts {
            finite &= (c.x - c.y) * 0.0 == 0.0;
        }
    }
    if !finite {
        return None;
    }
    let key = |pts: &[Coord], i: usize| {
        let (a, b) = (pts[i], pts[if i + 1 == pts.len() { 0 } else { i + 1 }]);
        sort_key(a.x.min(b.x))
    };
    for i in 0..raws.len() {
        for j in i + 1..raws.len() {
            if !meets(turns[i].1, turns[j].1) {
                continue;
            }
            // The smaller ring's segments against the larger's chunks.
            let (s, g) = if raws[i].pts.len() <= raws[j].pts.len() {
                (i, j)
            } else {
                (j, i)
            };
            let (small, big) = (&raws[s].pts, &raws[g].pts);
            let (ns, nb) = (small.len(), big.len());
            // Each chunk's box: its segments' ends, points from ..= to.
            chunks.clear();
            let mut from = 0;
            while from < nb {
                let to = (from + CHUNK).min(nb);
                let mut lo = big[from];
                let mut hi = lo;
                for &c in &big[from + 1..to] {
                    math::widen(&mut lo, &mut hi, c);
                }
                math::widen(&mut lo, &mut hi, big[if to == nb { 0 } else { to }]);
                chunks.push((lo, hi));
                from = to;
            }
            for k in 0..ns {
                let (a, b) = (small[k], small[if k + 1 == ns { 0 } else { k + 1 }]);
                let (xlo, xhi) = extent(a.x, b.x, true);
                let (ylo, yhi) = extent(a.y, b.y, true);
                for (ch, &(lo, hi)) in chunks.iter().enumerate() {
                    if hi.x < xlo || lo.x > xhi || hi.y < ylo || lo.y > yhi {
                        continue;
                    }
                    let from = ch * CHUNK;
                    for m in from..(from + CHUNK).min(nb) {
                        let (c, e) = (big[m], big[if m + 1 == nb { 0 } else { m + 1 }]);
                        let (cxlo, cxhi) = extent(c.x, e.x, true);
                        let (cylo, cyhi) = extent(c.y, e.y, true);
                        if cxhi < xlo || cxlo > xhi || cyhi < ylo || cylo > yhi {
                            continue;
                        }
                        // Which of the two the sweep takes first.
                        let here = (key(small, k), bases[s] + k as u32);
                        let there = (key(big, m), bases[g] + m as u32);
                        let (first, second, (e0, e1, r0, r1)) = if here < there {
                            (here, there, ((a, b), (c, e), (s, k), (g, m)))
                        } else {
                            (there, here, ((c, e), (a, b), (g, m), (s, k)))
                        };
                        match meet(e0, e1) {
                            Meet::Cut(t, u, at) => {
                                ranked.push(((first, second), found.len() as u32));
                                found.push(Cut {
                                    ring: [r0.0, r1.0],
                                    seg: [r0.1, r1.1],
                                    t: [t, u],
                                    at,
                                });
                            }
                            Meet::Touch => return Some(false),
                            Meet::Not => {}
                        }
                    }
                }
            }
        }
    }
    in_sweep_order(ranked, found, cuts);
    Some(true)
}

/// [`crossings`] for one ring of at most 64 segments (a star's or an L's loops where they
/// pinch), each segment a bit of a set. The ring's bounds are cut into columns and rows,
/// and each segment's box covers a range of each. A point's column is its `x` less the
/// bounds' least, times the columns per unit, rounded: each step keeps the order of
/// coordinates, so a segment's first and last columns are its ends' least and greatest,
/// and two boxes that meet (closed) cover columns that meet, and rows that meet. The
/// segments whose columns meet a segment's are those starting at or before its last
/// column and ending at or after its first: each column's set of those starting there
/// `or`ed from the left, of those ending there from the right, and the same in rows.
/// Each of those before it is tested as the sweep tests it (the same box test, its
/// neighbours left out, the segment first in the sweep's order as `e`), so every pair
/// the sweep tests is tested, and the cuts are put in the order the sweep finds them. No
/// list of edges and no sort (the sweep's setup was most of its cost on a star's pinched
/// loop of 35 segments; its ~120 pairs meeting in `x` are ~20 here). `None` (the sweep
/// decides) for more segments or fewer than 3, or where a coordinate or the bounds' size
/// is not finite.
#[inline(never)]
fn ring_crossings(
    pts: &[Coord],
    (ranked, found, _): &mut Pairs,
    cuts: &mut Vec<Cut>,
) -> Option<bool> {
    let n = pts.len();
    if !(3..=64).contains(&n) {
        return None;
    }
    let (mut lo, mut hi) = super::travel::bounds(&[]);
    // 0 where every coordinate is finite, else NaN.
    let mut finite = Coord { x: 0.0, y: 0.0 };
    for &c in pts {
        finite = finite + c * 0.0;
        math::widen(&mut lo, &mut hi, c);
    }
    let size = hi - lo;
    if finite.x != 0.0 || finite.y != 0.0 || size.x * size.y * 0.0 != 0.0 {
        return None;
    }
    // Columns (and rows): 32 for more than 16 segments (16 made a star's loop of 35 test
    // more pairs), else 8 (an L's loop of 10: fewer sets to gather). A point on the
    // greatest bound may round to `grid`: `grid + 1` of them in all.
    let grid = if n > 16 { 32 } else { 8 };
    // Cells per unit (0 where the ring has no width, or too little: one column).
    let scale = |w: f64| {
        let s = grid as f64 / w;
        if s.is_finite() { s } else { 0.0 }
    };
    let s = Coord {
        x: scale(size.x),
        y: scale(size.y),
    };
    // A point's column and row: from 0 to about `grid` rounded to a whole number by
    // adding 1.5·2⁵² (`as usize` costs a range check), `grid` at most.
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let at = |c: Coord| {
        let t = c - lo;
        let t = Coord {
            x: t.x * s.x + ROUND,
            y: t.y * s.y + ROUND,
        };
        let cell = |v: f64| (v.to_bits().wrapping_sub(ROUND.to_bits()) as usize) & 63;
        (cell(t.x), cell(t.y))
    };
    // For each column and row `k`, the segments whose first column is `k` and those whose
    // last column is `grid − k`, the same in rows; then each `or`ed with those before it:
    // the segments whose first column is at most `k` (ending at least at `grid − k`).
    let mut sets = [[0u64; 4]; 64];
    let mut spans = [[0u8; 4]; 64];
    let (mut x0, mut y0) = at(pts[0]);
    for (i, span) in spans.iter_mut().enumerate().take(n) {
        let (x1, y1) = at(pts[if i + 1 == n { 0 } else { i + 1 }]);
        let bit = 1u64 << i;
        let (c0, c1) = (x0.min(x1), x0.max(x1));
        let (r0, r1) = (y0.min(y1), y0.max(y1));
        sets[c0][0] |= bit;
        sets[(grid - c1) & 63][1] |= bit;
        sets[r0][2] |= bit;
        sets[(grid - r1) & 63][3] |= bit;
        *span = [c0 as u8, c1 as u8, r0 as u8, r1 as u8];
        (x0, y0) = (x1, y1);
    }
    let mut before = [0u64; 4];
    for set in &mut sets[..=grid] {
        for (s, b) in set.iter_mut().zip(&mut before) {
            *s |= *b;
            *b = *s;
        }
    }
    ranked.clear();
    found.clear();
    let bounds = |a: Coord, b: Coord| {
        let ((xlo, xhi), (ylo, yhi)) = (extent(a.x, b.x, true), extent(a.y, b.y, true));
        [xlo, xhi, ylo, yhi]
    };
    for (g, span) in spans[..n].iter().enumerate() {
        let [c0, c1, r0, r1] = span.map(usize::from);
        // Those before it whose columns and rows meet its own, but its neighbours (the
        // one before, and the first where it is the last), which meet it without
        // crossing: bits 0 to g − 2, not 0 for the last.
        let last = g + 1 == n;
        let mut near = sets[c1 & 63][0]
            & sets[(grid - c0) & 63][1]
            & sets[r1 & 63][2]
            & sets[(grid - r0) & 63][3];
        near &= (((1u64 << g) - 1) >> 1) & !u64::from(last);
        if near == 0 {
            continue;
        }
        let (a, b) = (pts[g], pts[if last { 0 } else { g + 1 }]);
        let [xlo, xhi, ylo, yhi] = bounds(a, b);
        while near != 0 {
            let j = near.trailing_zeros() as usize;
            near &= near - 1;
            // (j < g: its next point is j + 1.)
            let (c, e) = (pts[j], pts[j + 1]);
            let [cxlo, cxhi, cylo, cyhi] = bounds(c, e);
            if cxhi < xlo || cxlo > xhi || cyhi < ylo || cylo > yhi {
                continue;
            }
            if !ring_pair((a, b, g), (c, e, j), ranked, found) {
                return Some(false);
            }
        }
    }
    in_sweep_order(ranked, found, cuts);
    Some(true)
}

/// The cuts `found` into `cuts` in the order the sweep finds them: by the first segment's
/// place, then the second's (`ranked`; the ranks are distinct: by insertion, a few small
/// pairs). For [`convex_crossings`] and [`ring_crossings`].
fn in_sweep_order(ranked: &mut [(Rank, u32)], found: &[Cut], cuts: &mut Vec<Cut>) {
    for i in 1..ranked.len() {
        let x = ranked[i];
        let mut j = i;
        while j > 0 && ranked[j - 1].0 > x.0 {
            ranked[j] = ranked[j - 1];
            j -= 1;
        }
        ranked[j] = x;
    }
    cuts.extend(ranked.iter().map(|r| found[r.1 as usize]));
}

/// [`ring_crossings`]' test of segments `g` (from `a` to `b`) and `j` whose boxes meet,
/// as the sweep tests them: a cut into `found` with its place in the sweep's order into
/// `ranked`; `false` where they touch. The test gives the same answer either way round
/// (its four cross products are the same, in pairs swapped): a cut is worked out again
/// with the segment first in the sweep's order as `e` where that is `j`. (Not inlined:
/// the loop about it kept this one's values in its registers, spilling its own.)
#[inline(never)]
fn ring_pair(
    (a, b, g): (Coord, Coord, usize),
    (c, e, j): (Coord, Coord, usize),
    ranked: &mut Vec<(Rank, u32)>,
    found: &mut Vec<Cut>,
) -> bool {
    match meet((a, b), (c, e)) {
        Meet::Cut(mut t, mut u, mut at) => {
            let mine = (sort_key(a.x.min(b.x)), g as u32);
            let theirs = (sort_key(c.x.min(e.x)), j as u32);
            let (rank, seg) = if theirs < mine {
                if let Meet::Cut(t1, u1, at1) = meet((c, e), (a, b)) {
                    (t, u, at) = (t1, u1, at1);
                }
                ((theirs, mine), [j, g])
            } else {
                ((mine, theirs), [g, j])
            };
            ranked.push((rank, found.len() as u32));
            found.push(Cut {
                ring: [0, 0],
                seg,
                t: [t, u],
                at,
            });
            true
        }
        Meet::Touch => false,
        Meet::Not => true,
    }
}

/// Sorts `order` by insertion, moving elements at most `budget` places in all; `false`
/// (the order left a permutation, partly sorted) where that was not enough.
fn insertion_sort(order: &mut [(i64, u32)], budget: usize) -> bool {
    let mut moves = 0;
    for i in 1..order.len() {
        let x = order[i];
        let mut j = i;
        while j > 0 && order[j - 1] > x {
            order[j] = order[j - 1];
            j -= 1;
        }
        order[j] = x;
        moves += i - j;
        if moves > budget {
            return false;
        }
    }
    true
}

/// Whether a piece (or a ring not cut) that runs backwards somewhere (against the edge a
/// segment was moved from: an edge event passed) cannot be decided by one point: it is a
/// swallowtail, to be cut away whole, unless it was kept (`kept`), or another of its
/// segments would be kept (a swallowtail that crossed nothing to cut it off, the offset
/// only grazing itself: seen on random star-like outlines, where the ring kept a spike,
/// or was dropped whole where the erosion has a part). Its segments are raw segments
/// `first ..= first + count` (mod the ring's), segment `j` from `point(j)` to
/// `point(j + 1)`.
fn undecided(
    raw: &Raw,
    first: usize,
    count: usize,
    point: impl Fn(usize) -> Coord,
    kept: bool,
    boundary: &Boundary,
    d: f64,
) -> bool {
    if !raw.check {
        return false;
    }
    let n = raw.pts.len();
    let seg = |j: usize| {
        let s = first + j;
        if s >= n { s - n } else { s }
    };
    (0..=count).any(|j| raw.reversed(seg(j)))
        && (kept
            || (0..=count).any(|j| {
                !raw.reversed(seg(j))
                    && keep(
                        (point(j) + point(j + 1)) / 2.0,
                        || raw.own(seg(j)),
                        boundary,
                        d,
                    )
            }))
}

/// Whether a piece lies on the erosion's boundary: the point `p` in its middle inside the
/// region and not near it, as the raw offsets are drawn: at least `d` from every boundary
/// edge, except where its foot on an edge is a reflex corner drawn as an arc of chords,
/// where only a point inside those chords is near ([`Arcs::covers`]: a chord's own middle
/// is measured where it is, on the chord, not moved onto the exact arc). The pieces were
/// cut where the raw offsets cross, so each lies wholly on one side of every other ring's
/// raw offset: its middle point decides for all of it. The edges are looked at run by
/// run (`Boundary`): a run whose bounds, grown by `reach`, miss the point has no edge
/// near it, and its edges' crossings of the ray east of the point are counted from its
/// ends alone (every edge spanning the point's height crosses the ray where the run lies
/// wholly east of it, none where it lies west, above or below); only the runs about the
/// point are tested edge by edge, as before (a holed square's 68 edges were all tested
/// for every piece).
fn keep(p: Coord, own: impl Fn() -> Option<Coord>, boundary: &Boundary, d: f64) -> bool {
    let limit = d * (1.0 - 1e-9);
    // An edge whose bounds, grown by `limit` (and a margin for rounding), miss `p` is
    // farther than `limit`: only its crossing of the ray is counted.
    let reach = limit + 1e-9;
    let band = reach.max(0.0);
    let mut inside = false;
    for run in &boundary.runs {
        let grow = band + run.slack;
        let (lo, hi) = (run.lo, run.hi);
        if p.x >= lo.x - grow && p.x <= hi.x + grow && p.y >= lo.y - grow && p.y <= hi.y + grow {
            match near(
                p,
                &boundary.sides[run.sides.clone()],
                (&boundary.arcs, &own),
                d,
                reach,
                limit,
            ) {
                Some(flips) => inside ^= flips,
                None => return false,
            }
        } else if p.x < lo.x - grow {
            inside ^= (run.start <= p.y) != (run.end <= p.y);
        }
    }
    inside
}

/// Whether `p` is farther than `limit` from every one of these sides (`None` if not),
/// and then whether the ray east of it crosses an odd number of them: [`keep`]'s test of
/// one edge after another, for the runs about `p`. A side within `limit` whose foot is an
/// arc's vertex is near only where `p` lies inside that arc's chords (`clear_of_arc`).
#[inline]
fn near(
    p: Coord,
    sides: &[Side],
    (arcs, own): (&Arcs, &impl Fn() -> Option<Coord>),
    d: f64,
    reach: f64,
    limit: f64,
) -> Option<bool> {
    // An edge that misses the band `p.y ± reach` is neither near `p` nor crosses the ray
    // (a crossing edge spans `p.y`): most edges are passed on two comparisons.
    let band = reach.max(0.0);
    let mut inside = false;
    for &Side { a, b, lo, hi } in sides {
        if p.y < lo.y - band || p.y > hi.y + band {
            continue;
        }
        if p.x >= lo.x - reach && p.x <= hi.x + reach && p.y >= lo.y - reach && p.y <= hi.y + reach
        {
            let e = b - a;
            let len2 = e.x * e.x + e.y * e.y;
            let s = if len2 > 0.0 {
                ((p - a).x * e.x + (p - a).y * e.y) / len2
            } else {
                0.0
            };
            let q = a + e * s.clamp(0.0, 1.0) - p;
            if q.x * q.x + q.y * q.y < limit * limit {
                if arcs.fans.is_empty() {
                    return None;
                }
                // Its foot the vertex of the arc `p` is on a chord of: clear of it.
                let on_own = (s <= 0.0 || s >= 1.0)
                    && own().is_some_and(|v| v == if s >= 1.0 { b } else { a });
                if !(on_own || clear_of_arc(p, (a, b), s, arcs, d)) {
                    return None;
                }
            }
        }
        if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
            inside = !inside;
        }
    }
    Some(inside)
}

/// Whether `p`, within `d` of the side `a`–`b` at its parameter `s`, is not near it
/// after all: its foot an end that is an arc's vertex, and `p` not inside that arc's
/// chords (certainly inside within `deep·d` of the vertex: in the arc's wedge, and
/// nearer another edge than the vertex outside it).
#[cold]
#[inline(never)]
fn clear_of_arc(p: Coord, (a, b): (Coord, Coord), s: f64, arcs: &Arcs, d: f64) -> bool {
    if s > 0.0 && s < 1.0 {
        return false;
    }
    let end = if s >= 1.0 { b } else { a };
    let q = end - p;
    let deep = arcs.deep * d * (1.0 - 1e-6);
    q.x * q.x + q.y * q.y >= deep * deep && arcs.covers(end, p, d) == Some(false)
}

/// [`keep`] as it was, every edge tested one after another (the tests compare the two).
#[cfg(test)]
pub(super) fn keep_edge_by_edge(p: Coord, own: Option<Coord>, boundary: &Boundary, d: f64) -> bool {
    let limit = d * (1.0 - 1e-9);
    near(
        p,
        &boundary.sides,
        (&boundary.arcs, &|| own),
        d,
        limit + 1e-9,
        limit,
    )
    .unwrap_or(false)
}

/// The kept pieces joined end to start at their cuts into closed rings; `None` where a
/// cut has not exactly one piece leaving it. Each chain is walked twice: to check it
/// closes and measure it, then to copy its points into a ring of the right size.
fn chain(
    pieces: &[Piece],
    points: &[Coord],
    cuts: usize,
    (leaving, used): &mut (Vec<usize>, Vec<bool>),
    mut rings: Vec<Vec<Coord>>,
) -> Option<Vec<Vec<Coord>>> {
    leaving.clear();
    leaving.resize(cuts, usize::MAX);
    rings.clear();
    for (i, p) in pieces.iter().enumerate() {
        if p.from == usize::MAX {
            continue;
        }
        if leaving[p.from] != usize::MAX {
            return None;
        }
        leaving[p.from] = i;
    }
    used.clear();
    used.resize(pieces.len(), false);
    for start in 0..pieces.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut len = pieces[start].pts.len();
        if pieces[start].from != usize::MAX {
            let mut at = start;
            loop {
                let next = leaving[pieces[at].to];
                if next == usize::MAX {
                    return None;
                }
                if next == start {
                    break;
                }
                if used[next] {
                    return None;
                }
                used[next] = true;
                // Each next piece starts where the last ended: that point once.
                len += pieces[next].pts.len() - 1;
                at = next;
            }
        }
        if len < 4 {
            continue;
        }
        let mut ring = Vec::with_capacity(len);
        ring.extend_from_slice(&points[pieces[start].pts.clone()]);
        if pieces[start].from != usize::MAX {
            let mut at = leaving[pieces[start].to];
            while at != start {
                ring.pop();
                ring.extend_from_slice(&points[pieces[at].pts.clone()]);
                at = leaving[pieces[at].to];
            }
        }
        rings.push(ring);
    }
    Some(rings)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apart_(raws: &[Raw]) -> bool {
        apart(raws, &mut Vec::new()) == Layout::Apart
    }

    fn polygon(n: usize, r: f64, at: (f64, f64), turns: usize, clockwise: bool) -> Vec<Coord> {
        (0..n * turns)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let a = if clockwise { -a } else { a };
                Coord {
                    x: at.0 + r * math::cos(a),
                    y: at.1 + r * math::sin(a),
                }
            })
            .collect()
    }

    /// The star-shaped shortcut: a ring turning counter-clockwise about its centre once
    /// passes; one wound twice (a pentagram: every edge turns the same way about the
    /// centre, but it crosses itself), one with an edge turning back, a clockwise one and
    /// a notch seen from a centre outside its kernel do not.
    #[test]
    fn star_shaped_rings_go_round_their_centre_once() {
        let star: Vec<Coord> = (0..10)
            .map(|i| {
                let r = if i % 2 == 0 { 10.0 } else { 4.5 };
                let a = std::f64::consts::TAU * i as f64 / 10.0;
                Coord {
                    x: r * math::cos(a),
                    y: r * math::sin(a),
                }
            })
            .collect();
        assert!(star_shaped(&star));
        let pentagram: Vec<Coord> = (0..5)
            .map(|i| {
                let a = std::f64::consts::TAU * (2 * i) as f64 / 5.0;
                Coord {
                    x: 10.0 * math::cos(a),
                    y: 10.0 * math::sin(a),
                }
            })
            .collect();
        assert!(!star_shaped(&pentagram));
        assert!(!star_shaped(&polygon(7, 3.0, (0.0, 0.0), 2, false)));
        assert!(star_shaped(&polygon(7, 3.0, (5.0, -2.0), 1, false)));
        assert!(!star_shaped(&polygon(7, 3.0, (5.0, -2.0), 1, true)));
        // A notch whose far side turns back about the centre.
        let hooked = vec![
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 10.0, y: 0.0 },
            Coord { x: 10.0, y: 10.0 },
            Coord { x: 2.0, y: 10.0 },
            Coord { x: 2.0, y: 1.0 },
            Coord { x: 1.0, y: 1.0 },
            Coord { x: 1.0, y: 10.0 },
            Coord { x: 0.0, y: 10.0 },
        ];
        assert!(!star_shaped(&hooked));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// Where a raw offset is taken as star-shaped (no sweep), the sweep finds no
        /// crossing and no touching in it: random star-like outlines, some with sharp
        /// tips, eroded by distances up to past their middle.
        #[test]
        fn rings_taken_as_star_shaped_cross_nothing(
            radii in proptest::collection::vec(0.2f64..1.0, 3..16),
            size in 4.0f64..25.0,
            depth in 0.01f64..0.6,
        ) {
            let n = radii.len();
            let mut ring: Vec<Coord> = radii
                .iter()
                .enumerate()
                .map(|(i, r)| {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    Coord { x: r * size * math::cos(a), y: r * size * math::sin(a) }
                })
                .collect();
            ring.push(ring[0]);
            let region = MultiPolygon::new(vec![geo::Polygon::new(ring.into(), vec![])]);
            let mut eroder = Eroder::new(&region, 0.5);
            eroder.rings(depth * size);
            let raws = &eroder.raws;
            if raws.len() == 1 && star_shaped(&raws[0].pts) {
                let mut cuts = Vec::new();
                proptest::prop_assert!(crossings(raws, &mut Sweep::default(), &mut cuts));
                proptest::prop_assert_eq!(cuts.len(), 0);
            }
        }
    }

    /// The raw offsets' sizes counted as the corners are prepared (the buffers are
    /// reserved at them) are the points `fill` makes, tips not closed.
    #[test]
    fn each_raw_offset_has_the_points_counted() {
        for (name, shape) in crate::infill::shapes::ring_shapes() {
            let mut eroder = Eroder::new(&shape, 0.5).cutting_tips();
            for d in [0.3, 2.0, 5.0] {
                let _ = eroder.rings(d);
                assert_eq!(eroder.raws.len(), eroder.safes.len(), "{name}");
                for (raw, &(_, n)) in eroder.raws.iter().zip(&eroder.safes) {
                    assert_eq!(raw.pts.len(), n, "{name} by {d}");
                }
            }
        }
    }

    #[test]
    fn an_arcs_steps_are_its_quotient_rounded_up() {
        let mut xs = vec![0.0, -0.0, -0.5, 1e-300, 0.5, 1.0, 2.0, 3.5, 1e6, f64::NAN];
        for k in 1..40 {
            let x = k as f64 * 0.37;
            xs.extend([x, x.next_up(), x.next_down(), (k as f64).next_up()]);
        }
        for x in xs {
            assert_eq!(steps(x), x.ceil().max(1.0) as usize, "{x}");
        }
    }

    /// The sweep's reused order: nearly sorted pairs are sorted within the budget, and a
    /// reversed order runs past it (the caller then sorts in full) without losing a pair.
    #[test]
    fn the_reused_order_is_sorted_or_declined() {
        let mut near: Vec<(i64, u32)> = (0..40).map(|i| (i64::from(i / 2), i)).collect();
        near.swap(3, 4);
        near.swap(20, 22);
        let mut expected = near.clone();
        expected.sort_unstable();
        assert!(insertion_sort(&mut near, 8));
        assert_eq!(near, expected);
        let mut reversed: Vec<(i64, u32)> = (0..40).rev().map(|i| (i64::from(i), i)).collect();
        assert!(!insertion_sort(&mut reversed, 100));
        reversed.sort_unstable();
        assert_eq!(
            reversed,
            (0..40).map(|i| (i64::from(i), i)).collect::<Vec<_>>()
        );
    }

    /// The shortcut that skips the crossing sweep holds only where the sweep would find
    /// nothing: strictly convex rings going round once, nested or apart.
    #[test]
    fn the_sweep_is_skipped_only_for_convex_rings_nested_or_apart() {
        // A diamond, |x| + |y| < 10.
        let square = polygon(4, 10.0, (0.0, 0.0), 1, false);
        assert_eq!(convex(&square), 1.0);
        assert_eq!(convex(&polygon(7, 3.0, (0.0, 0.0), 1, true)), -1.0);
        // Round twice: every turn the same way, but it crosses itself.
        assert_eq!(convex(&polygon(7, 3.0, (0.0, 0.0), 2, false)), 0.0);
        // A reflex corner.
        let notched = vec![
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 4.0, y: 0.0 },
            Coord { x: 2.0, y: 1.0 },
            Coord { x: 4.0, y: 4.0 },
            Coord { x: 0.0, y: 4.0 },
        ];
        assert_eq!(convex(&notched), 0.0);
        let hole = |r: f64, at: (f64, f64)| Raw::of(polygon(12, r, at, 1, true));
        // A hole well inside the outline, and two holes apart.
        assert!(apart_(&[Raw::of(square.clone()), hole(2.0, (0.0, 0.0))]));
        assert!(apart_(&[
            Raw::of(square.clone()),
            hole(1.0, (-3.0, 0.0)),
            hole(1.0, (3.0, 0.0))
        ]));
        // A hole whose bounds' corners leave the diamond (|x| + |y| up to 12) though
        // its points stay inside (up to 8.5): the corners do not decide, the points do.
        assert!(apart_(&[Raw::of(square.clone()), hole(6.0, (0.0, 0.0))]));
        // A hole reaching out of the outline, and two holes overlapping.
        assert!(!apart_(&[Raw::of(square.clone()), hole(2.0, (9.0, 0.0))]));
        assert!(!apart_(&[
            Raw::of(square.clone()),
            hole(2.0, (-1.0, 0.0)),
            hole(2.0, (1.0, 0.0))
        ]));
        assert!(!apart_(&[Raw::of(notched)]));
    }
}

#[cfg(test)]
#[path = "loops_tests.rs"]
mod loops_tests;
