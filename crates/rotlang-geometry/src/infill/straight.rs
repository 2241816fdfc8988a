//! Patterns of straight walls: families of parallel lines, and the honeycomb.

use geo::Coord;

use super::clip::{Edges, Frame};
use super::{Region, scratch};

thread_local! {
    /// `families`' crossings, kept between layers.
    static CROSSINGS: std::cell::Cell<Vec<(i64, f64)>> = const { std::cell::Cell::new(Vec::new()) };
    /// The rings' heights in a family's frame (`scan_lines`), kept between layers.
    static LOCAL: std::cell::Cell<Vec<f64>> = const { std::cell::Cell::new(Vec::new()) };
}

/// One family of lines per offset (degrees from θ), `spacing` apart, every family with a
/// line through `centre` (so that three families at 60° meet in common points), or
/// `shift` mm to the left of it (cubic).
///
/// Each edge is met by the few lines across its height, so the edges are visited once per
/// family and each crossing is tagged with its line: sorted by line then x, consecutive
/// pairs are the inside intervals. The same crossings, by the same half-open rule and the
/// same formula, as a scan of every line against an edge index (`Edges::scan`, which the
/// tests compare against), without building that index: on a small layer (a star, an L, a
/// circle at 10%) the index cost more than the lines.
pub(crate) fn families(
    region: &Region,
    centre: Coord,
    theta: f64,
    offsets: &[f64],
    spacing: f64,
    shift: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    // The most lines a family can have: the region's diagonal over the spacing, and one
    // more at each end.
    let extent = region.max - region.min;
    let few = (extent.x * extent.x + extent.y * extent.y).sqrt() / spacing + 2.0 <= FEW as f64;
    families_by(region, centre, theta, offsets, spacing, shift, few, out);
}

/// Up to this many lines a family (a small region at a low density: a star's or an L's
/// triangles or grid at 10–20%), each line is scanned against every edge of the rings
/// turned once into the family's frame, rather than each edge's lines found from its
/// ends' line numbers: a comparison per edge and line against a rounding and two
/// comparisons per vertex.
const FEW: usize = 8;

/// [`families`] by the scan of every line (`few`) or by each edge's candidate lines: the
/// same crossings either way (the half-open rule decides both; the candidates are only
/// the lines it could take), with the same formula, so the same lines to the bit (a test
/// compares the two).
#[allow(clippy::too_many_arguments)]
pub(crate) fn families_by(
    region: &Region,
    centre: Coord,
    theta: f64,
    offsets: &[f64],
    spacing: f64,
    shift: f64,
    few: bool,
    out: &mut Vec<Vec<Coord>>,
) {
    // Room for a few lines' crossings at once: a small layer's never grow it. Kept from
    // one layer to the next (`scratch`).
    let mut crossings = scratch::take(&CROSSINGS);
    crossings.reserve(32);
    let mut local = if few {
        scratch::take(&LOCAL)
    } else {
        Vec::new()
    };
    for &offset in offsets {
        let frame = Frame::new(centre, theta + offset.to_radians());
        let shift = shift.rem_euclid(spacing);
        let inv = 1.0 / spacing;
        crossings.clear();
        if few {
            scan_lines(
                region.rings(),
                &frame,
                spacing,
                shift,
                inv,
                &mut local,
                &mut crossings,
            );
        } else {
            for ring in region.rings() {
                // Each vertex turned into the family's frame as its edge is reached (the
                // last one first, for the closing edge): no copy of the ring.
                let Some(&last) = ring.last() else {
                    continue;
                };
                let mut a = Vertex::new(frame.to_local(last), shift, inv);
                for &b in ring {
                    let b = Vertex::new(frame.to_local(b), shift, inv);
                    crossings_of(&a, &b, spacing, shift, &mut crossings);
                    a = b;
                }
            }
        }
        sort_crossings(&mut crossings);
        out.reserve(crossings.len() / 2);
        for line in crossings.chunk_by(|p, q| p.0 == q.0) {
            let y = line[0].0 as f64 * spacing + shift;
            for pair in line.chunks_exact(2) {
                out.push(vec![
                    frame.to_world(Coord { x: pair[0].1, y }),
                    frame.to_world(Coord { x: pair[1].1, y }),
                ]);
            }
        }
    }
    scratch::give(&CROSSINGS, crossings);
    scratch::give(&LOCAL, local);
}

/// `crossings` by line, then x (`total_cmp`). A small layer's family has a pair, in
/// order as often as not: told by one comparison, not the library's sort's setting up
/// (the same order: elements comparing equal are the same bits).
pub(crate) fn sort_crossings(crossings: &mut [(i64, f64)]) {
    let by_line = |p: &(i64, f64), q: &(i64, f64)| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1));
    if let [a, b] = crossings {
        if by_line(a, b).is_gt() {
            std::mem::swap(a, b);
        }
    } else {
        crossings.sort_unstable_by(by_line);
    }
}

/// The crossings of every line across the rings (turned into `frame`) with every edge,
/// by the half-open rule, each edge from the vertex before to the vertex (as
/// `crossings_of` takes them). The lines run from the first line above the lowest
/// vertex to the last below the highest, by `Vertex`'s margins: every line the rule can
/// take on some edge.
///
/// Only the vertices' heights in the frame are kept (`local`): the rule reads nothing
/// else. A crossed edge's two ends are turned whole where it is crossed (`to_local`:
/// the same products as their heights, so the same bits), a few edges a line against
/// every vertex's other coordinate made and stored.
///
/// Not inlined into `families_by`: inlined, its loops cost about 170 instructions a
/// layer more (star triangles 10%, callgrind), the registers of the caller's loop over
/// families and of the general path's crossing search crowding its own.
#[inline(never)]
fn scan_lines(
    rings: &[Vec<Coord>],
    frame: &Frame,
    spacing: f64,
    shift: f64,
    inv: f64,
    local: &mut Vec<f64>,
    out: &mut Vec<(i64, f64)>,
) {
    local.clear();
    for ring in rings {
        local.extend(ring.iter().map(|&p| frame.to_local(p).y));
    }
    // By comparisons, not `min`/`max` (which handle NaN): coordinates are finite. Two
    // at a time, into two pairs of bounds (compared in pairs: the least and the
    // greatest height are the same either way, but for a zero's sign, which gives the
    // same line numbers).
    let (pairs, rest) = local.as_chunks::<2>();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for pair in pairs {
        for j in 0..2 {
            if pair[j] < lo[j] {
                lo[j] = pair[j];
            }
            if pair[j] > hi[j] {
                hi[j] = pair[j];
            }
        }
    }
    for &q in rest {
        if q < lo[0] {
            lo[0] = q;
        }
        if q > hi[0] {
            hi[0] = q;
        }
    }
    let lo = if lo[1] < lo[0] { lo[1] } else { lo[0] };
    let hi = if hi[1] > hi[0] { hi[1] } else { hi[0] };
    if local.is_empty() {
        return;
    }
    let first = Vertex::new(Coord { x: 0.0, y: lo }, shift, inv).above;
    let last = Vertex::new(Coord { x: 0.0, y: hi }, shift, inv).below;
    for k in first..=last {
        let y = k as f64 * spacing + shift;
        let mut from = 0;
        for ring in rings {
            let r = &local[from..from + ring.len()];
            from += ring.len();
            let Some(&last) = r.last() else {
                continue;
            };
            // The edge into vertex i crosses where its ends are on two sides: the
            // edge's ends turned whole (the same products as their heights).
            let mut cross = |i: usize| {
                let before = if i == 0 { ring.len() - 1 } else { i - 1 };
                let (a, b) = (frame.to_local(ring[before]), frame.to_local(ring[i]));
                out.push((k, a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)));
            };
            // The half-open rule: an edge's ends on two sides of the line.
            let apart = |a: f64, b: f64| (a <= y) != (b <= y);
            if r.len() < BLOCKS {
                // Which side of the line the edge's start is on, carried from the edge
                // before (one comparison an edge, not two).
                let mut below = last <= y;
                for (i, &b) in r.iter().enumerate() {
                    let b_below = b <= y;
                    if below != b_below {
                        cross(i);
                    }
                    below = b_below;
                }
                continue;
            }
            if apart(last, r[0]) {
                cross(0);
            }
            // The other edges eight at a time, as the bits of a mask (each edge's two
            // comparisons, the end's shared with the next edge's start): where none
            // crosses (most, a line crossing a ring twice), one test passes them.
            let (starts, starts_rest) = r[..r.len() - 1].as_chunks::<8>();
            let (ends, ends_rest) = r[1..].as_chunks::<8>();
            for (c, (a, b)) in starts.iter().zip(ends).enumerate() {
                let mut mask = 0u32;
                for j in 0..8 {
                    mask |= u32::from(apart(a[j], b[j])) << j;
                }
                while mask != 0 {
                    cross(1 + 8 * c + mask.trailing_zeros() as usize);
                    mask &= mask - 1;
                }
            }
            for (j, (&a, &b)) in starts_rest.iter().zip(ends_rest).enumerate() {
                if apart(a, b) {
                    cross(1 + 8 * starts.len() + j);
                }
            }
        }
    }
}

/// From this many vertices a ring's edges are scanned eight at a time (`scan_lines`):
/// below, the blocks' setting up and the edges left over cost more than they spare (an
/// L's twelve).
const BLOCKS: usize = 16;

/// A vertex in the family's frame with the range of lines it might be on: the lines
/// within a margin far above rounding (a billionth of a line) below and above it, found
/// once per vertex (each is the end of two edges), not once per edge end.
struct Vertex {
    p: Coord,
    /// The first line at or above `p.y` less the margin.
    above: i64,
    /// The last line at or below `p.y` plus the margin.
    below: i64,
}

impl Vertex {
    #[inline]
    fn new(p: Coord, shift: f64, inv: f64) -> Vertex {
        let t = (p.y - shift) * inv;
        let margin = 1e-9 + 1e-12 * t.abs();
        // `ceil(t − margin)` and `floor(t + margin)` from one floor of `t` (one
        // float-to-integer cast, not two): with the margin under a half, `t − margin` lies
        // in `(f − 1, f + 1)` and `t + margin` in `[f, f + 2)`, so each is `f` or `f + 1`.
        // `t` is bounded (coordinates within MAX_COORDINATE over a spacing of 0.01 mm or
        // more: under 10⁹), far from where `f + 1` could overflow.
        debug_assert!(t.abs() < 1e15, "line number {t}");
        let f = floor(t);
        let whole = f as f64;
        Vertex {
            p,
            above: f + i64::from(t - margin > whole),
            below: f + i64::from(t + margin >= whole + 1.0),
        }
    }
}

/// The crossings of the edge from `a` to `b` with the lines `y = k·spacing + shift`:
/// the half-open rule of the scan (`(a.y <= y) != (b.y <= y)`), tested on each candidate
/// line. The candidates run from the lower end's first line above to the upper end's
/// last line below, each widened by its margin, so that none that the rule takes is
/// missed; an edge shorter than the spacing (most edges of a round or arc-cornered
/// region) usually has none, and costs a comparison.
#[inline]
fn crossings_of(a: &Vertex, b: &Vertex, spacing: f64, shift: f64, out: &mut Vec<(i64, f64)>) {
    let (first, last) = if a.p.y < b.p.y {
        (a.above, b.below)
    } else {
        (b.above, a.below)
    };
    let (a, b) = (a.p, b.p);
    for k in first..=last {
        let y = k as f64 * spacing + shift;
        if (a.y <= y) != (b.y <= y) {
            out.push((k, a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)));
        }
    }
}

/// `x.floor()` as an integer, by a truncating cast (no call to the C library's `floor`
/// on targets without SSE 4.1). `x` is bounded: coordinates over the spacing.
fn floor(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) > x { i - 1 } else { i }
}

#[cfg(test)]
fn ceil(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) < x { i + 1 } else { i }
}

/// A honeycomb of side `side` whose "vertical" walls run along θ: in the frame turned by
/// θ − 90°, zigzags along x (two walls per cell) joined by walls along y (one per cell),
/// three walls of length `side` per cell of area `3√3/2·side²`.
pub(crate) fn hexagons(
    region: &Region,
    centre: Coord,
    theta: f64,
    side: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let frame = Frame::new(centre, theta - std::f64::consts::FRAC_PI_2);
    let mut edges = Edges::new(region.rings(), &frame);
    let a = side;
    let half = 3f64.sqrt() * a / 2.0;
    let row = 1.5 * a;
    let (min, max) = (edges.min, edges.max);
    let j0 = (min.y / row).floor() as i64 - 2;
    let j1 = (max.y / row).ceil() as i64 + 1;
    let mut zigzag = Vec::new();
    let mut local = Vec::new();
    for j in j0..=j1 {
        let y = j as f64 * row;
        // Odd rows are shifted by half a cell.
        let cx = if j.rem_euclid(2) == 1 { half } else { 0.0 };
        // High points at cx + m·2·half, low points half-way between.
        let i0 = ((min.x - cx) / half).floor() as i64 - 2;
        let i1 = ((max.x - cx) / half).ceil() as i64 + 2;
        let i0 = i0 - i0.rem_euclid(2);
        zigzag.clear();
        for i in i0..=i1 {
            let x = cx + i as f64 * half;
            let high = i.rem_euclid(2) == 0;
            zigzag.push(Coord {
                x,
                y: y + if high { a } else { a / 2.0 },
            });
            if high && y + a <= max.y && y + 2.0 * a >= min.y && x >= min.x && x <= max.x {
                // The wall from this high point up to the next zigzag's low point.
                local.clear();
                edges.clip(
                    &[Coord { x, y: y + a }, Coord { x, y: y + 2.0 * a }],
                    &mut local,
                );
                out.extend(local.drain(..).map(|p| to_world(&frame, p)));
            }
        }
        if y + a < min.y || y + a / 2.0 > max.y {
            continue;
        }
        local.clear();
        edges.clip(&zigzag, &mut local);
        out.extend(local.drain(..).map(|p| to_world(&frame, p)));
    }
}

fn to_world(frame: &Frame, piece: Vec<Coord>) -> Vec<Coord> {
    piece.into_iter().map(|q| frame.to_world(q)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// `scan_lines` as it was: the heights' bounds one by one, and each line's edges
    /// one by one, the side of each edge's start carried from the edge before.
    fn scan_lines_each(
        rings: &[Vec<Coord>],
        frame: &Frame,
        spacing: f64,
        shift: f64,
        inv: f64,
    ) -> Vec<(i64, f64)> {
        let mut out = Vec::new();
        let local: Vec<f64> = rings
            .iter()
            .flat_map(|ring| ring.iter().map(|&p| frame.to_local(p).y))
            .collect();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &q in &local {
            if q < lo {
                lo = q;
            }
            if q > hi {
                hi = q;
            }
        }
        if local.is_empty() {
            return out;
        }
        let first = Vertex::new(Coord { x: 0.0, y: lo }, shift, inv).above;
        let last = Vertex::new(Coord { x: 0.0, y: hi }, shift, inv).below;
        for k in first..=last {
            let y = k as f64 * spacing + shift;
            let mut from = 0;
            for ring in rings {
                let r = &local[from..from + ring.len()];
                from += ring.len();
                let Some(&last) = r.last() else {
                    continue;
                };
                let mut below = last <= y;
                for (i, &b) in r.iter().enumerate() {
                    let b_below = b <= y;
                    if below != b_below {
                        let before = if i == 0 { ring.len() - 1 } else { i - 1 };
                        let (a, b) = (frame.to_local(ring[before]), frame.to_local(ring[i]));
                        out.push((k, a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)));
                    }
                    below = b_below;
                }
            }
        }
        out
    }

    proptest! {
        /// The lines scanned with the heights' bounds taken two at a time and a long
        /// ring's edges eight at a time (`BLOCKS`) cross the rings where the scan of
        /// each edge does, in the same order, to the bit: rings of every length about
        /// the blocks' (a ring shorter than `BLOCKS` by the plain scan, longer ones with
        /// edges left over or none), vertices on the lines (whole heights at a whole
        /// spacing, unturned) or anywhere, several rings, any spacing and shift.
        #[test]
        fn lines_scanned_by_blocks_are_the_lines_scanned_edge_by_edge(
            rings in prop::collection::vec(
                prop::collection::vec((-10.0f64..10.0, -6i32..6, -6.0f64..6.0), 3..42),
                1..4,
            ),
            on_lines in any::<bool>(),
            theta in prop_oneof![Just(0.0f64), -7.0f64..7.0],
            spacing in prop_oneof![Just(1.0f64), 0.2f64..8.0],
            shift in prop_oneof![Just(0.0f64), 0.0f64..1.0],
        ) {
            let rings: Vec<Vec<Coord>> = rings
                .into_iter()
                .map(|ring| {
                    ring.into_iter()
                        .map(|(x, whole, y)| Coord { x, y: if on_lines { whole as f64 } else { y } })
                        .collect()
                })
                .collect();
            let frame = Frame::new(Coord::zero(), theta);
            let shift = shift * spacing;
            let inv = 1.0 / spacing;
            let (mut local, mut scanned) = (Vec::new(), Vec::new());
            scan_lines(&rings, &frame, spacing, shift, inv, &mut local, &mut scanned);
            let each = scan_lines_each(&rings, &frame, spacing, shift, inv);
            let bits = |v: &[(i64, f64)]| v.iter().map(|&(k, x)| (k, x.to_bits())).collect::<Vec<_>>();
            prop_assert_eq!(bits(&scanned), bits(&each));
        }

        /// A vertex's range of lines from one floor is the two roundings of `t ∓ margin`,
        /// whole lines and their neighbours within a few margins included.
        #[test]
        fn lines_from_one_floor_are_the_two_roundings(
            k in -100_000_000i64..100_000_000,
            off in prop_oneof![
                -1.0f64..1.0,
                -1e-8f64..1e-8,
                Just(0.0),
                Just(1e-9),
                Just(-1e-9),
            ],
            spacing in prop_oneof![0.01f64..100.0, Just(0.5)],
            shift in -5.0f64..5.0,
        ) {
            let t_wanted = k as f64 + off;
            let y = t_wanted * spacing + shift;
            let p = Coord { x: 0.0, y };
            let inv = 1.0 / spacing;
            let v = Vertex::new(p, shift, inv);
            let t = (y - shift) * inv;
            let margin = 1e-9 + 1e-12 * t.abs();
            prop_assert_eq!(v.above, ceil(t - margin));
            prop_assert_eq!(v.below, floor(t + margin));
        }
    }
}
