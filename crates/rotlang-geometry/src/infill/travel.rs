//! Travel moves that stay inside the region, as slicers route them ("avoid crossing
//! walls"): a straight move that would cross a hole, or leave a concave outline, goes
//! around along that ring instead, the shorter way.

use geo::Coord;

/// Where a move from `p` to `q` crosses ring `r`: the fractions along the move.
fn hits(ring: &[Coord], r: usize, p: Coord, q: Coord, out: &mut Vec<(f64, usize)>) {
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
            out.push((t, r));
        }
    }
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
                    s += e.x.hypot(e.y);
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
        let mut cuts: Vec<(f64, usize)> = Vec::new();
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
        let mut bounds: Vec<(f64, Option<usize>)> = vec![(0.0, None)];
        bounds.extend(cuts.into_iter().map(|(t, r)| (t, Some(r))));
        bounds.push((1.0, None));
        let mut out = vec![p];
        for w in bounds.windows(2) {
            let ((ta, ra), (tb, rb)) = (w[0], w[1]);
            let (a, b) = (at(ta), at(tb));
            if (tb - ta) * (q - p).x.hypot((q - p).y) < 1e-6 || self.inside(at((ta + tb) / 2.0)) {
                out.push(b);
                continue;
            }
            let r = ra
                .or(rb)
                .unwrap_or_else(|| self.nearest(at((ta + tb) / 2.0)));
            out.extend(self.walk(r, a, b));
            out.push(b);
        }
        out.dedup();
        out
    }

    /// Even-odd over every ring.
    fn inside(&self, p: Coord) -> bool {
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
            let d = (p - c).x.hypot((p - c).y);
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

    /// The vertices of ring `r` between the points nearest `a` and `b`, the shorter way.
    fn walk(&self, r: usize, a: Coord, b: Coord) -> Vec<Coord> {
        let ring = &self.rings[r];
        let n = ring.len();
        let perimeter = self.cumulative[r][n];
        let ((i0, s0), (i1, s1)) = (self.project(r, a), self.project(r, b));
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

fn segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    let e = b - a;
    let len2 = e.x * e.x + e.y * e.y;
    let u = if len2 > 0.0 {
        (((p - a).x * e.x + (p - a).y * e.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c = a + e * u;
    (p - c).x.hypot((p - c).y)
}

pub(crate) fn length(path: &[Coord]) -> f64 {
    path.windows(2)
        .map(|w| (w[1] - w[0]).x.hypot((w[1] - w[0]).y))
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
