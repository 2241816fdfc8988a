//! Slicing a mesh into layer sections (crate `rotlang-geometry`): one layer at a time, memory
//! bounded by the triangles that cross the current height and the section itself.
//!
//! Each layer is cut at its middle, as slicers do. A triangle with corners on both sides
//! of the plane (a corner exactly on it counts as below, so that every crossing is
//! decided one way) gives one segment between two of its edges; segments are chained
//! through the mesh edges they share (exact, no tolerance: two triangles compute the same
//! point on the edge they share), which closes every loop of a closed (watertight) mesh.
//! A mesh with holes in its surface leaves open chains: their ends are joined to the
//! nearest other end within [`Slicer::max_gap`] (tiny gaps of a badly exported mesh), and
//! what still cannot be closed is counted in [`Section::open`], never guessed at. The
//! loops are read even-odd: a loop inside an odd number of others is a hole.
//!
//! ```
//! use rotlang_geometry::mesh::shapes;
//! use rotlang_geometry::slice::Slicer;
//!
//! let tube = shapes::tube(10.0, 5.0, 20.0, 64);
//! let mut slicer = Slicer::new(&tube);
//! let section = slicer.section(10.1);
//! assert_eq!(section.region.0.len(), 1);
//! assert_eq!(section.region.0[0].interiors().len(), 1);
//! ```

use crate::math;
use std::collections::HashMap;

use geo::{Coord, LineString, MultiPolygon, Polygon};

use crate::mesh::Mesh;

pub mod json;
pub mod part;
pub use part::{FilledArea, Part, PartLayer, PartOptions, Summary};

/// One layer's section.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// The height it was cut at (mm, in the mesh's coordinates).
    pub z: f64,
    /// The closed loops, outlines with their holes.
    pub region: MultiPolygon<f64>,
    /// Chains that could not be closed (the mesh has a hole there): left out.
    pub open: usize,
    /// Gaps closed by joining chain ends within the slicer's `max_gap`.
    pub bridged: usize,
}

/// Cuts a mesh at rising heights.
#[derive(Clone, Debug)]
pub struct Slicer<'m> {
    mesh: &'m Mesh,
    /// Triangles by their lowest corner.
    order: Vec<u32>,
    /// The next of `order` to join the active set.
    next: usize,
    active: Vec<u32>,
    last: f64,
    /// The widest gap between chain ends that is closed (mm).
    pub max_gap: f64,
}

impl<'m> Slicer<'m> {
    pub fn new(mesh: &'m Mesh) -> Slicer<'m> {
        let zmin = |t: &[u32; 3]| {
            t.iter()
                .map(|&i| mesh.vertices[i as usize][2])
                .fold(f64::INFINITY, f64::min)
        };
        let mut order: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
        order.sort_unstable_by(|&a, &b| {
            zmin(&mesh.triangles[a as usize]).total_cmp(&zmin(&mesh.triangles[b as usize]))
        });
        Slicer {
            mesh,
            order,
            next: 0,
            active: Vec::new(),
            last: f64::NEG_INFINITY,
            max_gap: 0.05,
        }
    }

    /// The section at height `z`. Heights should rise from call to call (each triangle is
    /// then looked at while the plane crosses it only); a lower one starts over.
    pub fn section(&mut self, z: f64) -> Section {
        let mesh = self.mesh;
        let vz = |i: u32| mesh.vertices[i as usize][2];
        if z < self.last {
            self.next = 0;
            self.active.clear();
        }
        self.last = z;
        while self.next < self.order.len() {
            let t = self.order[self.next];
            let [a, b, c] = mesh.triangles[t as usize];
            if vz(a).min(vz(b)).min(vz(c)) > z {
                break;
            }
            self.active.push(t);
            self.next += 1;
        }
        self.active.retain(|&t| {
            let [a, b, c] = mesh.triangles[t as usize];
            vz(a).max(vz(b)).max(vz(c)) > z
        });
        // Segments between the edges they cross, keyed by those edges.
        let key = |i: u32, j: u32| {
            let (lo, hi) = if i < j { (i, j) } else { (j, i) };
            (lo as u64) << 32 | hi as u64
        };
        let point = |i: u32, j: u32| {
            let (lo, hi) = if i < j { (i, j) } else { (j, i) };
            let (p, q) = (mesh.vertices[lo as usize], mesh.vertices[hi as usize]);
            let t = (z - p[2]) / (q[2] - p[2]);
            Coord {
                x: p[0] + (q[0] - p[0]) * t,
                y: p[1] + (q[1] - p[1]) * t,
            }
        };
        let mut segments: Vec<[u64; 2]> = Vec::with_capacity(self.active.len());
        let mut points: HashMap<u64, Coord> = HashMap::with_capacity(2 * self.active.len());
        for &t in &self.active {
            let tri = mesh.triangles[t as usize];
            let above = tri.map(|i| vz(i) > z);
            let mut crossing = [0u64; 2];
            let mut n = 0;
            for k in 0..3 {
                let (i, j) = (tri[k], tri[(k + 1) % 3]);
                if above[k] != above[(k + 1) % 3] && n < 2 {
                    let e = key(i, j);
                    points.entry(e).or_insert_with(|| point(i, j));
                    crossing[n] = e;
                    n += 1;
                }
            }
            if n == 2 {
                segments.push(crossing);
            }
        }
        let (loops, open, bridged) = chain(&segments, &points, self.max_gap);
        Section {
            z,
            region: nest(loops),
            open,
            bridged,
        }
    }
}

/// Chains segments (pairs of edge keys) into loops; returns the closed loops, how many
/// chains stayed open, and how many gaps were bridged.
fn chain(
    segments: &[[u64; 2]],
    points: &HashMap<u64, Coord>,
    max_gap: f64,
) -> (Vec<Vec<Coord>>, usize, usize) {
    // Each edge key's segments (two on a closed surface).
    let mut at: HashMap<u64, [u32; 2]> = HashMap::with_capacity(segments.len());
    for (s, seg) in segments.iter().enumerate() {
        for &e in seg {
            let slot = at.entry(e).or_insert([u32::MAX; 2]);
            if slot[0] == u32::MAX {
                slot[0] = s as u32;
            } else {
                slot[1] = s as u32;
            }
        }
    }
    let mut used = vec![false; segments.len()];
    let mut loops = Vec::new();
    let mut chains: Vec<Vec<u64>> = Vec::new();
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let [first, mut e] = segments[start];
        let mut keys = vec![first, e];
        // Walk forward from `e`, then, if the chain did not close, backward from `first`.
        let mut closed = false;
        for direction in 0..2 {
            if direction == 1 {
                keys.reverse();
                e = first;
            }
            while let Some(&[a, b]) = at.get(&e) {
                let next = [a, b]
                    .into_iter()
                    .find(|&s| s != u32::MAX && !used[s as usize]);
                let Some(s) = next else { break };
                used[s as usize] = true;
                let [p, q] = segments[s as usize];
                e = if p == e { q } else { p };
                if e == *keys.first().unwrap() && direction == 0 {
                    closed = true;
                    break;
                }
                keys.push(e);
            }
            if closed {
                break;
            }
        }
        if closed {
            loops.push(keys.iter().map(|k| points[k]).collect());
        } else {
            chains.push(keys);
        }
    }
    // Open chains: join each end to the nearest other end within max_gap.
    let mut open: Vec<Vec<Coord>> = chains
        .into_iter()
        .map(|c| c.iter().map(|k| points[k]).collect())
        .collect();
    let mut bridged = 0;
    let d = |a: Coord, b: Coord| math::hypot((a - b).x, (a - b).y);
    loop {
        let mut changed = false;
        let mut i = 0;
        while i < open.len() {
            let (head, tail) = (open[i][0], *open[i].last().unwrap());
            if open[i].len() >= 3 && d(head, tail) <= max_gap {
                loops.push(open.swap_remove(i));
                bridged += 1;
                changed = true;
                continue;
            }
            // The nearest start of another chain to this one's end, or end (reversed).
            let best = (0..open.len())
                .filter(|&j| j != i)
                .flat_map(|j| {
                    [
                        (j, false, d(tail, open[j][0])),
                        (j, true, d(tail, *open[j].last().unwrap())),
                    ]
                })
                .min_by(|a, b| a.2.total_cmp(&b.2));
            if let Some((j, reversed, gap)) = best.filter(|b| b.2 <= max_gap) {
                let mut other = open.swap_remove(j);
                if reversed {
                    other.reverse();
                }
                let i = if i == open.len() { j } else { i };
                open[i].extend(other);
                bridged += 1;
                changed = true;
                let _ = gap;
                continue;
            }
            i += 1;
        }
        if !changed {
            break;
        }
    }
    (loops, open.len(), bridged)
}

/// Loops into polygons, even-odd: a loop inside an odd number of others is a hole of the
/// smallest loop around it.
pub fn nest(mut loops: Vec<Vec<Coord>>) -> MultiPolygon<f64> {
    for l in &mut loops {
        drop_inline(l);
    }
    loops.retain(|l| l.len() >= 3 && area(l) != 0.0);
    // Largest first: a loop's containers come before it.
    loops.sort_by(|a, b| area(b).abs().total_cmp(&area(a).abs()));
    let boxes: Vec<(Coord, Coord)> = loops
        .iter()
        .map(|l| crate::infill::travel::bounds(l))
        .collect();
    let mut parent: Vec<Option<usize>> = vec![None; loops.len()];
    let mut depth = vec![0usize; loops.len()];
    for i in 0..loops.len() {
        let p = loops[i][0];
        // The smallest container: the last (smallest) loop before it that holds its point.
        for j in (0..i).rev() {
            let (lo, hi) = boxes[j];
            if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
                continue;
            }
            if contains(&loops[j], p) {
                parent[i] = Some(j);
                depth[i] = depth[j] + 1;
                break;
            }
        }
    }
    let mut polygons: Vec<(usize, Polygon<f64>)> = Vec::new();
    let mut slot: Vec<Option<usize>> = vec![None; loops.len()];
    let closed = |l: &Vec<Coord>| {
        let mut c = l.clone();
        c.push(c[0]);
        LineString::new(c)
    };
    for i in 0..loops.len() {
        if depth[i] % 2 == 0 {
            slot[i] = Some(polygons.len());
            polygons.push((i, Polygon::new(closed(&loops[i]), vec![])));
        } else if let Some(k) = parent[i].and_then(|j| slot[j]) {
            polygons[k].1.interiors_push(closed(&loops[i]));
        }
    }
    MultiPolygon::new(polygons.into_iter().map(|(_, p)| p).collect())
}

/// How far (mm) a dropped vertex may lie from the edge that replaces it.
pub const TOLERANCE: f64 = 1e-3;

/// Drops repeated points and the vertices that lie within [`TOLERANCE`] of the edge that
/// replaces them (a plane crossing a flat quad cuts both its triangles: the point on the
/// diagonal between them is in line): half the vertices for the infill to clip against.
///
/// Douglas-Peucker on the closed ring, so that every dropped vertex is measured against
/// the final edge over it (a vertex dropped against a chord that then keeps growing, one
/// step at a time, let a fine circle's section drift far from the circle). The ring is
/// split at its lowest-leftmost point (a corner of its hull, kept) and the point farthest
/// from it; each part keeps its farthest vertex from its chord while that is beyond the
/// tolerance. An explicit stack: no recursion as deep as the ring is long.
fn drop_inline(ring: &mut Vec<Coord>) {
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    let n = ring.len();
    if n < 4 {
        return;
    }
    let a = (0..n)
        .min_by(|&i, &j| {
            (ring[i].x, ring[i].y)
                .partial_cmp(&(ring[j].x, ring[j].y))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .unwrap_or(0);
    ring.rotate_left(a);
    let d2 = |p: Coord| (p - ring[0]).x.powi(2) + (p - ring[0]).y.powi(2);
    let b = (1..n)
        .max_by(|&i, &j| d2(ring[i]).total_cmp(&d2(ring[j])))
        .unwrap_or(n / 2);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[b] = true;
    // Spans (start, end) of indices into the ring, `end` may be `n` (the start again).
    let mut stack = vec![(0usize, b), (b, n)];
    while let Some((i, j)) = stack.pop() {
        if j - i < 2 {
            continue;
        }
        let (p, q) = (ring[i], ring[j % n]);
        let (far, dist) = (i + 1..j)
            .map(|k| (k, segment_distance(ring[k], p, q)))
            .fold((i + 1, -1.0), |best, c| if c.1 > best.1 { c } else { best });
        if dist > TOLERANCE {
            keep[far] = true;
            stack.push((i, far));
            stack.push((far, j));
        }
    }
    let mut k = 0;
    ring.retain(|_| {
        k += 1;
        keep[k - 1]
    });
}

/// The distance from `p` to the segment from `a` to `b`.
fn segment_distance(p: Coord, a: Coord, b: Coord) -> f64 {
    let (v, u) = (b - a, p - a);
    let len2 = v.x * v.x + v.y * v.y;
    let t = if len2 > 0.0 {
        ((u.x * v.x + u.y * v.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    math::hypot(u.x - t * v.x, u.y - t * v.y)
}

fn area(ring: &[Coord]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| ring[i].x * ring[(i + 1) % n].y - ring[(i + 1) % n].x * ring[i].y)
        .sum::<f64>()
        / 2.0
}

fn contains(ring: &[Coord], p: Coord) -> bool {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if (a.y <= p.y) != (b.y <= p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x {
            inside = !inside;
        }
    }
    inside
}

#[cfg(test)]
mod tests;
