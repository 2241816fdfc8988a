//! A layer's region, inset by half a nozzle, ready to be filled many times.

use geo::{Area, Buffer, Coord, LineString, MultiPolygon, Polygon};

use super::clip::Frame;
use super::{Error, MAX_COORDINATE, MAX_VERTICES, Order, Params, Pattern, Toolpaths};
use super::{check, curves, lightning, order, straight};

/// The infill area of a layer: the region inset by half a nozzle.
#[derive(Clone, Debug)]
pub struct Region {
    /// The inset area.
    inset: MultiPolygon<f64>,
    /// The region as given, without degenerate rings: concentric loops are offset from
    /// it (it has fewer vertices than the inset, whose holes have grown arcs).
    outline: MultiPolygon<f64>,
    /// Its rings (outlines and holes) without the repeated closing point.
    rings: Vec<Vec<Coord>>,
    /// How many of `rings` are outlines (they come first).
    outlines: usize,
    /// The bounding box of the region as given (the object centre is its centre).
    min: Coord,
    max: Coord,
    area: f64,
    nozzle: f64,
}

impl Region {
    /// Insets `region` by half of `nozzle`. Coordinates must be finite and within
    /// ±[`MAX_COORDINATE`] mm; rings with fewer than three points or no area are ignored.
    pub fn new(region: &MultiPolygon<f64>, nozzle: f64) -> Result<Region, Error> {
        if !(0.01..=10.0).contains(&nozzle) {
            return Err(Error::Nozzle(nozzle));
        }
        let (mut min, mut max) = (
            Coord {
                x: f64::INFINITY,
                y: f64::INFINITY,
            },
            Coord {
                x: f64::NEG_INFINITY,
                y: f64::NEG_INFINITY,
            },
        );
        for polygon in &region.0 {
            for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
                for c in ring.coords() {
                    for v in [c.x, c.y] {
                        if !(v.is_finite() && v.abs() <= MAX_COORDINATE) {
                            return Err(Error::Coordinate(v));
                        }
                    }
                    min = Coord {
                        x: min.x.min(c.x),
                        y: min.y.min(c.y),
                    };
                    max = Coord {
                        x: max.x.max(c.x),
                        y: max.y.max(c.y),
                    };
                }
            }
        }
        let cleaned = clean(region);
        let inset = convex_inset(&cleaned, nozzle / 2.0).unwrap_or_else(|| {
            if cleaned.0.is_empty() {
                cleaned.clone()
            } else {
                cleaned.buffer(-nozzle / 2.0)
            }
        });
        let mut rings = Vec::new();
        for p in &inset.0 {
            rings.push(open_ring(p.exterior()));
        }
        let outlines = rings.len();
        for p in &inset.0 {
            rings.extend(p.interiors().iter().map(open_ring));
        }
        rings.retain(|r| r.len() >= 3);
        let area = inset.unsigned_area();
        if !min.x.is_finite() {
            min = Coord::zero();
            max = Coord::zero();
        }
        Ok(Region {
            inset,
            outline: cleaned,
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
        &self.inset
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

    /// The rings of the inset: outlines first, then holes.
    pub(crate) fn rings(&self) -> &[Vec<Coord>] {
        &self.rings
    }

    pub(crate) fn outlines(&self) -> &[Vec<Coord>] {
        &self.rings[..self.outlines.min(self.rings.len())]
    }

    /// Fills the inset with one layer's pattern. `params.nozzle` should be the one the
    /// region was inset for; a different one is used for the lines but not re-inset.
    pub fn fill(&self, params: &Params) -> Result<Toolpaths, Error> {
        check(params)?;
        if self.rings.is_empty() || self.area <= 0.0 {
            return Ok(Toolpaths::default());
        }
        let w = params.nozzle;
        let rho = params.density;
        // Every pattern puts about `area·ρ/w` mm of line in the region, curves with a
        // vertex at least every quarter nozzle; and each of the (at most three families
        // of) lines is tested against every edge of the outline.
        let extent = (self.max - self.min).x.hypot((self.max - self.min).y);
        let edges: usize = self.rings.iter().map(Vec::len).sum();
        let length = self.area * rho / w;
        let lines = 3.0 * extent * rho / w;
        let estimate = length / (w / 4.0) + lines * edges as f64 / 8.0;
        if estimate > MAX_VERTICES {
            return Err(Error::TooLarge { estimate });
        }
        let centre = match params.centring {
            super::Centring::Object => self.centre(),
            super::Centring::Global => Coord::zero(),
        };
        let theta = params.angle.rem_euclid(360.0).to_radians();
        let mut paths: Vec<Vec<Coord>> = Vec::new();
        match params.pattern {
            Pattern::Lines => straight::families(self, centre, theta, &[0.0], w / rho, &mut paths),
            Pattern::Grid => {
                straight::families(self, centre, theta, &[0.0, 90.0], 2.0 * w / rho, &mut paths)
            }
            Pattern::Triangles => straight::families(
                self,
                centre,
                theta,
                &[0.0, 60.0, 120.0],
                3.0 * w / rho,
                &mut paths,
            ),
            Pattern::Hexagons => {
                let side = 2.0 * w / (3f64.sqrt() * rho);
                straight::hexagons(self, centre, theta, side, &mut paths);
            }
            Pattern::Concentric => curves::concentric(self, theta, w / rho, &mut paths),
            Pattern::Gyroid => {
                let scale = w * super::GYROID_LAMBDA / rho;
                curves::gyroid(self, centre, theta, scale, params.z, &mut paths);
            }
            Pattern::Spiral => curves::spiral(self, centre, theta, w / rho, &mut paths),
            Pattern::Lightning => {
                lightning::lightning(self, centre, theta, 2.0 * w / rho, &mut paths)
            }
        }
        let min_segment = w / 10.0;
        paths.retain_mut(|p| order::simplify(p, min_segment));
        let monotonic = params.order == Order::Monotonic;
        Ok(order::order(paths, monotonic, Frame::new(centre, theta)))
    }
}

/// The region without degenerate rings, every ring closed.
fn clean(region: &MultiPolygon<f64>) -> MultiPolygon<f64> {
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

/// The exact inward offset of one convex polygon without holes; `None` when the region
/// is anything else (then geo's general buffer does it). Most layers of most parts are convex, and
/// this is a hundred times faster than the general offset.
pub(crate) fn convex_inset(region: &MultiPolygon<f64>, d: f64) -> Option<MultiPolygon<f64>> {
    let [polygon] = region.0.as_slice() else {
        return None;
    };
    if !polygon.interiors().is_empty() {
        return None;
    }
    let mut pts = open_ring(polygon.exterior());
    // Counter-clockwise, without collinear vertices (their offset lines are parallel).
    if signed_area(&pts) < 0.0 {
        pts.reverse();
    }
    let n = pts.len();
    let mut kept = Vec::with_capacity(n);
    for i in 0..n {
        let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        let cross = cross(b - a, c - b);
        let scale = (b - a).x.hypot((b - a).y) * (c - b).x.hypot((c - b).y);
        if cross < -1e-12 * scale {
            return None; // a reflex vertex: not convex
        }
        if cross > 1e-12 * scale {
            kept.push(b);
        }
    }
    let n = kept.len();
    if n < 3 {
        return None;
    }
    // The inset of a convex polygon is the intersection of its edges' half-planes, each
    // moved inward by d: clip the polygon by each in turn (exact, and empty when the
    // polygon is thinner than 2d).
    let mut out = kept.clone();
    let mut next = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (a, b) = (kept[i], kept[(i + 1) % n]);
        let dir = b - a;
        let len = dir.x.hypot(dir.y);
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
            return Some(MultiPolygon::new(vec![]));
        }
    }
    if signed_area(&out) <= 0.0 {
        return Some(MultiPolygon::new(vec![]));
    }
    out.push(out[0]);
    Some(MultiPolygon::new(vec![Polygon::new(
        LineString::new(out),
        vec![],
    )]))
}

pub(crate) fn cross(a: Coord, b: Coord) -> f64 {
    a.x * b.y - a.y * b.x
}

pub(crate) fn signed_area(ring: &[Coord]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| cross(ring[i], ring[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}
