//! The options of `rotlang preview` (a leaf: `preview.rs` runs them, `part.rs` previews a
//! mesh with them, and neither names the other's code for them).

use std::ops::Range;
use std::path::PathBuf;

use crate::cli::part::PartArgs;
use crate::cli::paths::ProfileArgs;
use crate::cli::plot::ModelArgs;
use crate::cli::{ColorArg, TargetArg};
use crate::infill::Pattern;

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang preview '+45' --pattern grid --density 20 --out grid.svg
  rotlang preview '0, 90, 0MB' --pattern gyroid --shape circle --layers 0..8 > gyroid.svg
  rotlang preview '+30/50%' --pattern hexagons --shape ring --layers 10..=13 --format json
  rotlang preview '+15' --pattern lines --shape part.svg --size 40 --centring global
  rotlang preview '+15' --shape outline.json --pattern triangles --density 15%
  rotlang preview '0MB, +30' --shape part.stl --layers 10..14 --walls 3
  rotlang preview part.stl --layers all --format json > part.json    every layer, at 0°
  rotlang preview '+45' --shape part.stl --pattern gyroid --3d part.html --out layers.svg
  rotlang preview project.3mf --object Bracket --layers 20..24 --out bracket.svg
  rotlang preview '0, 90' --shape part.stl --solid-template '+90' --density 15

Each panel shows one layer: the region's outline and holes, the infill lines at the
nozzle's width coloured by print order (blue first, red last), travel moves dashed, and
the layer's index, height, angle, fill and governing instruction. Solid layers use their
fill kind at 100%: D the pattern, S --solid-pattern, O concentric, M monotonic lines,
R lines.

--shape FILE.stl|.obj|.3mf (a mesh; --object NAME picks one of a 3MF's): the part is
sliced at the middle of each layer (the model is as tall as the mesh unless --height or
--model says otherwise) and each section less --walls loops of a line's width is filled.
Top and bottom surfaces are solid as a slicer makes them: the part of a layer not
covered by all of the T layers above it (or the B layers below it) is filled solid
(--solid-pattern, turned by --solid-template, else by the template), the rest sparse. A
cube's first B and last T layers are solid throughout; a step's top is solid on the T
layers under it, beside the tower, which stays sparse. --format json gives each layer's
`areas` (sparse and solid, each with its region, angle and paths), a layer at a time:
--layers all lists every one (a picture shows at most 256). A summary of the
whole part (infill extrusion, solid included, travel, time at --speed) is printed to
stderr, and under `summary` with --format json, so templates can be compared.

An OrcaSlicer project (rotlang preview project.3mf [--object NAME]) or --profile FILE
gives what the command line does not: the templates (sparse_infill_rotate_template,
solid_infill_rotate_template), sparse_infill_density, sparse_infill_pattern,
internal_solid_infill_pattern, wall_loops, the line width (sparse_infill_line_width,
line_width or nozzle_diameter), layer_height, initial_layer_print_height and the shell
counts, with the object's overrides from Metadata/model_settings.config (as `check`
reads them). A note on stderr says what came from the file.

--shape FILE: an .svg file (every <path> and <polygon>; user units read as mm, y up,
transforms not applied; nested outlines become holes) or a .json multi-polygon
(GeoJSON MultiPolygon or Polygon, or its coordinates: [[[[x, y], ...], [hole...]], ...]).

Exit status: 0 on success, 1 when the template has errors, 2 on a usage error.")]
pub struct PreviewArgs {
    /// The template, e.g. '+30/50%'. Put `--` before one that begins with `-`.
    /// Without it, the template is read from --file or stdin.
    #[arg(
        value_name = "TEMPLATE",
        allow_negative_numbers = true,
        conflicts_with = "file"
    )]
    pub template: Option<String>,
    /// Read the template from a file (newlines separate instructions).
    #[arg(long, short = 'f', value_name = "PATH")]
    pub file: Option<PathBuf>,
    /// Which setting the template is for (solid signs are errors in a solid template).
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,
    /// The infill pattern [default: lines, or a mesh project's sparse_infill_pattern].
    #[arg(long, short = 'p', value_enum, help_heading = "Infill")]
    pub pattern: Option<PatternArg>,
    /// The infill density in percent, e.g. 20 or 20% [default: 20, or a mesh project's
    /// sparse_infill_density].
    #[arg(long, short = 'd', value_name = "PERCENT", value_parser = parse_density, help_heading = "Infill")]
    pub density: Option<f64>,
    /// The nozzle diameter (line width) in mm [default: 0.4, or a mesh project's line
    /// width].
    #[arg(long, value_name = "MM", help_heading = "Infill")]
    pub nozzle: Option<f64>,
    /// Where the pattern is anchored: the object's centre, or the origin for every object.
    #[arg(long, value_enum, default_value_t, help_heading = "Infill")]
    pub centring: CentringArg,
    /// The pattern of `S` layers and of a part's solid areas [default: lines, or a mesh
    /// project's internal_solid_infill_pattern].
    #[arg(long, value_enum, help_heading = "Infill")]
    pub solid_pattern: Option<PatternArg>,
    #[command(flatten)]
    pub part: PartArgs,
    /// The region: square, circle, ring, star, l, or a FILE (.svg or .json).
    #[arg(
        long,
        short = 's',
        value_name = "SHAPE",
        default_value = "square",
        help_heading = "Region"
    )]
    pub shape: String,
    /// The width of a built-in shape in mm [default: 20]; a shape file is scaled about
    /// its centre so that its wider side is this long (without it, the file's own size).
    #[arg(long, value_name = "MM", help_heading = "Region")]
    pub size: Option<f64>,
    /// The layers to show: A..B (B excluded), A..=B, one index, or `all` [default: 0..8].
    /// A picture shows at most 256; `--format json` lists any number, a layer at a time.
    #[arg(long, value_name = "A..B", value_parser = parse_layers)]
    pub layers: Option<Range<usize>>,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub profile: ProfileArgs,
    /// `svg`: the picture; `json`: {"layers": [{"index", "angle", "fill", "pattern",
    /// "density", "length", "travel", "polylines": [[[x, y], ...], ...]}, ...]}.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Panels per row (1 to 64).
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = crate::cli::args::columns,
          allow_negative_numbers = true)]
    pub columns: usize,
    /// Write to this file instead of stdout.
    #[arg(long, short = 'o', value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Colour the diagnostics printed to stderr.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum PatternArg {
    #[default]
    Lines,
    Grid,
    Triangles,
    Hexagons,
    Concentric,
    Gyroid,
    Spiral,
    Lightning,
    Cubic,
}

impl From<PatternArg> for Pattern {
    fn from(p: PatternArg) -> Pattern {
        match p {
            PatternArg::Lines => Pattern::Lines,
            PatternArg::Grid => Pattern::Grid,
            PatternArg::Triangles => Pattern::Triangles,
            PatternArg::Hexagons => Pattern::Hexagons,
            PatternArg::Concentric => Pattern::Concentric,
            PatternArg::Gyroid => Pattern::Gyroid,
            PatternArg::Spiral => Pattern::Spiral,
            PatternArg::Lightning => Pattern::Lightning,
            PatternArg::Cubic => Pattern::Cubic,
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum CentringArg {
    /// At the centre of the region's bounding box
    #[default]
    Object,
    /// At the origin (0, 0), shared by every object
    Global,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    #[default]
    Svg,
    Json,
}

/// The most panels one picture draws (JSON lists any number of layers).
pub(crate) const MAX_PANELS: usize = 256;

fn parse_density(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .trim_end_matches('%')
        .trim()
        .parse()
        .map_err(|_| format!("expected a percentage like 20 or 20%, found {s:?}"))?;
    if v > 0.0 && v <= 100.0 {
        Ok(v / 100.0)
    } else {
        Err(format!(
            "the density must be above 0% and at most 100%, found {s:?}"
        ))
    }
}

fn parse_layers(s: &str) -> Result<Range<usize>, String> {
    if s.trim() == "all" {
        return Ok(0..usize::MAX);
    }
    let bad = || format!("expected A..B, A..=B, one layer index or all, found {s:?}");
    let n = |v: &str| v.trim().parse::<usize>().map_err(|_| bad());
    let range = if let Some((a, b)) = s.split_once("..=") {
        n(a)?..n(b)?.checked_add(1).ok_or_else(bad)?
    } else if let Some((a, b)) = s.split_once("..") {
        n(a)?..n(b)?
    } else {
        let a = n(s)?;
        a..a + 1
    };
    if range.is_empty() {
        return Err(format!("the range {s:?} holds no layer"));
    }
    Ok(range)
}
