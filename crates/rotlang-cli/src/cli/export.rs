//! `rotlang export`: a template as the settings of another slicer.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::model::ModelArgs;
use super::{ColorArg, Input, UsageError, args, gather};
use crate::eval::Options;
use crate::export::{self, Export, ExportError, Slicer};
use crate::number;

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang export --to cura '0, 90'                      infill_angles = [90,0]
  rotlang export --to superslicer '+30'                 fill_angle_increment = 30
  rotlang export --to cura '+10L25%, -10l25%' --layers 150 --layer-height 0.2
  rotlang export --to orcaslicer '0 90'                 a template OrcaSlicer reads as rotlang does
  rotlang export --to cura '+30/50%' --solid '0, 90'    skin_angles for the solid layers too
  rotlang export --to prusaslicer '+45#3' --height 20 --mesh part.stl --out part.3mf
  rotlang export --to cura --profile 'process/0.20mm Standard.json' --format json

The settings are printed as `key = value` lines to paste (notes go to stderr), or with
--format json as {\"slicer\", \"template\", \"layers\", \"settings\": {...}, \"ranges\": [...],
\"max_error\", \"notes\": [{\"code\", \"message\"}]}. Lists that are not periodic are computed
for the model (the 20 mm cube unless --layers, --height, --model or --profile): export
again for another height.

Each slicer's reading (checked on CuraEngine 4.13 and PrusaSlicer 2.5, tests/slicers.rs):
  cura         infill_angles, cycled per layer; 0° runs along Y, turning clockwise;
               whole degrees (the rounding is a note)
  superslicer  fill_angle + fill_angle_increment, or fill_angle_template (cycled)
  prusaslicer  one fill_angle per height range: a 3MF project with layer-range
               modifiers (--mesh PART.stl --out FILE.3mf); fill_pattern alignedrectilinear
  orcaslicer   the template, its compat-fixed form, or a plain list
Solid signs are reported (no slicer but OrcaSlicer's forks makes chosen layers solid from
an angle setting; OrcaSlicer itself does not read them: an error).

Exit status: 0 on success, 1 when the template has errors or the slicer cannot express
it, 2 on a usage error.")]
pub struct ExportArgs {
    /// The slicer to export to.
    #[arg(long, value_enum)]
    pub to: SlicerArg,
    /// The template, e.g. '0, 90'. Put `--` before one that begins with `-`.
    #[arg(
        value_name = "TEMPLATE",
        allow_negative_numbers = true,
        conflicts_with = "file"
    )]
    pub template: Option<String>,
    /// Read the template from a file; `-` is stdin.
    #[arg(long, short = 'f', value_name = "PATH")]
    pub file: Option<PathBuf>,
    /// Take the template, model and direction from an OrcaSlicer profile or project.
    #[arg(long, value_name = "PATH", conflicts_with_all = ["template", "file"])]
    pub profile: Option<PathBuf>,
    #[command(flatten)]
    pub model: ModelArgs,
    /// A solid_infill_rotate_template for the solid layers: Cura's skin_angles,
    /// OrcaSlicer's solid_infill_rotate_template (SuperSlicer and PrusaSlicer have none).
    #[arg(long, value_name = "TEMPLATE", allow_hyphen_values = true)]
    pub solid: Option<String>,
    /// The base infill direction in degrees, added to every angle.
    #[arg(long, value_name = "DEG", default_value_t = 0.0, value_parser = args::finite,
          allow_negative_numbers = true)]
    pub base: f64,
    /// The seed of the random joints `~` and `^`.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = args::seed)]
    pub seed: u64,
    /// `text`: `key = value` lines; `json`: one object.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Write the result to a file instead of stdout: the settings (`key = value`, what
    /// PrusaSlicer's and SuperSlicer's --load read), or for prusaslicer a .3mf project.
    #[arg(long, short = 'o', value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// prusaslicer: the part (STL, binary or ASCII) the .3mf project holds.
    #[arg(long, value_name = "PART.stl")]
    pub mesh: Option<PathBuf>,
    /// Colour the diagnostics printed to stderr.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SlicerArg {
    /// Cura (CuraEngine): infill_angles
    Cura,
    /// SuperSlicer: fill_angle, fill_angle_increment, fill_angle_template
    Superslicer,
    /// PrusaSlicer: fill_angle per height range (a 3MF project)
    Prusaslicer,
    /// OrcaSlicer: sparse_infill_rotate_template
    Orcaslicer,
}

impl From<SlicerArg> for Slicer {
    fn from(s: SlicerArg) -> Slicer {
        match s {
            SlicerArg::Cura => Slicer::Cura,
            SlicerArg::Superslicer => Slicer::SuperSlicer,
            SlicerArg::Prusaslicer => Slicer::PrusaSlicer,
            SlicerArg::Orcaslicer => Slicer::OrcaSlicer,
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// `key = value` lines
    #[default]
    Text,
    /// One JSON object
    Json,
}

fn io(e: std::io::Error) -> UsageError {
    UsageError(format!("cannot write output: {e}"))
}

/// Runs the export; returns the exit code.
pub fn run(args: &ExportArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    let slicer: Slicer = args.to.into();
    if args.mesh.is_some() && slicer != Slicer::PrusaSlicer {
        return Err(UsageError(
            "--mesh is for --to prusaslicer (its 3MF project)".into(),
        ));
    }
    let three_mf = args
        .out
        .as_deref()
        .is_some_and(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("3mf")));
    if three_mf && slicer != Slicer::PrusaSlicer {
        return Err(UsageError(
            "a .3mf project is written for --to prusaslicer only".into(),
        ));
    }
    if three_mf && args.mesh.is_none() {
        return Err(UsageError(
            "a .3mf project needs the part: --mesh PART.stl".into(),
        ));
    }
    let mut resolved = args.model.resolve()?;
    let mut base = args.base;
    let input = match &args.profile {
        Some(path) => {
            let p = super::files::profile_template(
                path,
                crate::Target::Sparse,
                None,
                args.model.height,
            )?;
            // A broken profile is reported as `check` reports it, and stops the command.
            if let Some(report) = &p.errors {
                err.write_all(report.as_bytes()).map_err(io)?;
                return Ok(1);
            }
            for note in &p.notes {
                writeln!(err, "note: {note}").map_err(io)?;
            }
            if args.model.model.is_none() && args.model.layers.is_none() {
                resolved.model = p.model;
            }
            if base == 0.0 {
                base = p.base;
            }
            Input {
                name: path.display().to_string(),
                text: p.text,
                path: Some(path.clone()),
            }
        }
        None => {
            let templates: Vec<String> = args.template.iter().cloned().collect();
            let files: Vec<PathBuf> = args.file.iter().cloned().collect();
            gather(&templates, &files)?
                .into_iter()
                .next()
                .ok_or_else(|| UsageError("no template given".into()))?
        }
    };
    let model = &resolved.model;
    let options = Options {
        base,
        seed: args.seed,
    };
    let result = export::export(&input.text, slicer, model, options);
    // The solid template's errors are reported against its own text.
    let solid_input = args.solid.as_ref().map(|t| Input {
        name: "<solid template>".into(),
        text: t.clone(),
        path: None,
    });
    let (input, result) = match (result, &solid_input) {
        (Ok(mut e), Some(solid)) => {
            let r = export::export_solid(&mut e, &solid.text, model, options).map(|()| e);
            match r {
                Err(ExportError::Template(p)) => (solid.clone(), Err(ExportError::Template(p))),
                other => (input, other),
            }
        }
        (r, _) => (input, r),
    };
    let exported = match result {
        Ok(e) => e,
        Err(ExportError::Template(parse)) => {
            if args.format == Format::Json {
                writeln!(out, "{}", super::report_json(&input, &parse)).map_err(io)?;
            }
            err.write_all(
                super::render_diagnostics(&input, &parse.diagnostics, args.color.enabled(false))
                    .as_bytes(),
            )
            .map_err(io)?;
            return Ok(1);
        }
        Err(e @ ExportError::Inexpressible { .. }) => {
            if args.format == Format::Json
                && let ExportError::Inexpressible { code, message } = &e
            {
                let v = serde_json::json!({
                    "slicer": slicer.name(), "template": input.text,
                    "error": {"code": code, "message": message},
                });
                writeln!(out, "{v}").map_err(io)?;
            }
            writeln!(err, "error: {e}").map_err(io)?;
            return Ok(1);
        }
    };
    for n in &exported.notes {
        writeln!(err, "note[{}]: {}", n.code, n.message).map_err(io)?;
    }
    if three_mf {
        let mesh_path = args.mesh.as_deref().unwrap_or(Path::new(""));
        let bytes = std::fs::read(mesh_path)
            .map_err(|e| UsageError(format!("cannot read {}: {e}", mesh_path.display())))?;
        let mesh = export::threemf::read_stl(&bytes)
            .map_err(|e| UsageError(format!("{}: {e}", mesh_path.display())))?;
        let name = mesh_path
            .file_stem()
            .map_or("part".into(), |s| s.to_string_lossy().into_owned());
        let project = export::threemf::project(&exported, &mesh, &name).map_err(UsageError)?;
        let target = args.out.as_deref().unwrap_or(Path::new(""));
        std::fs::write(target, project)
            .map_err(|e| UsageError(format!("cannot write {}: {e}", target.display())))?;
        writeln!(
            err,
            "wrote {} ({} layer ranges, {} triangles)",
            target.display(),
            exported.ranges.len(),
            mesh.triangles.len()
        )
        .map_err(io)?;
        return Ok(0);
    }
    let body = match args.format {
        Format::Json => format!("{}\n", json(&exported, &input.text)),
        Format::Text => text(&exported),
    };
    match &args.out {
        Some(path) => std::fs::write(path, body)
            .map_err(|e| UsageError(format!("cannot write {}: {e}", path.display())))?,
        None => out.write_all(body.as_bytes()).map_err(io)?,
    }
    Ok(0)
}

/// `key = value` lines, with PrusaSlicer's ranges as comments after them.
pub fn text(e: &Export) -> String {
    let mut s = String::new();
    for (k, v) in &e.settings {
        s.push_str(&format!("{k} = {v}\n"));
    }
    if e.ranges.len() > 1 {
        s.push_str("# layer ranges (mm above the object's bottom): fill_angle\n");
        for r in &e.ranges {
            s.push_str(&format!(
                "# {}..{} = {}\n",
                number::height(r.min_z).as_str(),
                number::height(r.max_z).as_str(),
                number::angle(r.fill_angle).as_str()
            ));
        }
    }
    s
}

/// The JSON object of `--format json`.
pub fn json(e: &Export, template: &str) -> serde_json::Value {
    let settings: serde_json::Map<String, serde_json::Value> = e
        .settings
        .iter()
        .map(|(k, v)| (k.clone(), serde_json::Value::from(v.as_str())))
        .collect();
    serde_json::json!({
        "slicer": e.slicer.name(),
        "template": template,
        "layers": e.layers,
        "settings": settings,
        "ranges": e.ranges,
        "max_error": e.max_error,
        "notes": e.notes,
    })
}
