//! The dominant direction of a set of segments, modulo 180°, in constant memory.

/// Histogram bins per 180°: half a degree each.
const BINS: usize = 360;
/// Moves within this many degrees of the peak count as "along" it.
const WINDOW_DEG: f64 = 5.0;

/// A measured direction.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Direction {
    /// Degrees in [0, 180), counter-clockwise from the +X axis of the G-code.
    pub direction: f64,
    /// Share (0–1) of the extruded length running within 5° of `direction`.
    pub straightness: f64,
    /// Extruded length (mm in XY) of the feature on this layer.
    pub length: f64,
    /// Number of extrusion moves.
    pub moves: u64,
}

/// Accumulates segments: per bin, the length and the doubled-angle vector sums.
#[derive(Clone, Debug)]
pub(crate) struct Accumulator {
    length: Box<[f64; BINS]>,
    cos2: Box<[f64; BINS]>,
    sin2: Box<[f64; BINS]>,
    total: f64,
    moves: u64,
}

impl Default for Accumulator {
    fn default() -> Self {
        Accumulator {
            length: Box::new([0.0; BINS]),
            cos2: Box::new([0.0; BINS]),
            sin2: Box::new([0.0; BINS]),
            total: 0.0,
            moves: 0,
        }
    }
}

impl Accumulator {
    /// Adds the segment (dx, dy) (mm).
    #[inline]
    pub(crate) fn add(&mut self, dx: f64, dy: f64) {
        let sq = dx * dx + dy * dy;
        // NaN fails `is_finite` and every comparison: it is skipped here.
        if !sq.is_finite() || sq <= 1e-12 {
            return;
        }
        let len = sq.sqrt();
        // The doubled angle makes θ and θ + 180° the same vector: lines have no head.
        let (c, s) = ((dx * dx - dy * dy) / len, 2.0 * dx * dy / len);
        let mut deg = dy.atan2(dx).to_degrees();
        if deg < 0.0 {
            deg += 180.0;
        }
        if deg >= 180.0 {
            deg -= 180.0;
        }
        let bin = ((deg * (BINS as f64 / 180.0)) as usize).min(BINS - 1);
        self.length[bin] += len;
        self.cos2[bin] += c;
        self.sin2[bin] += s;
        self.total += len;
        self.moves += 1;
    }

    #[cfg(test)]
    pub(crate) fn is_empty(&self) -> bool {
        self.moves == 0
    }

    /// The dominant direction, or `None` with no moves. Resets the accumulator.
    pub(crate) fn take(&mut self) -> Option<Direction> {
        if self.moves == 0 {
            return None;
        }
        let half = (WINDOW_DEG * BINS as f64 / 180.0) as isize;
        let at = |i: isize| i.rem_euclid(BINS as isize) as usize;
        // The peak: the bin whose ±1° neighbourhood holds the most length.
        let narrow = 2isize;
        let mut best = (0usize, -1.0f64);
        for i in 0..BINS as isize {
            let sum: f64 = (-narrow..=narrow).map(|k| self.length[at(i + k)]).sum();
            if sum > best.1 {
                best = (i as usize, sum);
            }
        }
        let peak = best.0 as isize;
        let (mut c, mut s, mut along) = (0.0, 0.0, 0.0);
        for k in -half..=half {
            let b = at(peak + k);
            c += self.cos2[b];
            s += self.sin2[b];
            along += self.length[b];
        }
        let mut direction = (s.atan2(c) / 2.0).to_degrees();
        if direction < 0.0 {
            direction += 180.0;
        }
        if direction >= 180.0 {
            direction -= 180.0;
        }
        let result = Direction {
            direction,
            straightness: (along / self.total).clamp(0.0, 1.0),
            length: self.total,
            moves: self.moves,
        };
        self.length.fill(0.0);
        self.cos2.fill(0.0);
        self.sin2.fill(0.0);
        self.total = 0.0;
        self.moves = 0;
        Some(result)
    }
}

/// The signed difference `a − b` of two directions modulo 180°, in (−90, 90].
pub fn difference(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(180.0);
    if d > 90.0 { d - 180.0 } else { d }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zigzag_lines_read_as_their_direction_despite_connectors() {
        let mut acc = Accumulator::default();
        let t = 30f64.to_radians();
        for _ in 0..20 {
            acc.add(20.0 * t.cos(), 20.0 * t.sin());
            acc.add(0.0, 0.9); // a short connector along the wall
            acc.add(-20.0 * t.cos(), -20.0 * t.sin());
        }
        let d = acc.take().expect("moves");
        assert!((d.direction - 30.0).abs() < 1e-9, "{d:?}");
        assert!(d.straightness > 0.9 && d.straightness < 1.0, "{d:?}");
        assert!(acc.take().is_none(), "reset");
    }

    #[test]
    fn directions_wrap_at_180() {
        let mut acc = Accumulator::default();
        for a in [179.8f64, 0.2, 179.9, 0.1] {
            let t = a.to_radians();
            acc.add(t.cos(), t.sin());
        }
        let d = acc.take().expect("moves");
        assert!(difference(d.direction, 0.0).abs() < 1e-6, "{d:?}");
        assert_eq!(difference(179.0, 1.0), -2.0);
        assert_eq!(difference(1.0, 179.0), 2.0);
    }

    #[test]
    fn degenerate_moves_are_ignored() {
        let mut acc = Accumulator::default();
        acc.add(0.0, 0.0);
        acc.add(f64::NAN, 1.0);
        acc.add(f64::INFINITY, 0.0);
        assert!(acc.is_empty());
        assert!(acc.take().is_none());
    }
}
