//! Cleaning and ordering the paths of a layer.

use geo::{Coord, LineString};

use super::Toolpaths;
use super::clip::Frame;

// Plain square roots, not `hypot` (several times slower, and coordinates are bounded by
// MAX_COORDINATE, so nothing overflows); comparisons use squared distances.
fn dist2(a: Coord, b: Coord) -> f64 {
    let d = b - a;
    d.x * d.x + d.y * d.y
}

fn dist(a: Coord, b: Coord) -> f64 {
    dist2(a, b).sqrt()
}

/// Drops vertices closer than `min` to the previous one, keeping both ends; `false` when
/// the whole path is shorter than `min` (a sliver at a corner: nothing to print).
/// A dropped vertex moves the path by less than `min`.
pub(crate) fn simplify(path: &mut Vec<Coord>, min: f64) -> bool {
    let n = path.len();
    let Some(&end) = path.last() else {
        return false;
    };
    let min2 = min * min;
    if n == 2 {
        // A line: kept whole, or cut down to its start when too short.
        let long = dist2(path[0], end) >= min2;
        if !long {
            path.truncate(1);
        }
        return long;
    }
    // The last vertex kept is carried in a register, not read back. Until a first vertex
    // is dropped (most paths drop none) every vertex stays where it is: nothing written.
    let mut last = path[0];
    let mut i = 1;
    while i + 1 < n {
        let c = path[i];
        // Kept as `simplify_each` keeps it: at least `min` away (a NaN is dropped).
        if dist2(last, c) >= min2 {
            last = c;
            i += 1;
        } else {
            break;
        }
    }
    // From the first vertex dropped, the ones kept move down.
    let mut kept = i;
    for j in i + 1..n.saturating_sub(1) {
        let c = path[j];
        if dist2(last, c) >= min2 {
            path[kept] = c;
            kept += 1;
            last = c;
        }
    }
    // The kept vertices too near the end give way to it (`last` is the last kept).
    let mut d = dist2(last, end);
    while kept > 1 && d < min2 {
        kept -= 1;
        d = dist2(path[kept - 1], end);
    }
    path.truncate(kept);
    if d >= min2 {
        path.push(end);
    }
    path.len() >= 2
}

/// `simplify` as it was: each vertex measured against the last kept one read back
/// (tests compare the two).
#[cfg(test)]
pub(crate) fn simplify_each(path: &mut Vec<Coord>, min: f64) -> bool {
    let Some(&end) = path.last() else {
        return false;
    };
    let min2 = min * min;
    let mut kept = 1;
    for i in 1..path.len() - 1 {
        if dist2(path[kept - 1], path[i]) >= min2 {
            path[kept] = path[i];
            kept += 1;
        }
    }
    path.truncate(kept);
    while path.len() > 1 && dist2(path[path.len() - 1], end) < min2 {
        path.pop();
    }
    if dist2(path[path.len() - 1], end) >= min2 {
        path.push(end);
    }
    path.len() >= 2
}

/// Puts the paths in print order and measures them; travel between them is routed
/// inside `rings` (the inset's outlines and holes). `monotonic`: the pattern's frame
/// for a monotonic order (made only then: its sine and cosine), else nearest first.
/// `lengths`: each path's length as this would sum it, where known (NaN where not, or
/// none at all; `simplify_measured`'s), given back emptied. `left`: `rings` is one ring
/// known counter-clockwise (`Region::one_ring_left`; `Router::told`).
pub(crate) fn order(
    paths: Vec<Vec<Coord>>,
    lengths: Vec<f64>,
    monotonic: Option<Frame>,
    rings: &[Vec<Coord>],
    left: bool,
) -> Toolpaths {
    order_with(paths, lengths, monotonic, rings, left, false, None)
}

/// [`order`] of paths whose ends lie well inside `region` (concentric loops): each move
/// asked of `Region::clear_inside` first, straight where it proves it inside, the
/// router made only for one it does not.
pub(crate) fn order_inside(
    paths: Vec<Vec<Coord>>,
    lengths: Vec<f64>,
    monotonic: Option<Frame>,
    rings: &[Vec<Coord>],
    left: bool,
    region: &super::Region,
) -> Toolpaths {
    order_with(paths, lengths, monotonic, rings, left, false, Some(region))
}

/// [`order`], the router made even for a single path (no move to route) where
/// `always_route` (tests compare the two), each move asked of `inside` first where
/// given ([`order_inside`]).
pub(crate) fn order_with(
    paths: Vec<Vec<Coord>>,
    mut lengths: Vec<f64>,
    monotonic: Option<Frame>,
    rings: &[Vec<Coord>],
    left: bool,
    always_route: bool,
    inside: Option<&super::Region>,
) -> Toolpaths {
    let ordered = match monotonic {
        Some(frame) => {
            // (Paths turned round: their lengths summed again.)
            lengths.clear();
            monotonic_order(paths, &frame)
        }
        None => nearest_measured(paths, &mut lengths),
    };
    // A length for each path, or none.
    let measured = lengths.len() == ordered.len();
    let mut toolpaths = Toolpaths {
        polylines: Vec::with_capacity(ordered.len()),
        travels: Vec::with_capacity(ordered.len().saturating_sub(1)),
        ..Toolpaths::default()
    };
    let mut ordered = ordered;
    if ordered.len() < 2 && !always_route {
        // A single path (a star's one concentric loop), or none: no move, no router.
        for path in ordered.drain(..) {
            toolpaths.length += match lengths.first() {
                Some(&known) if measured && !known.is_nan() => known,
                _ => path.windows(2).map(|w| dist(w[0], w[1])).sum::<f64>(),
            };
            toolpaths.polylines.push(LineString::new(path));
        }
    } else if let Some(region) = inside {
        // Moves proved inside are straight; the router is made for the first that is not.
        let mut route = Inside {
            region,
            rings,
            left,
            router: None,
        };
        if measured {
            lay_out::<true, _>(&mut ordered, &lengths, &mut route, &mut toolpaths);
        } else {
            lay_out::<false, _>(&mut ordered, &lengths, &mut route, &mut toolpaths);
        }
    } else {
        let router = super::travel::Router::told(rings, left);
        // (Two copies: the lines' paths, with no lengths, laid out as they were without.)
        if measured {
            lay_out::<true, _>(&mut ordered, &lengths, &mut &router, &mut toolpaths);
        } else {
            lay_out::<false, _>(&mut ordered, &lengths, &mut &router, &mut toolpaths);
        }
    }
    // The emptied lists serve the next layer's paths.
    super::scratch::give(&PATHS, ordered);
    super::scratch::give(&LENGTHS, lengths);
    toolpaths
}

/// The paths in order into `toolpaths`, each measured (where `MEASURED`, by its known
/// length if it has one) and the travel to it routed (`route`: a move's ends, and
/// whether the path it leads to is closed, `Router::route_on`'s).
#[inline(always)]
fn lay_out<const MEASURED: bool, R: Route>(
    ordered: &mut Vec<Vec<Coord>>,
    lengths: &[f64],
    router: &mut R,
    toolpaths: &mut Toolpaths,
) {
    let mut last: Option<Coord> = None;
    // (Counted only where `MEASURED`: no counter in the lines' copy.)
    let mut k = 0;
    for path in ordered.drain(..) {
        if let (Some(l), Some(&first)) = (last, path.first()) {
            // A closed path (a loop) ends where it starts: the next move starts there.
            let route = router.route(l, first, path.last() == Some(&first));
            toolpaths.travel += super::travel::length(&route);
            toolpaths.travels.push(LineString::new(route));
        }
        // The sum worked out while simplifying, where the path is as it was then (not
        // turned round): the same bits.
        let known = if MEASURED {
            k += 1;
            lengths[k - 1]
        } else {
            f64::NAN
        };
        toolpaths.length += if known.is_nan() {
            path.windows(2).map(|w| dist(w[0], w[1])).sum::<f64>()
        } else {
            known
        };
        last = path.last().copied();
        toolpaths.polylines.push(LineString::new(path));
    }
}

/// What routes a layer's moves: a move's ends, and whether the path it leads to is
/// closed (`Router::route_on`'s).
trait Route {
    fn route(&mut self, p: Coord, q: Coord, looped: bool) -> Vec<Coord>;
}

impl Route for &super::travel::Router<'_> {
    #[inline(always)]
    fn route(&mut self, p: Coord, q: Coord, looped: bool) -> Vec<Coord> {
        self.route_on(p, q, looped)
    }
}

/// Moves between paths that lie well inside `region` (concentric loops): each asked of
/// `Region::clear_inside` first, straight where it proves them inside; the router over
/// `rings` made for the first it does not.
struct Inside<'a> {
    region: &'a super::Region,
    rings: &'a [Vec<Coord>],
    left: bool,
    router: Option<super::travel::Router<'a>>,
}

impl Route for Inside<'_> {
    fn route(&mut self, p: Coord, q: Coord, looped: bool) -> Vec<Coord> {
        if self.region.clear_inside(p, q) {
            return vec![p, q];
        }
        let (rings, left) = (self.rings, self.left);
        self.router
            .get_or_insert_with(|| super::travel::Router::told(rings, left))
            .route_on(p, q, looped)
    }
}

thread_local! {
    /// A layer's paths' lengths where simplifying measured them (`Region::fill` takes
    /// it), kept between layers.
    pub(crate) static LENGTHS: std::cell::Cell<Vec<f64>> = const { std::cell::Cell::new(Vec::new()) };
    /// A layer's paths before they are ordered (`Region::fill` takes it), kept between
    /// layers.
    pub(crate) static PATHS: std::cell::Cell<Vec<Vec<Coord>>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Every path running in +x of the pattern frame, in order of their y then x: the
/// monotonic fill of `M` layers (no line is printed beside a neighbour that is not yet
/// there).
fn monotonic_order(mut paths: Vec<Vec<Coord>>, frame: &Frame) -> Vec<Vec<Coord>> {
    for p in &mut paths {
        if let (Some(&a), Some(&b)) = (p.first(), p.last())
            && frame.to_local(a).x > frame.to_local(b).x
        {
            p.reverse();
        }
    }
    let key = |p: &Vec<Coord>| {
        p.first().map_or((0.0, 0.0), |&a| {
            let q = frame.to_local(a);
            (q.y, q.x)
        })
    };
    paths.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.total_cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    paths
}

/// Greedy nearest neighbour with reversal, starting with the first path as generated.
/// Path ends are kept in a grid of about one end per cell, rebuilt coarser as paths are
/// used up, so that a layer of many thousand short walls orders in O(n) rather than O(n²).
#[cfg(test)]
pub(crate) fn nearest(paths: Vec<Vec<Coord>>) -> Vec<Vec<Coord>> {
    nearest_measured(paths, &mut Vec::new())
}

/// [`nearest`], each path's known length (`lengths`, one a path, or none) moved with it,
/// made NaN (not known) where the path is turned round (its sum would be made the other
/// way); none kept where the paths are many (the grid search's order).
pub(crate) fn nearest_measured(paths: Vec<Vec<Coord>>, lengths: &mut Vec<f64>) -> Vec<Vec<Coord>> {
    // (Two copies: the lines' paths, with no list, ordered as they were without one.)
    if lengths.len() == paths.len() {
        nearest_in::<true>(paths, lengths)
    } else {
        lengths.clear();
        nearest_in::<false>(paths, lengths)
    }
}

/// [`nearest_measured`], the lengths moved with the paths where `MEASURED`.
fn nearest_in<const MEASURED: bool>(
    paths: Vec<Vec<Coord>>,
    lengths: &mut Vec<f64>,
) -> Vec<Vec<Coord>> {
    let n = paths.len();
    // One path has no order to choose; two still may need the second reversed.
    if n <= 1 {
        return paths;
    }
    if n <= 64 {
        // Few paths: a plain scan, in place. The paths not yet taken stay in their order
        // (rotated, not swapped), so ties go to the lowest index as in the grid search.
        let mut paths = paths;
        let mut at = paths[0][paths[0].len() - 1];
        for i in 1..n {
            let mut best = (f64::INFINITY, i, false);
            // Each path's first end, then its last (a tie goes to the first found).
            for (j, p) in paths.iter().enumerate().skip(i) {
                if let (Some(&first), Some(&last)) = (p.first(), p.last()) {
                    let d = dist2(at, first);
                    if d < best.0 {
                        best = (d, j, false);
                    }
                    let d = dist2(at, last);
                    if d < best.0 {
                        best = (d, j, true);
                    }
                }
            }
            let (_, j, reversed) = best;
            // Path j to place i, the ones between moved up one: a rotation, by swaps
            // over a few paths (no call to move memory), else by the library's.
            if j - i <= 8 {
                for k in (i..j).rev() {
                    paths.swap(k, k + 1);
                    if MEASURED {
                        lengths.swap(k, k + 1);
                    }
                }
            } else {
                paths[i..=j].rotate_right(1);
                if MEASURED {
                    lengths[i..=j].rotate_right(1);
                }
            }
            if reversed {
                paths[i].reverse();
                if MEASURED {
                    lengths[i] = f64::NAN;
                }
            }
            at = paths[i][paths[i].len() - 1];
        }
        return paths;
    }
    lengths.clear();
    let ends: Vec<[Coord; 2]> = paths.iter().map(|p| [p[0], p[p.len() - 1]]).collect();
    let mut used = vec![false; n];
    let mut order: Vec<(usize, bool)> = Vec::with_capacity(n);
    used[0] = true;
    order.push((0, false));
    let mut at = ends[0][1];
    let mut grid = Grid::new(&ends, &used, n - 1);
    let mut left = n - 1;
    while left > 0 {
        if left * 4 < grid.population {
            grid = Grid::new(&ends, &used, left);
        }
        let Some((i, reversed)) = grid.nearest(at, &ends, &used) else {
            break;
        };
        used[i] = true;
        left -= 1;
        order.push((i, reversed));
        at = ends[i][if reversed { 0 } else { 1 }];
    }
    take_in_order(paths, order)
}

fn take_in_order(paths: Vec<Vec<Coord>>, order: Vec<(usize, bool)>) -> Vec<Vec<Coord>> {
    let mut taken: Vec<Option<Vec<Coord>>> = paths.into_iter().map(Some).collect();
    order
        .into_iter()
        .filter_map(|(i, reversed)| {
            let mut p = taken[i].take()?;
            if reversed {
                p.reverse();
            }
            Some(p)
        })
        .collect()
}

struct Grid {
    min: Coord,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Per cell: path index × 2 + which end (1 = the last point: entering there reverses).
    cells: Vec<Vec<u32>>,
    population: usize,
}

impl Grid {
    fn new(ends: &[[Coord; 2]], used: &[bool], live: usize) -> Grid {
        let mut min = Coord {
            x: f64::INFINITY,
            y: f64::INFINITY,
        };
        let mut max = Coord {
            x: f64::NEG_INFINITY,
            y: f64::NEG_INFINITY,
        };
        for (e, _) in ends.iter().zip(used).filter(|(_, u)| !**u) {
            for p in e {
                min = Coord {
                    x: min.x.min(p.x),
                    y: min.y.min(p.y),
                };
                max = Coord {
                    x: max.x.max(p.x),
                    y: max.y.max(p.y),
                };
            }
        }
        let size = max - min;
        let cells_wanted = (2 * live).max(1) as f64;
        let cell = ((size.x.max(1e-9) * size.y.max(1e-9)) / cells_wanted)
            .sqrt()
            .max(size.x.max(size.y) / 2048.0)
            .max(1e-9);
        let nx = ((size.x / cell) as usize + 1).min(4096);
        let ny = ((size.y / cell) as usize + 1).min(4096);
        let mut grid = Grid {
            min,
            cell,
            nx,
            ny,
            cells: vec![Vec::new(); nx * ny],
            population: 0,
        };
        for (i, e) in ends.iter().enumerate() {
            if used[i] {
                continue;
            }
            for (side, &p) in e.iter().enumerate() {
                let (cx, cy) = grid.cell_of(p);
                grid.cells[cy * nx + cx].push((i * 2 + side) as u32);
                grid.population += 1;
            }
        }
        grid
    }

    fn cell_of(&self, p: Coord) -> (usize, usize) {
        let cx = ((p.x - self.min.x) / self.cell)
            .floor()
            .clamp(0.0, (self.nx - 1) as f64) as usize;
        let cy = ((p.y - self.min.y) / self.cell)
            .floor()
            .clamp(0.0, (self.ny - 1) as f64) as usize;
        (cx, cy)
    }

    /// The live path end nearest `at` (ties: the lowest index, then its first end).
    fn nearest(&mut self, at: Coord, ends: &[[Coord; 2]], used: &[bool]) -> Option<(usize, bool)> {
        let (cx, cy) = self.cell_of(at);
        let mut best: Option<(f64, u32)> = None;
        let max_ring = self.nx.max(self.ny);
        for ring in 0..=max_ring {
            let (x0, x1) = (cx.saturating_sub(ring), (cx + ring).min(self.nx - 1));
            let (y0, y1) = (cy.saturating_sub(ring), (cy + ring).min(self.ny - 1));
            for y in y0..=y1 {
                // Only the ring's border (Chebyshev distance `ring`): the inside was
                // searched already. Full rows at its top and bottom, two cells between.
                let edge_row = y.abs_diff(cy) == ring;
                let step = if edge_row || x1 == x0 { 1 } else { x1 - x0 };
                let mut x = x0;
                while x <= x1 {
                    if x.abs_diff(cx).max(y.abs_diff(cy)) == ring {
                        let cell = &mut self.cells[y * self.nx + x];
                        let before = cell.len();
                        cell.retain(|&id| !used[id as usize / 2]);
                        self.population -= before - cell.len();
                        for &id in cell.iter() {
                            let p = ends[id as usize / 2][id as usize % 2];
                            let d = dist2(at, p);
                            if best.is_none_or(|(bd, bid)| d < bd || (d == bd && id < bid)) {
                                best = Some((d, id));
                            }
                        }
                    }
                    x += step;
                }
            }
            // Cells beyond this ring are at least `ring × cell` away from `at`.
            if let Some((d2, _)) = best
                && d2 <= (ring as f64 * self.cell).powi(2)
            {
                break;
            }
        }
        best.map(|(_, id)| (id as usize / 2, id % 2 == 1))
    }
}
