//! Ready-made regions (centred on the origin, in mm) and the JSON multi-polygon reader.

use crate::math;
use std::f64::consts::TAU;

use geo::{Coord, LineString, MultiPolygon, Polygon};

fn ring(points: impl IntoIterator<Item = (f64, f64)>) -> LineString<f64> {
    let mut coords: Vec<Coord> = points.into_iter().map(|(x, y)| Coord { x, y }).collect();
    if let Some(&first) = coords.first() {
        coords.push(first);
    }
    LineString::new(coords)
}

fn regular(n: usize, radius: f64, clockwise: bool) -> LineString<f64> {
    ring((0..n).map(|i| {
        let a = TAU * i as f64 / n as f64 * if clockwise { -1.0 } else { 1.0 };
        (radius * math::cos(a), radius * math::sin(a))
    }))
}

/// A square of side `side`.
pub fn square(side: f64) -> MultiPolygon<f64> {
    let h = side / 2.0;
    MultiPolygon::new(vec![Polygon::new(
        ring([(-h, -h), (h, -h), (h, h), (-h, h)]),
        vec![],
    )])
}

/// A circle of `radius` as a regular 64-gon.
pub fn circle(radius: f64) -> MultiPolygon<f64> {
    MultiPolygon::new(vec![Polygon::new(regular(64, radius, false), vec![])])
}

/// A ring (tube section): a 64-gon of `outer` radius with a 64-gon hole of `inner`.
pub fn ring_shape(outer: f64, inner: f64) -> MultiPolygon<f64> {
    MultiPolygon::new(vec![Polygon::new(
        regular(64, outer, false),
        vec![regular(64, inner, true)],
    )])
}

/// A five-pointed star of `outer` radius (tips) and `inner` radius (notches).
pub fn star(outer: f64, inner: f64) -> MultiPolygon<f64> {
    MultiPolygon::new(vec![Polygon::new(
        ring((0..10).map(|i| {
            let r = if i % 2 == 0 { outer } else { inner };
            let a = TAU * i as f64 / 10.0 + TAU / 4.0;
            (r * math::cos(a), r * math::sin(a))
        })),
        vec![],
    )])
}

/// An L: a `size` square without its upper right quarter.
pub fn l_shape(size: f64) -> MultiPolygon<f64> {
    let h = size / 2.0;
    MultiPolygon::new(vec![Polygon::new(
        ring([(-h, -h), (h, -h), (h, 0.0), (0.0, 0.0), (0.0, h), (-h, h)]),
        vec![],
    )])
}

/// A square of side `side` with a round hole (64-gon) of `radius` in its middle.
pub fn holed_square(side: f64, radius: f64) -> MultiPolygon<f64> {
    let h = side / 2.0;
    MultiPolygon::new(vec![Polygon::new(
        ring([(-h, -h), (h, -h), (h, h), (-h, h)]),
        vec![regular(64, radius, true)],
    )])
}

/// Reads a multi-polygon from JSON: a GeoJSON `MultiPolygon` or `Polygon` geometry
/// object, or its bare `coordinates` (`[[[x, y], ...], [hole...]]` for one polygon,
/// one more level of brackets for several). Coordinates in mm.
pub fn from_json(text: &str) -> Result<MultiPolygon<f64>, String> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("invalid JSON: {e}"))?;
    let coordinates = match &value {
        serde_json::Value::Object(o) => o
            .get("coordinates")
            .ok_or("a JSON object must be a GeoJSON geometry with \"coordinates\"")?,
        other => other,
    };
    // Depth: 3 = one polygon (rings of points), 4 = several.
    let depth = {
        let (mut d, mut v) = (0, coordinates);
        while let Some(first) = v.as_array().and_then(|a| a.first()) {
            d += 1;
            v = first;
        }
        d
    };
    let polygons: Vec<&serde_json::Value> = match depth {
        3 => vec![coordinates],
        4 => coordinates
            .as_array()
            .map(|a| a.iter().collect())
            .unwrap_or_default(),
        _ => {
            return Err(
                "expected a multi-polygon: [[[[x, y], ...], [hole...]], ...] or one polygon [[[x, y], ...]]"
                    .into(),
            );
        }
    };
    let point = |p: &serde_json::Value| -> Result<Coord, String> {
        match p.as_array().map(|a| a.as_slice()) {
            Some([x, y, ..]) => match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) => Ok(Coord { x, y }),
                _ => Err(format!("a point must be two numbers, found {p}")),
            },
            _ => Err(format!("a point must be [x, y], found {p}")),
        }
    };
    let ring = |r: &serde_json::Value| -> Result<LineString<f64>, String> {
        let points = r.as_array().ok_or("a ring must be an array of points")?;
        let coords = points.iter().map(point).collect::<Result<Vec<_>, _>>()?;
        if coords.len() < 3 {
            return Err(format!(
                "a ring needs at least three points, found {}",
                coords.len()
            ));
        }
        Ok(LineString::new(coords))
    };
    let mut out = Vec::new();
    for polygon in polygons {
        let rings = polygon
            .as_array()
            .ok_or("a polygon must be an array of rings")?;
        let (first, holes) = rings.split_first().ok_or("a polygon needs an outline")?;
        let holes = holes.iter().map(ring).collect::<Result<Vec<_>, _>>()?;
        out.push(Polygon::new(ring(first)?, holes));
    }
    Ok(MultiPolygon::new(out))
}

/// The concave and many-ringed shapes the erosion and concentric are tested on: the
/// comparison's L, star and holed square, a star with a hole, two islands, and a square
/// with two round holes.
#[cfg(test)]
pub(crate) fn ring_shapes() -> Vec<(&'static str, MultiPolygon<f64>)> {
    use geo::Translate;
    let star_with_hole = MultiPolygon::new(vec![Polygon::new(
        star(10.0, 4.5).0[0].exterior().clone(),
        vec![circle(1.5).0[0].exterior().clone()],
    )]);
    let mut islands = star(10.0, 4.5);
    islands.0.extend(l_shape(10.0).translate(30.0, 0.0).0);
    let two_holes = MultiPolygon::new(vec![Polygon::new(
        square(40.0).0[0].exterior().clone(),
        vec![
            circle(6.0).0[0].exterior().clone().translate(-8.3, 0.0),
            circle(6.0).0[0].exterior().clone().translate(8.5, 1.3),
        ],
    )]);
    vec![
        ("L", l_shape(20.0)),
        ("star", star(10.0, 4.5)),
        ("holed square", holed_square(40.0, 10.0)),
        ("star with a hole", star_with_hole),
        ("islands", islands),
        ("two holes", two_holes),
    ]
}
