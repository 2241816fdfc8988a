//! The options of `rotlang preview` that only a mesh takes (a leaf: `PreviewArgs` holds
//! them, `part.rs` reads them).

#[derive(clap::Args, Debug, Clone)]
pub struct PartArgs {
    /// For a mesh: wall loops around the infill, each a line wide [default: 2, or a
    /// project's wall_loops].
    #[arg(long, value_name = "N", help_heading = "Part (a mesh as --shape)",
          value_parser = clap::value_parser!(u32).range(0..=100))]
    pub walls: Option<u32>,
    /// For a mesh: the solid infill's template (as `solid_infill_rotate_template`), which
    /// turns the solid areas (top and bottom surfaces) [default: a project's or
    /// --profile's; without one they turn with the template].
    #[arg(
        long,
        value_name = "TEMPLATE",
        allow_hyphen_values = true,
        help_heading = "Part (a mesh as --shape)"
    )]
    pub solid_template: Option<String>,
    /// For a mesh: turn the solid areas with the template, even where a project or
    /// --profile sets a solid template (to compare the two on the same part).
    #[arg(
        long,
        conflicts_with = "solid_template",
        help_heading = "Part (a mesh as --shape)"
    )]
    pub no_solid_template: bool,
    /// For a mesh: the infill print speed in mm/s, for the summary's time.
    #[arg(
        long,
        value_name = "MM/S",
        default_value_t = 100.0,
        help_heading = "Part (a mesh as --shape)"
    )]
    pub speed: f64,
    /// For a mesh: the travel speed in mm/s, for the summary's time.
    #[arg(
        long,
        value_name = "MM/S",
        default_value_t = 200.0,
        help_heading = "Part (a mesh as --shape)"
    )]
    pub travel_speed: f64,
    /// For a mesh: also draw the part's layers stacked in 3D (isometric) to FILE: an
    /// .svg, or an .html page holding it. At most 150 layers are drawn, evenly spread.
    #[arg(
        long = "3d",
        value_name = "FILE",
        help_heading = "Part (a mesh as --shape)"
    )]
    pub three_d: Option<std::path::PathBuf>,
}
