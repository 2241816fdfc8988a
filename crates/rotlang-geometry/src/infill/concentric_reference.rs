//! The concentric loops as they were computed before `concentric.rs` and `loops::Eroder`
//! (each loop's erosion from scratch, every point tested against every earlier segment):
//! kept for the tests only, which check that the quicker code gives the same loops. Two
//! rules of the erosion were added to both since, in plain code here: a sharp tip closed
//! at its mitre where its moved edges cross (`close_tips`), and a swallowtail that one
//! point cannot decide left to the buffer (`undecided`).

use std::f64::consts::TAU;

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{Buffer, Coord, MultiPolygon};

use crate::infill::Region;
use crate::infill::curves::mitres;
use crate::infill::offset::{cross, inside_left};
use crate::math;

/// Loops at `(k + ½)·spacing` inside the inset outline (and around its holes), each
/// starting at its farthest vertex in direction θ and closed.
pub(crate) fn concentric(region: &Region, theta: f64, spacing: f64, out: &mut Vec<Vec<Coord>>) {
    with_middle_step(region, theta, spacing, super::concentric::MIDDLE_STEP, out);
}

/// As `concentric`, the middle ring's points `step` spacings apart at most (the former
/// code's quarter, for the test of the half).
pub(crate) fn with_middle_step(
    region: &Region,
    theta: f64,
    spacing: f64,
    step: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let direction = Coord {
        x: math::cos(theta),
        y: math::sin(theta),
    };
    // Each loop offset from the inset itself, not from the previous loop: offsets of
    // offsets pile up the arcs at reflex corners.
    // The previous loops' distance and (perimeter, outline rings − hole rings).
    let mut previous: Option<(f64, f64, f64)> = None;
    // The previous loops themselves (closed rings).
    let mut last_loops: Vec<Vec<Coord>> = Vec::new();
    for k in 0.. {
        let mut d = (k as f64 + 0.5) * spacing;
        // From the region itself: the inset's offset by d is its offset by w/2 + d.
        let mut current = shrink(region.outline(), region.nozzle() / 2.0 + d);
        // A region thinner than a spacing still gets one loop, as far in as it can be.
        while k == 0 && current.rings.is_empty() && d > region.nozzle() / 4.0 {
            d /= 2.0;
            current = shrink(region.outline(), region.nozzle() / 2.0 + d);
        }
        let shape = perimeter(&current);
        // Where part of the region ended between the last loops and these (an L's arm),
        // a band up to two spacings wide would stay empty: its middle gets the pieces of
        // a loop half a spacing further in that no loop here is near. (Not where the
        // whole region ends: a last loop there costs more density than the gap.)
        // Offsets shrink each outline's perimeter by 2π per unit (and grow each hole's),
        // and by more at each convex corner still there (`mitres::excess`): a larger
        // drop says a part ended.
        if let Some((d0, length, turns)) = previous {
            let expected = TAU * spacing * turns
                + (d - d0) * mitres::excess(region.outline(), region.nozzle() / 2.0 + d0);
            if !current.rings.is_empty() && length - shape.0 > expected + 4.0 * spacing {
                let middle = shrink(region.outline(), region.nozzle() / 2.0 + d0 + spacing / 2.0);
                uncovered(&middle, &current, &last_loops, spacing, step, out);
            }
        }
        if current.rings.is_empty() {
            break;
        }
        previous = Some((d, shape.0, shape.1));
        last_loops.clear();
        for ring in current.rings {
            let mut pts = ring;
            if pts.len() > 1 && pts.first() == pts.last() {
                pts.pop();
            }
            if pts.len() < 3 {
                continue;
            }
            let start = pts
                .iter()
                .enumerate()
                .max_by(|(_, a), (_, b)| {
                    (a.x * direction.x + a.y * direction.y)
                        .total_cmp(&(b.x * direction.x + b.y * direction.y))
                })
                .map_or(0, |(i, _)| i);
            pts.rotate_left(start);
            pts.push(pts[0]);
            last_loops.push(pts);
        }
        apart(&last_loops, 0.75 * spacing, out);
    }
}

/// The loops of one distance, each less its stretches within `gap` of an earlier one.
/// Where an outline's loop and a hole's approach (the band between them narrower than
/// a spacing, before their offsets meet), both would be printed side by side, down to a
/// fraction of a spacing apart: the later gives way to the earlier there.
fn apart(loops: &[Vec<Coord>], gap: f64, out: &mut Vec<Vec<Coord>>) {
    let boxes: Vec<(Coord, Coord)> = loops
        .iter()
        .map(|l| crate::infill::travel::bounds(l))
        .collect();
    for (j, ring) in loops.iter().enumerate() {
        let (lo, hi) = boxes[j];
        let near: Vec<(&[Coord], (Coord, Coord))> = (0..j)
            .filter(|&i| {
                let (a, b) = boxes[i];
                a.x - gap <= hi.x && b.x + gap >= lo.x && a.y - gap <= hi.y && b.y + gap >= lo.y
            })
            .map(|i| (loops[i].as_slice(), boxes[i]))
            .collect();
        if near.is_empty() {
            out.push(ring.clone());
            continue;
        }
        let flags: Vec<bool> = ring
            .iter()
            .map(|&p| !near.iter().any(|&(l, b)| within(l, b, p, gap)))
            .collect();
        runs(ring, &flags, out);
    }
}

/// Whether `p` is within `r` of a segment of `path` (whose bounds are `bounds`): the
/// same answer as measuring the distance to its nearest segment, without measuring every segment (a point
/// outside the bounds grown by `r` measures none, the first near segment ends it).
fn within(path: &[Coord], bounds: (Coord, Coord), p: Coord, r: f64) -> bool {
    let (lo, hi) = bounds;
    if p.x < lo.x - r || p.x > hi.x + r || p.y < lo.y - r || p.y > hi.y + r {
        return false;
    }
    let r2 = r * r;
    path.windows(2).any(|w| {
        let (a, e) = (w[0], w[1] - w[0]);
        let len2 = e.x * e.x + e.y * e.y;
        let t = if len2 > 0.0 {
            (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = a + e * t;
        (p - q).x * (p - q).x + (p - q).y * (p - q).y <= r2
    })
}

/// The runs of a closed ring's vertices whose flag is set (the whole ring when all are).
fn runs(pts: &[Coord], flags: &[bool], out: &mut Vec<Vec<Coord>>) {
    if flags.iter().all(|&f| f) {
        out.push(pts.to_vec());
        return;
    }
    // Read from an unflagged vertex so that no run wraps.
    let n = pts.len().saturating_sub(1);
    let Some(start) = (0..n).find(|&i| !flags[i]) else {
        return;
    };
    let mut run: Vec<Coord> = Vec::new();
    for k in 1..=n {
        let i = (start + k) % n;
        if flags[i] {
            run.push(pts[i]);
        } else if run.len() >= 2 {
            out.push(std::mem::take(&mut run));
        } else {
            run.clear();
        }
    }
}

/// The total length of a region's rings, and its outline rings less its hole rings.
fn perimeter(area: &Loops) -> (f64, f64) {
    let length = area
        .rings
        .iter()
        .map(|ring| {
            ring.windows(2)
                .map(|w| math::hypot((w[1] - w[0]).x, (w[1] - w[0]).y))
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
    step: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let gap = 0.75 * spacing;
    let covered: Vec<(&[Coord], (Coord, Coord))> = covered
        .rings
        .iter()
        .map(|r| (r.as_slice(), crate::infill::travel::bounds(r)))
        .collect();
    let last: Vec<(&[Coord], (Coord, Coord))> = last
        .iter()
        .map(|r| (r.as_slice(), crate::infill::travel::bounds(r)))
        .collect();
    let far = |p: Coord| {
        // Farther than `gap` from every covered ring (exactly: within is `<=`), and
        // near at most one of the last loops.
        !covered.iter().any(|&(r, b)| within(r, b, p, gap))
            && last
                .iter()
                .filter(|&&(l, b)| within(l, b, p, 2.0 * spacing))
                .nth(1)
                .is_none()
    };
    for ring in &middle.rings {
        // Points every `step` spacing at least (`MIDDLE_STEP`; a quarter in the former
        // code): a ring cut from the raw offset has long edges, and a stretch is kept from
        // vertex to vertex.
        let mut dense = Vec::with_capacity(ring.len());
        for w in ring.windows(2) {
            let e = w[1] - w[0];
            let steps = ((math::hypot(e.x, e.y) / (step * spacing)).ceil() as usize).clamp(1, 1000);
            dense.extend((0..steps).map(|i| w[0] + e * (i as f64 / steps as f64)));
        }
        dense.extend(ring.last().copied());
        let flags: Vec<bool> = dense.iter().map(|&c| far(c)).collect();
        let mut pieces = Vec::new();
        runs(&dense, &flags, &mut pieces);
        // A stretch shorter than a spacing (a star's tip) leaves no gap worth a line.
        out.extend(pieces.into_iter().filter(|p| {
            p.windows(2)
                .map(|w| math::hypot((w[1] - w[0]).x, (w[1] - w[0]).y))
                .sum::<f64>()
                >= spacing
        }));
    }
}

/// A region's rings (closed), and its outline rings less its hole rings.
struct Loops {
    rings: Vec<Vec<Coord>>,
    turns: f64,
}

/// The loops' offsets: arcs in steps of 0.5 rad (not geo's 0.2): the loops are far from
/// the outline, and a third of the vertices makes the offset three times quicker. Where
/// the region is not convex, the raw offset cut where it crosses itself
/// (`loops::eroded_rings`): parts pinching off and holes meeting the outline cost no
/// polygon rebuilt.
fn shrink(area: &MultiPolygon<f64>, d: f64) -> Loops {
    // A convex region without holes: its exact inset is cheapest. With holes, that
    // inset takes geo's boolean difference once a hole meets the outline.
    let holes = area.0.iter().any(|p| !p.interiors().is_empty());
    let convex = if holes {
        None
    } else {
        crate::infill::region::convex_inset(area, d, 0.5)
    };
    if convex.is_none()
        && let Some(rings) = eroded_rings(area, d, 0.5)
    {
        let turns = rings
            .iter()
            .map(|r| {
                let twice: f64 = r
                    .windows(2)
                    .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
                    .sum();
                twice.signum()
            })
            .sum();
        return Loops { rings, turns };
    }
    let polygons = convex.unwrap_or_else(|| {
        if holes && let Some(inset) = crate::infill::region::convex_inset(area, d, 0.5) {
            return inset;
        }
        area.buffer_with_style(BufferStyle::new(-d).line_join(LineJoin::Round(0.5)))
    });
    Loops {
        turns: polygons
            .0
            .iter()
            .map(|p| 1.0 - p.interiors().len() as f64)
            .sum(),
        rings: polygons
            .0
            .iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
            .map(|r| r.0.clone())
            .collect(),
    }
}

// The erosion, as `loops.rs` computed it.

/// More raw segments than this go to the buffer (the crossing sweep could go quadratic).
const MAX_SEGMENTS: usize = 20_000;

/// The rings (closed: first point = last) bounding the erosion of `region` by `d`, arcs in
/// steps of at most `arc` radians, each with the inside on its left (outlines
/// counter-clockwise, holes clockwise). Empty when nothing is left.
pub(super) fn eroded_rings(
    region: &MultiPolygon<f64>,
    d: f64,
    arc: f64,
) -> Option<Vec<Vec<Coord>>> {
    let mut boundary: Vec<&[Coord]> = Vec::new();
    let mut raws: Vec<Raw> = Vec::new();
    for polygon in &region.0 {
        for (i, ring) in std::iter::once(polygon.exterior())
            .chain(polygon.interiors())
            .enumerate()
        {
            boundary.push(&ring.0);
            if let Some(raw) = raw_ring(&ring.0, d, arc, i == 0) {
                raws.push(raw);
            }
        }
    }
    if raws.iter().map(|r| r.pts.len()).sum::<usize>() > MAX_SEGMENTS {
        return None;
    }
    let cuts = crossings(&raws)?;
    let fans = fans(&raws);
    let boundary = Boundary {
        rings: boundary,
        fans,
    };
    // Cut every raw ring at its crossings into pieces; keep those `d` from the boundary.
    let mut pieces: Vec<Piece> = Vec::new();
    for (r, raw) in raws.iter().enumerate() {
        let n = raw.pts.len();
        let mut here: Vec<(usize, f64, usize)> = cuts
            .iter()
            .enumerate()
            .flat_map(|(id, c)| {
                let mut v = Vec::with_capacity(2);
                if c.ring[0] == r {
                    v.push((c.seg[0], c.t[0], id));
                }
                if c.ring[1] == r {
                    v.push((c.seg[1], c.t[1], id));
                }
                v
            })
            .collect();
        if here.is_empty() {
            let mut pts = raw.pts.clone();
            pts.push(pts[0]);
            let kept = keep(&pts, &boundary, d);
            // The region's one ring, uncut, with an edge run backwards and turned the
            // wrong way round: inside out, none of it on the erosion.
            let area: f64 = pts.windows(2).map(|w| cross(w[0], w[1])).sum();
            let inverted = raws.len() == 1 && (0..n).any(|i| raw.reversed(i)) && area < 0.0;
            if !inverted && undecided(raw, &pts, 0, kept, &boundary, d) {
                return None;
            }
            if kept && !inverted {
                pieces.push(Piece {
                    pts,
                    from: usize::MAX,
                    to: usize::MAX,
                });
            }
            continue;
        }
        here.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        for k in 0..here.len() {
            let (s0, t0, id0) = here[k];
            let (s1, t1, id1) = here[(k + 1) % here.len()];
            let mut pts = vec![cuts[id0].at];
            // The segments the piece runs along.
            let first = s0;
            let mut s = s0;
            let wraps = k + 1 == here.len();
            if !(s1 == s0 && t1 > t0 && !wraps) {
                loop {
                    s = (s + 1) % n;
                    pts.push(raw.pts[s]);
                    if s == s1 {
                        break;
                    }
                }
            }
            pts.push(cuts[id1].at);
            let kept = keep(&pts, &boundary, d);
            if undecided(raw, &pts, first, kept, &boundary, d) {
                return None;
            }
            if kept {
                pieces.push(Piece {
                    pts,
                    from: id0,
                    to: id1,
                });
            }
        }
    }
    chain(pieces, cuts.len())
}

/// One ring's raw offset: its points (not closed) and, for the segment from each point,
/// the arc's centre where it is a chord of a reflex corner's arc.
struct Raw {
    pts: Vec<Coord>,
    centres: Vec<Option<Coord>>,
    /// For each segment along an edge of the ring, that edge's vertices.
    along: Vec<Option<(Coord, Coord)>>,
}

impl Raw {
    /// Whether segment `i` runs against the edge it was moved from.
    fn reversed(&self, i: usize) -> bool {
        let n = self.pts.len();
        self.along[i % n].is_some_and(|(a, b)| {
            let (s, e) = (self.pts[(i + 1) % n] - self.pts[i % n], b - a);
            s.x * e.x + s.y * e.y < 0.0
        })
    }
}

struct Piece {
    pts: Vec<Coord>,
    /// The cuts it starts and ends at (`usize::MAX`: a whole ring).
    from: usize,
    to: usize,
}

/// Where two raw segments cross: ring, segment and parameter on each, and the point.
struct Cut {
    ring: [usize; 2],
    seg: [usize; 2],
    t: [f64; 2],
    at: Coord,
}

/// The raw offset of one ring toward the region's inside (`exterior`: an outline).
fn raw_ring(ring: &[Coord], d: f64, arc: f64, exterior: bool) -> Option<Raw> {
    let pts = inside_left(ring, exterior)?;
    let n = pts.len();
    let unit = |e: Coord| e / math::hypot(e.x, e.y);
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    let mut out = Vec::with_capacity(n + n / 2);
    let mut centres = Vec::with_capacity(n + n / 2);
    let cos_arc = math::cos(arc);
    let mut tips = Vec::new();
    let mut along = Vec::with_capacity(n + n / 2);
    for i in 0..n {
        let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        let (u, v) = (unit(b - a), unit(c - b));
        let (nu, nv) = (left(u), left(v));
        let turn = cross(u, v);
        let dot = u.x * v.x + u.y * v.y;
        if turn >= 0.0 || dot > 1.0 - 1e-12 {
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            if k >= 0.5 {
                // The mitre, where both moved edges meet.
                out.push(b + (nu + nv) * (d / k));
                centres.push(None);
                along.push(Some((b, c)));
            } else {
                // A sharp tip: its mitre would be far away; through the vertex instead
                // (that stretch is nearer the boundary than `d`, and is cut away).
                tips.push(out.len());
                out.push(b + nu * d);
                centres.push(None);
                out.push(b);
                centres.push(None);
                out.push(b + nv * d);
                centres.push(None);
                along.extend([None, None, Some((b, c))]);
            }
        } else if dot >= cos_arc {
            // A reflex corner within one step (a round hole's): the mitre, which strays
            // outside the arc no more than a chord inside it, and is one point, not two.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            out.push(b + (nu + nv) * (d / k));
            centres.push(None);
            along.push(Some((b, c)));
        } else {
            let angle = math::atan2(turn, dot);
            let steps = (-angle / arc).ceil().max(1.0) as usize;
            out.push(b + nu * d);
            centres.push(Some(b));
            along.push(None);
            let (s, co) = math::sin_cos(angle / steps as f64);
            let mut w = nu;
            for _ in 1..steps {
                w = Coord {
                    x: w.x * co - w.y * s,
                    y: w.x * s + w.y * co,
                };
                out.push(b + w * d);
                centres.push(Some(b));
                along.push(None);
            }
            out.push(b + nv * d);
            centres.push(None);
            along.push(Some((b, c)));
        }
    }
    Some(close_tips(
        Raw {
            pts: out,
            centres,
            along,
        },
        &tips,
    ))
}

/// Each tip's three points (from `at`) made the point where the moved edges on either
/// side cross (the segment into it `e`, the one out `f`), where every tip's do cross
/// properly and two tips in a row keep their mitres in order; otherwise the ring as it is.
fn close_tips(raw: Raw, tips: &[usize]) -> Raw {
    let n = raw.pts.len();
    let at = |i: usize| raw.pts[i % n];
    let mitres: Vec<Option<Coord>> = tips
        .iter()
        .map(|&t| {
            let (p, a, b, q) = (at(t + n - 1), at(t), at(t + 2), at(t + 3));
            let (e, f) = (a - p, q - b);
            let (d1, d2) = (cross(e, b - p), cross(e, q - p));
            let (d3, d4) = (cross(f, p - b), cross(f, a - b));
            let proper = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
            (proper(d1, d2) && proper(d3, d4)).then(|| p + e * (d3 / (d3 - d4)))
        })
        .collect();
    if mitres.iter().all(Option::is_none) {
        return raw;
    }
    for i in 0..tips.len() {
        let j = (i + 1) % tips.len();
        if let (Some(x), Some(y)) = (mitres[i], mitres[j])
            && tips[j] == (tips[i] + 3) % n
        {
            let e = at(tips[j]) - at(tips[i] + 2);
            if (y - x).x * e.x + (y - x).y * e.y <= 0.0 {
                return raw;
            }
        }
    }
    let mut out = Raw {
        pts: Vec::new(),
        centres: Vec::new(),
        along: Vec::new(),
    };
    let mut i = 0;
    while i < n {
        match tips.iter().position(|&t| t == i) {
            Some(k) if mitres[k].is_some() => {
                out.pts.push(mitres[k].expect("a mitre"));
                out.centres.push(None);
                out.along.push(raw.along[i + 2]);
                i += 3;
            }
            _ => {
                out.pts.push(raw.pts[i]);
                out.centres.push(raw.centres[i]);
                out.along.push(raw.along[i]);
                i += 1;
            }
        }
    }
    out
}

/// Whether a piece with a segment run backwards (a swallowtail) is not cut away whole:
/// kept, or another of its segments would be kept. Then the erosion is left to the
/// buffer.
fn undecided(
    raw: &Raw,
    pts: &[Coord],
    first: usize,
    kept: bool,
    boundary: &Boundary,
    d: f64,
) -> bool {
    (0..pts.len() - 1).any(|j| raw.reversed(first + j))
        && (kept
            || (0..pts.len() - 1)
                .any(|j| !raw.reversed(first + j) && keep(&pts[j..=j + 1], boundary, d)))
}

/// Every proper crossing between the raw rings' segments (neighbours excepted); `None`
/// where two touch without crossing.
fn crossings(raws: &[Raw]) -> Option<Vec<Cut>> {
    struct Edge {
        a: Coord,
        b: Coord,
        xlo: f64,
        xhi: f64,
        ring: usize,
        seg: usize,
    }
    let mut edges = Vec::with_capacity(raws.iter().map(|r| r.pts.len()).sum());
    for (r, raw) in raws.iter().enumerate() {
        let n = raw.pts.len();
        for i in 0..n {
            let (a, b) = (raw.pts[i], raw.pts[(i + 1) % n]);
            edges.push(Edge {
                a,
                b,
                xlo: a.x.min(b.x),
                xhi: a.x.max(b.x),
                ring: r,
                seg: i,
            });
        }
    }
    edges.sort_unstable_by(|p, q| p.xlo.total_cmp(&q.xlo));
    let mut cuts = Vec::new();
    for (i, e) in edges.iter().enumerate() {
        let (ylo, yhi) = (e.a.y.min(e.b.y), e.a.y.max(e.b.y));
        for f in &edges[i + 1..] {
            if f.xlo > e.xhi {
                break;
            }
            if f.a.y.max(f.b.y) < ylo || f.a.y.min(f.b.y) > yhi {
                continue;
            }
            if e.ring == f.ring {
                let n = raws[e.ring].pts.len();
                if (e.seg + 1) % n == f.seg || (f.seg + 1) % n == e.seg || e.seg == f.seg {
                    continue;
                }
            }
            let (p, r) = (e.b - e.a, f.b - f.a);
            let d1 = cross(p, f.a - e.a);
            let d2 = cross(p, f.b - e.a);
            let d3 = cross(r, e.a - f.a);
            let d4 = cross(r, e.b - f.a);
            let proper = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
            if proper(d1, d2) && proper(d3, d4) {
                let t = d3 / (d3 - d4);
                let u = d1 / (d1 - d2);
                cuts.push(Cut {
                    ring: [e.ring, f.ring],
                    seg: [e.seg, f.seg],
                    t: [t, u],
                    at: e.a + p * t,
                });
            } else if d1 == 0.0 || d2 == 0.0 || d3 == 0.0 || d4 == 0.0 {
                // Touching or collinear (their boxes overlap): a tangency.
                let on = |a: Coord, b: Coord, c: Coord| {
                    c.x >= a.x.min(b.x)
                        && c.x <= a.x.max(b.x)
                        && c.y >= a.y.min(b.y)
                        && c.y <= a.y.max(b.y)
                };
                if (d1 == 0.0 && on(e.a, e.b, f.a))
                    || (d2 == 0.0 && on(e.a, e.b, f.b))
                    || (d3 == 0.0 && on(f.a, f.b, e.a))
                    || (d4 == 0.0 && on(f.a, f.b, e.b))
                {
                    return None;
                }
            }
        }
    }
    Some(cuts)
}

/// The region's rings as given, and each reflex corner drawn as an arc of chords: its
/// vertex and the chords' ends (the raw points).
struct Boundary<'a> {
    rings: Vec<&'a [Coord]>,
    fans: Vec<(Coord, Vec<Coord>)>,
}

/// Every arc of chords of the raw rings: a run of segments whose centre is one vertex.
fn fans(raws: &[Raw]) -> Vec<(Coord, Vec<Coord>)> {
    let mut out: Vec<(Coord, Vec<Coord>)> = Vec::new();
    for raw in raws {
        let n = raw.pts.len();
        let mut i = 0;
        while i < n {
            let Some(b) = raw.centres[i] else {
                i += 1;
                continue;
            };
            let mut ends = vec![raw.pts[i]];
            while i < n && raw.centres[i] == Some(b) {
                ends.push(raw.pts[(i + 1) % n]);
                i += 1;
            }
            out.push((b, ends));
        }
    }
    out
}

/// Whether a piece lies on the erosion's boundary: the point in its middle inside the
/// region and not near it as the raw offsets are drawn: at least `d` from every boundary
/// edge, except where its foot on an edge is a vertex whose reflex corner is an arc of
/// chords: there near only inside the polygon of the vertex and the chords.
fn keep(pts: &[Coord], boundary: &Boundary, d: f64) -> bool {
    let m = (pts.len() - 2) / 2;
    let p = (pts[m] + pts[m + 1]) / 2.0;
    let limit = d * (1.0 - 1e-9);
    // Inside some arc's chords at the vertex `v` (`None`: no arc there).
    let in_chords = |v: Coord| -> Option<bool> {
        let mut found = None;
        for (b, ends) in &boundary.fans {
            if *b != v {
                continue;
            }
            let x = p - v;
            let inside = ends.windows(2).any(|w| {
                let (a, c) = (w[0] - v, w[1] - v);
                let e = c - a;
                cross(a, x) <= 0.0
                    && cross(x, c) <= 0.0
                    && cross(e, x - a) < -1e-9 * d * math::hypot(e.x, e.y)
            });
            found = Some(found == Some(true) || inside);
        }
        found
    };
    let mut inside = false;
    for ring in &boundary.rings {
        for w in ring.windows(2) {
            let (a, b) = (w[0], w[1]);
            let e = b - a;
            let len2 = e.x * e.x + e.y * e.y;
            let s = if len2 > 0.0 {
                ((p - a).x * e.x + (p - a).y * e.y) / len2
            } else {
                0.0
            };
            let q = a + e * s.clamp(0.0, 1.0) - p;
            if q.x * q.x + q.y * q.y < limit * limit {
                let end = (s <= 0.0 || s >= 1.0).then_some(if s >= 1.0 { b } else { a });
                if end.and_then(in_chords) != Some(false) {
                    return false;
                }
            }
            if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
                inside = !inside;
            }
        }
    }
    inside
}

/// The kept pieces joined end to start at their cuts into closed rings; `None` where a
/// cut has not exactly one piece leaving it.
fn chain(pieces: Vec<Piece>, cuts: usize) -> Option<Vec<Vec<Coord>>> {
    let mut leaving = vec![usize::MAX; cuts];
    let mut rings = Vec::new();
    for (i, p) in pieces.iter().enumerate() {
        if p.from == usize::MAX {
            continue;
        }
        if leaving[p.from] != usize::MAX {
            return None;
        }
        leaving[p.from] = i;
    }
    let mut used = vec![false; pieces.len()];
    for start in 0..pieces.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut ring = pieces[start].pts.clone();
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
                ring.pop();
                ring.extend_from_slice(&pieces[next].pts);
                at = next;
            }
        }
        if ring.len() >= 4 {
            rings.push(ring);
        }
    }
    Some(rings)
}
