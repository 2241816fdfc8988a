//! `rotlang expand`: the angle and fill of every layer of a model, streamed.

use std::io::{BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::{ColorArg, Input, TargetArg, UsageError, gather, read_file};
use crate::eval::{self, Layer, Model, Options};

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang expand '5, 10!, +20'                       the 20 mm cube (100 × 0.2 mm, B=3, T=4)
  rotlang expand '+30/50%' --layers 300 --layer-height 0.12 --first-layer-height 0.2
  rotlang expand '+10L25%, -10l25%' --height 42 --wrap 180 --format csv > angles.csv
  rotlang expand 'B!, +30' --model part.json --format json
  rotlang expand -- -50%Z1cm                          a template that begins with '-'
  rotlang expand --file profile.rot --base 45         from a file, infill direction 45°

A --model file is one JSON object, like an entry of the conformance models.json:
  {\"layer_heights\": [0.3, 0.2, 0.2], \"layer_height\": 0.2,
   \"bottom_shell_layers\": 3, \"top_shell_layers\": 4, \"description\": \"optional\"}

Output columns: the layer index, its bottom and top height (mm), the angle (degrees, base
included), the fill (sparse, or dense/solid/concentric/monotonic/rectilinear for solid
signs) and the governing instruction (byte offsets start..end into the template; none when
every instruction is spent and the angle holds).

Exit status: 0 on success (warnings are printed to stderr), 1 when the template has
errors (nothing is expanded), 2 on a usage error (bad model, conflicting options).")]
pub struct ExpandArgs {
    /// The template to expand, e.g. '+30/50%'. Put `--` before one that begins with `-`.
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
    /// Take the template (of --target), the model and the base direction from a profile:
    /// an OrcaSlicer preset (.json), an exported .ini or a .3mf project. Layer heights,
    /// shell counts and infill direction come from the profile (notes on stderr name every
    /// default used); the object is 20 mm tall unless --height, --layers or --model; a
    /// --base other than 0 replaces the profile's direction.
    #[arg(long, value_name = "PATH", conflicts_with_all = ["template", "file"])]
    pub profile: Option<PathBuf>,
    /// Which setting the template is for (solid signs are errors in a solid template).
    #[arg(long, value_enum, default_value_t)]
    pub target: TargetArg,

    /// A uniform model of N layers (see --layer-height, --first-layer-height).
    /// Without --layers, --height or --model: the documentation's 20 mm cube.
    #[arg(long, value_name = "N", help_heading = "Model", conflicts_with_all = ["height", "model"])]
    pub layers: Option<usize>,
    /// A uniform model tall enough for an object of MM millimetres, e.g. --height 42.
    #[arg(
        long,
        value_name = "MM",
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub height: Option<f64>,
    /// The standard layer height h in mm, with --layers or --height [default: 0.2].
    /// `#` lengths count it, and counts reaching past the top extend by it.
    #[arg(
        long,
        value_name = "MM",
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub layer_height: Option<f64>,
    /// The first layer's height in mm, with --layers or --height [default: the layer height].
    #[arg(
        long,
        value_name = "MM",
        help_heading = "Model",
        conflicts_with = "model",
        allow_negative_numbers = true
    )]
    pub first_layer_height: Option<f64>,
    /// A model from a JSON file: {"layer_heights": [...], "layer_height": H,
    /// "bottom_shell_layers": B, "top_shell_layers": T} (one models.json entry).
    #[arg(long, value_name = "PATH", help_heading = "Model")]
    pub model: Option<PathBuf>,
    /// The bottom shell layer count, what `B` counts [default: 3, or the --model file's].
    #[arg(long, value_name = "N", help_heading = "Model")]
    pub bottom_shell_layers: Option<u32>,
    /// The top shell layer count, what `T` counts [default: 4, or the --model file's].
    #[arg(long, value_name = "N", help_heading = "Model")]
    pub top_shell_layers: Option<u32>,

    /// The base infill direction in degrees, added to every angle (e.g. --base 45).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub base: f64,
    /// The seed of the random joints `~` and `^`: the same seed gives the same angles.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub seed: u64,
    /// `rotlang`: the language as documented; `orcaslicer`: exactly the angles OrcaSlicer
    /// computes, for any text (valid or not); where it hangs, crashes or yields NaN the
    /// layers are reported on stderr and the angles stay finite.
    #[arg(long, value_name = "DIALECT", default_value_t)]
    pub dialect: eval::Dialect,
    /// Wrap the printed angles: `none` (90, 180, 270, 360, 450, ...), `360` (into
    /// [0, 360)), or `180` (into [0, 180): infill lines at θ and θ+180° are the same lines).
    #[arg(long, value_enum, default_value_t)]
    pub wrap: Wrap,
    /// `table`: aligned columns for people; `csv`: `index,bottom,top,angle,fill,start,end`;
    /// `json`: {"layers":[{"index":0,"bottom":0.0,"top":0.2,"angle":30.0,"fill":"sparse",
    /// "instruction":{"start":0,"end":3}}, ...]}.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Colour the diagnostics printed to stderr.
    #[arg(long, value_enum, default_value_t)]
    pub color: ColorArg,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Wrap {
    /// Angles as evaluated: not wrapped
    #[default]
    None,
    /// Into [0, 360)
    #[value(name = "360")]
    Full,
    /// Into [0, 180): the direction of the infill lines
    #[value(name = "180")]
    Half,
}

impl Wrap {
    fn apply(self, angle: f64) -> f64 {
        let wrapped = match self {
            Wrap::None => angle,
            Wrap::Full => angle.rem_euclid(360.0),
            Wrap::Half => angle.rem_euclid(180.0),
        };
        // `rem_euclid` can round up to the modulus itself for tiny negative angles, and
        // `-0.0` would print as such: both are 0 here.
        match self {
            Wrap::Full if wrapped >= 360.0 => 0.0,
            Wrap::Half if wrapped >= 180.0 => 0.0,
            _ => wrapped + 0.0,
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Aligned columns for people
    #[default]
    Table,
    /// Comma-separated values with a header line
    Csv,
    /// One JSON object: {"layers": [...]}
    Json,
}

/// One entry of the conformance `models.json`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    layer_heights: Vec<f64>,
    layer_height: f64,
    bottom_shell_layers: u32,
    top_shell_layers: u32,
    #[serde(default, rename = "description")]
    _description: Option<String>,
}

/// Runs the expansion; returns the exit code.
pub fn run(args: &ExpandArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32, UsageError> {
    // The model first: a usage error should not wait for stdin.
    let mut model = model(args)?;
    let mut base = args.base;
    let input = match &args.profile {
        Some(path) => {
            let p = super::files::profile_template(path, args.target.into(), args.height)?;
            for note in &p.notes {
                writeln!(err, "note: {note}").map_err(|e| UsageError(e.to_string()))?;
            }
            if args.model.is_none() && args.layers.is_none() {
                model = p.model;
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
    let options = Options {
        base,
        seed: args.seed,
    };
    if args.dialect == eval::Dialect::OrcaSlicer {
        return super::dialect::expand(&input.text, &model, options, err, |layers| {
            write_layers(layers, &input.text, args, out)
        });
    }
    // The IR is not kept: a megabyte template costs a small multiple of its size.
    let (parse, layers) = eval::parse_layers(&input.text, args.target.into(), &model, options);
    let write_error = |e: std::io::Error| UsageError(format!("cannot write to stderr: {e}"));
    if !parse.diagnostics.is_empty() {
        err.write_all(report(&input, &parse.diagnostics, args.color).as_bytes())
            .map_err(write_error)?;
    }
    if parse.has_errors() {
        return Ok(1);
    }
    match write_layers(layers, &input.text, args, out) {
        Ok(()) => Ok(0),
        // The reader went away (`| head`): what it wanted was written.
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(0),
        Err(e) => Err(UsageError(format!("cannot write output: {e}"))),
    }
}

/// The one place diagnostics are rendered for `expand`.
fn report(input: &Input, diagnostics: &[crate::Diagnostic], color: ColorArg) -> String {
    super::render_diagnostics(input, diagnostics, color.enabled(false))
}

/// The model the options describe (exit 2 on any problem, with the reason).
fn model(args: &ExpandArgs) -> Result<Model, UsageError> {
    let h = args.layer_height.unwrap_or(0.2);
    let h0 = args.first_layer_height;
    let invalid = |e: eval::ModelError| UsageError(format!("invalid model: {e}"));
    let model = match (&args.model, args.layers, args.height) {
        (Some(path), _, _) => model_file(path)?,
        (None, Some(layers), _) => Model::uniform(layers, h, h0).map_err(invalid)?,
        (None, None, Some(height)) => Model::from_total_height(height, h, h0).map_err(invalid)?,
        (None, None, None) if args.layer_height.is_some() || h0.is_some() => {
            return Err(UsageError(
                "--layer-height and --first-layer-height need --layers N or --height MM \
                 (without them the model is the 20 mm cube)"
                    .into(),
            ));
        }
        (None, None, None) => Model::cube20(),
    };
    let (bottom, top) = (
        args.bottom_shell_layers.unwrap_or(model.bottom_shells()),
        args.top_shell_layers.unwrap_or(model.top_shells()),
    );
    Ok(model.with_shells(bottom, top))
}

fn model_file(path: &Path) -> Result<Model, UsageError> {
    let text = read_file(path)?;
    let file: ModelFile = serde_json::from_str(&text).map_err(|e| {
        UsageError(format!(
            "invalid model file {}: {e}\n  expected one JSON object like \
             {{\"layer_heights\": [0.3, 0.2, 0.2], \"layer_height\": 0.2, \
             \"bottom_shell_layers\": 3, \"top_shell_layers\": 4}}",
            path.display()
        ))
    })?;
    Model::from_heights(file.layer_heights, file.layer_height)
        .map(|m| m.with_shells(file.bottom_shell_layers, file.top_shell_layers))
        .map_err(|e| UsageError(format!("invalid model file {}: {e}", path.display())))
}

/// Writes every layer as it is evaluated: memory stays constant however many layers.
fn write_layers(
    layers: impl ExactSizeIterator<Item = Layer>,
    text: &str,
    args: &ExpandArgs,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    // Our own buffer, so that each small write is a static call into it and only full
    // buffers go through `dyn Write`.
    let mut out = BufWriter::with_capacity(1 << 16, out);
    let wrap = args.wrap;
    match args.format {
        Format::Csv => {
            writeln!(out, "index,bottom,top,angle,fill,start,end")?;
            for l in layers {
                write!(
                    out,
                    "{},{:?},{:?},{:?},{},",
                    l.index,
                    l.bottom,
                    l.top,
                    wrap.apply(l.angle),
                    l.fill.name()
                )?;
                match l.instruction {
                    Some(s) => writeln!(out, "{},{}", s.start, s.end)?,
                    None => writeln!(out, ",")?,
                }
            }
        }
        Format::Json => {
            out.write_all(b"{\"layers\":[")?;
            for l in layers {
                if l.index > 0 {
                    out.write_all(b",")?;
                }
                // `{:?}` prints the shortest round-trip form with a `.0` or an exponent,
                // which is valid JSON for every finite number (angles are always finite).
                write!(
                    out,
                    "\n{{\"index\":{},\"bottom\":{:?},\"top\":{:?},\"angle\":{:?},\"fill\":\"{}\",\"instruction\":",
                    l.index,
                    l.bottom,
                    l.top,
                    wrap.apply(l.angle),
                    l.fill.name()
                )?;
                match l.instruction {
                    Some(s) => write!(out, "{{\"start\":{},\"end\":{}}}}}", s.start, s.end)?,
                    None => out.write_all(b"null}")?,
                }
            }
            out.write_all(b"\n]}\n")?;
        }
        Format::Table => {
            let width = layers.len().saturating_sub(1).to_string().len().max(5);
            writeln!(
                out,
                "{:>width$}  {:>10}  {:>10}  {:>12}  {:<11}  instruction",
                "layer", "bottom", "top", "angle", "fill"
            )?;
            for l in layers {
                write_table_row(&mut out, &l, text, wrap, width)?;
            }
        }
    }
    out.flush()
}

fn write_table_row(
    out: &mut impl Write,
    l: &Layer,
    text: &str,
    wrap: Wrap,
    width: usize,
) -> std::io::Result<()> {
    let instruction = l
        .instruction
        .and_then(|s| text.get(s.range()))
        .unwrap_or("(holds)");
    // Heights to the micrometre (slicers keep no finer), angles to 1e-4° (the corpus's
    // tolerance): running sums print as 0.600, not 0.6000000000000001.
    writeln!(
        out,
        "{:>width$}  {:>10.3}  {:>10.3}  {:>12.4}  {:<11}  {}",
        l.index,
        l.bottom,
        l.top,
        wrap.apply(l.angle),
        l.fill.name(),
        instruction.trim()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: ExpandArgs,
    }

    /// Runs `rotlang expand ARGS…`: (exit code or usage error, stdout, stderr).
    fn expand(argv: &[&str]) -> (Result<i32, String>, String, String) {
        let cli = Cli::try_parse_from(std::iter::once("expand").chain(argv.iter().copied()))
            .unwrap_or_else(|e| panic!("{argv:?}: {e}"));
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let code = run(&cli.args, &mut out, &mut err).map_err(|e| e.0);
        let s = |b: Vec<u8>| String::from_utf8(b).expect("utf-8 output");
        (code, s(out), s(err))
    }

    #[test]
    fn csv_of_the_default_cube() {
        let (code, out, err) = expand(&["5, 10!, +20", "--format", "csv"]);
        assert_eq!((code, err.as_str()), (Ok(0), ""));
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), 101);
        assert_eq!(lines[0], "index,bottom,top,angle,fill,start,end");
        assert_eq!(lines[1], "0,0.0,0.2,5.0,sparse,0,1");
        assert_eq!(lines[2], "1,0.2,0.4,10.0,sparse,3,6");
        assert_eq!(lines[5].split(',').nth(3), Some("25.0"));
    }

    #[test]
    fn json_is_one_valid_object() {
        let (code, out, _) = expand(&[
            "+30/3!", "--layers", "5", "--format", "json", "--wrap", "360",
        ]);
        assert_eq!(code, Ok(0));
        let value: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
        let layers = value["layers"].as_array().expect("layers");
        assert_eq!(layers.len(), 5);
        assert_eq!(layers[0]["index"], 0);
        assert_eq!(layers[0]["fill"], "sparse");
        assert_eq!(
            layers[0]["instruction"],
            serde_json::json!({"start": 0, "end": 6})
        );
        assert_eq!(layers[2]["angle"], 30.0);
        // Spent: the angle holds and no instruction governs.
        assert_eq!(layers[4]["instruction"], serde_json::Value::Null);
    }

    #[test]
    fn table_shows_instruction_text_and_wraps() {
        let (code, out, _) = expand(&["+90, M", "--layers", "4", "--wrap", "180"]);
        assert_eq!(code, Ok(0));
        let rows: Vec<&str> = out.lines().collect();
        assert!(rows[0].contains("layer") && rows[0].contains("instruction"));
        assert!(rows[1].ends_with("sparse       +90"), "{rows:?}");
        assert!(
            rows[2].contains("90.0000") && rows[2].contains("monotonic"),
            "{rows:?}"
        );
        assert!(rows[3].contains(" 0.0000"), "{rows:?}");
    }

    #[test]
    fn errors_exit_1_and_warnings_go_to_stderr() {
        let (code, out, err) = expand(&["+30X5"]);
        assert_eq!(code, Ok(1));
        assert!(out.is_empty());
        assert!(err.contains("error"), "{err}");
        let (code, out, err) = expand(&["10,,20", "--format", "csv"]);
        assert_eq!(code, Ok(0));
        assert!(err.contains("warning"), "{err}");
        assert_eq!(out.lines().count(), 101);
    }

    #[test]
    fn usage_errors() {
        for argv in [
            &["0", "--layers", "0"][..],
            &["0", "--layers", "10", "--layer-height=-1"],
            &["0", "--height", "nan"],
            &["0", "--layer-height", "0.1"],
            &["0", "--model", "/nonexistent/model.json"],
        ] {
            let (code, _, _) = expand(argv);
            assert!(code.is_err(), "{argv:?}: {code:?}");
        }
        assert!(Cli::try_parse_from(["expand", "0", "--layers", "5", "--height", "3"]).is_err());
        assert!(Cli::try_parse_from(["expand", "0", "--file", "x.rot"]).is_err());
    }

    #[test]
    fn model_files_are_validated() {
        let dir = std::env::temp_dir().join(format!("rotlang-expand-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let write = |name: &str, text: &str| {
            let path = dir.join(name);
            std::fs::write(&path, text).expect("write");
            path.display().to_string()
        };
        let good = write(
            "good.json",
            r#"{"description": "x", "layer_heights": [0.3, 0.2, 0.2], "layer_height": 0.2,
                "bottom_shell_layers": 1, "top_shell_layers": 2}"#,
        );
        let (code, out, _) = expand(&["+10B", "--model", &good, "--format", "csv"]);
        assert_eq!(code, Ok(0));
        assert_eq!(
            out.lines().nth(3).and_then(|l| l.split(',').nth(2)),
            Some("0.7")
        );
        // B = 1 from the file: one layer turning 10°.
        assert_eq!(
            out.lines().nth(2).and_then(|l| l.split(',').nth(3)),
            Some("20.0")
        );
        let (_, out, _) = expand(&[
            "+10B",
            "--model",
            &good,
            "--bottom-shell-layers",
            "2",
            "--format",
            "csv",
        ]);
        // B = 2: 20° over layers of 0.3 and 0.2 mm, by progress in height.
        assert_eq!(
            out.lines().nth(1).and_then(|l| l.split(',').nth(3)),
            Some("12.0")
        );
        assert_eq!(
            out.lines().nth(2).and_then(|l| l.split(',').nth(3)),
            Some("20.0")
        );
        for (name, text, says) in [
            (
                "missing.json",
                r#"{"layer_heights": [0.2]}"#,
                "missing field",
            ),
            (
                "typo.json",
                r#"{"layer_heights": [0.2], "layer_hieght": 0.2}"#,
                "unknown field",
            ),
            (
                "zero.json",
                r#"{"layer_heights": [0.2, 0], "layer_height": 0.2, "bottom_shell_layers": 3, "top_shell_layers": 4}"#,
                "layer 1",
            ),
            (
                "empty.json",
                r#"{"layer_heights": [], "layer_height": 0.2, "bottom_shell_layers": 3, "top_shell_layers": 4}"#,
                "no layers",
            ),
            ("list.json", "[0.2, 0.2]", "expected one JSON object"),
        ] {
            let path = write(name, text);
            let (code, _, _) = expand(&["0", "--model", &path]);
            let message = code.expect_err(name);
            assert!(message.contains(says), "{name}: {message}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
