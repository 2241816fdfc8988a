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
        // The curves' paths (long: many segments each) kept with their lengths where
        // simplifying left them as they were (measured with the test of their segments:
        // `order` sums them again only for the others). The lines' (a segment or a few
        // each) are measured by `order` (keeping the list would cost more).
        let curves = matches!(
            params.pattern,
            Pattern::Concentric | Pattern::Gyroid | Pattern::Spiral
        );
        let mut lengths = Vec::new();
        if curves {
            lengths = super::scratch::take(&order::LENGTHS);
            simplify_all_measured(&mut paths, min_segment, &mut lengths);
        } else {
            paths.retain_mut(|p| simplify(p, min_segment));
        }
        let monotonic = (params.order == Order::Monotonic).then(|| Frame::new(centre, theta));
        let rings: &[Vec<Coord>] = if self.convex { &[] } else { &self.rings };
        let left = !self.convex && self.one_ring_left();
        // Concentric loops lie well inside the region: their moves are asked of the
        // region's outline first (`Region::clear_inside`).
        Ok(
            if params.pattern == Pattern::Concentric && self.proves_inside() {
                order::order_inside(paths, lengths, monotonic, rings, left, self)
            } else {
                order::order(paths, lengths, monotonic, rings, left)
            },
        )
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
    simplify_with::<false>(path, min).0
}

/// Every path simplified (`simplify_measured`), those left out dropped, and each kept
/// one's measured length pushed onto `lengths` (NaN where not known), in order.
pub(crate) fn simplify_all_measured(paths: &mut Vec<Vec<Coord>>, min: f64, lengths: &mut Vec<f64>) {
    paths.retain_mut(|p| {
        let (kept, length) = simplify_measured(p, min);
        if kept {
            lengths.push(length);
        }
        kept
    });
}

/// [`simplify`], with the path's length where it is left as it was (NaN otherwise): the
/// sum `order` makes of its segments' lengths, in its order (each a square root of the
/// squared length the test of the segment works out, the same bits), so that `order`
/// need not make it again.
pub(crate) fn simplify_measured(path: &mut Vec<Coord>, min: f64) -> (bool, f64) {
    simplify_with::<true>(path, min)
}

/// [`simplify_measured`], the length summed only where `MEASURE` (else 0 where kept as
/// it was).
#[inline(always)]
fn simplify_with<const MEASURE: bool>(path: &mut Vec<Coord>, min: f64) -> (bool, f64) {
    let min2 = min * min;
    // `simplify`'s distances: each point from the one before (all kept); the last
    // segment first (a clipped curve's short one is there most often). The lengths'
    // sum from the first segment on, the last added last (as `order` sums them: from
    // zero, every term a square root, never −0).
    let long = |path: &[Coord]| {
        let squared = |a: Coord, b: Coord| {
            let d = b - a;
            d.x * d.x + d.y * d.y
        };
        let n = path.len();
        let last = squared(path[n - 2], path[n - 1]);
        if last < min2 {
            return None;
        }
        let (mut a, mut length) = (path[0], 0.0);
        for &b in &path[1..n - 1] {
            let segment = squared(a, b);
            if segment < min2 {
                return None;
            }
            if MEASURE {
                length += segment.sqrt();
            }
            a = b;
        }
        Some(if MEASURE { length + last.sqrt() } else { 0.0 })
    };
    if path.len() >= 2
        && let Some(length) = long(path)
    {
        return (true, length);
    }
    (order::simplify(path, min), f64::NAN)
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

        /// Simplifying with the length measured keeps and leaves the paths as
        /// `simplify` does, and gives the length `order` sums (its bits) where the path
        /// is left as it was, NaN where it is not: random paths (short segments, none
        /// or one point, repeated points, closed) at random lengths.
        #[test]
        fn simplify_measured_is_simplify_with_order_s_length(
            points in prop::collection::vec((-5.0f64..5.0, -5.0f64..5.0), 0..12),
            closed in any::<bool>(),
            min in prop_oneof![Just(0.0), 0.0f64..3.0],
        ) {
            let mut path: Vec<Coord> = points.into_iter().map(|(x, y)| Coord { x, y }).collect();
            if closed && !path.is_empty() {
                path.push(path[0]);
            }
            let (mut measured, mut plain) = (path.clone(), path.clone());
            let (kept, length) = super::simplify_measured(&mut measured, min);
            prop_assert_eq!(kept, super::simplify(&mut plain, min));
            prop_assert_eq!(&measured, &plain);
            let summed = measured
                .windows(2)
                .map(|w| {
                    let d = w[1] - w[0];
                    (d.x * d.x + d.y * d.y).sqrt()
                })
                .sum::<f64>();
            if kept && measured == path {
                prop_assert_eq!(length.to_bits(), summed.to_bits());
            } else {
                prop_assert!(length.is_nan());
            }
        }

        /// A layer of one path (or none) laid out without a router gives the toolpaths
        /// (path, length to the bit, no travel) that laying it out with one gives: random
        /// open and closed paths, none to three of them, measured or not, nearest first
        /// and monotonic, in a star (one ring known counter-clockwise) and a holed square.
        #[test]
        fn a_single_path_laid_out_without_a_router_is_laid_out_with_one(
            paths in prop::collection::vec(
                (
                    prop::collection::vec((-4.0f64..4.0, -4.0f64..4.0, any::<bool>()), 2..8),
                    any::<bool>(),
                ),
                0..4,
            ),
            measure in any::<bool>(),
            holed in any::<bool>(),
            monotonic in any::<bool>(),
        ) {
            // Some points a hundredth of a millimetre from the one before: simplified
            // away, the path's measured length not known (NaN).
            let mut paths: Vec<Vec<Coord>> = paths
                .into_iter()
                .map(|(points, closed)| {
                    let mut p: Vec<Coord> = Vec::new();
                    for (x, y, near) in points {
                        p.push(match p.last() {
                            Some(&c) if near => c + Coord { x: 0.01, y: 0.0 },
                            _ => Coord { x, y },
                        });
                    }
                    if closed {
                        p.push(p[0]);
                    }
                    p
                })
                .collect();
            let mut lengths = Vec::new();
            super::simplify_all_measured(&mut paths, 0.04, &mut lengths);
            if !measure {
                lengths.clear();
            }
            let region = crate::infill::Region::new(
                &if holed {
                    crate::infill::shapes::holed_square(20.0, 5.0)
                } else {
                    crate::infill::shapes::star(10.0, 4.5)
                },
                0.4,
            )
            .unwrap();
            let left = region.one_ring_left();
            let frame = monotonic.then(|| super::Frame::new(Coord { x: 1.0, y: -2.0 }, 0.7));
            let routed = super::order::order_with(
                paths.clone(), lengths.clone(), frame, region.rings(), left, true, None,
            );
            let plain = super::order::order(paths, lengths, frame, region.rings(), left);
            prop_assert_eq!(plain.length.to_bits(), routed.length.to_bits());
            prop_assert_eq!(plain.travel.to_bits(), routed.travel.to_bits());
            prop_assert_eq!(plain.polylines, routed.polylines);
            prop_assert_eq!(plain.travels, routed.travels);
        }

        /// Ordering paths with the lengths simplifying measured gives the toolpaths
        /// (paths, travel, length to the bit) ordering them without: random open and
        /// closed paths (some turned round by the nearest-first order, some lengths not
        /// known), up to the scan's 64 and past them, in a convex region and a holed
        /// one, nearest first and monotonic.
        #[test]
        fn ordering_with_measured_lengths_is_ordering_without(
            paths in prop::collection::vec(
                (prop::collection::vec((-9.0f64..9.0, -9.0f64..9.0), 2..8), any::<bool>()),
                1..80,
            ),
            min in prop_oneof![Just(0.0), 0.0f64..1.0],
            holed in any::<bool>(),
            monotonic in any::<bool>(),
        ) {
            let mut paths: Vec<Vec<Coord>> = paths
                .into_iter()
                .map(|(points, closed)| {
                    let mut p: Vec<Coord> = points.into_iter().map(|(x, y)| Coord { x, y }).collect();
                    if closed {
                        p.push(p[0]);
                    }
                    p
                })
                .collect();
            let mut lengths = Vec::new();
            super::simplify_all_measured(&mut paths, min, &mut lengths);
            let region = crate::infill::Region::new(
                &if holed {
                    crate::infill::shapes::holed_square(20.0, 5.0)
                } else {
                    crate::infill::shapes::square(20.0)
                },
                0.4,
            )
            .unwrap();
            let frame = monotonic.then(|| super::Frame::new(Coord { x: 1.0, y: -2.0 }, 0.7));
            let with = super::order::order(paths.clone(), lengths, frame, region.rings(), false);
            let without = super::order::order(paths, Vec::new(), frame, region.rings(), false);
            prop_assert_eq!(with.length.to_bits(), without.length.to_bits());
            prop_assert_eq!(with.travel.to_bits(), without.travel.to_bits());
            prop_assert_eq!(with.polylines, without.polylines);
            prop_assert_eq!(with.travels, without.travels);
        }
    }
}
