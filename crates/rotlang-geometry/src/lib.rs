//! Geometry for rotlang, on `geo`: what the angles look like.
//!
//! - [`infill`]: nine infill patterns turned by a template's schedule, clipped to a region;
//! - [`mesh`]: STL, OBJ and (feature `3mf`) 3MF meshes;
//! - [`slice`](mod@slice): a mesh cut into layer sections, each filled at its layer's angle;
//! - [`plot`]: the angle chart (no geometry library: a pure function of its inputs); the
//!   infill preview is [`infill::preview`].
//!
//! The language itself is the `rotlang` crate; the evaluator never needs geo.

// The modules were part of the `rotlang` crate and name its items as `crate::…`: the
// language core stands in for the crate root here (privately: not re-exported).
#[allow(unused_imports)]
use rotlang::*;

pub mod infill;
pub(crate) mod math;
pub mod mesh;
pub mod plot;
pub mod slice;
