//! Lightning: branches from the outline toward the pattern centre.
//!
//! A light tree, not Cura's supporting-overhang lightning (that needs the layers above):
//! from points spaced `2.5 × spacing` along each outline, starting at its farthest point in
//! direction θ, a branch runs 80% of the way to the centre, turned ±10° on alternate
//! branches; at 40% of its length it forks into two twigs at ±45°, each 40% as long.
//! Everything is clipped to the region (holes included). A given spacing covers 0.57–0.69
//! of the density on compact shapes: `Region::fill` measures a first tree and respaces.

use crate::math;
use geo::Coord;

use super::clip::{Edges, Frame};
use super::{Region, scratch};

thread_local! {
    /// `clip_tree`'s piece in world coordinates, kept between layers.
    static WORLD: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    /// A tree's polylines before clipping (`branches_into`), kept between layers.
    static BRANCHES: std::cell::Cell<Vec<[Coord; 3]>> = const { std::cell::Cell::new(Vec::new()) };
    /// The first tree as one flat list and its pieces' ends (`Region::fill` measures it
    /// there), kept between layers: grown from nothing, they cost four reallocations a
    /// layer.
    pub(crate) static FLAT: std::cell::Cell<Vec<Coord>> = const { std::cell::Cell::new(Vec::new()) };
    pub(crate) static ENDS: std::cell::Cell<Vec<usize>> = const { std::cell::Cell::new(Vec::new()) };
    /// `Outlines`' list, kept between layers.
    static OUTLINES: std::cell::Cell<Vec<(usize, f64)>> = const { std::cell::Cell::new(Vec::new()) };
}
use super::offset::next;

/// How many branches each outline gets at `spacing`: all that the tree depends the
/// spacing on (two spacings with the same counts make the same tree).
#[cfg(test)]
pub(crate) fn counts(region: &Region, spacing: f64) -> Vec<usize> {
    let gap = 2.5 * spacing;
    region
        .outlines()
        .iter()
        .map(|ring| (perimeter(ring) / gap).floor().max(1.0) as usize)
        .collect()
}

/// Whether every outline gets as many branches at `a` as at `b` (`counts` equal: the
/// same tree), each perimeter measured once, nothing listed.
#[cfg(test)]
pub(crate) fn same_counts(region: &Region, a: f64, b: f64) -> bool {
    Outlines::new(region, 0.0).same_counts(a, b)
}

/// What both trees of a layer share: per outline the vertex farthest in the direction
/// θ (where the branches start) and the perimeter, found once for the layer
/// (`Region::fill` builds two trees), by the same sums as each tree found them.
pub(crate) struct Outlines {
    /// Per outline: its start vertex and its perimeter.
    each: Vec<(usize, f64)>,
}

impl Outlines {
    pub(crate) fn new(region: &Region, theta: f64) -> Outlines {
        // One call for both (the same kernels as `cos` and `sin`, to the bit: a test
        // compares them).
        let (sin, cos) = math::sin_cos(theta);
        let direction = Coord { x: cos, y: sin };
        let mut each = scratch::take(&OUTLINES);
        each.extend(
            region
                .outlines()
                .iter()
                .map(|ring| (farthest(ring, direction), perimeter(ring))),
        );
        Outlines { each }
    }

    /// Whether every outline gets as many branches at `a` as at `b` (`counts` equal: the
    /// same tree), nothing listed.
    pub(crate) fn same_counts(&self, a: f64, b: f64) -> bool {
        let (gap_a, gap_b) = (2.5 * a, 2.5 * b);
        self.each.iter().all(|&(_, perimeter)| {
            (perimeter / gap_a).floor().max(1.0) as usize
                == (perimeter / gap_b).floor().max(1.0) as usize
        })
    }
}

impl Drop for Outlines {
    fn drop(&mut self) {
        scratch::give(&OUTLINES, std::mem::take(&mut self.each));
    }
}

/// The vertex of `ring` farthest in `direction` (0 for an empty ring): the last of
/// equals, by `total_cmp`, as `Iterator::max_by` picks, each vertex's projection found
/// once (`max_by` finds both sides' at each comparison).
fn farthest(ring: &[Coord], direction: Coord) -> usize {
    let Some(&first) = ring.first() else {
        return 0;
    };
    let (mut best, mut at) = (dot(first, direction), 0);
    for (i, &p) in ring.iter().enumerate().skip(1) {
        let d = dot(p, direction);
        if d.total_cmp(&best) != std::cmp::Ordering::Less {
            (best, at) = (d, i);
        }
    }
    at
}

fn perimeter(ring: &[Coord]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| length(ring[next(i, n)] - ring[i])).sum()
}

/// The tree for one spacing, appended to `out`. `edges` are the region's in `frame`
/// ([`frame`]): built once for every tree of the layer (`Region::fill` builds two).
#[cfg(test)]
pub(crate) fn lightning(
    region: &Region,
    centre: Coord,
    theta: f64,
    spacing: f64,
    edges: &mut Edges,
    out: &mut Vec<Vec<Coord>>,
) {
    lightning_of(
        region,
        &Outlines::new(region, theta),
        centre,
        spacing,
        edges,
        out,
    );
}

/// [`lightning`] with the layer's [`Outlines`] found already.
pub(crate) fn lightning_of(
    region: &Region,
    outlines: &Outlines,
    centre: Coord,
    spacing: f64,
    edges: &mut Edges,
    out: &mut Vec<Vec<Coord>>,
) {
    let mut branches = scratch::take(&BRANCHES);
    branches_into(region, outlines, centre, spacing, &mut branches);
    // A piece per polyline, unless one is cut: the list made at about its size, not grown.
    out.reserve(branches.len() + branches.len() / 4);
    clip_tree(&branches, centre, region.is_convex(), edges, |piece| {
        out.push(piece.to_vec())
    });
    scratch::give(&BRANCHES, branches);
}

/// The tree's pieces, in world coordinates, each handed to `piece` (in the order
/// `lightning` appends them).
pub(crate) fn tree(
    region: &Region,
    outlines: &Outlines,
    centre: Coord,
    spacing: f64,
    edges: &mut Edges,
    piece: impl FnMut(&[Coord]),
) {
    let mut branches = scratch::take(&BRANCHES);
    branches_into(region, outlines, centre, spacing, &mut branches);
    clip_tree(&branches, centre, region.is_convex(), edges, piece);
    scratch::give(&BRANCHES, branches);
}

/// The polylines of [`branches`] clipped, each piece handed to `piece`.
fn clip_tree(
    branches: &[[Coord; 3]],
    centre: Coord,
    convex: bool,
    edges: &mut Edges,
    mut piece: impl FnMut(&[Coord]),
) {
    let frame = frame(centre);
    // Each piece back in world coordinates, in one buffer (kept between layers).
    let mut world = scratch::take(&WORLD);
    // In a convex region a polyline whose ends are inside is inside whole. A branch starts
    // on the outline and its fork lies between its start and its tip, so with the tip
    // inside, each of its polylines is inside when its twig's end is: no clipping, which
    // is most of the work.
    for pair in branches.chunks_exact(2) {
        // The fork, shared by both polylines, mapped once.
        let fork = frame.to_local(pair[0][1]);
        let local =
            |branch: &[Coord; 3]| [frame.to_local(branch[0]), fork, frame.to_local(branch[2])];
        let pair = [local(&pair[0]), local(&pair[1])];
        let tip_inside = convex && edges.contains(pair[1][0]);
        for branch in pair {
            if tip_inside && edges.contains(branch[2]) {
                piece(&branch.map(|q| frame.to_world(q)));
                continue;
            }
            edges.clip_each(&branch, |local| {
                world.clear();
                world.extend(local.iter().map(|&q| frame.to_world(q)));
                piece(&world);
            });
        }
    }
    scratch::give(&WORLD, world);
}

/// The tree's polylines before clipping, in world coordinates: per branch, its start, fork
/// and left twig's end, then its tip, fork and right twig's end.
#[cfg(test)]
pub(crate) fn branches(
    region: &Region,
    centre: Coord,
    theta: f64,
    spacing: f64,
) -> Vec<[Coord; 3]> {
    let mut branches = Vec::new();
    branches_into(
        region,
        &Outlines::new(region, theta),
        centre,
        spacing,
        &mut branches,
    );
    branches
}

/// [`branches`] appended to `branches` (a list kept between layers).
fn branches_into(
    region: &Region,
    outlines: &Outlines,
    centre: Coord,
    spacing: f64,
    branches: &mut Vec<[Coord; 3]>,
) {
    let gap = 2.5 * spacing;
    // Each branch as two polylines through its fork: the main branch's first part and one
    // twig, then the main branch's tip, back to the fork and the other twig. A tree of four
    // ends needs two paths at least; three separate segments (as before) made three paths
    // and three travels per branch, each travel routed inside the region.
    let [even, odd, left_twig, right_twig] = [EVEN, ODD, LEFT_TWIG, RIGHT_TWIG];
    for (ring, &(start, perimeter)) in region.outlines().iter().zip(&outlines.each) {
        let n = ring.len();
        let count = (perimeter / gap).floor().max(1.0) as usize;
        let step = perimeter / count as f64;
        branches.reserve(2 * count);
        // Walk the ring from `start`, dropping a branch every `step` of arc length.
        let (mut i, mut along, mut next) = (0usize, 0.0, 0.0);
        let mut k = 0usize;
        while k < count && i < n {
            // Vertex start + i round the ring (both under n: one subtraction, not a
            // division).
            let at = if start + i >= n {
                start + i - n
            } else {
                start + i
            };
            let (a, b) = (ring[at], ring[super::offset::next(at, n)]);
            let len = length(b - a);
            if along + len < next || len == 0.0 {
                along += len;
                i += 1;
                continue;
            }
            let p = a + (b - a) * ((next - along) / len);
            let to_centre = centre - p;
            let dist = length(to_centre);
            if dist > 1e-9 {
                let turn = if k.is_multiple_of(2) { even } else { odd };
                let main = rotate(to_centre / dist, turn);
                let reach = 0.8 * dist;
                let fork = p + main * (0.4 * reach);
                let [left, right] =
                    [left_twig, right_twig].map(|side| fork + rotate(main, side) * (0.4 * reach));
                branches.push([p, fork, left]);
                branches.push([p + main * reach, fork, right]);
            }
            k += 1;
            next = k as f64 * step;
        }
    }
}

/// The turns' sines and cosines: `math::sin_cos` of ±10° (the main branch, on alternate
/// branches) and ±45° (the twigs), to the bit (a test computes them), not computed for
/// every tree.
const EVEN: (f64, f64) = (
    f64::from_bits(0x3fc63a1a7e0b7389),
    f64::from_bits(0x3fef838b8c811c17),
);
const ODD: (f64, f64) = (
    f64::from_bits(0xbfc63a1a7e0b7389),
    f64::from_bits(0x3fef838b8c811c17),
);
const LEFT_TWIG: (f64, f64) = (
    f64::from_bits(0x3fe6a09e667f3bcc),
    f64::from_bits(0x3fe6a09e667f3bcd),
);
const RIGHT_TWIG: (f64, f64) = (
    f64::from_bits(0xbfe6a09e667f3bcc),
    f64::from_bits(0x3fe6a09e667f3bcd),
);

/// The frame the tree is clipped in: unturned, about the pattern centre.
pub(crate) fn frame(centre: Coord) -> Frame {
    Frame::new(centre, 0.0)
}

fn dot(a: Coord, b: Coord) -> f64 {
    a.x * b.x + a.y * b.y
}

fn length(a: Coord) -> f64 {
    (a.x * a.x + a.y * a.y).sqrt()
}

/// `v` turned by the angle whose sine and cosine are given.
fn rotate(v: Coord, (s, c): (f64, f64)) -> Coord {
    Coord {
        x: v.x * c - v.y * s,
        y: v.x * s + v.y * c,
    }
}

#[cfg(test)]
#[path = "lightning_tests.rs"]
mod tests;
