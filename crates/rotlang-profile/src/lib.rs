//! Slicer files for rotlang: where templates live and what slicers make of them.
//!
//! - [`profile`]: templates in OrcaSlicer presets (`.json`, `.jsonc`), `.ini` exports,
//!   `.3mf` projects (feature `3mf`) and `.rot` files, with the model each one sets;
//! - [`gcode`]: the G-code a slicer printed, read back layer by layer and compared;
//! - [`export`]: a template's settings for Cura, SuperSlicer, PrusaSlicer and OrcaSlicer.
//!
//! The language itself is the `rotlang` crate; this one adds file formats (zip, XML).

// The modules were part of the `rotlang` crate and name its items as `crate::…`: the
// language core stands in for the crate root here (privately: not re-exported).
#[allow(unused_imports)]
use rotlang::*;

pub mod api;
pub mod export;
pub mod gcode;
pub mod profile;
