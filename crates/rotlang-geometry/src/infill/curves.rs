//! Curved patterns: gyroid, spiral, concentric.

use std::f64::consts::{PI, TAU};

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{Buffer, Coord, MultiPolygon};

use super::Region;
use super::clip::{Edges, Frame};

/// The gyroid `sin x cos y + sin y cos z + sin z cos x = 0` cut at height `z`, one unit
/// of the surface being `scale` mm, turned by θ about `centre`.
///
/// For a fixed x the equation is `a cos y + b sin y = −c`, with two solutions per period
/// in y: `y = atan2(b, a) ± acos(−c/R)`. Where |sin z| > |cos z| the curves run along y
/// instead and are solved for x the same way; either way `|c| ≤ R`, so every curve is
/// defined along its whole length (this is how the section turns from waves along x to
/// waves along y and back as z rises).
pub(crate) fn gyroid(
    region: &Region,
    centre: Coord,
    theta: f64,
    scale: f64,
    z: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let frame = Frame::new(centre, theta);
    let mut edges = Edges::new(region.rings(), &frame);
    let (sz, cz) = (z / scale).sin_cos();
    let along_y = sz.abs() > cz.abs();
    // In the frame where the waves run along "u" and repeat along "v".
    let (u0, u1, v0, v1) = if along_y {
        (edges.min.y, edges.max.y, edges.min.x, edges.max.x)
    } else {
        (edges.min.x, edges.max.x, edges.min.y, edges.max.y)
    };
    // A vertex every 1/16 of a period (the chord strays less than a twentieth of a
    // nozzle from the curve at 20%), but not closer than a quarter nozzle.
    let period = TAU * scale;
    let per_period = (period / (region.nozzle() / 4.0)).clamp(8.0, 16.0);
    let step = TAU / per_period;
    let (s0, s1) = (
        (u0 / scale / step).floor() as i64,
        (u1 / scale / step).ceil() as i64,
    );
    // Both branches' offsets at every sample: the trigonometry is done once per sample
    // and shared by every wave (they differ by whole periods).
    let samples: Vec<(f64, f64, f64)> = (s0..=s1)
        .map(|i| {
            let u = i as f64 * step;
            let (su, cu) = u.sin_cos();
            let (a, b, c) = if along_y {
                (sz, cu, su * cz)
            } else {
                (su, cz, sz * cu)
            };
            let r = (a * a + b * b).sqrt();
            // The phase must be continuous along u. atan2 jumps by 2π where its first
            // argument crosses 0 with the second negative: along y, `a = sin z` is fixed and
            // `b = cos u` crosses 0, so for `sin z < 0` measure the phase from the opposite
            // direction (continuous there) and add π. Along x, `b = cos z` is fixed and at
            // least √½ in size, so atan2 never reaches its cut.
            let phi = if along_y && a < 0.0 {
                (-b).atan2(-a) + PI
            } else {
                b.atan2(a)
            };
            let delta = (-c / r).clamp(-1.0, 1.0).acos();
            (u, phi + delta, phi - delta)
        })
        .collect();
    // The whole periods to shift each branch by to cover [v0, v1].
    let (lo, hi) = samples
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &(_, p, m)| {
            (l.min(p.min(m)), h.max(p.max(m)))
        });
    let (m0, m1) = (
        ((v0 / scale - hi) / TAU).floor() as i64,
        ((v1 / scale - lo) / TAU).ceil() as i64,
    );
    // The region's extent in v over each interval between samples (its boundary's, hence
    // the region's): a curve is built and clipped only from the first to the last interval
    // where it can meet the region, not across the whole bounding box.
    let n = samples.len();
    let mut envelope = vec![(f64::INFINITY, f64::NEG_INFINITY); n.saturating_sub(1)];
    let u_first = s0 as f64 * step * scale;
    let width = step * scale;
    for (a, b) in edges.segments() {
        let (a, b) = if along_y {
            ((a.y, a.x), (b.y, b.x))
        } else {
            ((a.x, a.y), (b.x, b.y))
        };
        let ((ua, va), (ub, vb)) = if a.0 <= b.0 { (a, b) } else { (b, a) };
        let v_at = |u: f64| {
            if ub > ua {
                va + (vb - va) * ((u - ua) / (ub - ua)).clamp(0.0, 1.0)
            } else {
                va
            }
        };
        if n < 2 {
            break;
        }
        let index = |u: f64| (((u - u_first) / width).floor().max(0.0) as usize).min(n - 2);
        let (i0, i1) = (index(ua), index(ub));
        for (i, e) in envelope.iter_mut().enumerate().take(i1 + 1).skip(i0) {
            let (l, r) = (u_first + i as f64 * width, u_first + (i + 1) as f64 * width);
            // Across the interval, or the whole edge when it is parallel to v.
            let (p, q) = if ub > ua {
                (v_at(l.max(ua)), v_at(r.min(ub)))
            } else {
                (va, vb)
            };
            let (lo, hi) = (p.min(q), p.max(q));
            *e = (e.0.min(lo), e.1.max(hi));
        }
    }
    // Half a nozzle of slack: the test is only a shortcut, the clip decides.
    let slack = region.nozzle() / 2.0;
    let mut curve = Vec::with_capacity(samples.len());
    let mut local = Vec::new();
    for branch in 0..2 {
        for m in m0..=m1 {
            let shift = m as f64 * TAU;
            let v = |i: usize| {
                let (_, plus, minus) = samples[i];
                (if branch == 0 { plus } else { minus } + shift) * scale
            };
            let meets = |i: usize| {
                let (p, q) = (v(i), v(i + 1));
                let (lo, hi) = envelope[i];
                p.max(q) >= lo - slack && p.min(q) <= hi + slack
            };
            let Some(first) = (0..n.saturating_sub(1)).find(|&i| meets(i)) else {
                continue;
            };
            let last = (first..n - 1).rev().find(|&i| meets(i)).unwrap_or(first);
            curve.clear();
            curve.extend((first..=last + 1).map(|i| {
                let (v, u) = (v(i), samples[i].0 * scale);
                if along_y {
                    Coord { x: v, y: u }
                } else {
                    Coord { x: u, y: v }
                }
            }));
            local.clear();
            edges.clip(&curve, &mut local);
            out.extend(
                local
                    .drain(..)
                    .map(|piece| piece.into_iter().map(|q| frame.to_world(q)).collect()),
            );
        }
    }
}

/// The Archimedean spiral `r = spacing·φ/2π` about `centre`, starting in direction θ,
/// from the region's nearest point out to its farthest.
pub(crate) fn spiral(
    region: &Region,
    centre: Coord,
    theta: f64,
    spacing: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let frame = Frame::new(centre, theta);
    let mut edges = Edges::new(region.rings(), &frame);
    let (min, max) = (edges.min, edges.max);
    let far = [min.x.abs().max(max.x.abs()), min.y.abs().max(max.y.abs())];
    let r_max = far[0].hypot(far[1]);
    let near = Coord {
        x: 0f64.clamp(min.x, max.x),
        y: 0f64.clamp(min.y, max.y),
    };
    let r_min = near.x.hypot(near.y);
    let k = spacing / TAU;
    // Start a whole turn inside the region's nearest point (the spiral starts at angle 0).
    let mut phi = ((r_min / k / TAU).floor() - 1.0).max(0.0) * TAU;
    let phi_end = r_max / k + TAU;
    // Chords that stray at most 0.02 mm from the curve (sagitta c²/8r), at most 2 mm
    // long and 20° apart.
    let mut curve = Vec::new();
    while phi <= phi_end {
        let r = k * phi;
        let (s, c) = phi.sin_cos();
        curve.push(Coord { x: r * c, y: r * s });
        let chord = (8.0 * r * 0.02).sqrt().min(2.0);
        // Never a zero step (at the centre the chord is zero).
        phi += (chord / r.max(1e-9)).clamp(1e-3, PI / 9.0);
    }
    let mut local = Vec::new();
    edges.clip(&curve, &mut local);
    out.extend(
        local
            .into_iter()
            .map(|piece| piece.into_iter().map(|q| frame.to_world(q)).collect()),
    );
}

/// Loops at `(k + ½)·spacing` inside the inset outline (and around its holes), each
/// starting at its farthest vertex in direction θ and closed.
pub(crate) fn concentric(region: &Region, theta: f64, spacing: f64, out: &mut Vec<Vec<Coord>>) {
    let direction = Coord {
        x: theta.cos(),
        y: theta.sin(),
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
        // Offsets shrink each outline's perimeter by 2π per unit (and grow each hole's):
        // a larger drop says a part ended.
        if let Some((d0, length, turns)) = previous {
            let expected = TAU * spacing * turns;
            if !current.rings.is_empty() && length - shape.0 > expected + 4.0 * spacing {
                let middle = shrink(region.outline(), region.nozzle() / 2.0 + d0 + spacing / 2.0);
                uncovered(&middle, &current, &last_loops, spacing, out);
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
    let boxes: Vec<(Coord, Coord)> = loops.iter().map(|l| super::travel::bounds(l)).collect();
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
                .map(|w| (w[1] - w[0]).x.hypot((w[1] - w[0]).y))
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
    out: &mut Vec<Vec<Coord>>,
) {
    let gap = 0.75 * spacing;
    let covered: Vec<(&[Coord], (Coord, Coord))> = covered
        .rings
        .iter()
        .map(|r| (r.as_slice(), super::travel::bounds(r)))
        .collect();
    let last: Vec<(&[Coord], (Coord, Coord))> = last
        .iter()
        .map(|r| (r.as_slice(), super::travel::bounds(r)))
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
        // Points every quarter spacing at least: a ring cut from the raw offset has
        // long edges, and a stretch is kept from vertex to vertex.
        let mut dense = Vec::with_capacity(ring.len());
        for w in ring.windows(2) {
            let e = w[1] - w[0];
            let steps = ((e.x.hypot(e.y) / (0.25 * spacing)).ceil() as usize).clamp(1, 1000);
            dense.extend((0..steps).map(|i| w[0] + e * (i as f64 / steps as f64)));
        }
        dense.extend(ring.last().copied());
        let flags: Vec<bool> = dense.iter().map(|&c| far(c)).collect();
        let mut pieces = Vec::new();
        runs(&dense, &flags, &mut pieces);
        // A stretch shorter than a spacing (a star's tip) leaves no gap worth a line.
        out.extend(pieces.into_iter().filter(|p| {
            p.windows(2)
                .map(|w| (w[1] - w[0]).x.hypot((w[1] - w[0]).y))
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
        super::region::convex_inset(area, d, 0.5)
    };
    if convex.is_none()
        && let Some(rings) = super::loops::eroded_rings(area, d, 0.5)
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
        if holes && let Some(inset) = super::region::convex_inset(area, d, 0.5) {
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
