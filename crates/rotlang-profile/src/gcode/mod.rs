//! Reading back what a slicer printed: the infill direction of every layer of a G-code
//! file, measured from its extrusion moves, and the slicer's settings.
//!
//! [`scan`] streams any reader in fixed-size blocks (memory does not grow with the file),
//! follows the layer-change and feature-type comments of OrcaSlicer, Bambu Studio,
//! PrusaSlicer, SuperSlicer and Cura, and hands each finished layer to a callback. A
//! layer's direction is the dominant direction of the extrusion moves of one feature
//! (sparse infill, solid infill), modulo 180°: the peak of a length-weighted histogram of
//! the moves' directions, refined by the mean of the moves within 5° of it. Its
//! `straightness` is the share of the feature's extruded length within those 5°: near 1
//! for lines, near 0.5 for a grid, low for gyroid or concentric.
//!
//! ```
//! let gcode = b";LAYER_CHANGE\n;Z:0.2\n;TYPE:Internal infill\nG1 X0 Y0\nG1 X10 Y10 E1\n";
//! let scan = rotlang_profile::gcode::scan_all(&gcode[..], &Default::default())?;
//! let d = scan.layers[0].sparse.expect("the layer has sparse infill");
//! assert!((d.direction - 45.0).abs() < 1e-9);
//! # Ok::<(), std::io::Error>(())
//! ```

mod compare;
mod measure;
mod read;
mod settings;

pub use compare::{
    Comparison, Expected, Row, compare, cura_to_direction, expected_directions,
    expected_from_settings, model,
};
pub use measure::Direction;
pub use measure::difference;
pub use read::{Flavor, Layer, MAX_LAYERS, Scan, ScanOptions, scan, scan_all};
pub use settings::Settings;
