//! The infill core: the toolpaths of one layer's infill, turned by the layer's angle.
//!
//! Behind the `infill` cargo feature (it needs `geo`); the evaluator does not.
//!
//! A layer's **region** is a [`MultiPolygon`] in millimetres (holes allowed, any number of
//! islands). It is first inset by half a nozzle ([`Region::new`]); the patterns fill that
//! inset area and never leave it: every line is clipped exactly against the inset outline
//! and its holes (concave ones too), by an even-odd scan for straight lines and by
//! segment-edge intersection for curves.
//!
//! ```
//! use rotlang_geometry::infill::{self, Centring, Params, Pattern, Region};
//!
//! let square = infill::shapes::square(20.0);
//! let region = Region::new(&square, 0.4)?;
//! let params = Params::new(Pattern::Grid, 0.2, 0.4).angle(30.0);
//! let paths = region.fill(&params)?;
//! // Covered length × nozzle ÷ area: the requested 20%.
//! let density = paths.length * 0.4 / region.area();
//! assert!((density - 0.2).abs() < 0.02, "{density}");
//! # Ok::<(), rotlang_geometry::infill::Error>(())
//! ```
//!
//! The template drives it through [`Schedule`]: evaluate once, fill any layer.
//!
//! # Spacing
//!
//! The density ρ is the covered area fraction: covered length × nozzle ÷ infill area
//! (the inset area). With nozzle `w`:
//!
//! | pattern | geometry | spacing |
//! |---|---|---|
//! | `lines` | one family at θ | `w/ρ` |
//! | `grid` | θ and θ+90° | `2w/ρ` per family |
//! | `triangles` | θ, θ+60°, θ+120°, concurrent | `3w/ρ` per family |
//! | `hexagons` | honeycomb, one wall family along θ | side `a = 2w/(√3ρ)` |
//! | `concentric` | loops at `(k+½)s` inside the inset outline | `s = w/ρ` |
//! | `gyroid` | the cross-section at the layer's height of the gyroid surface | period `2π·wλ̄/ρ` |
//! | `spiral` | Archimedean spiral from the pattern centre | `w/ρ` between turns |
//! | `lightning` | branches from the outline toward the centre | measured, then respaced to ρ |
//! | `cubic` | θ, θ+120°, θ+240°, each shifted `z/√2` along its normal | `3w/ρ` per family |
//!
//! `cubic` is the section at height z of a lattice of cubes standing on a corner (a body
//! diagonal vertical): each family of cube faces cuts the layer in parallel lines that
//! move `z/√2` per mm of height (a face's normal is `1/√3` up and `√(2/3)` across), so the
//! layers' triangles grow, turn into hexagons and shrink again, and the walls meet in
//! three dimensions. Polyslice documents it only as a future pattern.
//!
//! **How closely a layer meets ρ depends on the region's size.** The spacing is exact, but
//! a region only a few lines across gets a line more or fewer than its share: the density
//! holds within 10% once the region spans at least **12 repeats** of the pattern across its
//! narrowest part (a repeat is `w/ρ` for `lines`, `concentric` and `spiral`, `2w/ρ` for
//! `grid` and `hexagons`, `3w/ρ` for `triangles` and `cubic`, the period for `gyroid`). At 20% with a
//! 0.4 mm nozzle that is 24 mm for `lines` but 72 mm for `triangles`; a 20 mm part at 5%
//! (two to six repeats) measures anywhere from about 0.2 to 2.9 times ρ by pattern and
//! shape, and at four repeats a quarter off is common. The property tests scale each
//! shape to 12 repeats. `gyroid` varies with z too (below). `lightning`'s branches are
//! spaced along the outline, so what a given spacing covers depends on the shape (0.57–0.69
//! of ρ on compact shapes, about ρ on a star): a first tree is measured and the branches
//! spaced again, so that the density printed is the one asked (within 10%).
//!
//! Where this differs from Polyslice's documentation (seed 002), on purpose:
//! - **hexagons**: its side `3w/(√3ρ)` gives two thirds of the density asked (about 13%
//!   at 20%). A honeycomb of side `a` has `2/(√3a)` mm of wall per mm², hence `a` above.
//! - **gyroid**: its "spacing × 1.5" with hand-drawn sine waves is replaced by the true
//!   cross-section `sin x cos y + sin y cos z + sin z cos x = 0`, scaled so that its wall
//!   length per area, averaged over z (λ̄ = [`GYROID_LAMBDA`] per unit), gives ρ. A single
//!   layer's density varies with z from −6% to +23% of ρ, as the surface's does.
//! - **concentric**: loops start half a spacing inside the inset outline, so each loop
//!   owns a band of one spacing and the density is ρ (starting at the outline adds half a
//!   loop's worth, +20% on a small part).
//! - **grid** runs along θ and θ+90°: the profile's usual ±45° is the base direction 45°.
//! - **holes** are clipped exactly for every pattern, concave ones included.
//!
//! # Turning
//!
//! Every pattern turns with the layer's angle θ (degrees, counter-clockwise from +x):
//! `lines`, `grid`, `triangles`, `cubic` run along θ (and the other families at their
//! fixed offsets from it); `hexagons` and `gyroid` are their fixed pattern rotated by θ about the
//! pattern centre. A turn of `concentric` moves each loop's start (its seam) to the loop's
//! farthest point in direction θ; a turn of `spiral` rotates the spiral about its centre,
//! so it starts in direction θ; `lightning`'s branches start at points spaced along the
//! outline from its farthest point in direction θ.
//!
//! # Centring
//!
//! [`Centring::Object`] puts the pattern's centre (the point every family's lines pass
//! through, the spiral's centre, the rotation centre) at the centre of the region's
//! bounding box; [`Centring::Global`] at the origin (0, 0), so that every object shares
//! one pattern (place regions in plate coordinates, plate centre at the origin).
//! Concentric loops follow the outline whatever the centring.

mod clip;
mod curves;
mod lightning;
mod loops;
mod offset;
mod order;
mod patterns;
pub mod preview;
mod region;
mod schedule;
mod scratch;
pub mod shapes;
mod straight;
pub(crate) mod travel;

pub use geo::{Coord, LineString, MultiPolygon, Polygon};
pub use patterns::fill;
pub use region::{Region, inset};
pub use schedule::{LayerFill, Schedule, Settings};

use std::fmt;
use std::str::FromStr;

/// The wall length per unit area of the gyroid's cross-section (unit period 2π), averaged
/// over a period of heights. Recomputed by a unit test.
pub const GYROID_LAMBDA: f64 = 0.391_316;

/// The largest region side (mm): a kilometre. Coordinates beyond are rejected, so that
/// no squared distance or line count can overflow.
pub const MAX_COORDINATE: f64 = 1e6;

/// The most vertices one layer may produce (about 300 MB of output): a finer pattern
/// over a larger region is an error, not an out-of-memory.
pub const MAX_VERTICES: f64 = 2e7;

/// An infill pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Pattern {
    /// One family of parallel lines along θ (rectilinear).
    #[default]
    Lines,
    /// Two families at θ and θ+90°.
    Grid,
    /// Three concurrent families at θ, θ+60°, θ+120°: equilateral triangles.
    Triangles,
    /// A honeycomb with one wall family along θ.
    Hexagons,
    /// Loops following the outline; θ places their seams.
    Concentric,
    /// The gyroid surface's cross-section at the layer's height, turned by θ.
    Gyroid,
    /// An Archimedean spiral from the pattern centre, starting in direction θ.
    Spiral,
    /// Branches from the outline toward the centre: sparse, for supporting top skins.
    Lightning,
    /// Three families at θ, θ+120°, θ+240° that shift with z: the section of a lattice
    /// of cubes standing on a corner.
    Cubic,
}

impl Pattern {
    /// Every pattern; new ones are appended (bindings index this list).
    pub const ALL: [Pattern; 9] = [
        Pattern::Lines,
        Pattern::Grid,
        Pattern::Triangles,
        Pattern::Hexagons,
        Pattern::Concentric,
        Pattern::Gyroid,
        Pattern::Spiral,
        Pattern::Lightning,
        Pattern::Cubic,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Pattern::Lines => "lines",
            Pattern::Grid => "grid",
            Pattern::Triangles => "triangles",
            Pattern::Hexagons => "hexagons",
            Pattern::Concentric => "concentric",
            Pattern::Gyroid => "gyroid",
            Pattern::Spiral => "spiral",
            Pattern::Lightning => "lightning",
            Pattern::Cubic => "cubic",
        }
    }
}

impl fmt::Display for Pattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Pattern {
    type Err = String;
    fn from_str(s: &str) -> Result<Pattern, String> {
        Pattern::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| {
                let names: Vec<&str> = Pattern::ALL.iter().map(|p| p.name()).collect();
                format!(
                    "unknown pattern {s:?}; expected one of {}",
                    names.join(", ")
                )
            })
    }
}

/// Where the pattern is anchored (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Centring {
    /// At the centre of the region's bounding box.
    #[default]
    Object,
    /// At the origin (0, 0): every object on the plate shares one pattern.
    Global,
}

impl FromStr for Centring {
    type Err = String;
    fn from_str(s: &str) -> Result<Centring, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "object" => Ok(Centring::Object),
            "global" => Ok(Centring::Global),
            _ => Err(format!("unknown centring {s:?}; expected object or global")),
        }
    }
}

/// The order the toolpaths are printed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Order {
    /// Nearest neighbour: from where the last path ended, the closest path end next,
    /// reversing paths as needed.
    #[default]
    Nearest,
    /// Monotonic (`M`): lines in order across the region, every one in the same direction.
    Monotonic,
}

/// What to fill one layer with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub pattern: Pattern,
    /// The covered fraction of the area, in (0, 1] (0.2 for 20%).
    pub density: f64,
    /// The nozzle diameter, i.e. the line width (mm).
    pub nozzle: f64,
    /// The layer's angle θ in degrees (any value; unwrapped angles are fine).
    pub angle: f64,
    /// The height of the layer's middle (mm): the gyroid's phase.
    pub z: f64,
    pub centring: Centring,
    pub order: Order,
}

impl Params {
    pub fn new(pattern: Pattern, density: f64, nozzle: f64) -> Params {
        Params {
            pattern,
            density,
            nozzle,
            angle: 0.0,
            z: 0.0,
            centring: Centring::Object,
            order: Order::Nearest,
        }
    }

    pub fn angle(self, angle: f64) -> Params {
        Params { angle, ..self }
    }

    pub fn z(self, z: f64) -> Params {
        Params { z, ..self }
    }

    pub fn centring(self, centring: Centring) -> Params {
        Params { centring, ..self }
    }

    pub fn order(self, order: Order) -> Params {
        Params { order, ..self }
    }
}

/// The toolpaths of one layer, in print order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Toolpaths {
    /// Each one printed without lifting; a closed loop repeats its first point last.
    pub polylines: Vec<LineString<f64>>,
    /// Their total length (mm).
    pub length: f64,
    /// The total travel between them, from the end of one to the start of the next (mm),
    /// along `travels`.
    pub travel: f64,
    /// The travel moves, one between each two paths: straight, or around the holes (and
    /// along concave outlines) that a straight move would cross, as slicers route them.
    pub travels: Vec<LineString<f64>>,
}

/// Why a layer could not be filled.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// The density is not in (0, 1].
    Density(f64),
    /// The nozzle is not in [0.01, 10] mm.
    Nozzle(f64),
    /// A coordinate is not finite or beyond ±[`MAX_COORDINATE`].
    Coordinate(f64),
    /// The angle or height is not finite.
    NotFinite(&'static str, f64),
    /// The pattern would need more than [`MAX_VERTICES`] vertices on this region.
    TooLarge { estimate: f64 },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Density(d) => write!(
                f,
                "the density is {}; it must be above 0% and at most 100%",
                d * 100.0
            ),
            Error::Nozzle(w) => write!(
                f,
                "the nozzle diameter is {w} mm; it must be between 0.01 and 10 mm"
            ),
            Error::Coordinate(c) => write!(
                f,
                "the region has a coordinate {c}; coordinates must be finite and within ±{MAX_COORDINATE} mm"
            ),
            Error::NotFinite(what, v) => write!(f, "the {what} is {v}; it must be finite"),
            Error::TooLarge { estimate } => write!(
                f,
                "the pattern would have about {estimate:.0} vertices on this region (at most {MAX_VERTICES:.0}): \
                 use a lower density, a larger nozzle or a smaller region"
            ),
        }
    }
}

impl std::error::Error for Error {}

fn check(params: &Params) -> Result<(), Error> {
    if !(params.density > 0.0 && params.density <= 1.0) {
        return Err(Error::Density(params.density));
    }
    if !(0.01..=10.0).contains(&params.nozzle) {
        return Err(Error::Nozzle(params.nozzle));
    }
    if !params.angle.is_finite() {
        return Err(Error::NotFinite("angle", params.angle));
    }
    if !params.z.is_finite() {
        return Err(Error::NotFinite("height", params.z));
    }
    Ok(())
}

#[cfg(test)]
mod inset_tests;
#[cfg(test)]
mod tests;
