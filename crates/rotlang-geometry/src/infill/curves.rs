//! Curved patterns: gyroid, spiral, concentric (in `concentric.rs`).

#[path = "concentric.rs"]
mod concentric;
#[cfg(test)]
#[path = "concentric_reference.rs"]
mod concentric_reference;
#[cfg(test)]
#[path = "concentric_tests.rs"]
mod concentric_tests;
#[path = "mitres.rs"]
mod mitres;

pub(crate) use concentric::concentric;

use std::f64::consts::{PI, TAU};

use crate::math;
use geo::Coord;

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
    let (sz, cz) = math::sin_cos(z / scale);
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
            let (su, cu) = math::sin_cos(u);
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
                math::atan2(-b, -a) + PI
            } else {
                math::atan2(b, a)
            };
            let delta = math::acos((-c / r).clamp(-1.0, 1.0));
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
    let r_max = math::hypot(far[0], far[1]);
    let near = Coord {
        x: 0f64.clamp(min.x, max.x),
        y: 0f64.clamp(min.y, max.y),
    };
    let r_min = math::hypot(near.x, near.y);
    let k = spacing / TAU;
    // Start a whole turn inside the region's nearest point (the spiral starts at angle 0).
    let mut phi = ((r_min / k / TAU).floor() - 1.0).max(0.0) * TAU;
    let phi_end = r_max / k + TAU;
    // Chords that stray at most 0.02 mm from the curve (sagitta c²/8r), at most 2 mm
    // long and 20° apart.
    let mut curve = Vec::new();
    while phi <= phi_end {
        let r = k * phi;
        let (s, c) = math::sin_cos(phi);
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
