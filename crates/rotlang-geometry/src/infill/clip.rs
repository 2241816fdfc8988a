//! Exact clipping against the inset region, in a pattern's own frame.
//!
//! Straight lines are clipped by an even-odd scan (the crossings of a line with every
//! edge of every ring, sorted and paired), curves by splitting them wherever they cross an
//! edge and keeping the pieces whose middle is inside. Both are exact for any polygon
//! with holes, concave or not; the half-open rule on edge ends (an edge owns its lower
//! end) counts a vertex on the line once.

use super::offset::cross;
use super::scratch;
use crate::math;
use geo::Coord;

/// A pattern's frame: its origin (the pattern centre) and its x axis at angle θ.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub centre: Coord,
    cos: f64,
    sin: f64,
}

impl Frame {
    pub fn new(centre: Coord, theta: f64) -> Frame {
        let (sin, cos) = math::sin_cos(theta);
        Frame { centre, cos, sin }
    }

    pub fn to_local(self, p: Coord) -> Coord {
        let d = p - self.centre;
        Coord {
            x: d.x * self.cos + d.y * self.sin,
            y: -d.x * self.sin + d.y * self.cos,
        }
    }

    pub fn to_world(self, q: Coord) -> Coord {
        Coord {
            x: self.centre.x + q.x * self.cos - q.y * self.sin,
            y: self.centre.y + q.x * self.sin + q.y * self.cos,
        }
    }
}

#[derive(Clone, Copy, Debug)]
struct Edge {
    a: Coord,
    b: Coord,
}

/// An edge's box (the lesser and greater of its ends' coordinates, by comparisons), for
/// the test that passes an edge wholly beside a segment's box on one comparison a side.
/// The first `edges.len()` (at most `N`, `N` ≤ 256) of `(key(edge), index)` sorted by
/// key, by insertion: a few dozen at most, each key a pair of words moved, not an edge
/// and its box (equal keys keep their order).
fn sorted_keys<const N: usize>(edges: &[Edge], key: impl Fn(&Edge) -> f64) -> [(f64, u8); N] {
    let mut keys = [(0.0f64, 0u8); N];
    for (i, e) in edges.iter().enumerate() {
        let k = (key(e), i as u8);
        let mut j = i;
        while j > 0 && keys[j - 1].0 > k.0 {
            keys[j] = keys[j - 1];
            j -= 1;
        }
        keys[j] = k;
    }
    keys
}

fn edge_box(Edge { a, b }: Edge) -> (Coord, Coord) {
    let (x0, x1) = if a.x < b.x { (a.x, b.x) } else { (b.x, a.x) };
    let (y0, y1) = if a.y < b.y { (a.y, b.y) } else { (b.y, a.y) };
    (Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 })
}

/// The region's edges in one frame, bucketed in horizontal strips so that a line or a
/// short segment meets only the edges near it.
pub(crate) struct Edges {
    edges: Vec<Edge>,
    /// Each edge with its box, for a region of at most `PLAIN` edges (`clip` tests them
    /// all), by the box's least x: a segment's scan stops at the first edge wholly to
    /// its right (the crossings are sorted by where they are after, so the order they
    /// are found in is not seen).
    boxes: Vec<(Coord, Coord, Edge)>,
    /// For a region of at most `FEW` edges (which gets no strips): each edge with its
    /// lower and upper y, by the lower, for `contains`.
    by_y: Vec<(f64, f64, Edge)>,
    /// Strip `s` holds `strip_edges[strip_start[s]..strip_start[s + 1]]` (one flat list:
    /// two allocations, not one per strip), by index, ascending.
    strip_start: Vec<u32>,
    strip_edges: Vec<u32>,
    pub min: Coord,
    pub max: Coord,
    height: f64,
    /// Per edge: the last segment that tested it (a segment spanning strips would
    /// otherwise meet an edge once per strip).
    stamp: Vec<u32>,
    segment: u32,
    /// `clip`'s cuts and the piece it hands out, kept for the next call.
    cuts: Vec<f64>,
    piece: Vec<Coord>,
    /// For `clip`, built by its first call: the edges in a grid of square cells, so that a
    /// short segment well inside the region tests no edge at all.
    grid: Option<Grid>,
    /// The last point `clip` tested with `contains`, by its bits, and the answer: a
    /// lightning branch's two polylines share their fork, and where neither is cut both
    /// test it (the answer depends on the point and the edges alone).
    tested: ([u64; 2], bool),
    /// Whether a polyline crossing nothing is cut as any other (in tests: the general
    /// path its shortcut is compared with).
    whole_as_cut: bool,
}

/// Edges by cell, in one flat list: cell `c` holds `edges[start[c]..start[c + 1]]`.
struct Grid {
    min: Coord,
    /// 1 / the cell's side.
    inv: f64,
    nx: usize,
    ny: usize,
    start: Vec<u32>,
    edges: Vec<u32>,
}

impl Grid {
    fn new(edges: &[Edge], min: Coord, max: Coord) -> Grid {
        let size = max - min;
        let wanted = (4 * edges.len()).clamp(16, 1 << 16) as f64;
        let side = ((size.x.max(0.0) * size.y.max(0.0) / wanted).sqrt())
            .max(size.x.max(size.y) / 1024.0)
            .max(1e-9);
        let inv = 1.0 / side;
        let nx = ((size.x * inv) as usize + 1).min(1024);
        let ny = ((size.y * inv) as usize + 1).min(1024);
        let col = |x: f64| (((x - min.x) * inv).max(0.0) as usize).min(nx - 1);
        let row = |y: f64| (((y - min.y) * inv).max(0.0) as usize).min(ny - 1);
        // A little slack on each side so that rounding never drops an edge from the cell
        // a crossing lies in.
        let slack = side * 1e-6;
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(edges.len() * 4);
        for (i, e) in edges.iter().enumerate() {
            let (lo, hi) = (e.a.y.min(e.b.y), e.a.y.max(e.b.y));
            for r in row(lo - slack)..=row(hi + slack) {
                // The edge's x range within this row.
                let (y0, y1) = (
                    (min.y + r as f64 * side).max(lo),
                    (min.y + (r + 1) as f64 * side).min(hi),
                );
                let x_at = |y: f64| {
                    if e.b.y == e.a.y {
                        e.a.x
                    } else {
                        e.a.x + (y - e.a.y) * (e.b.x - e.a.x) / (e.b.y - e.a.y)
                    }
                };
                let (xa, xb) = if e.b.y == e.a.y {
                    (e.a.x.min(e.b.x), e.a.x.max(e.b.x))
                } else {
                    let (p, q) = (x_at(y0.min(y1)), x_at(y1.max(y0)));
                    (p.min(q), p.max(q))
                };
                for c in col(xa - slack)..=col(xb + slack) {
                    pairs.push(((r * nx + c) as u32, i as u32));
                }
            }
        }
        let mut start = vec![0u32; nx * ny + 1];
        for &(c, _) in &pairs {
            start[c as usize + 1] += 1;
        }
        for c in 0..nx * ny {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut list = vec![0u32; pairs.len()];
        for &(c, i) in &pairs {
            list[fill[c as usize] as usize] = i;
            fill[c as usize] += 1;
        }
        Grid {
            min,
            inv,
            nx,
            ny,
            start,
            edges: list,
        }
    }

    fn col(&self, x: f64) -> usize {
        (((x - self.min.x) * self.inv).max(0.0) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.min.y) * self.inv).max(0.0) as usize).min(self.ny - 1)
    }

    fn cell(&self, r: usize, c: usize) -> &[u32] {
        let k = r * self.nx + c;
        &self.edges[self.start[k] as usize..self.start[k + 1] as usize]
    }
}

impl Edges {
    pub fn new(rings: &[Vec<Coord>], frame: &Frame) -> Edges {
        // Its lists are kept from one layer to the next (`scratch`, given back on drop).
        let mut edges = scratch::take(&EDGE_LIST);
        edges.reserve(rings.iter().map(Vec::len).sum());
        let mut min = Coord {
            x: f64::INFINITY,
            y: f64::INFINITY,
        };
        let mut max = Coord {
            x: f64::NEG_INFINITY,
            y: f64::NEG_INFINITY,
        };
        for ring in rings {
            let Some(&first) = ring.first() else {
                continue;
            };
            let first = frame.to_local(first);
            let mut a = first;
            for k in 0..ring.len() {
                // The edge from vertex k to the next (the last one closes the ring).
                let b = match ring.get(k + 1) {
                    Some(&p) => frame.to_local(p),
                    None => first,
                };
                crate::math::widen(&mut min, &mut max, a);
                if a != b {
                    edges.push(Edge { a, b });
                }
                a = b;
            }
        }
        let n = (edges.len() / 2).clamp(1, 512);
        let height = ((max.y - min.y) / n as f64).max(f64::MIN_POSITIVE);
        let span = |e: &Edge| {
            let (lo, hi) = if e.a.y < e.b.y {
                (e.a.y, e.b.y)
            } else {
                (e.b.y, e.a.y)
            };
            // The first strip and one past the last (an exclusive range: an inclusive
            // one costs a flag and a test per step).
            (strip(lo, min.y, height, n), strip(hi, min.y, height, n) + 1)
        };
        let mut strip_start = scratch::take(&STRIP_START);
        let mut strip_edges = scratch::take(&STRIP_EDGES);
        // A region of `FEW` edges or fewer gets no strips (`by_y` instead).
        if edges.len() > FEW {
            // A counting sort by strip: counts, their running sums (each strip's end), then
            // the edges placed from each end down, in reverse, which leaves every strip's
            // start in `strip_start` and its edges in ascending order.
            strip_start.resize(n + 1, 0);
            // Each edge's strips found once (two divisions), for both passes.
            let mut spans = scratch::take(&SPANS);
            spans.extend(edges.iter().map(|e| {
                let (first, end) = span(e);
                (first as u32, end as u32)
            }));
            for &(first, end) in &spans {
                for count in &mut strip_start[first as usize..end as usize] {
                    *count += 1;
                }
            }
            for s in 1..n {
                strip_start[s] += strip_start[s - 1];
            }
            strip_start[n] = strip_start[n - 1];
            strip_edges.resize(strip_start[n] as usize, 0);
            for (i, &(first, end)) in spans.iter().enumerate().rev() {
                for at in &mut strip_start[first as usize..end as usize] {
                    *at -= 1;
                    strip_edges[*at as usize] = i as u32;
                }
            }
            scratch::give(&SPANS, spans);
        }
        let mut by_y = scratch::take(&BY_Y);
        if edges.len() <= FEW {
            // The edges' lower y with their index (as `boxes` below).
            let keys = sorted_keys::<FEW>(&edges, |e| if e.a.y < e.b.y { e.a.y } else { e.b.y });
            by_y.extend(keys[..edges.len()].iter().map(|&(lo, i)| {
                let e = edges[usize::from(i)];
                (lo, if e.a.y < e.b.y { e.b.y } else { e.a.y }, e)
            }));
        }
        let mut boxes = scratch::take(&BOXES);
        if edges.len() <= PLAIN {
            // The edges' least x with their index, then the boxes listed in that order.
            let keys = sorted_keys::<PLAIN>(&edges, |e| if e.a.x < e.b.x { e.a.x } else { e.b.x });
            boxes.extend(keys[..edges.len()].iter().map(|&(_, i)| {
                let e = edges[usize::from(i)];
                let (lo, hi) = edge_box(e);
                (lo, hi, e)
            }));
        }
        Edges {
            // Allocated by the first `clip`: straight lines never need it.
            stamp: Vec::new(),
            boxes,
            by_y,
            edges,
            strip_start,
            strip_edges,
            min,
            max,
            height,
            segment: 0,
            cuts: scratch::take(&CUTS),
            piece: scratch::take(&PIECE),
            grid: None,
            // No point has these bits (NaNs: never a middle that is tested).
            tested: ([u64::MAX; 2], false),
            whole_as_cut: false,
        }
    }

    /// The same edges clipping a polyline that crosses nothing as any other (tests
    /// compare the two).
    #[cfg(test)]
    pub fn cutting_whole(mut self) -> Edges {
        self.whole_as_cut = true;
        self
    }

    /// The edges, in the frame.
    pub fn segments(&self) -> impl Iterator<Item = (Coord, Coord)> + '_ {
        self.edges.iter().map(|e| (e.a, e.b))
    }

    fn strip(&self, y: f64) -> usize {
        strip(y, self.min.y, self.height, self.strip_start.len() - 1)
    }

    /// The inside intervals `[x0, x1]` of the horizontal line at `y`, left to right (the
    /// reference the straight families, found edge by edge, are tested against).
    #[cfg(test)]
    pub fn scan(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        out.clear();
        if !(y >= self.min.y && y < self.max.y) {
            return;
        }
        let mut crossings = Vec::new();
        let strip: Vec<Edge> = if self.strip_start.is_empty() {
            self.edges.clone()
        } else {
            let s = self.strip(y);
            let (from, to) = (self.strip_start[s], self.strip_start[s + 1]);
            self.strip_edges[from as usize..to as usize]
                .iter()
                .map(|&i| self.edges[i as usize])
                .collect()
        };
        for Edge { a, b } in strip {
            if (a.y <= y) != (b.y <= y) {
                crossings.push(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        }
        crossings.sort_unstable_by(f64::total_cmp);
        out.extend(crossings.chunks_exact(2).map(|c| (c[0], c[1])));
    }

    /// Even-odd: whether `p` is inside the region (on an edge: either).
    pub fn contains(&self, p: Coord) -> bool {
        let mut inside = false;
        if self.strip_start.is_empty() {
            // No strips (`FEW` edges at most): every edge, the same parity (an edge not
            // in the point's strip does not reach its height).
            // By their lower end, so the scan stops at the first edge wholly above `p`;
            // an edge reaches its height (`(a.y <= p.y) != (b.y <= p.y)`, the half-open
            // rule) exactly when `lo <= p.y < hi`. Below the box (or NaN) no edge reaches
            // `p`'s height, nor above it: outside, as the box's test says, so only its
            // x half is made.
            if !(p.x >= self.min.x && p.x <= self.max.x) {
                return false;
            }
            for &(lo, hi, Edge { a, b }) in &self.by_y {
                if lo > p.y {
                    break;
                }
                if hi > p.y && crosses_right(a, b, p) {
                    inside = !inside;
                }
            }
            return inside;
        }
        if !(p.y >= self.min.y && p.y <= self.max.y && p.x >= self.min.x && p.x <= self.max.x) {
            return false;
        }
        let s = self.strip(p.y);
        let (from, to) = (self.strip_start[s], self.strip_start[s + 1]);
        for &i in &self.strip_edges[from as usize..to as usize] {
            let Edge { a, b } = self.edges[i as usize];
            if ray_crosses(a, b, p) {
                inside = !inside;
            }
        }
        inside
    }

    /// The pieces of the polyline `pts` inside the region, appended to `out`.
    pub fn clip(&mut self, pts: &[Coord], out: &mut Vec<Vec<Coord>>) {
        self.clip_each(pts, |piece| out.push(piece.to_vec()));
    }

    /// The pieces of the polyline `pts` inside the region, each handed to `piece` in turn
    /// (from a buffer kept for the next call: nothing is allocated for a caller that only
    /// measures them).
    pub fn clip_each(&mut self, pts: &[Coord], mut piece: impl FnMut(&[Coord])) {
        if pts.len() < 2 {
            return;
        }
        // Where the polyline crosses an edge, as `segment index + t`.
        let mut cuts = std::mem::take(&mut self.cuts);
        cuts.clear();
        cuts.push(0.0);
        for (k, w) in pts.windows(2).enumerate() {
            let (p, q) = (w[0], w[1]);
            // The segment's box by comparisons, not `min`/`max` (which handle NaN at
            // several instructions each): a pattern's points are finite, and a segment
            // with a NaN end is cut nowhere either way (its fractions are NaN), so the box
            // only says which edges are tested.
            let (x0, x1) = if p.x < q.x { (p.x, q.x) } else { (q.x, p.x) };
            let (lo, hi) = if p.y < q.y { (p.y, q.y) } else { (q.y, p.y) };
            if hi < self.min.y || lo > self.max.y || x1 < self.min.x || x0 > self.max.x {
                continue;
            }
            let first = cuts.len();
            let segment = Segment {
                p,
                d: q - p,
                x0,
                x1,
                y0: lo,
                y1: hi,
                k: k as f64,
            };
            if self.edges.len() <= PLAIN {
                // Few edges (a star, an L): every one, no grid to build or walk.
                // Each edge's box made once (the grid's edges, many more, go without:
                // their twice longer list cost more than the comparisons saved).
                for &(lo, hi, edge) in &self.boxes {
                    if lo.x > segment.x1 {
                        break;
                    }
                    segment.cut_boxed(edge, (lo, hi), &mut cuts);
                }
            } else {
                self.cut_through_grid(&segment, lo, hi, &mut cuts);
            }
            // One crossing or none (most segments): nothing to sort.
            if cuts.len() - first > 1 {
                cuts[first..].sort_unstable_by(f64::total_cmp);
            }
        }
        let end = (pts.len() - 1) as f64;
        cuts.push(end);
        let mut buffer = std::mem::take(&mut self.piece);
        // `g` is never negative: truncation is its floor (no call to the C library's).
        let at = |g: f64| {
            let k = (g as usize).min(pts.len() - 2);
            let t = g - k as f64;
            pts[k] + (pts[k + 1] - pts[k]) * t
        };
        if cuts.len() == 2 && !self.whole_as_cut {
            // Nothing crossed (most of a tree's polylines): the one stretch is the whole
            // polyline, its ends `at(0)` and `at(end)` with their segment and fraction
            // known (the first segment at 0, the last at 1: the same products as `at`'s),
            // and its points between, without the casts that find them for a cut.
            let n = pts.len();
            let middle = at(end / 2.0);
            let bits = [middle.x.to_bits(), middle.y.to_bits()];
            let inside = if bits == self.tested.0 {
                self.tested.1
            } else {
                let inside = self.contains(middle);
                self.tested = (bits, inside);
                inside
            };
            if inside {
                buffer.clear();
                buffer.push(pts[0] + (pts[1] - pts[0]) * 0.0);
                buffer.extend(pts[1..n - 1].iter().copied());
                buffer.push(pts[n - 2] + (pts[n - 1] - pts[n - 2]) * 1.0);
                piece(&buffer);
            }
            self.cuts = cuts;
            self.piece = buffer;
            return;
        }
        for w in cuts.windows(2) {
            let (g0, g1) = (w[0], w[1]);
            if g1 <= g0 {
                continue;
            }
            let middle = at((g0 + g1) / 2.0);
            let bits = [middle.x.to_bits(), middle.y.to_bits()];
            let inside = if bits == self.tested.0 {
                self.tested.1
            } else {
                let inside = self.contains(middle);
                self.tested = (bits, inside);
                inside
            };
            if !inside {
                continue;
            }
            let first = g0 as usize + 1;
            let last = {
                let whole = g1 as usize;
                if (whole as f64) < g1 {
                    whole + 1
                } else {
                    whole
                }
            };
            buffer.clear();
            buffer.push(at(g0));
            buffer.extend(pts[first.min(last)..last].iter().copied());
            buffer.push(at(g1));
            piece(&buffer);
        }
        self.cuts = cuts;
        self.piece = buffer;
    }

    /// The crossings of one segment (`lo`..`hi` its y range) with the edges of the grid
    /// cells it passes: row by row, only the cells of its x range within the row.
    fn cut_through_grid(&mut self, segment: &Segment, lo: f64, hi: f64, cuts: &mut Vec<f64>) {
        if self.stamp.len() != self.edges.len() {
            self.stamp = vec![u32::MAX; self.edges.len()];
        }
        let grid = self
            .grid
            .get_or_insert_with(|| Grid::new(&self.edges, self.min, self.max));
        let (p, d1) = (segment.p, segment.d);
        let (c0, c1) = (grid.col(segment.x0), grid.col(segment.x1));
        let (r0, r1) = (grid.row(lo), grid.row(hi));
        // Within one cell an edge is met once; across cells, the stamp skips repeats.
        let stamped = c0 != c1 || r0 != r1;
        if stamped {
            self.segment = self.segment.wrapping_add(1);
        }
        for r in r0..=r1 {
            // Only the cells of this row that the segment passes (its x range within the
            // row's band, with the grid's slack), not every cell of its box: a long
            // diagonal branch meets a line of cells, not a square of them.
            let (c0, c1) = if r0 == r1 || c0 == c1 {
                (c0, c1)
            } else {
                let side = 1.0 / grid.inv;
                let band = (
                    (grid.min.y + r as f64 * side).max(lo),
                    (grid.min.y + (r + 1) as f64 * side).min(hi),
                );
                let x_at = |y: f64| p.x + (y - p.y) * d1.x / d1.y;
                let (xa, xb) = (x_at(band.0), x_at(band.1));
                let slack = side * 1e-6;
                (
                    grid.col(xa.min(xb) - slack).max(c0),
                    grid.col(xa.max(xb) + slack).min(c1),
                )
            };
            for c in c0..=c1 {
                for &i in grid.cell(r, c) {
                    let i = i as usize;
                    if stamped {
                        if self.stamp[i] == self.segment {
                            continue;
                        }
                        self.stamp[i] = self.segment;
                    }
                    segment.cut(self.edges[i], cuts);
                }
            }
        }
    }
}

impl Drop for Edges {
    /// The lists go back to the pool for the next layer's edges.
    fn drop(&mut self) {
        scratch::give(&EDGE_LIST, std::mem::take(&mut self.edges));
        scratch::give(&BOXES, std::mem::take(&mut self.boxes));
        scratch::give(&BY_Y, std::mem::take(&mut self.by_y));
        scratch::give(&STRIP_START, std::mem::take(&mut self.strip_start));
        scratch::give(&STRIP_EDGES, std::mem::take(&mut self.strip_edges));
        scratch::give(&CUTS, std::mem::take(&mut self.cuts));
        scratch::give(&PIECE, std::mem::take(&mut self.piece));
    }
}

thread_local! {
    /// `Edges`' lists, kept from one layer to the next.
    static EDGE_LIST: std::cell::Cell<Vec<Edge>> = const { std::cell::Cell::new(Vec::new()) };
    static BOXES: std::cell::Cell<Vec<(Coord, Coord, Edge)>> = const { std::cell::Cell::new(Vec::new()) };
    static BY_Y: std::cell::Cell<Vec<(f64, f64, Edge)>> = const { std::cell::Cell::new(Vec::new()) };
    static STRIP_START: std::cell::Cell<Vec<u32>> = const { std::cell::Cell::new(Vec::new()) };
    static STRIP_EDGES: std::cell::Cell<Vec<u32>> = const { std::cell::Cell::new(Vec::new()) };
    /// Each edge's first and last strip while `Edges::new` sorts them.
    static SPANS: std::cell::Cell<Vec<(u32, u32)>> = const { std::cell::Cell::new(Vec::new()) };
    static CUTS: std::cell::Cell<Vec<f64>> = const { std::cell::Cell::new(Vec::new()) };
    static PIECE: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Up to this many edges (an L's inset, a square's, a holed square's) the region gets no
/// strips: `contains` scans the edges by their lower y (`by_y`), about half of them, for
/// less than the strips cost to build.
const FEW: usize = 16;

/// Up to this many edges, `clip` tests every edge: cheaper than building and walking the
/// grid.
const PLAIN: usize = 32;

/// One segment of a polyline being clipped: its start, direction, x and y ranges and
/// index.
struct Segment {
    p: Coord,
    d: Coord,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    k: f64,
}

impl Segment {
    /// Where the segment crosses `edge`, as `k + t`, pushed to `cuts`.
    #[inline]
    fn cut(&self, Edge { a, b }: Edge, cuts: &mut Vec<f64>) {
        // Both ends left of the segment's x range, or both right, below or above: by
        // comparisons, not `max`/`min` (which handle NaN at several instructions each;
        // coordinates are finite). An edge wholly beside the segment's box cannot cross
        // it.
        if (a.x < self.x0 && b.x < self.x0)
            || (a.x > self.x1 && b.x > self.x1)
            || (a.y < self.y0 && b.y < self.y0)
            || (a.y > self.y1 && b.y > self.y1)
        {
            return;
        }
        self.crossing(a, b, cuts);
    }

    /// `cut` with the edge's box made already (`edge_box`): the same test, one
    /// comparison a side (the greater of two finite numbers is below `x0` exactly when
    /// both are), in the loop over every edge of a small region.
    #[inline]
    fn cut_boxed(&self, edge: Edge, (lo, hi): (Coord, Coord), cuts: &mut Vec<f64>) {
        if hi.x < self.x0 || lo.x > self.x1 || hi.y < self.y0 || lo.y > self.y1 {
            return;
        }
        self.crossing(edge.a, edge.b, cuts);
    }

    /// Where the segment crosses the edge from `a` to `b` (not wholly beside it).
    #[inline]
    fn crossing(&self, a: Coord, b: Coord, cuts: &mut Vec<f64>) {
        let (p, d1) = (self.p, self.d);
        // The edge's ends on opposite sides of the segment's line (cheap, and false for
        // nearly every edge) before any division.
        let (sa, sb) = (cross(d1, a - p), cross(d1, b - p));
        if (sa > 0.0) == (sb > 0.0) && sa != 0.0 && sb != 0.0 {
            return;
        }
        let d2 = b - a;
        let den = d1.x * d2.y - d1.y * d2.x;
        if den == 0.0 {
            return;
        }
        let ap = a - p;
        let t = (ap.x * d2.y - ap.y * d2.x) / den;
        let u = (ap.x * d1.y - ap.y * d1.x) / den;
        if (0.0..1.0).contains(&t) && (0.0..1.0).contains(&u) {
            cuts.push(self.k + t);
        }
    }
}

/// Whether the edge from `a` to `b` crosses the ray from `p` toward +x, by the half-open
/// rule (`(a.y <= p.y) != (b.y <= p.y)`) and the crossing's x computed as
/// `a.x + (p.y − a.y)(b.x − a.x)/(b.y − a.y) > p.x`. That x lies between the edge's ends
/// (within a few ulps), so an edge wholly to the right or left of `p` by more than a
/// trillionth of the coordinates decides without the division: the same answer, cheaper.
#[inline]
pub(crate) fn ray_crosses(a: Coord, b: Coord, p: Coord) -> bool {
    if (a.y <= p.y) == (b.y <= p.y) {
        return false;
    }
    crosses_right(a, b, p)
}

/// [`ray_crosses`] for an edge known to reach `p`'s height: whether it crosses to the
/// right of `p`.
#[inline]
fn crosses_right(a: Coord, b: Coord, p: Coord) -> bool {
    let (lo, hi) = if a.x < b.x { (a.x, b.x) } else { (b.x, a.x) };
    let margin = 1e-12 * (lo.abs() + hi.abs() + p.x.abs()) + f64::MIN_POSITIVE;
    if lo > p.x + margin {
        return true;
    }
    if hi < p.x - margin {
        return false;
    }
    a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x
}

/// The strip of `y` (`height` positive). The cast saturates: below `min` (and NaN) is
/// strip 0 without a `max(0.0)` (several instructions for its NaN rule).
fn strip(y: f64, min: f64, height: f64, n: usize) -> usize {
    (((y - min) / height) as usize).min(n - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = Coord> {
        // Whole numbers often, so that ends meet, lie on lines and share coordinates.
        prop_oneof![
            (-10.0f64..10.0, -10.0f64..10.0).prop_map(|(x, y)| Coord { x, y }),
            (-4i32..4, -4i32..4).prop_map(|(x, y)| Coord {
                x: x as f64,
                y: y as f64
            }),
        ]
    }

    /// A ring of `radii.len()` vertices at those distances from the origin, evenly turned.
    fn radial(radii: &[f64]) -> Vec<Coord> {
        let n = radii.len() as f64;
        radii
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let a = std::f64::consts::TAU * i as f64 / n;
                Coord {
                    x: r * a.cos(),
                    y: r * a.sin(),
                }
            })
            .collect()
    }

    /// Every piece `clip_each` hands out, by its coordinates' bits.
    fn pieces_of(edges: &mut Edges, pts: &[Coord], out: &mut Vec<Vec<[u64; 2]>>) {
        edges.clip_each(pts, |piece| {
            out.push(
                piece
                    .iter()
                    .map(|p| [p.x.to_bits(), p.y.to_bits()])
                    .collect(),
            )
        });
    }

    proptest! {
        /// `clip_each` keeps the last point it tested and its answer: polylines clipped
        /// one after another on one edge list (each often sharing its middle vertex with
        /// the one before, as a lightning branch's two do, or only that vertex's x) give,
        /// to the bit, what each clipped on an edge list of its own gives.
        #[test]
        fn clipping_after_a_shared_point_is_clipping_afresh(
            radii in prop::collection::vec(1.0f64..10.0, 3..14),
            lines in prop::collection::vec((coord(), coord(), coord(), 0u8..3), 1..12),
        ) {
            let rings = vec![radial(&radii)];
            let frame = Frame::new(Coord { x: 0.0, y: 0.0 }, 0.0);
            let mut shared = Edges::new(&rings, &frame);
            let (mut kept, mut fresh) = (Vec::new(), Vec::new());
            let mut previous: Option<Coord> = None;
            for (a, mut m, b, share) in lines {
                if let Some(p) = previous {
                    match share {
                        // The previous polyline's middle vertex: tested by both.
                        0 => m = p,
                        // Only its x: a different point with some of the same bits.
                        1 => m = Coord { x: p.x, y: -p.y + 0.5 },
                        _ => {}
                    }
                }
                previous = Some(m);
                // A polyline with no cut has its middle vertex tested (`[0, 2]`).
                let pts = [a, m, b];
                pieces_of(&mut shared, &pts, &mut kept);
                pieces_of(&mut Edges::new(&rings, &frame), &pts, &mut fresh);
                prop_assert_eq!(&kept, &fresh);
            }
        }

        /// A polyline that crosses no edge is handed out whole (its ends recomputed as
        /// a cut's are) or not at all, to the bit as the general path cuts it: short
        /// polylines inside, outside and across star-shaped regions of a few edges (the
        /// plain scan) and of many (the grid), each clipped on its own.
        #[test]
        fn a_polyline_crossing_nothing_is_clipped_as_any_other(
            radii in prop::collection::vec(1.0f64..10.0, 3..60),
            lines in prop::collection::vec((coord(), coord(), coord(), 0u8..2), 1..12),
            scale in prop_oneof![Just(1.0f64), Just(0.05), Just(0.3)],
        ) {
            let rings = vec![radial(&radii)];
            let frame = Frame::new(Coord { x: 0.0, y: 0.0 }, 0.0);
            let (mut shortcut, mut general) = (Vec::new(), Vec::new());
            for (a, m, b, three) in lines {
                // Small polylines about a point: most cross nothing.
                let (m, b) = (a + (m - a) * scale, a + (b - a) * scale);
                let pts: Vec<Coord> = if three == 1 { vec![a, m, b] } else { vec![a, b] };
                pieces_of(&mut Edges::new(&rings, &frame), &pts, &mut shortcut);
                pieces_of(&mut Edges::new(&rings, &frame).cutting_whole(), &pts, &mut general);
                prop_assert_eq!(&shortcut, &general);
            }
        }

        /// A region of `FEW` edges or fewer (no strips: `contains` scans them by their
        /// lower y and stops at the first above the point) answers as the ray's parity
        /// over every edge: at its vertices, at their heights, on its edges and anywhere
        /// about it, with a hole or not.
        #[test]
        fn contains_on_few_edges_is_the_parity_over_every_edge(
            radii in prop::collection::vec(1.0f64..10.0, 3..9),
            hole in prop::collection::vec(0.2f64..0.8, 0..8),
            points in prop::collection::vec((coord(), 0usize..16, 0u8..4), 1..24),
        ) {
            let mut rings = vec![radial(&radii)];
            if hole.len() >= 3 {
                // Inside the outline (every radius of the hole under its least).
                rings.push(radial(&hole).into_iter().rev().collect());
            }
            let frame = Frame::new(Coord { x: 0.0, y: 0.0 }, 0.0);
            let edges = Edges::new(&rings, &frame);
            prop_assert!(edges.edges.len() <= FEW);
            prop_assert!(edges.strip_start.is_empty());
            prop_assert_eq!(edges.by_y.len(), edges.edges.len());
            let segments: Vec<(Coord, Coord)> = edges.segments().collect();
            for (free, at, kind) in points {
                let (a, b) = segments[at % segments.len()];
                let p = match kind {
                    0 => free,
                    // A vertex, a point at its height, a point on the edge.
                    1 => a,
                    2 => Coord { x: free.x, y: a.y },
                    _ => a + (b - a) * 0.5,
                };
                let parity = segments.iter().filter(|&&(a, b)| ray_crosses(a, b, p)).count() % 2 == 1;
                prop_assert_eq!(edges.contains(p), parity, "{:?}", p);
            }
        }

        /// An edge's box (made once) passes the edges wholly beside a segment's box: `cut`
        /// with it finds what `cut` without it and the sign test and the division alone
        /// find.
        #[test]
        fn cut_by_the_edge_box_is_the_unboxed_cut(
            p in coord(), q in coord(), a in coord(), b in coord(), k in 0usize..4,
        ) {
            let segment = Segment {
                p,
                d: q - p,
                x0: p.x.min(q.x),
                x1: p.x.max(q.x),
                y0: p.y.min(q.y),
                y1: p.y.max(q.y),
                k: k as f64,
            };
            let edge = Edge { a, b };
            let (lo, hi) = edge_box(edge);
            prop_assert_eq!(lo, Coord { x: a.x.min(b.x), y: a.y.min(b.y) });
            prop_assert_eq!(hi, Coord { x: a.x.max(b.x), y: a.y.max(b.y) });
            let (mut boxed, mut plain, mut unboxed) = (Vec::new(), Vec::new(), Vec::new());
            segment.cut_boxed(edge, (lo, hi), &mut boxed);
            segment.cut(edge, &mut plain);
            segment.crossing(a, b, &mut unboxed);
            prop_assert_eq!(&boxed, &unboxed);
            prop_assert_eq!(&plain, &unboxed);
        }
    }
}
