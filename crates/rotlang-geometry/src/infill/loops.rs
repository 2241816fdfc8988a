//! The boundary of a region's erosion by `d` as closed rings, for concentric loops, where
//! parts pinch off or a grown hole meets the outline: the raw offset of every ring (edges
//! moved by `d`, convex corners mitred, reflex corners an arc about the vertex) is cut
//! where it crosses itself or another ring's, and the pieces that stay `d` from the
//! boundary are chained back into rings. The erosion's boundary is made of exactly those
//! pieces; no polygon is rebuilt, which is what made geo's buffer and boolean difference
//! cost 10–40 µs a loop. `None` where the offset touches itself without crossing (a
//! tangency) or a chain does not close: the buffer decides then.

use geo::{Coord, MultiPolygon};

use super::offset::{cross, inside_left};

/// More raw segments than this go to the buffer (the crossing sweep could go quadratic).
const MAX_SEGMENTS: usize = 20_000;

/// The rings (closed: first point = last) bounding the erosion of `region` by `d`, arcs in
/// steps of at most `arc` radians, each with the inside on its left (outlines
/// counter-clockwise, holes clockwise). Empty when nothing is left.
pub(crate) fn eroded_rings(
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
            if keep(&pts, &raw.centres, 0, &boundary, d) {
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
            // The segments the piece runs along, for the arc centre of its test point.
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
            if keep(&pts, &raw.centres, first, &boundary, d) {
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
    let unit = |e: Coord| e / e.x.hypot(e.y);
    let left = |u: Coord| Coord { x: -u.y, y: u.x };
    let mut out = Vec::with_capacity(n + n / 2);
    let mut centres = Vec::with_capacity(n + n / 2);
    let cos_arc = arc.cos();
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
            } else {
                // A sharp tip: its mitre would be far away; through the vertex instead
                // (that stretch is nearer the boundary than `d`, and is cut away).
                out.push(b + nu * d);
                centres.push(None);
                out.push(b);
                centres.push(None);
                out.push(b + nv * d);
                centres.push(None);
            }
        } else if dot >= cos_arc {
            // A reflex corner within one step (a round hole's): the mitre, which strays
            // outside the arc no more than a chord inside it, and is one point, not two.
            let k = 1.0 + nu.x * nv.x + nu.y * nv.y;
            out.push(b + (nu + nv) * (d / k));
            centres.push(None);
        } else {
            let angle = turn.atan2(dot);
            let steps = (-angle / arc).ceil().max(1.0) as usize;
            out.push(b + nu * d);
            centres.push(Some(b));
            let (s, co) = (angle / steps as f64).sin_cos();
            let mut w = nu;
            for _ in 1..steps {
                w = Coord {
                    x: w.x * co - w.y * s,
                    y: w.x * s + w.y * co,
                };
                out.push(b + w * d);
                centres.push(Some(b));
            }
            out.push(b + nv * d);
            centres.push(None);
        }
    }
    Some(Raw { pts: out, centres })
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

/// Whether a piece lies on the erosion's boundary: a point in its middle (on the arc, for
/// a chord) at least `d` from every boundary edge and inside the region.
fn keep(
    pts: &[Coord],
    centres: &[Option<Coord>],
    first: usize,
    boundary: &[&[Coord]],
    d: f64,
) -> bool {
    let m = (pts.len() - 2) / 2;
    let mut p = (pts[m] + pts[m + 1]) / 2.0;
    // Segment m of the piece is raw segment first + m (the piece starts inside `first`).
    let n = centres.len();
    if let Some(c) = centres[(first + m) % n] {
        let r = p - c;
        let len = r.x.hypot(r.y);
        if len > 0.0 {
            p = c + r * (d / len);
        }
    }
    let limit = d * (1.0 - 1e-9);
    let mut inside = false;
    for ring in boundary {
        for w in ring.windows(2) {
            let (a, b) = (w[0], w[1]);
            let e = b - a;
            let len2 = e.x * e.x + e.y * e.y;
            let t = if len2 > 0.0 {
                (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let q = a + e * t - p;
            if q.x * q.x + q.y * q.y < limit * limit {
                return false;
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
