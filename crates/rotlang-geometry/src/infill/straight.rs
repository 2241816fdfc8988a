//! Patterns of straight walls: families of parallel lines, and the honeycomb.

use geo::Coord;

use super::Region;
use super::clip::{Edges, Frame};

/// One family of lines per offset (degrees from θ), `spacing` apart, every family with a
/// line through `centre` (so that three families at 60° meet in common points), or
/// `shift` mm to the left of it (cubic).
pub(crate) fn families(
    region: &Region,
    centre: Coord,
    theta: f64,
    offsets: &[f64],
    spacing: f64,
    shift: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let mut intervals = Vec::new();
    for &offset in offsets {
        let frame = Frame::new(centre, theta + offset.to_radians());
        let mut edges = Edges::new(region.rings(), &frame);
        let shift = shift.rem_euclid(spacing);
        let first = ((edges.min.y - shift) / spacing).ceil() as i64;
        let last = ((edges.max.y - shift) / spacing).floor() as i64;
        for k in first..=last {
            let y = k as f64 * spacing + shift;
            edges.scan(y, &mut intervals);
            for &(x0, x1) in &intervals {
                out.push(vec![
                    frame.to_world(Coord { x: x0, y }),
                    frame.to_world(Coord { x: x1, y }),
                ]);
            }
        }
    }
}

/// A honeycomb of side `side` whose "vertical" walls run along θ: in the frame turned by
/// θ − 90°, zigzags along x (two walls per cell) joined by walls along y (one per cell),
/// three walls of length `side` per cell of area `3√3/2·side²`.
pub(crate) fn hexagons(
    region: &Region,
    centre: Coord,
    theta: f64,
    side: f64,
    out: &mut Vec<Vec<Coord>>,
) {
    let frame = Frame::new(centre, theta - std::f64::consts::FRAC_PI_2);
    let mut edges = Edges::new(region.rings(), &frame);
    let a = side;
    let half = 3f64.sqrt() * a / 2.0;
    let row = 1.5 * a;
    let (min, max) = (edges.min, edges.max);
    let j0 = (min.y / row).floor() as i64 - 2;
    let j1 = (max.y / row).ceil() as i64 + 1;
    let mut zigzag = Vec::new();
    let mut local = Vec::new();
    for j in j0..=j1 {
        let y = j as f64 * row;
        // Odd rows are shifted by half a cell.
        let cx = if j.rem_euclid(2) == 1 { half } else { 0.0 };
        // High points at cx + m·2·half, low points half-way between.
        let i0 = ((min.x - cx) / half).floor() as i64 - 2;
        let i1 = ((max.x - cx) / half).ceil() as i64 + 2;
        let i0 = i0 - i0.rem_euclid(2);
        zigzag.clear();
        for i in i0..=i1 {
            let x = cx + i as f64 * half;
            let high = i.rem_euclid(2) == 0;
            zigzag.push(Coord {
                x,
                y: y + if high { a } else { a / 2.0 },
            });
            if high && y + a <= max.y && y + 2.0 * a >= min.y && x >= min.x && x <= max.x {
                // The wall from this high point up to the next zigzag's low point.
                local.clear();
                edges.clip(
                    &[Coord { x, y: y + a }, Coord { x, y: y + 2.0 * a }],
                    &mut local,
                );
                out.extend(local.drain(..).map(|p| to_world(&frame, p)));
            }
        }
        if y + a < min.y || y + a / 2.0 > max.y {
            continue;
        }
        local.clear();
        edges.clip(&zigzag, &mut local);
        out.extend(local.drain(..).map(|p| to_world(&frame, p)));
    }
}

fn to_world(frame: &Frame, piece: Vec<Coord>) -> Vec<Coord> {
    piece.into_iter().map(|q| frame.to_world(q)).collect()
}
