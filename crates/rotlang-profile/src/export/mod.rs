//! Turning a template into the settings other slicers understand.
//!
//! Every slicer gets the same layers: the template is evaluated on a model (rotlang's
//! reading), each layer's direction taken modulo 180° (lines have no head), and the
//! shortest setting of that slicer that gives those directions is chosen:
//!
//! - **Cura** (`infill_angles`, a list cycled per layer): the template's period, or one
//!   angle per layer of the model. Cura measures from +Y clockwise (our `d` is Cura's
//!   `90 − d`) and keeps integers: the rounding is reported.
//! - **SuperSlicer** (`fill_angle`, `fill_angle_increment`, `fill_angle_template`): a
//!   constant, a constant turn per layer, or a list cycled per layer.
//! - **PrusaSlicer** (one `fill_angle` per object or per height range): one layer range
//!   per run of layers of one direction, written as a 3MF project's layer-range modifiers
//!   ([`threemf`], feature `3mf`).
//! - **OrcaSlicer**: a template OrcaSlicer reads as rotlang does: the template, its
//!   compat-fixed form, a plain list of its period, or of every layer; or an error naming
//!   what no OrcaSlicer template expresses (solid signs).
//!
//! ```
//! use rotlang_profile::export::{Slicer, export};
//! let out = export("0, 90", Slicer::Cura, &rotlang::eval::Model::cube20(), Default::default())
//!     .expect("a valid template");
//! assert_eq!(out.setting("infill_angles"), Some("[90,0]"));
//! ```

mod slicers;
#[cfg(feature = "3mf")]
pub mod threemf;

pub use slicers::{Range, export, export_solid};

use crate::Parse;

/// The slicers a template can be exported to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slicer {
    Cura,
    SuperSlicer,
    PrusaSlicer,
    OrcaSlicer,
}

impl Slicer {
    pub const ALL: [Slicer; 4] = [
        Slicer::Cura,
        Slicer::SuperSlicer,
        Slicer::PrusaSlicer,
        Slicer::OrcaSlicer,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Slicer::Cura => "cura",
            Slicer::SuperSlicer => "superslicer",
            Slicer::PrusaSlicer => "prusaslicer",
            Slicer::OrcaSlicer => "orcaslicer",
        }
    }
}

/// A remark on an export: what was rounded, approximated or left out.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Note {
    /// A stable code (`rotlang explain CODE`).
    pub code: &'static str,
    pub message: String,
}

/// The settings to give a slicer.
#[derive(Clone, Debug, PartialEq)]
pub struct Export {
    pub slicer: Slicer,
    /// `key = value` pairs, in the slicer's own spelling, in the order to paste them.
    pub settings: Vec<(String, String)>,
    /// PrusaSlicer: the height ranges and their `fill_angle`.
    pub ranges: Vec<Range>,
    pub notes: Vec<Note>,
    /// The largest difference (degrees, modulo 180) between a layer's exported direction
    /// and the template's: 0 unless the slicer rounds (Cura's integers).
    pub max_error: f64,
    /// How many layers of the model the export was computed for.
    pub layers: usize,
}

impl Export {
    /// The value of one setting.
    pub fn setting(&self, key: &str) -> Option<&str> {
        self.settings
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

/// Why a template cannot be exported.
#[derive(Clone, Debug)]
pub enum ExportError {
    /// The template has errors (the parse has them).
    Template(Box<Parse>),
    /// No setting of the slicer gives these layers.
    Inexpressible { code: &'static str, message: String },
}

impl std::fmt::Display for ExportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExportError::Template(p) => write!(f, "the template has {} error(s)", p.errors.max(1)),
            ExportError::Inexpressible { code, message } => write!(f, "{message} [{code}]"),
        }
    }
}

impl std::error::Error for ExportError {}
