//! Filling a region with one layer's pattern: the patterns (straight, curves, lightning)
//! called for the region, their lines simplified and ordered. Apart from the region
//! (`region.rs`, which the patterns read) so that no pattern's file and the region's name
//! each other.

use crate::math;
use geo::{Coord, MultiPolygon};

use super::clip::{Edges, Frame};
use super::{Error, MAX_VERTICES, Order, Params, Pattern, Region, Toolpaths};
use super::{check, curves, lightning, order, straight};

/// Fills `region` (inset by half a nozzle first) with one layer's pattern.
/// For many layers of the same region, build the [`Region`] once and call [`Region::fill`].
pub fn fill(region: &MultiPolygon<f64>, params: &Params) -> Result<Toolpaths, Error> {
    // The outline as given is kept only for concentric loops (offset from it).
    Region::build(region, params.nozzle, params.pattern == Pattern::Concentric)?.fill(params)
}

impl Region {
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
        let edges: usize = self.rings.iter().map(Vec::len).sum();
        if let Some(estimate) = too_large(self.max - self.min, self.area, rho, w, edges) {
            return Err(Error::TooLarge { estimate });
        }
        let centre = match params.centring {
            super::Centring::Object => self.centre(),
            super::Centring::Global => Coord::zero(),
        };
        let theta = turned(params.angle).to_radians();
        // A list kept from one layer to the next (`order` gives it back emptied).
        let mut paths: Vec<Vec<Coord>> = super::scratch::take(&order::PATHS);
        match params.pattern {
            Pattern::Lines => {
                straight::families(self, centre, theta, &[0.0], w / rho, 0.0, &mut paths)
            }
            Pattern::Grid => straight::families(
                self,
                centre,
                theta,
                &[0.0, 90.0],
                2.0 * w / rho,
                0.0,
                &mut paths,
            ),
            Pattern::Triangles => straight::families(
                self,
                centre,
                theta,
                &[0.0, 60.0, 120.0],
                3.0 * w / rho,
                0.0,
                &mut paths,
            ),
            Pattern::Cubic => straight::families(
                self,
                centre,
                theta,
                &[0.0, 120.0, 240.0],
                3.0 * w / rho,
                params.z / std::f64::consts::SQRT_2,
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
                // Branches are spaced along the outline, so how much they cover depends on
                // the shape (a star's long outline gets more): measure a first tree and
                // space the branches again so that the density printed is the one asked.
                // The first tree is kept in one flat list while it is measured (no vector
                // per path), and made paths only if it is the one printed: close enough,
                // or a respacing that gives every outline as many branches (the same
                // tree). Otherwise the second tree is built as paths directly.
                let mut spacing = 2.0 * w / rho;
                // The region's edges (and their grid) serve both trees.
                let mut edges = Edges::new(&self.rings, &lightning::frame(centre));
                // Its lists kept between layers (`scratch`).
                let (mut flat, mut ends, mut length) = (
                    super::scratch::take(&lightning::FLAT),
                    super::scratch::take(&lightning::ENDS),
                    0.0,
                );
                // The outlines' starts and perimeters serve both trees too.
                let outlines = lightning::Outlines::new(self, theta);
                lightning::tree(self, &outlines, centre, spacing, &mut edges, |piece| {
                    flat.extend_from_slice(piece);
                    ends.push(flat.len());
                    // Summed path by path, as the paths' lengths would be.
                    length += super::travel::length(piece);
                });
                let printed = length * w / self.area;
                let respaced = spacing * (printed / rho).clamp(0.25, 4.0);
                if printed.is_nan()
                    || printed <= 0.0
                    || (printed / rho - 1.0).abs() < 0.03
                    || outlines.same_counts(respaced, spacing)
                {
                    let mut start = 0;
                    paths.reserve(ends.len());
                    for &end in &ends {
                        paths.push(flat[start..end].to_vec());
                        start = end;
                    }
                } else {
                    spacing = respaced;
                    lightning::lightning_of(
                        self, &outlines, centre, spacing, &mut edges, &mut paths,
                    );
                }
                super::scratch::give(&lightning::FLAT, flat);
                super::scratch::give(&lightning::ENDS, ends);
            }
        }
        let min_segment = w / 10.0;
        paths.retain_mut(|p| simplify(p, min_segment));
        let monotonic = params.order == Order::Monotonic;
        Ok(order::order(
            paths,
            monotonic.then(|| Frame::new(centre, theta)),
            if self.convex { &[] } else { &self.rings },
        ))
    }
}

/// The estimate of the vertices a layer makes, where it is past `MAX_VERTICES`: every
/// pattern puts about `area·ρ/w` mm of line in the region, curves with a vertex at least
/// every quarter nozzle; and each of the (at most three families of) lines is tested
/// against every edge of the outline (`span`: the region's box). The box's diagonal by
/// a plain square root (within a few units in the last place of `hypot`'s), `hypot`'s
/// only where that estimate comes near the limit (so the answer is `hypot`'s) and for
/// the one reported.
pub(crate) fn too_large(span: Coord, area: f64, rho: f64, w: f64, edges: usize) -> Option<f64> {
    let length = area * rho / w;
    let estimate_of = |extent: f64| {
        let lines = 3.0 * extent * rho / w;
        length / (w / 4.0) + lines * edges as f64 / 8.0
    };
    let estimate = estimate_of((span.x * span.x + span.y * span.y).sqrt());
    if estimate > MAX_VERTICES * (1.0 - 1e-9) {
        let estimate = estimate_of(math::hypot(span.x, span.y));
        return (estimate > MAX_VERTICES).then_some(estimate);
    }
    None
}

/// An angle (degrees) turned into [0, 360): `rem_euclid(360)`, not called for an angle
/// already there (its `fmod` returns it exactly).
pub(crate) fn turned(angle: f64) -> f64 {
    if (0.0..360.0).contains(&angle) {
        angle
    } else {
        angle.rem_euclid(360.0)
    }
}

/// `order::simplify`, told without a write where it would change nothing (every
/// segment at least `min` long: most of a loop's or a line's), so it is not run.
pub(crate) fn simplify(path: &mut Vec<Coord>, min: f64) -> bool {
    let min2 = min * min;
    // `simplify`'s distances: each point from the one before (all kept); the last
    // segment first (a clipped curve's short one is there most often).
    let long = |path: &[Coord]| {
        let short = |a: Coord, b: Coord| {
            let d = b - a;
            d.x * d.x + d.y * d.y < min2
        };
        let n = path.len();
        if short(path[n - 2], path[n - 1]) {
            return false;
        }
        let mut a = path[0];
        for &b in &path[1..n - 1] {
            if short(a, b) {
                return false;
            }
            a = b;
        }
        true
    };
    (path.len() >= 2 && long(path)) || order::simplify(path, min)
}

#[cfg(test)]
mod tests {
    use geo::Coord;
    use proptest::prelude::*;

    proptest! {
        /// The layer's estimate told with a plain square root is the one told with
        /// `hypot` (the former), error or not, to the bit where reported: boxes, areas,
        /// densities and edge counts about the limit; and angles turned without
        /// `rem_euclid` in [0, 360) are its (negative zero, 360 and beyond included).
        #[test]
        fn estimate_and_angle_told_cheaply_are_the_former(
            span in (0.0f64..2e6, 0.0f64..2e6),
            area in 0.0f64..4e12,
            rho in 0.01f64..1.0,
            w in 0.1f64..1.0,
            edges in 3usize..100_000,
            near in any::<bool>(),
            angle in prop::sample::select(vec![-720.5, -0.0, 0.0, 45.0, 359.999, 360.0, 1e6, f64::NAN]),
            random_angle in -1e4f64..1e4,
        ) {
            let span = Coord { x: span.0, y: span.1 };
            let estimate = |span: Coord, area: f64, edges: usize| {
                let extent = crate::math::hypot(span.x, span.y);
                let length = area * rho / w;
                let lines = 3.0 * extent * rho / w;
                length / (w / 4.0) + lines * edges as f64 / 8.0
            };
            let former = |span: Coord, area: f64, edges: usize| {
                let estimate = estimate(span, area, edges);
                (estimate > super::MAX_VERTICES).then_some(estimate)
            };
            // Scaled to within a few units in the last place of the limit, either side (the
            // box first made small enough for its lines to leave room).
            let span = if near {
                let lines = estimate(span, 0.0, edges);
                span * (0.5 * super::MAX_VERTICES / lines.max(1.0)).min(1.0)
            } else {
                span
            };
            let area = if near {
                let rest = (super::MAX_VERTICES - estimate(span, 0.0, edges)).max(0.0);
                rest * (w / 4.0) * w / rho
            } else {
                area
            };
            for nudge in [-4.0, -1.0, 0.0, 1.0, 4.0] {
                let area = area * (1.0 + nudge * f64::EPSILON);
                let (got, want) = (super::too_large(span, area, rho, w, edges), former(span, area, edges));
                prop_assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
            }
            // What the square root's estimate relies on: a few units in the last place.
            let (fast, exact) = ((span.x * span.x + span.y * span.y).sqrt(), crate::math::hypot(span.x, span.y));
            prop_assert!((fast - exact).abs() <= 1e-15 * exact);
            for a in [angle, random_angle] {
                prop_assert_eq!(super::turned(a).to_bits(), a.rem_euclid(360.0).to_bits());
            }
        }

        /// Paths whose every segment is long enough are kept as they are without a
        /// write: the same paths and answers as `order::simplify` on random paths
        /// (short segments, none or one point included) at random lengths.
        #[test]
        fn simplify_told_without_a_write_is_simplify(
            points in prop::collection::vec((-5.0f64..5.0, -5.0f64..5.0), 0..12),
            min in 0.0f64..3.0,
        ) {
            let path: Vec<Coord> = points.into_iter().map(|(x, y)| Coord { x, y }).collect();
            let (mut fast, mut general) = (path.clone(), path);
            let kept = super::simplify(&mut fast, min);
            prop_assert_eq!(kept, super::order::simplify(&mut general, min));
            prop_assert_eq!(fast, general);
        }
    }
}
