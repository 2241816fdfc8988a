//! A plain cycle of layers (a leaf: the evaluator and the OrcaSlicer dialect both give
//! one, and neither names the other for it).

use crate::ir::Fill;

/// A template that gives layer `k` the angle and fill `cycle[k mod n]`, whatever the
/// model: see [`Layers::plain_cycle`](super::Layers::plain_cycle).
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// Angle (degrees, base included) and fill of each entry.
    pub entries: Vec<(f64, Fill)>,
}

impl Cycle {
    /// Layer `index`'s angle and fill.
    #[inline]
    pub fn at(&self, index: usize) -> (f64, Fill) {
        self.entries[index % self.entries.len()]
    }

    /// The angles (and fills) of layers `first..first + angles.len()`, written in turn:
    /// copies of the cycle, no per-layer arithmetic but the wrap.
    pub fn write(&self, first: usize, angles: &mut [f64], mut fills: Option<&mut [Fill]>) {
        let n = self.entries.len();
        let mut k = first % n;
        for (i, slot) in angles.iter_mut().enumerate() {
            let (angle, fill) = self.entries[k];
            *slot = angle;
            if let Some(f) = fills.as_deref_mut().and_then(|f| f.get_mut(i)) {
                *f = fill;
            }
            k += 1;
            if k == n {
                k = 0;
            }
        }
    }
}
