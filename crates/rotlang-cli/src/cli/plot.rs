//! `rotlang plot`: the angle against height, as an SVG chart.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::{ColorArg, Input, TargetArg, UsageError};
use crate::eval::{self, Model, Options};
use crate::plot::PlotOptions;

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang plot '+10L25%, -10l25%' --out angles.svg          the 20 mm cube (100 × 0.2 mm)
  rotlang plot '0, 90, 0MB' --height 40 --layer-height 0.1 > angles.svg
  rotlang plot --file profile.rot --model part.json --base 45 --out angles.svg
  rotlang plot -- -30/50%                                    a template that begins with '-'

The chart has two panels over the object's height: above, the angle as evaluated (base
included, not wrapped) as a line; below, the direction of the infill lines (the angle
modulo 180°) as points, solid layers (D S O M R) as orange squares and marks under the
axis. The layers each instruction governs are shaded, one colour per instruction, and
labelled with its text where there is room.

Exit status: 0 on success (warnings are printed to stderr), 1 when the template has
errors (nothing is drawn), 2 on a usage error.")]
pub struct PlotArgs {
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
    /// A uniform model of N layers. Without --layers, --height or --model: the 20 mm cube.
    #[arg(long, value_name = "N", help_heading = "Model", conflicts_with_all = ["height", "model"],
          value_parser = super::args::layers, allow_negative_numbers = true)]
    pub layers: Option<usize>,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub profile: super::paths::ProfileArgs,
    /// `rotlang`: the language as documented; `orcaslicer`: exactly the angles OrcaSlicer
    /// computes, for any text (as `expand --dialect`); where it hangs, crashes or yields
    /// NaN the layers are reported on stderr and the angles stay finite.
    #[arg(long, value_name = "DIALECT", default_value_t)]
    pub dialect: eval::Dialect,
    /// Write the SVG to this file instead of stdout.
    #[arg(long, short = 'o', value_name = "FILE.svg")]
    pub out: Option<PathBuf>,
    /// The picture's size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "960x560", value_parser = parse_size)]
    pub size: (f64, f64),
    /// The chart's title [default: the template].
    #[arg(long)]
    pub title: Option<String>,
    /// Colour the diagnostics printed to stderr.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

/// The model options `plot` and `preview` share (each adds its own `--layers`).
#[derive(clap::Args, Debug, Default)]
pub struct ModelArgs {
    /// A uniform model tall enough for an object of MM millimetres, e.g. --height 42.
    #[arg(
        long,
        value_name = "MM",
        value_parser = super::args::millimetres,
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub height: Option<f64>,
    /// The standard layer height h in mm [default: 0.2].
    #[arg(
        long,
        value_name = "MM",
        value_parser = super::args::millimetres,
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub layer_height: Option<f64>,
    /// The first layer's height in mm [default: the layer height].
    #[arg(
        long,
        value_name = "MM",
        value_parser = super::args::millimetres,
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub first_layer_height: Option<f64>,
    /// A model from a JSON file, as for `rotlang expand --model`.
    #[arg(long, value_name = "PATH", help_heading = "Model")]
    pub model: Option<PathBuf>,
    /// The bottom shell layer count, what `B` counts [default: 3, or the --model file's].
    #[arg(long, value_name = "N", help_heading = "Model", value_parser = super::args::shells,
          allow_negative_numbers = true)]
    pub bottom_shell_layers: Option<u32>,
    /// The top shell layer count, what `T` counts [default: 4, or the --model file's].
    #[arg(long, value_name = "N", help_heading = "Model", value_parser = super::args::shells,
          allow_negative_numbers = true)]
    pub top_shell_layers: Option<u32>,
    /// The base infill direction in degrees, added to every angle (e.g. --base 45).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true,
        help_heading = "Model"
    )]
    pub base: f64,
    /// The seed of the random joints `~` and `^`.
    #[arg(long, value_name = "N", default_value_t = 0, help_heading = "Model",
          value_parser = super::args::seed, allow_negative_numbers = true)]
    pub seed: u64,
}

impl ModelArgs {
    /// The model: `layers` uniform layers, or --height, or --model, or the 20 mm cube.
    pub fn build(&self, layers: Option<usize>) -> Result<Model, UsageError> {
        let h = self.layer_height.unwrap_or(0.2);
        let h0 = self.first_layer_height;
        let invalid = |e: eval::ModelError| UsageError(format!("invalid model: {e}"));
        let model = match (&self.model, layers, self.height) {
            (Some(path), _, _) => {
                super::model::ModelArgs {
                    model: Some(path.display().to_string()),
                    ..Default::default()
                }
                .resolve()?
                .model
            }
            (None, Some(n), _) => Model::uniform(n, h, h0).map_err(invalid)?,
            (None, None, Some(height)) => {
                Model::from_total_height(height, h, h0).map_err(invalid)?
            }
            (None, None, None) if self.layer_height.is_some() || h0.is_some() => {
                return Err(UsageError(
                    "--layer-height and --first-layer-height need the model's size (--height MM, or \
                     --layers N for plot); without it the model is the 20 mm cube"
                        .into(),
                ));
            }
            (None, None, None) => Model::cube20(),
        };
        let (bottom, top) = (
            self.bottom_shell_layers.unwrap_or(model.bottom_shells()),
            self.top_shell_layers.unwrap_or(model.top_shells()),
        );
        Ok(model.with_shells(bottom, top))
    }

    pub fn options(&self) -> Options {
        Options {
            base: self.base,
            seed: self.seed,
        }
    }
}

fn parse_size(s: &str) -> Result<(f64, f64), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, e.g. 960x560, found {s:?}"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| (200.0..=20000.0).contains(v))
            .ok_or_else(|| format!("a size must be between 200 and 20000 pixels, found {v:?}"))
    };
    Ok((parse(w)?, parse(h)?))
}

/// What a picture is drawn from: the template, its parse, and its model and options
/// (a profile's unless the command line gives them).
pub(super) struct Drawn {
    pub input: Input,
    pub parse: crate::Parse,
    pub model: Model,
    pub options: Options,
}

/// The template to draw (by the one path rule, or from --profile), its diagnostics
/// printed; `Err(1)` when it or its profile has errors.
pub(super) fn template(
    text: &Option<String>,
    file: &Option<PathBuf>,
    profile: &super::paths::ProfileArgs,
    (target, dialect): (TargetArg, eval::Dialect),
    color: ColorArg,
    model: (&ModelArgs, Option<usize>),
    err: &mut dyn Write,
) -> Result<Result<Drawn, i32>, UsageError> {
    let (model_args, layers) = model;
    // The model first: a usage error should not wait for stdin.
    let built = model_args.build(layers)?;
    let source = match super::paths::source(
        text.as_ref(),
        file.as_ref(),
        profile,
        target.into(),
        model_args.height,
        err,
    )? {
        Ok(s) => s,
        Err(code) => return Ok(Err(code)),
    };
    let mut options = model_args.options();
    let mut model = built;
    if let Some(p) = source.profile {
        let given = layers.is_some() || model_args.height.is_some() || model_args.model.is_some();
        if !given {
            let (b, t) = (
                model_args
                    .bottom_shell_layers
                    .unwrap_or(p.model.bottom_shells()),
                model_args.top_shell_layers.unwrap_or(p.model.top_shells()),
            );
            model = p.model.with_shells(b, t);
        }
        // The profile's direction (for an empty template), unless --base replaces it.
        if options.base == 0.0 {
            options.base = p.base;
        }
    }
    let input = source.input;
    let parse = crate::parse(&input.text, target.into());
    // OrcaSlicer has no grammar: any text is drawn as it reads it.
    if dialect == eval::Dialect::OrcaSlicer {
        return Ok(Ok(Drawn {
            input,
            parse,
            model,
            options,
        }));
    }
    if !parse.diagnostics.is_empty() {
        let report = super::render_diagnostics(&input, &parse.diagnostics, color.enabled(false));
        err.write_all(report.as_bytes())
            .map_err(|e| UsageError(format!("cannot write to stderr: {e}")))?;
    }
    if parse.has_errors() {
        return Ok(Err(1));
    }
    Ok(Ok(Drawn {
        input,
        parse,
        model,
        options,
    }))
}

/// Writes `text` to `path`, or to `out` when there is none.
pub(super) fn emit(text: &str, path: Option<&Path>, out: &mut dyn Write) -> Result<(), UsageError> {
    match path {
        Some(path) => std::fs::write(path, text)
            .map_err(|e| UsageError(format!("cannot write {}: {e}", path.display()))),
        None => match out.write_all(text.as_bytes()) {
            Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                Err(UsageError(format!("cannot write output: {e}")))
            }
            _ => Ok(()),
        },
    }
}

/// Runs `rotlang plot`; returns the exit code.
pub fn run(args: &PlotArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    let drawn = match template(
        &args.template,
        &args.file,
        &args.profile,
        (args.target, args.dialect),
        args.color,
        (&args.model, args.layers),
        err,
    )? {
        Ok(t) => t,
        Err(code) => return Ok(code),
    };
    let options = PlotOptions {
        width: args.size.0,
        height: args.size.1,
        title: args.title.clone(),
    };
    let svg = match args.dialect {
        eval::Dialect::Rotlang => crate::plot::svg(
            &drawn.parse.template,
            &drawn.model,
            drawn.options,
            &drawn.input.text,
            &options,
        ),
        eval::Dialect::OrcaSlicer => {
            let (svg, findings) = crate::plot::svg_orcaslicer(
                &drawn.parse.template,
                &drawn.model,
                drawn.options,
                &drawn.input.text,
                &options,
            );
            for f in findings {
                writeln!(
                    err,
                    "warning[{}]: {} ({} layers from layer {}; drawn with finite angles)",
                    f.code, f.message, f.layers, f.first_layer
                )
                .map_err(|e| UsageError(format!("cannot write to stderr: {e}")))?;
            }
            svg
        }
    };
    emit(&svg, args.out.as_deref(), out)?;
    Ok(0)
}
