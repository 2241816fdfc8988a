//! Travel moves that stay inside the region, as slicers route them ("avoid crossing
//! walls"): a straight move that would cross a hole, or leave a concave outline, goes
//! around along that ring instead, the shorter way.
//!
//! Plain square roots, not `hypot` (several times slower; coordinates are bounded by
//! `MAX_COORDINATE`, so nothing overflows).

use geo::Coord;

/// Where a move from `p` to `q` crosses ring `r`: the fraction along the move, and where
/// on the ring (its index, the edge's and the fraction along that edge).
fn hits(ring: &[Coord], r: usize, p: Coord, q: Coord, out: &mut Vec<(f64, Cut)>) {
    let n = ring.len();
    let d = q - p;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let e = b - a;
        let denom = d.x * e.y - d.y * e.x;
        if denom == 0.0 {
            continue;
        }
        let ap = a - p;
        let t = (ap.x * e.y - ap.y * e.x) / denom;
        let u = (ap.x * d.y - ap.y * d.x) / denom;
        if (0.0..=1.0).contains(&t) && (0.0..1.0).contains(&u) {
            out.push((
                t,
                Cut {
                    ring: r,
                    edge: i,
                    u,
                },
            ));
        }
    }
}

/// Where a move crosses a ring.
#[derive(Clone, Copy, Debug)]
struct Cut {
    ring: usize,
    edge: usize,
    /// The fraction along the edge.
    u: f64,
}

/// The rings with their cumulative lengths, ready for many moves.
pub(crate) struct Router<'a> {
    rings: &'a [Vec<Coord>],
    cumulative: Vec<Vec<f64>>,
    /// Each ring's bounding box: a move or point outside it cannot cross it or be in it.
    boxes: Vec<(Coord, Coord)>,
}

impl<'a> Router<'a> {
    pub(crate) fn new(rings: &'a [Vec<Coord>]) -> Router<'a> {
        let cumulative = rings
            .iter()
            .map(|r| {
                let n = r.len();
                let mut c = Vec::with_capacity(n + 1);
                let mut s = 0.0;
                c.push(0.0);
                for i in 0..n {
                    let e = r[(i + 1) % n] - r[i];
                    s += (e.x * e.x + e.y * e.y).sqrt();
                    c.push(s);
                }
                c
            })
            .collect();
        let boxes = rings.iter().map(|r| bounds(r)).collect();
        Router {
            rings,
            cumulative,
            boxes,
        }
    }

    /// The move from `p` to `q`: `[p, q]` when it stays inside, else each stretch that
    /// leaves the region (into a hole, or out of a concave outline) replaced by a walk
    /// along the ring it crossed, the shorter way round.
    pub(crate) fn route(&self, p: Coord, q: Coord) -> Vec<Coord> {
        // No rings: a convex region, where every straight move stays inside.
        if self.rings.iter().any(|r| r.len() < 3) || self.rings.is_empty() {
            return vec![p, q];
        }
        let mut cuts: Vec<(f64, Cut)> = Vec::new();
        let (lo, hi) = (
            Coord {
                x: p.x.min(q.x),
                y: p.y.min(q.y),
            },
            Coord {
                x: p.x.max(q.x),
                y: p.y.max(q.y),
            },
        );
        for (r, ring) in self.rings.iter().enumerate() {
            let (a, b) = self.boxes[r];
            if hi.x < a.x || lo.x > b.x || hi.y < a.y || lo.y > b.y {
                continue;
            }
            hits(ring, r, p, q, &mut cuts);
        }
        // The usual move, between two ends on a ring and across nothing: straight.
        let interior = |t: f64| t > 1e-9 && t < 1.0 - 1e-9;
        if !cuts.iter().any(|&(t, _)| interior(t)) && self.inside((p + q) / 2.0) {
            return vec![p, q];
        }
        // A move between two points of one ring (line ends lie on the inset's rings) may
        // find no crossing at all, its ends being on the ring: the middle of each
        // stretch decides whether it is inside.
        cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let at = |t: f64| if t >= 1.0 { q } else { p + (q - p) * t };
        let mut bounds: Vec<(f64, Option<Cut>)> = vec![(0.0, None)];
        bounds.extend(cuts.into_iter().map(|(t, c)| (t, Some(c))));
        bounds.push((1.0, None));
        let mut out = vec![p];
        for w in bounds.windows(2) {
            let ((ta, ra), (tb, rb)) = (w[0], w[1]);
            let (a, b) = (at(ta), at(tb));
            let move2 = (q - p).x * (q - p).x + (q - p).y * (q - p).y;
            if (tb - ta) * move2.sqrt() < 1e-6 || self.inside(at((ta + tb) / 2.0)) {
                out.push(b);
                continue;
            }
            let r = ra
                .or(rb)
                .map_or_else(|| self.nearest(at((ta + tb) / 2.0)), |c| c.ring);
            // Where each end is on ring r: known for a crossing, else projected.
            let place = |cut: Option<Cut>, p: Coord| match cut {
                Some(c) if c.ring == r => {
                    let cumulative = &self.cumulative[r];
                    let (s0, s1) = (cumulative[c.edge], cumulative[c.edge + 1]);
                    (c.edge, s0 + c.u * (s1 - s0))
                }
                _ => self.project(r, p),
            };
            out.extend(self.walk(r, place(ra, a), place(rb, b)));
            out.push(b);
        }
        out.dedup();
        out
    }

    /// Even-odd over every ring; a point on an edge (within a nanometre) counts as
    /// inside: a move along an edge (between two line ends on one side of the outline)
    /// stays on the boundary, and need not be walked around.
    fn inside(&self, p: Coord) -> bool {
        const ON: f64 = 1e-6 * 1e-6;
        let mut inside = false;
        for (ring, &(lo, hi)) in self.rings.iter().zip(&self.boxes) {
            if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
                continue;
            }
            let n = ring.len();
            for i in 0..n {
                let (a, b) = (ring[i], ring[(i + 1) % n]);
                if (a.y <= p.y) != (b.y <= p.y)
                    && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x
                {
                    inside = !inside;
                }
                if p.y >= a.y.min(b.y) - 1e-6
                    && p.y <= a.y.max(b.y) + 1e-6
                    && p.x >= a.x.min(b.x) - 1e-6
                    && p.x <= a.x.max(b.x) + 1e-6
                {
                    let e = b - a;
                    let c = cross(e, p - a);
                    if c * c <= ON * (e.x * e.x + e.y * e.y) {
                        return true;
                    }
                }
            }
        }
        inside
    }

    /// The ring nearest to `p`.
    fn nearest(&self, p: Coord) -> usize {
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

    /// Where `p` projects on ring `r`: (edge index, distance along the ring).
    fn project(&self, r: usize, p: Coord) -> (usize, f64) {
        let (ring, cumulative) = (&self.rings[r], &self.cumulative[r]);
        let n = ring.len();
        let mut best = (f64::INFINITY, 0, 0.0);
        for i in 0..n {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
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
        (best.1, best.2)
    }

    /// The vertices of ring `r` between two of its points (edge, distance along the ring),
    /// the shorter way.
    fn walk(&self, r: usize, (i0, s0): (usize, f64), (i1, s1): (usize, f64)) -> Vec<Coord> {
        let ring = &self.rings[r];
        let n = ring.len();
        let perimeter = self.cumulative[r][n];
        let forward = (s1 - s0).rem_euclid(perimeter);
        let mut walk = Vec::new();
        if forward <= perimeter - forward {
            let mut i = (i0 + 1) % n;
            if !(i0 == i1 && s1 >= s0) {
                for _ in 0..n {
                    walk.push(ring[i]);
                    if i == i1 {
                        break;
                    }
                    i = (i + 1) % n;
                }
            }
        } else if !(i0 == i1 && s1 <= s0) {
            let mut i = i0;
            for _ in 0..n {
                walk.push(ring[i]);
                i = (i + n - 1) % n;
                if i == i1 {
                    break;
                }
            }
        }
        walk
    }
}

fn cross(a: Coord, b: Coord) -> f64 {
    a.x * b.y - a.y * b.x
}

fn segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    let e = b - a;
    let len2 = e.x * e.x + e.y * e.y;
    let u = if len2 > 0.0 {
        (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c = a + e * u;
    ((p - c).x * (p - c).x + (p - c).y * (p - c).y).sqrt()
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
